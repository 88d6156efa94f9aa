"""The arm matrix kept on disk (dhsym.kinematics.chain: the disk cache of ^0T_n)."""

from __future__ import annotations

import dhsym
import dhsym.kinematics.chain as chain
from dhsym.cache.memo import MEMO
from dhsym.cache.store import Store


def test_arm_matrix_read_back_and_refused_when_changed(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    MEMO.clear()  # derived in this test, whatever the tests before derived
    first = dhsym.load("stanford").arm_matrix()
    store = Store(tmp_path / "c")
    (entry,) = [p for p in store.entries.glob("transform-*") if not p.name.endswith(".hmac")]
    MEMO.clear()  # a new process, as far as the memo knows
    calls = []
    compose = chain.compose
    monkeypatch.setattr(chain, "compose", lambda word: calls.append(1) or compose(word))
    again = dhsym.load("stanford").arm_matrix()
    assert again == first and again.text() == first.text() and calls == []
    entry.write_bytes(entry.read_bytes().replace(b'"d3"', b'"d4"'))  # tampered
    MEMO.clear()
    third = dhsym.load("stanford").arm_matrix()
    assert third == first and calls == [1]  # refused, derived again
