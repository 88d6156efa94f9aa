"""Three parallel axes (the UR arms): eight solutions, 1,000 random configurations, both
conventions, the same solutions as the numeric solver and as EAIK."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.ik import numeric_ik

from ._roundtrip import random_q, recovered


def test_ur5_has_eight_named_solutions() -> None:
    r = dhsym.load("ur5")
    q = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.4])
    sol = r.ik(r.fk(q))
    assert len(sol) == 8 and len(set(sol.branches)) == 8
    assert np.abs(r.fk_function()(sol.q) - r.fk(q)).max() < 1e-9
    assert np.abs(sol.q - q).max(axis=1).min() < 1e-9


@pytest.mark.slow
@pytest.mark.parametrize("name", ["ur3", "ur5", "ur10"])
def test_ur_recovers_a_thousand_random_configurations(name: str) -> None:
    r = dhsym.load(name)
    q = random_q(r, 1000)
    ok = recovered(r, q)
    # the few misses are configurations within rounding of sin θ5 = 0 (none in 1,000 draws)
    assert ok.mean() == 1.0


@pytest.mark.slow
def test_ur5_in_modified_dh_is_solved_directly() -> None:
    r = dhsym.Robot(dhsym.to_modified(dhsym.load("ur5").table))
    assert r.inverse().family == "three parallel axes"
    q = random_q(r, 1000, seed=1)
    assert recovered(r, q).all()


def test_closed_form_and_levenberg_marquardt_agree_on_ur5() -> None:
    r = dhsym.load("ur5")
    q = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.4])
    found = numeric_ik(r, r.fk(q), q + 0.05)
    assert found.converged
    sol = r.ik(r.fk(q))
    d = np.angle(np.exp(1j * (sol.q - found.q)))
    assert np.abs(d).max(axis=1).min() < 1e-8


@pytest.mark.parametrize("name", ["puma560", "ur5"])
def test_the_same_solutions_as_eaik(name: str) -> None:
    """EAIK (an optional peer, not a dependency) finds the same solutions."""
    eaik = pytest.importorskip("eaik.IK_DH")
    r = dhsym.load(name)
    vals = r.table.value_map
    col = {k: [float(getattr(row, k).xreplace(vals)) for row in r.table.rows] for k in ("a", "d")}
    alpha = [float(row.alpha) for row in r.table.rows]
    bot = eaik.DhRobot(np.array(alpha), np.array(col["a"]), np.array(col["d"]))
    for q in random_q(r, 20, seed=5):
        T = r.fk(q)
        ours = r.ik(T).q
        found = bot.IK(T)
        exact = np.asarray(found.Q)[~np.asarray(found.is_LS, dtype=bool)]  # not least squares
        assert len(exact) == len(ours)
        for qe in exact:
            d = np.angle(np.exp(1j * (ours - qe)))
            assert np.abs(d).max(axis=1).min() < 1e-6


@pytest.mark.slow
@settings(max_examples=4, deadline=None)
@given(
    lengths=st.lists(st.floats(0.05, 1.0), min_size=6, max_size=6),
    seed=st.integers(0, 2**16),
)
def test_any_arm_of_the_ur_shape_recovers_random_configurations(
    lengths: list[float], seed: int
) -> None:
    r = dhsym.load("ur5")
    d1, a2, a3, d4, d5, d6 = lengths
    values = {"d1": d1, "a2": -a2, "a3": -a3, "d4": d4, "d5": d5, "d6": d6}
    q = random_q(r, 200, seed)
    batch = r.ik(r.fk(q, values=values), values=values)
    d = np.abs(np.angle(np.exp(1j * (batch.q - q[:, None, :]))))
    found = np.nan_to_num(d, nan=np.inf).max(axis=-1).min(axis=-1) < 1e-7
    assert found.mean() > 0.99
