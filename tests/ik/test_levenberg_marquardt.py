"""The numeric solver: one local solution, joints held, several starts."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.ik.levenberg_marquardt import numeric_ik, numeric_solutions


def test_a_held_joint_keeps_its_value_and_the_others_reach_the_pose() -> None:
    r = dhsym.load("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T = r.fk(q)
    sol = numeric_ik(r, T, q + 0.1, fixed={1: 0.3})
    assert sol.converged and sol.q[0, 0] == 0.3
    assert np.abs(r.fk(sol.q[0]) - T).max() < 1e-10
    # held at a value no solution has, it does not converge and says so
    far = numeric_ik(r, T, q, fixed={1: 2.0})
    assert not far.converged and "did not converge" in far.reason


def test_a_held_joint_out_of_range_is_refused() -> None:
    r = dhsym.load("planar2r")
    with pytest.raises(DHError, match="fixed: joints are 1 … 2"):
        numeric_ik(r, r.fk([0.4, 0.9]), fixed={3: 0.0})


def test_several_starts_give_the_distinct_solutions() -> None:
    r = dhsym.load("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T = r.fk(q)
    sol = numeric_solutions(r, T, starts=24)
    closed = r.ik(T)
    assert 2 <= len(sol) <= len(closed) and sol.method == "numeric"
    for row in sol.q:  # each numeric solution is one of the closed form's branches
        d = np.angle(np.exp(1j * (closed.q - row)))
        assert np.abs(d).max(axis=1).min() < 1e-8
    assert not sol.near_singular.any()
