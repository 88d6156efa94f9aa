"""The closed-form solver's programs kept in the disk cache (dhsym.ik.kept_programs):
read back only when verified, the same answers cold and warm."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.cache.store import Store
from dhsym.ik import closed_form_solver as cfs
from dhsym.ik.choices import build_solver
from dhsym.ik.kept_programs import Remainder, kept_program, stable_names
from dhsym.ik.rewriting import REMAINDER


def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    return Store(tmp_path / "c")


def _entries(store):
    return sorted(p for p in (store.root / "entries").glob("ik_program-*") if p.suffix != ".hmac")


def _counting(monkeypatch):
    calls = []
    rewritten = cfs.ClosedFormSolver._rewritten

    def counted(self, kind):
        calls.append(kind)
        return rewritten(self, kind)

    monkeypatch.setattr(cfs.ClosedFormSolver, "_rewritten", counted)
    return calls


def _poses(r, n=20):
    rng = np.random.default_rng(3)
    return r.fk(rng.uniform(-3, 3, (n, len(r.variables))))


def test_a_warm_solver_reads_its_programs(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    r = dhsym.load("puma560")
    calls = _counting(monkeypatch)
    T = _poses(r)
    cold = build_solver(r.inverse(), None)
    one, batch = cold.solve(T[0]), cold.solve(T)
    assert sorted(calls) == ["checked", "scalar"] and len(_entries(store)) == 2
    warm = build_solver(r.inverse(), None)
    again, batch_again = warm.solve(T[0]), warm.solve(T)
    assert sorted(calls) == ["checked", "scalar"]  # nothing rewritten again
    assert np.array_equal(one.q, again.q) and np.array_equal(batch.q, batch_again.q, equal_nan=True)


def test_a_warm_solver_at_a_singular_wrist_finds_its_factors(tmp_path, monkeypatch):
    """A program read from disk was never rewritten in this process: the batch at a
    singular wrist still knows how many singular factors the program returns (it once
    read 0 and failed to broadcast)."""
    _cache(tmp_path, monkeypatch)
    r = dhsym.load("puma560")
    rng = np.random.default_rng(3)
    q = rng.uniform(-3, 3, (50, 6))
    q[::2, 4] = 1e-9
    T = r.fk(q)
    cold = build_solver(r.inverse(), None).solve(T)
    warm = build_solver(r.inverse(), None).solve(T)
    assert np.array_equal(cold.valid, warm.valid)
    assert np.allclose(cold.q, warm.q, equal_nan=True, atol=1e-12)
    assert np.array_equal(cold.near, warm.near)
    assert all(np.abs(r.fk(warm.solution(k).q) - T[k]).max() < 1e-9 for k in range(len(q)))


def test_a_tampered_program_is_refused(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    r = dhsym.load("puma560")
    T = _poses(r, 1)[0]
    first = build_solver(r.inverse(), None).solve(T)
    (entry,) = _entries(store)
    text = entry.read_bytes()
    changed = text.replace(b'"sin"', b'"cos"', 1)
    assert changed != text
    entry.write_bytes(changed)
    calls = _counting(monkeypatch)
    again = build_solver(r.inverse(), None).solve(T)
    assert calls == ["scalar"]  # refused (HMAC), rewritten from the derivation
    assert np.array_equal(first.q, again.q)
    assert entry.read_bytes() == text  # and kept again


def test_other_values_are_another_entry(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    r = dhsym.load("puma560")
    ik = r.inverse()
    T = _poses(r, 1)[0]
    build_solver(ik, None).solve(T)
    a2 = next(s for s in r.table.value_map if str(s) == "a2")
    other = build_solver(ik, {a2: 0.5})
    calls = _counting(monkeypatch)
    other.solve(T)
    assert calls == ["scalar"] and len(_entries(store)) == 2


def test_no_cache_keeps_nothing(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    monkeypatch.setenv("DHSYM_NO_CACHE", "1")
    x = sp.Symbol("x")
    built = kept_program(lambda: "ik_program-x", lambda: ([x], [], [x + 1]))
    assert built == ((x,), (), (x + 1,)) and not store.root.exists()


def test_stable_names_write_the_remainder_as_a_class():
    d = sp.Dummy("t", real=True)
    _, _, (out,) = stable_names([d], [], [REMAINDER(d, 2)])
    assert isinstance(out, Remainder) and out.args[0].name == "_k0"


@pytest.mark.slow
def test_a_warm_and_a_cold_process_agree(tmp_path):
    script = textwrap.dedent("""
        import sys
        import numpy as np
        import dhsym
        r = dhsym.load("puma560")
        q = np.random.default_rng(7).uniform(-3, 3, (100, 6))
        out = [r.ik(T).q for T in r.fk(q)]
        out.append(r.ik(r.fk(q)).q.reshape(-1, 6))
        np.save(sys.argv[1], np.concatenate(out))
    """)
    env = {**os.environ, "DHSYM_CACHE": str(tmp_path / "c")}
    env.pop("DHSYM_NO_CACHE", None)
    for name in ("cold", "warm"):
        subprocess.run([sys.executable, "-c", script, str(tmp_path / name)], env=env, check=True)
    assert any((tmp_path / "c" / "entries").glob("ik_program-*"))
    cold, warm = np.load(tmp_path / "cold.npy"), np.load(tmp_path / "warm.npy")
    assert cold.shape[0] > 700 and np.array_equal(cold, warm, equal_nan=True)
