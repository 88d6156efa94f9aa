"""One memo per process, shared by equal tables (dhsym.cache.memo)."""

from __future__ import annotations

import threading
from dataclasses import replace

import pytest

import dhsym
from dhsym.cache.memo import MEMO, Memo, MemoKey
from dhsym.model.library import load_table


class _State:
    def __init__(self, size: int) -> None:
        self.size = size

    def memo_size(self) -> int:
        return self.size


def test_equal_tables_share_one_state():
    a = dhsym.load("puma560")
    b = dhsym.load("puma560")
    assert a.table is not b.table and a._state is b._state and a._shared is b._shared
    T0 = a.arm_matrix()
    assert b.arm_matrix() is T0  # the second derives nothing


def test_second_robot_derives_nothing(monkeypatch):
    import dhsym.kinematics.chain as chain

    monkeypatch.setenv("DHSYM_NO_CACHE", "1")  # derived here, not read from the disk cache
    table = replace(load_table("planar2r"), name="memo test")  # an entry of its own
    calls = []
    compose = chain.compose
    monkeypatch.setattr(chain, "compose", lambda word: calls.append(1) or compose(word))
    dhsym.Robot(table).arm_matrix()
    first = len(calls)
    dhsym.Robot(table).arm_matrix()
    assert first > 0 and len(calls) == first
    assert dhsym.Robot(table).inverse() is dhsym.Robot(table).inverse()


def test_notation_is_part_of_the_key():
    a, b = dhsym.load("planar2r"), dhsym.load("planar2r", compact=False)
    assert a._state is not b._state
    assert a.arm_matrix().notation != b.arm_matrix().notation
    assert "C12" in a.arm_matrix().text() and "C12" not in b.arm_matrix().text()


def test_threads_build_once():
    memo = Memo()
    key = MemoKey(load_table("planar2r"), _State)
    calls = []
    barrier = threading.Barrier(6)

    def build() -> _State:
        calls.append(1)
        return _State(1)

    got = []

    def ask() -> None:
        barrier.wait()
        got.append(memo.get(key, build))

    threads = [threading.Thread(target=ask) for _ in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(calls) == 1 and all(s is got[0] for s in got)


def test_threads_deriving_the_same_robot():
    table = replace(load_table("planar2r"), name="threads")
    out = []
    barrier = threading.Barrier(4)

    def derive() -> None:
        barrier.wait()
        r = dhsym.Robot(table)
        out.append((r.inverse(), r._state))

    threads = [threading.Thread(target=derive) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len({id(i) for i, _ in out}) == 1 and len({id(s) for _, s in out}) == 1


def test_bounded_least_recently_used():
    memo = Memo(budget=10)
    tables = [replace(load_table("planar2r"), name=f"t{k}") for k in range(4)]
    keys = [MemoKey(t, _State) for t in tables]
    memo.get(keys[0], lambda: _State(4))
    memo.get(keys[1], lambda: _State(4))
    memo.get(keys[0], lambda: _State(99))  # used again: now the most recent
    memo.get(keys[2], lambda: _State(4))  # 12 > 10: the least recently used (1) goes
    assert keys[1] not in memo and keys[0] in memo and keys[2] in memo
    assert memo.size == 8
    memo.get(keys[3], lambda: _State(50))  # larger than the budget: kept alone
    assert len(memo) == 1 and keys[3] in memo


def test_sizes_are_read_again():
    memo = Memo(budget=10)
    keys = [MemoKey(replace(load_table("planar2r"), name=f"s{k}"), _State) for k in range(2)]
    first = memo.get(keys[0], lambda: _State(1))
    memo.get(keys[1], lambda: _State(1))
    first.size = 20  # it grew (more derived)
    memo.get(MemoKey(load_table("planar2r"), _State, "x"), lambda: _State(1))
    assert keys[0] not in memo


def test_the_process_memo_is_bounded():
    assert MEMO.budget > 0 and isinstance(MEMO, Memo)


@pytest.mark.parametrize("kind", [list, dict])
def test_kind_is_a_type(kind):
    memo = Memo()
    table = load_table("planar2r")
    assert memo.get(MemoKey(table, kind), kind) is memo.get(MemoKey(table, kind), kind)
