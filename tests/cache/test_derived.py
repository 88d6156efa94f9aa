"""Derived results kept on disk and read back only when verified: the singular factors,
the compiled dynamics (dhsym.kinematics.singularities, dhsym.dynamics.compiled_dynamics)."""

from __future__ import annotations

import numpy as np

import dhsym
from dhsym.cache.store import Store
from dhsym.kinematics import singularities as sing


def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    return Store(tmp_path / "c")


def test_singularities_read_back_without_deriving(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    r = dhsym.load("stanford")
    first = sing.singularities(r)
    assert len(list(_entries(store, "singularities"))) == 1
    monkeypatch.setattr(sing, "_derive", None)  # a second call must not derive
    again = sing.singularities(r)
    assert again == first and again.text() == first.text()
    assert [f.latex() for f in again.factors] == [f.latex() for f in first.factors]


def test_changed_singularities_are_derived_again(tmp_path, monkeypatch):
    store = _cache(tmp_path, monkeypatch)
    r = dhsym.load("stanford")
    first = sing.singularities(r)
    (entry,) = list(_entries(store, "singularities"))
    entry.write_bytes(entry.read_bytes().replace(b'"shoulder"', b'"elbow"'))
    calls = []
    derive = sing._derive
    monkeypatch.setattr(sing, "_derive", lambda robot: calls.append(1) or derive(robot))
    assert sing.singularities(r) == first and calls == [1]


def test_singularities_of_another_notation(tmp_path, monkeypatch):
    _cache(tmp_path, monkeypatch)
    sing.singularities(dhsym.load("stanford"))
    lower = sing.singularities(dhsym.load("stanford", style="c1"))
    assert lower.text() == "det J = d3**2*s2*s5"


def test_compiled_dynamics_cold_and_warm_agree(tmp_path, monkeypatch):
    from dhsym.dynamics.compiled_dynamics import dynamics_functions
    from dhsym.model.tablefile import read_table_text

    _cache(tmp_path, monkeypatch)
    arm = dhsym.Robot(
        read_table_text("""
joints:
  - {type: R, theta: q1, d: 0, a: 1, alpha: pi/2, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}
  - {type: R, theta: q2, d: 0, a: 1, alpha: 0, m: 1, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}
""")
    )
    x = np.array([[0.3, -0.7], [0.1, 0.2]])
    cold = dynamics_functions(arm)
    warm = dynamics_functions(arm)
    assert np.array_equal(cold.rne(x, x, x), warm.rne(x, x, x))
    assert np.array_equal(cold.inertia(x[0]), warm.inertia(x[0]))


def test_a_refusal_is_kept(tmp_path, monkeypatch):
    import pytest

    from dhsym.kinematics.decoupling import StructureError

    _cache(tmp_path, monkeypatch)
    # seven joints: a redundant arm's determinant is refused (a six-joint arm without a
    # spherical wrist is no longer refused: its whole J is factored)
    panda = dhsym.load("panda")
    with pytest.raises(StructureError) as first:
        sing.singularities(panda)
    monkeypatch.setattr(sing, "_derive", None)
    with pytest.raises(StructureError) as again:
        sing.singularities(panda)
    assert again.value.message == first.value.message


def _entries(store, kind):
    """The entries of one kind (their HMAC files left out)."""
    return [p for p in store.entries.glob(f"{kind}-*") if not p.name.endswith(".hmac")]
