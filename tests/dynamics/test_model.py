# ruff: noqa: E501
"""The dynamic model's joint rates: a joint variable q entering its cell as ``k q + c``
(``theta: -q1``, ``theta: 2*q2 + pi/2``, ``d: -d3``; the Jaco's ``-theta1``) turns its
joint at ``k q̇``, and τ is the generalized force of q, ``k`` times the moment (force) along
the axis. Lagrange–Euler and Newton–Euler agree exactly in both conventions, and both equal
an independent reference that never scales a column: the same arm written with rate-1
variables ``p = k q`` and its equations carried over by the chain rule
(``M_q = K M_p K``, ``g_q = K g_p``, ``τ_q = K τ_p(K q, K q̇, K q̈)``, ``K = diag(k)``)."""

from __future__ import annotations

import pytest
import sympy as sp

import dhsym
from dhsym.dynamics.lagrange_euler import lagrange
from dhsym.dynamics.model import dynamic_model
from dhsym.dynamics.recursive_newton_euler import newton_euler
from dhsym.kinematics.simplification import prove_equal
from dhsym.model.tablefile import read_table_text
from dhsym.robot import Robot

# the rows, with {c1} … for the cells of the joint variables (planar links: only Izz; the
# RRP: diagonal inertias X, Y, Z)
_PLANAR_2R = (
    "  - {{type: R, theta: {c1}, d: 0, a: a1, alpha: 0, m: m1, r: [rx1, ry1, 0], I: [0, 0, I1]}}\n"
    "  - {{type: R, theta: {c2}, d: 0, a: a2, alpha: 0, m: m2, r: [rx2, 0, 0], I: [0, 0, I2]}}\n"
)
_PLANAR_3R = _PLANAR_2R + (
    "  - {{type: R, theta: {c3}, d: 0, a: a3, alpha: 0, m: m3, r: [rx3, 0, 0], I: [0, 0, I3]}}\n"
)
_RRP = (
    "  - {{type: R, theta: {c1}, d: d1, a: 0, alpha: pi/2, m: m1, r: [0, y1, 0], I: [X1, Y1, Z1]}}\n"
    "  - {{type: R, theta: {c2}, d: 0, a: a2, alpha: pi/2, m: m2, r: [x2, 0, 0], I: [X2, Y2, Z2]}}\n"
    "  - {{type: P, theta: 0, d: {c3}, a: 0, alpha: 0, m: m3, r: [0, 0, rz3], I: [X3, Y3, Z3]}}\n"
)
# name: (rows, the cells, the same cells with their variables at rate 1, the rates)
CASES = {
    "2R, theta: -q1": (_PLANAR_2R, {"c1": "-q1", "c2": "q2"}, {"c1": "q1", "c2": "q2"}, (-1, 1)),
    "2R, theta: 2*q2 + pi/2": (
        _PLANAR_2R,
        {"c1": "q1", "c2": "2*q2 + pi/2"},
        {"c1": "q1", "c2": "q2 + pi/2"},
        (1, 2),
    ),
    "3R, -q1, 2*q2 + pi/2, pi/3 - q3/2": (
        _PLANAR_3R,
        {"c1": "-q1", "c2": "2*q2 + pi/2", "c3": "pi/3 - q3/2"},
        {"c1": "q1", "c2": "q2 + pi/2", "c3": "pi/3 + q3"},
        (-1, 2, sp.Rational(-1, 2)),
    ),
    "RRP, d: -d3": (
        _RRP,
        {"c1": "q1", "c2": "pi/2 - q2", "c3": "-d3"},
        {"c1": "q1", "c2": "pi/2 + q2", "c3": "d3"},
        (1, -1, -1),
    ),
}


def _robot(rows: str, cells: dict[str, str], convention: str) -> Robot:
    text = f"convention: {convention}\nangles: rad\ngravity: [0, -g, 0]\njoints:\n"
    return Robot(read_table_text(text + rows.format(**cells)))


@pytest.fixture(scope="module", params=["standard", "modified"])
def convention(request) -> str:
    return request.param


