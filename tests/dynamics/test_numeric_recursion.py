"""The numeric recursion (what ``robot.rne``, ``inertia``, ``coriolis``, ``gravload`` and
``simulate`` compute) against the exact equations of motion at random states: the exact
Newton–Euler τ of :func:`rne_expressions` and Lagrange–Euler's M, C q̇ and g, each
evaluated by the tree walker (:func:`evaluate_many`), to 1e-9 relative; the PUMA 560 in
both conventions, the Stanford arm and the SCARA (prismatic joints), Spong's 2R, an arm
with a turned base and gravity off every axis."""

# ruff: noqa: E501  (table rows are one line each, as in a table file)
from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.dynamics import lagrange
from dhsym.dynamics.compiled_dynamics import dynamics_functions, numeric_model
from dhsym.dynamics.numeric_recursion import numeric_recursion
from dhsym.dynamics.recursive_newton_euler import rne_expressions
from dhsym.errors import DHError
from dhsym.kinematics.interpreter import evaluate_many
from dhsym.model.tablefile import read_table_text
from dhsym.robot import Robot

TURNED = """
name: turned arm
convention: modified
base: [{Rx: 30}, {Tz: 0.2}, {Ry: -20}]
angles: deg
gravity: [0.3, -1.2, -9.7]
joints:
  - {type: R, theta: q1, d: 0.2, a: 0, alpha: 0, m: 2, r: [0.02, 0.01, 0.1], I: [0.02, 0.03, 0.015, 0.001, 0, -0.002]}
  - {type: P, theta: 15, d: q2 + 0.1, a: 0.1, alpha: -90, m: 1.5, r: [0, 0.05, -0.1], I: [0.01, 0.01, 0.005]}
  - {type: R, theta: q3 - 10, d: 0, a: 0.3, alpha: 90, m: 1, r: [0.1, 0, 0.02], I: [0.002, 0.01, 0.01, 0, 0.0005, 0], Jm: 0.0003, G: -20}
  - {type: F, theta: 30, d: 0.1, a: 0.05, alpha: 45, m: 0.4, r: [0, 0, 0.03], I: [0.001, 0.001, 0.001]}
"""


def _values(robot: Robot, seed: int) -> dict[sp.Symbol, float]:
    """Numbers for the inertial symbols the table leaves open (textbook sets, Spong's)."""
    rng = np.random.default_rng(seed)
    dm = numeric_model(robot)
    out: dict[sp.Symbol, float] = {}
    for s in dm.parameters:
        name = s.name
        if name.startswith("I") and len(set(name[1:3])) == 2 and name[1:3].isalpha():
            out[s] = float(rng.uniform(-0.01, 0.01))  # products of inertia
        elif name.startswith(("I", "m")):
            out[s] = float(rng.uniform(0.5, 3.0))
        elif name == "g":
            out[s] = 9.81
        else:  # centres of mass
            out[s] = float(rng.uniform(-0.2, 0.2))
    return out


def _states(n: int, m: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    return tuple(rng.uniform(-2, 2, (m, n)) for _ in range(3))  # type: ignore[return-value]


def _exact(exprs, dm, Q, V, A) -> np.ndarray:
    """Exact expressions of q, q̇, q̈ at the states, by the tree walker: ``(m, len)``."""
    env = {}
    for syms, X in ((dm.variables, Q), (dm.rates, V), (dm.accelerations, A)):
        env.update({s: X[:, k] for k, s in enumerate(syms)})
    return evaluate_many(list(exprs), env, Q.shape[0]).T


def _close(ours: np.ndarray, exact: np.ndarray) -> None:
    """Equal to 1e-9 relative to the largest entry of each state."""
    ours, exact = ours.reshape(len(ours), -1), exact.reshape(len(exact), -1)
    scale = np.maximum(np.abs(exact).max(axis=1, keepdims=True), 1.0)
    assert np.all(np.abs(ours - exact) <= 1e-9 * scale), np.abs(ours - exact).max()


ROBOTS = {
    "puma560": lambda: dhsym.load("puma560"),
    "puma560_modified": lambda: dhsym.load("puma560_modified"),
    "stanford": lambda: dhsym.load("stanford"),
    "scara": lambda: dhsym.load("scara"),
    "spong2r": lambda: dhsym.load("spong2r"),
    "turned": lambda: Robot(read_table_text(TURNED)),
}


@pytest.mark.parametrize("name", list(ROBOTS))
def test_rne_equals_the_exact_newton_euler(name):
    robot = ROBOTS[name]()
    values = _values(robot, 7)
    dm = numeric_model(robot, values)
    f = dynamics_functions(robot, values)
    Q, V, A = _states(dm.n, 6, 11)
    _close(f.rne(Q, V, A, friction=False), _exact(rne_expressions(dm), dm, Q, V, A))
    for q, v, a, row in zip(Q, V, A, f.rne(Q, V, A)):  # one state: as the batch
        np.testing.assert_allclose(f.rne(q, v, a), row, rtol=1e-13, atol=1e-12)


SIX_JOINTS = [pytest.param(name, marks=pytest.mark.slow) for name in ("puma560", "stanford")]


@pytest.mark.parametrize("name", ["spong2r", "scara", "turned", *SIX_JOINTS])
def test_inertia_coriolis_and_gravity_equal_lagrange(name):
    robot = ROBOTS[name]()
    values = _values(robot, 3)
    dm = numeric_model(robot, values)
    eom = lagrange(dm.robot, dm)
    f = dynamics_functions(robot, values)
    Q, V, _ = _states(dm.n, 5, 13)
    _close(f.inertia(Q), _exact(eom.M, dm, Q, V, V))
    _close(f.gravload(Q), _exact(eom.g, dm, Q, V, V))
    _close(f.coriolis(Q, V) @ V[..., None], _exact(eom.C * sp.Matrix(dm.rates), dm, Q, V, V))


def test_forward_dynamics_inverts_rne_with_friction():
    puma = dhsym.load("puma560")
    f = puma.dynamics_functions()
    assert f.has_friction
    Q, V, A = _states(6, 3, 19)
    V[0, :3] = 0.0  # joints at rest: no Coulomb friction there
    np.testing.assert_allclose(f.accel(Q, V, f.rne(Q, V, A)), A, rtol=1e-9, atol=1e-9)


def test_a_symbol_without_a_number_is_named():
    robot = dhsym.load("spong2r")
    with pytest.raises(DHError, match=r"row 1, m: no numeric value for m1"):
        numeric_recursion(numeric_model(robot))
    with pytest.raises(DHError, match="no numeric value for g"):
        dynamics_functions(robot, {"m1": 1, "m2": 1, "I1": 0.1, "I2": 0.1})
