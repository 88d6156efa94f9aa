"""The closed-form derivations kept in the disk cache (dhsym.ik.kept_derivations): read back
equal to what is derived, verified before use, the same answers cold and warm."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import sympy as sp

from dhsym.cache.store import Store
from dhsym.ik.choices import IKCache, build_solver
from dhsym.ik.families import inverse
from dhsym.ik.kept_derivations import (
    closed_form_data,
    derivation_entry,
    kept_inverse,
    stored_closed_form,
)
from dhsym.kinematics.chain import KinematicChain
from dhsym.kinematics.decoupling import StructureError
from dhsym.model.library import load_table
from dhsym.notation.layout import sentence_runs


def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    return Store(tmp_path / "c")


def _counted(calls):
    def derive(chain):
        calls.append(chain.name)
        return inverse(chain)

    return derive


def _printed(ik):
    """Everything a derivation prints: its sentences in text and LaTeX (the robot's
    notation), each step's equation, the branches' sentences."""
    nota = ik.robot.notation
    out = [ik.structure, ik.family]
    for st in ik.steps:
        runs = sentence_runs(st.sentence, nota)
        out += [st.part, ik.text(st), ik.latex(st), st.text, repr(st.branch and st.branch.role)]
        out += [r.words + (r.math.latex if r.math else "") for r in runs]
        out += [sp.srepr(e) for e in (st.lhs, st.rhs, st.equation, st.singular)]
        out += [sp.srepr(v) if isinstance(v, sp.Basic) else repr(v) for _, v in st.sentence.args]
    for b in ik.branches:
        out += [sp.srepr(b.symbol), b.role, str(b.joint), b.text]
    return out


@pytest.mark.parametrize("name", ["puma560", "ur5", "stanford", "scara", "cylindrical"])
def test_a_derivation_reads_back_equal_and_prints_the_same(name):
    chain = KinematicChain(load_table(name))
    ik = inverse(chain)
    data = closed_form_data(ik)
    assert data is not None
    back = stored_closed_form(data, chain)
    assert back == ik and back is not ik and back.robot is chain
    assert _printed(back) == _printed(ik)


def test_a_chain_read_backwards_reads_back_equal():
    """The Panda with joint 7 given is read backwards: its steps keep the reversed chain's
    branches (another role than the arm's), and a sentence holds joint numbers."""
    chain = IKCache(KinematicChain(load_table("panda"))).given(7).cache.chain
    ik = inverse(chain)
    assert ik.family == "inverted chain"
    back = stored_closed_form(closed_form_data(ik), chain)
    assert back == ik and _printed(back) == _printed(ik)


def test_a_warm_cache_reads_the_derivation_instead_of_deriving(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    chain = KinematicChain(load_table("puma560"))
    calls = []
    cold = kept_inverse(chain, _counted(calls))
    assert calls == ["PUMA 560"] and store.read(derivation_entry(chain)) is not None
    other = KinematicChain(load_table("puma560"))
    warm = kept_inverse(other, _counted(calls))
    assert calls == ["PUMA 560"]  # read, not derived
    assert warm == cold and warm.robot is other
    T = chain.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    a, b = build_solver(cold, None).solve(T), build_solver(warm, None).solve(T)
    assert np.array_equal(a.q, b.q) and a.branches == b.branches


def test_a_refusal_is_kept_and_raised_again(tmp_path, monkeypatch):
    _cache(tmp_path, monkeypatch)
    chain = KinematicChain(load_table("planar4r"))
    calls = []
    with pytest.raises(StructureError) as first:
        kept_inverse(chain, _counted(calls))
    with pytest.raises(StructureError) as again:
        kept_inverse(chain, _counted(calls))
    assert len(calls) == 1 and again.value.message == first.value.message


def test_another_name_is_another_entry(tmp_path, monkeypatch):
    """A refusal names the arm: a table renamed does not read the other name's entry."""
    from dataclasses import replace

    table = load_table("planar4r")
    a, b = KinematicChain(table), KinematicChain(replace(table, name="Another arm"))
    assert derivation_entry(a) != derivation_entry(b)
    _cache(tmp_path, monkeypatch)
    with pytest.raises(StructureError):
        kept_inverse(a, inverse)
    with pytest.raises(StructureError, match="Another arm"):
        kept_inverse(b, inverse)


def test_a_tampered_derivation_is_derived_again(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    chain = KinematicChain(load_table("scara"))
    calls = []
    first = kept_inverse(chain, _counted(calls))
    entry = store.entries / derivation_entry(chain)
    text = entry.read_bytes()
    changed = text.replace(b'\\"cos\\"', b'\\"sin\\"', 1)  # in the expressions' document
    assert changed != text
    entry.write_bytes(changed)
    again = kept_inverse(chain, _counted(calls))
    assert len(calls) == 2 and again == first  # refused (HMAC) and derived again
    assert entry.read_bytes() == text  # and kept again


def test_a_verified_entry_that_is_not_a_derivation_is_derived_again(tmp_path, monkeypatch):
    """Data this version does not read (an older format, a wrong shape) is never used,
    even when its HMAC is right."""
    store = _cache(tmp_path, monkeypatch)
    chain = KinematicChain(load_table("planar2r"))
    name = derivation_entry(chain)
    good = closed_form_data(inverse(chain))
    doc = json.loads(good)
    bad = [
        b"[]",
        b'{"closed_form": {"format": "dhsym-closed-form 0"}}',
        json.dumps({**doc, "exprs": doc["exprs"].replace('"cos"', '"__import__"')}).encode(),
        json.dumps(
            {"closed_form": {**doc["closed_form"], "pose": 10_000}, **{"exprs": doc["exprs"]}}
        ).encode(),
        json.dumps(
            {"closed_form": {**doc["closed_form"], "steps": [{"lhs": 0}]}, "exprs": doc["exprs"]}
        ).encode(),
    ]
    for data in bad:
        assert stored_closed_form(data, chain) is None
        store.write(name, data)
        calls = []
        ik = kept_inverse(chain, _counted(calls))
        assert calls == ["Planar 2R"] and ik == inverse(chain)
        assert store.read(name) == good  # rewritten


def test_no_cache_derives_and_keeps_nothing(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    monkeypatch.setenv("DHSYM_NO_CACHE", "1")
    calls = []
    kept_inverse(KinematicChain(load_table("planar2r")), _counted(calls))
    kept_inverse(KinematicChain(load_table("planar2r")), _counted(calls))
    assert len(calls) == 2 and not store.root.exists()


_SCRIPT = textwrap.dedent("""
    import sys
    import numpy as np
    import dhsym
    out = []
    for name in ("puma560", "ur5", "stanford"):
        r = dhsym.load(name)
        q = np.random.default_rng(7).uniform(-3, 3, (40, 6))
        q[::5, 4] = 0.0  # a singular wrist now and then
        out += [r.ik(T).q for T in r.fk(q)]
        out.append(r.ik(r.fk(q)).q.reshape(-1, 6))
        out.append(r.ik(np.round(r.fk(q), 4)).q.reshape(-1, 6))  # rounded: stretched
        texts = [st.text + r.inverse().text(st) for st in r.inverse().steps]
        print(name, r.ik(r.fk(q[1])).branches, len("".join(texts)), hash("".join(texts)))
    np.save(sys.argv[1], np.concatenate(out))
""")


@pytest.mark.slow
def test_a_warm_and_a_cold_process_agree_to_the_bit(tmp_path):
    """The PUMA 560, UR5 and Stanford arm in a fresh process with an empty cache, then in
    one that reads the derivations and programs the first wrote: the same joint values
    (one pose, a batch, rounded poses) to the bit, the same branch names and step texts."""
    env = {**os.environ, "DHSYM_CACHE": str(tmp_path / "c"), "PYTHONHASHSEED": "0"}
    env.pop("DHSYM_NO_CACHE", None)
    printed = []

    def derivations():
        found = (tmp_path / "c" / "entries").glob("ik_derivation-*")
        # a rewrite moves a new file in (another inode); a read only marks the entry used
        return {p.name: p.stat().st_ino for p in found if p.suffix != ".hmac"}

    for name in ("cold", "warm"):
        done = subprocess.run(
            [sys.executable, "-c", _SCRIPT, str(tmp_path / name)],
            env=env,
            check=True,
            capture_output=True,
            text=True,
        )
        printed.append(done.stdout)
        if name == "cold":
            written = derivations()
            assert len(written) == 3
    assert derivations() == written  # the warm process read them: none derived and rewritten
    cold, warm = np.load(tmp_path / "cold.npy"), np.load(tmp_path / "warm.npy")
    assert cold.shape[0] > 3 * 8 * 80 and np.isfinite(cold).any()
    assert np.array_equal(cold, warm, equal_nan=True)
    assert printed[0] == printed[1] and printed[0].count("\n") == 3