@pytest.mark.parametrize("case", sorted(CASES))
def test_lagrange_and_newton_euler_agree_and_carry_the_rate(case, convention):
    """Lagrange = Newton–Euler (M, C, g, τ), and τ is the rate-1 arm's carried over by the
    chain rule; both fail when the joint's rate is taken as q̇ (the arithmetic before)."""
    rows, cells, unit, rates = CASES[case]
    robot = _robot(rows, cells, convention)
    dm = dynamic_model(robot)
    assert dm.cell_rates == tuple(sp.Integer(1) * k for k in rates)
    lag = lagrange(robot, dm)
    ne = newton_euler(robot, dm)
    for part in ("M", "C", "g", "tau"):
        assert prove_equal(getattr(lag, part), getattr(ne, part)), part

    ref_robot = _robot(rows, unit, convention)
    ref = dynamic_model(ref_robot)
    assert ref.cell_rates == (1,) * dm.n and ref.variables == dm.variables
    K = sp.diag(*dm.cell_rates)
    at_p = dict(zip(ref.variables, K * sp.Matrix(dm.variables)))  # p = K q
    at_p |= dict(zip(ref.rates, K * sp.Matrix(dm.rates)))
    at_p |= dict(zip(ref.accelerations, K * sp.Matrix(dm.accelerations)))
    ref_eom = lagrange(ref_robot, ref)
    assert prove_equal(lag.M, K * ref_eom.M.xreplace(at_p) * K)
    assert prove_equal(lag.g, K * ref_eom.g.xreplace(at_p))
    assert prove_equal(
        lag.C * sp.Matrix(dm.rates), K * (ref_eom.C * sp.Matrix(ref.rates)).xreplace(at_p)
    )
    assert prove_equal(lag.tau, K * ref_eom.tau.xreplace(at_p))


def test_the_kinetic_energy_is_the_rate_one_arms():
    """½ q̇ᵀ M q̇ of ``theta: 2*q2 + pi/2`` is the rate-1 arm's energy at ṗ = 2 q̇: the
    second link spins at 2 q̇2 (M[1, 1] = 4 (I2 + m2 (a2 + rx2)²), not I2 + …)."""
    rows, cells, _, _ = CASES["2R, theta: 2*q2 + pi/2"]
    eom = lagrange(_robot(rows, cells, "standard"))
    I2, m2, a2, rx2 = sp.symbols("I2 m2 a2 rx2", real=True)
    assert sp.expand(eom.M[1, 1] - 4 * (I2 + m2 * (a2 + rx2) ** 2)) == 0


def test_motor_inertia_stays_on_the_joint_variable():
    """``Jm G²`` is added to M[k, k] as it is given, whatever the joint's rate (it is
    defined on the joint variable q, as friction is)."""
    rows, cells, _, _ = CASES["2R, theta: 2*q2 + pi/2"]
    plain = _robot(rows, cells, "standard")
    rows_drive = rows.replace("I: [0, 0, I2]}", "I: [0, 0, I2], Jm: Jm2, G: G2}")
    driven = _robot(rows_drive, cells, "standard")
    Jm2, G2 = sp.symbols("Jm2 G2", real=True)
    extra = lagrange(driven).M - lagrange(plain).M
    assert sp.expand(extra[1, 1] - Jm2 * G2**2) == 0 and extra[0, 0] == extra[0, 1] == 0
    assert sp.expand(newton_euler(driven).M[1, 1] - newton_euler(plain).M[1, 1]) == Jm2 * G2**2


def test_the_jaco_has_its_first_joint_flipped():
    dm = dynamic_model(dhsym.load("jaco"))
    assert dm.cell_rates == (-1, 1, 1, 1, 1, 1)


@pytest.mark.parametrize("cell", ["theta2**2", "theta2*a2", "sin(theta2)"])
def test_a_cell_not_linear_in_its_variable_is_refused_with_row_and_field(cell):
    """The rate must be a nonzero constant: ``joint_rows`` refuses the rest, naming the
    row and field (the kinematics' Jacobians read the joints through it too)."""
    text = (
        "convention: standard\nangles: rad\njoints:\n"
        "  - {type: R, theta: theta1, d: 0, a: a1, alpha: 0}\n"
        f"  - {{type: R, theta: {cell}, d: 0, a: a2, alpha: 0}}\n"
    )
    robot = Robot(read_table_text(text))
    with pytest.raises(dhsym.DHError, match="linear in theta2") as err:
        dynamic_model(robot)
    assert (err.value.row, err.value.field) == (2, "theta")
