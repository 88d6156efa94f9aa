"""The exported C built into a shared library and loaded back (dhsym.export.shared_library)."""

from __future__ import annotations

import shutil

import numpy as np

import dhsym
from dhsym.export.shared_library import compiled
from dhsym.ik.choices import IKCache
from dhsym.kinematics.chain import KinematicChain

from ..conftest import _need


def test_compiled_matches_robot(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    r = dhsym.load("puma560")
    fast = compiled(r)
    assert (
        fast.backend == "c" and fast.library is not None and fast.library.parent.parent == tmp_path
    )
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert np.abs(fast.fk(q) - r.fk(q)).max() <= 1e-12
    assert np.abs(fast.jacobian(q) - r.jacob0(q)).max() <= 1e-12
    assert np.abs(fast.ik(r.fk(q)).q - r.ik(r.fk(q)).q).max() <= 1e-9
    again = dhsym.load("puma560").compiled("c")  # the cache: the same library, not rebuilt
    assert again.library == fast.library


def test_compiled_without_a_compiler(monkeypatch, tmp_path):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    monkeypatch.setenv("CC", "")
    monkeypatch.setattr(shutil, "which", lambda name: None)
    r = dhsym.load("planar2r")
    slow = compiled(r)
    assert slow.backend == "numpy"
    assert np.abs(slow.fk([0.1, 0.2]) - r.fk([0.1, 0.2])).max() == 0
    T = r.fk([0.4, 0.9])
    assert np.array_equal(slow.ik(T).q, r.ik(T).q)


def test_compiled_derives_in_the_cache_it_is_given(monkeypatch, tmp_path):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    monkeypatch.setenv("CC", "")
    monkeypatch.setattr(shutil, "which", lambda name: None)
    r = dhsym.load("planar2r")
    cache = IKCache(KinematicChain(r.table))
    compiled(cache.chain, cache=cache)
    derived = cache.inverse()
    assert derived is cache.inverse()  # derived once, by compiled, and kept
    assert r.compiled().backend == "numpy" and r.ik_cache().inverse() is r.inverse()


def test_compiled_ik_at_a_singular_wrist(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    r = dhsym.load("puma560")
    fast = r.compiled("c")
    for q5 in (0.0, 1e-7):  # sin θ5 = 0 (θ4 = 0 and θ6 from the whole rotation) and near it
        T = r.fk([0.3, -0.5, 0.4, 0.2, q5, -1.1])
        got, want = fast.ik(T).q, r.ik(T)
        assert got.shape == want.q.shape
        assert np.abs(np.angle(np.exp(1j * (got - want.q)))).max() <= 1e-9
