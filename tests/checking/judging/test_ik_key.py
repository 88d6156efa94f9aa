"""The prepared part of an ik key: a numeric question's variants kept in the disk cache."""

from __future__ import annotations

import numpy as np
import pytest

from dhsym.cache.keys import entry_name
from dhsym.cache.memo import MEMO
from dhsym.cache.store import Store
from dhsym.checking import Key, check_answer
from dhsym.checking.judging import ik_key
from dhsym.checking.judging.key import PreparedKeys, prepare
from dhsym.checking.mistakes import _ik_mistakes

QUESTION = "ik@0.3,0.9"
#: wrong answers of the 2R at the question's pose: an elbow angle's sign slip, nonsense
WRONG = ("theta1 = 0.3\ntheta2 = -0.9", "theta1 = 2.1\ntheta2 = 0.4", "theta1 = -0.3\ntheta2 = 0.9")


@pytest.fixture(autouse=True)
def _fresh_memo() -> None:
    """Each test starts as a new process would: no key prepared yet (the memo keeps
    prepared keys, :func:`dhsym.checking.judging.key.prepare`)."""
    MEMO.clear()


def _builds(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Every build of the key's names and variants from now on."""
    built: list[str] = []
    original = ik_key.prepare_ik_variants

    def counted(*args, **kwargs):  # type: ignore[no-untyped-def]
        built.append("variants")
        return original(*args, **kwargs)

    monkeypatch.setattr(ik_key, "prepare_ik_variants", counted)
    return built


def _same(a: ik_key.IKPart, b: ik_key.IKPart) -> None:
    """Two parts that diagnose alike: the names, the key, each mistake's values and texts."""
    va, vb = a.diagnosis[False], b.diagnosis[False]
    assert a.branch_names == b.branch_names
    assert np.array_equal(va.key, vb.key, equal_nan=True)
    assert [m.kind for m in va.whole] == [m.kind for m in vb.whole]
    for m in va.whole:
        assert [d for _, d in va.whole[m]] == [d for _, d in vb.whole[m]]
        for (x, _), (y, _) in zip(va.whole[m], vb.whole[m], strict=True):
            assert np.array_equal(x, y, equal_nan=True)
    assert [m.kind for m in va.steps] == [m.kind for m in vb.steps]
    for m in va.steps:
        assert va.steps[m].edits == vb.steps[m].edits  # the expressions equal, the texts too
        assert np.array_equal(va.steps[m].values, vb.steps[m].values, equal_nan=True)
    assert vb.sample is b.pose and b.diagnosis[True] is vb


def test_a_numeric_questions_variants_are_read_back_not_built(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    built = _builds(monkeypatch)
    cold_keys, warm_keys = PreparedKeys(), PreparedKeys()  # two workers, one after the other
    key = Key.load("planar2r", QUESTION, keys=cold_keys)  # prepared once, to check it
    assert built == ["variants"]
    assert any(n.startswith("ik_variants-") for n in Store(tmp_path / "cache")._names())
    cold = cold_keys.get(key)
    MEMO.clear()  # the second worker: a new process, as far as the memo knows
    warm = warm_keys.get(key)
    assert built == ["variants"]  # read back: nothing built again
    assert isinstance(cold.part, ik_key.IKPart) and isinstance(warm.part, ik_key.IKPart)
    _same(cold.part, warm.part)
    assert any(len(s.edits) for s in warm.part.diagnosis[False].steps.values())
    # a wrong answer is diagnosed alike by a key built and a key read back
    for wrong in WRONG:
        a = check_answer(key, wrong, keys=cold_keys)
        b = check_answer(key, wrong, keys=warm_keys)
        assert not a.correct and (a.message, a.kinds) == (b.message, b.kinds)
    assert built == ["variants"] and len(cold_keys) == len(warm_keys) == 1


def test_an_entry_this_version_does_not_read_is_built_again(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    key = Key.load("planar2r", QUESTION)
    cold = prepare(key)
    part = cold.part
    assert isinstance(part, ik_key.IKPart) and part.pose is not None
    robot = part.ik.robot
    name = entry_name(
        robot.table, "ik_variants", ik_key._variants_text(part.ik, robot.notation, part.pose)
    )
    store = Store(tmp_path / "cache")
    good = store.read(name)
    assert good is not None
    header, _, array = good.partition(b"\n")
    built = _builds(monkeypatch)
    for bad in (
        b'{"format": "dhsym-ik-variants 0"}\n' + array,  # another version's
        header + b"\n" + array[:-8],  # one value short
        header.replace(b"atan2_swapped", b"atan2_swapped_", 1) + b"\n" + array,  # other kinds
        header + b"\n" + b"\x93NUMPY not an array",
    ):
        store.write(name, bad)  # written by the store: its HMAC holds, the content is wrong
        MEMO.clear()  # a new process, as far as the memo knows
        again = prepare(key)
        assert built == ["variants"], bad[:40]
        _same(cold.part, again.part)
        assert store.read(name) == good  # rewritten
        del built[:]
    # a question whose pose differs has an entry of its own
    other = prepare(Key.load("planar2r", "ik@0.3,0.8")).part
    assert built == ["variants"] and other.pose is not None
    assert not np.array_equal(other.diagnosis[False].key, part.diagnosis[False].key)


def test_the_variants_are_built_where_the_cache_is_off(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("DHSYM_NO_CACHE", "1")
    built = _builds(monkeypatch)
    key = Key.load("planar2r", QUESTION)
    MEMO.clear()  # a new process, as far as the memo knows
    prepare(key)
    assert built == ["variants", "variants"]
    assert not (tmp_path / "cache").exists()
    assert _ik_mistakes.IK_MISTAKES  # the catalogue the entry is checked against
