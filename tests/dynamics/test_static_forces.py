"""Statics: τ = Jᵀ F, exact and numeric."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.dynamics.static_forces import WRENCH, Statics, static_torques, statics


def test_planar_arm_statics_in_compact_form():
    s = statics(dhsym.load("planar2r"))
    text = s.notation.text(s.tau)
    assert "C12" in text and "cos" not in text
    fx, fy = WRENCH[:2]
    t1, t2 = dhsym.load("planar2r").variables
    a2 = sp.Symbol("a2", real=True)
    assert (
        sp.expand(s.tau[1] - (-a2 * fx * sp.sin(t1 + t2) + a2 * fy * sp.cos(t1 + t2) + WRENCH[5]))
        == 0
    )


def test_numeric_statics_is_batched_and_matches_the_jacobian():
    robot = dhsym.load("stanford")
    rng = np.random.default_rng(0)
    Q = rng.uniform(-1, 1, (5, 6))
    F = rng.uniform(-1, 1, (5, 6))
    tau = robot.static_torques(Q, F)
    J = robot.jacob0(Q)
    assert tau.shape == (5, 6)
    assert np.allclose(tau, np.einsum("nij,ni->nj", J, F))
    assert np.allclose(robot.static_torques(Q[0], F[0]), tau[0])
    assert np.array_equal(static_torques(robot, Q, F), tau)
    with pytest.raises(dhsym.DHError, match="6 entries"):
        robot.static_torques(Q[0], [1, 2, 3])


def test_statics_of_q_is_an_alias_of_the_numbers():
    robot = dhsym.load("planar2r")
    q, F = [0.3, -0.4], [1.0, 2.0, 0.0, 0.0, 0.0, 0.5]
    assert isinstance(robot.statics(), Statics)
    assert np.array_equal(robot.statics(q, F), robot.static_torques(q, F))
    values = {"a1": 2}
    assert np.array_equal(
        robot.statics(q, F, values=values), robot.static_torques(q, F, values=values)
    )
    with pytest.raises(dhsym.DHError, match="static_torques"):
        robot.statics(wrench=F)  # type: ignore[call-overload]  # a wrench needs a q


def test_exact_statics_equals_the_numbers():
    robot = dhsym.load("planar2r")
    s = robot.statics()
    q = [0.3, -0.4]
    F = [1.0, 2.0, 0.0, 0.0, 0.0, 0.5]
    subs = dict(zip(robot.variables, q)) | dict(zip(WRENCH, F)) | robot.table.value_map
    exact = np.array(s.tau.subs(subs), dtype=float).ravel()
    assert np.allclose(exact, robot.static_torques(q, F))
