"""Lagrange–Euler: Spong's two-link planar elbow arm exactly, and the laws M and C obey."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.dynamics import lagrange
from dhsym.dynamics.lagrange_euler import christoffel_symbols, link_jacobians, tidy
from dhsym.dynamics.model import dynamic_model
from dhsym.kinematics.simplification import prove_equal
from dhsym.model.tablefile import read_table_text
from dhsym.robot import Robot

S = sp.Symbol


def R(name: str) -> sp.Symbol:
    return sp.Symbol(name, real=True)


SPONG = """
name: Two-link planar elbow arm (Spong)
convention: {convention}
gravity: [0, -g, 0]
joints:
{rows}
"""
STANDARD_ROWS = """\
  - {type: R, theta: q1, d: 0, a: l1, alpha: 0, m: m1, r: [lc1 - l1, 0, 0], I: [Ix1, Iy1, I1]}
  - {type: R, theta: q2, d: 0, a: l2, alpha: 0, m: m2, r: [lc2 - l2, 0, 0], I: [Ix2, Iy2, I2]}"""
# Craig's frames: frame i sits at joint i, so the centre of mass is at lc_i along x_i
MODIFIED_ROWS = """\
  - {type: R, theta: q1, d: 0, a: 0, alpha: 0, m: m1, r: [lc1, 0, 0], I: [Ix1, Iy1, I1]}
  - {type: R, theta: q2, d: 0, a: l1, alpha: 0, m: m2, r: [lc2, 0, 0], I: [Ix2, Iy2, I2]}"""


def spong_arm(convention: str = "standard") -> Robot:
    rows = STANDARD_ROWS if convention == "standard" else MODIFIED_ROWS
    return Robot(read_table_text(SPONG.format(convention=convention, rows=rows)))


def spong_D_and_g() -> tuple[sp.Matrix, sp.Matrix]:
    """Spong, Hutchinson and Vidyasagar, Robot Modeling and Control, §7.3 (two-link
    planar elbow manipulator), written out by hand."""
    q1, q2, m1, m2, l1, lc1, lc2, I1, I2, g = (
        R(n) for n in ("q1", "q2", "m1", "m2", "l1", "lc1", "lc2", "I1", "I2", "g")
    )
    d11 = m1 * lc1**2 + m2 * (l1**2 + lc2**2 + 2 * l1 * lc2 * sp.cos(q2)) + I1 + I2
    d12 = m2 * (lc2**2 + l1 * lc2 * sp.cos(q2)) + I2
    d22 = m2 * lc2**2 + I2
    D = sp.Matrix([[d11, d12], [d12, d22]])
    phi1 = (m1 * lc1 + m2 * l1) * g * sp.cos(q1) + m2 * lc2 * g * sp.cos(q1 + q2)
    phi2 = m2 * lc2 * g * sp.cos(q1 + q2)
    return D, sp.Matrix([phi1, phi2])


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_spong_two_link_arm_exactly(convention):
    eom = lagrange(spong_arm(convention))
    D, phi = spong_D_and_g()
    assert sp.expand(eom.M - D) == sp.zeros(2, 2)
    assert sp.expand(eom.g - phi) == sp.zeros(2, 1)
    # Spong's Christoffel symbols: c_121 = c_211 = c_221 = -h, c_112 = h, the rest 0
    h = -R("m2") * R("l1") * R("lc2") * sp.sin(R("q2"))
    expected = {(1, 2, 1): h, (2, 1, 1): h, (2, 2, 1): h, (1, 1, 2): -h}
    for i in (1, 2):
        for j in (1, 2):
            for k in (1, 2):
                assert sp.expand(eom.c(i, j, k) - expected.get((i, j, k), 0)) == 0, (i, j, k)


def test_the_built_in_spong2r_is_spongs_arm_with_gravity():
    eom = lagrange(dhsym.load("spong2r"))  # joint angles theta1, theta2 (Spong's q1, q2)
    q = {R("q1"): R("theta1"), R("q2"): R("theta2")}
    D, phi = (x.xreplace(q) for x in spong_D_and_g())
    assert sp.expand(eom.M - D) == sp.zeros(2, 2)
    assert sp.expand(eom.g - phi) == sp.zeros(2, 1) and eom.g != sp.zeros(2, 1)
    assert eom.model.gravity == (0, -R("g"), 0)
    h = -R("m2") * R("l1") * R("lc2") * sp.sin(R("theta2"))  # Spong's h; c_112 = -h
    expected = {(1, 2, 1): h, (2, 1, 1): h, (2, 2, 1): h, (1, 1, 2): -h}
    for i, j, k in ((i, j, k) for i in (1, 2) for j in (1, 2) for k in (1, 2)):
        assert sp.expand(eom.c(i, j, k) - expected.get((i, j, k), 0)) == 0, (i, j, k)
    qd1, qd2 = eom.rates  # C(q, q̇) of Spong: [[h q̇2, h q̇2 + h q̇1], [-h q̇1, 0]]
    C = sp.Matrix([[h * qd2, h * qd2 + h * qd1], [-h * qd1, 0]])
    assert sp.expand(eom.C - C) == sp.zeros(2, 2)


def test_spong_arm_prints_in_lecture_form():
    eom = lagrange(spong_arm())
    text = eom.notation.text(eom.M[0, 1])
    assert "C2" in text and "cos" not in text
    assert text.startswith("I2 + m2*(") or text.startswith("m2*(")  # collected by the mass


def test_energies_add_up_to_the_kinetic_energy_of_M():
    eom = lagrange(spong_arm())
    qd = sp.Matrix(eom.rates)
    total = sp.expand((qd.T * eom.M * qd)[0, 0] / 2 - sum(eom.kinetic))
    assert total == 0
    assert len(eom.potential) == 2 and eom.potential[0].has(R("g"))


def test_textbook_parameters_on_request():
    eom = dhsym.load("planar2r").dynamics()
    names = {s.name for s in eom.M.free_symbols}
    assert {"m1", "m2", "Izz1", "Izz2", "rx2", "ry2", "a1", "a2"} <= names
    assert "Ixx2" not in names  # a planar arm turns about z only


def test_link_jacobians_are_written_in_the_link_frame():
    dm = dynamic_model(spong_arm())
    Jv, Jw = link_jacobians(dm, 1)
    lc1 = R("lc1")
    assert sp.expand(Jv - sp.Matrix([[0, 0], [lc1, 0], [0, 0]])) == sp.zeros(3, 2)
    assert Jw == sp.Matrix([[0, 0], [0, 0], [1, 0]])


def test_tidy_folds_and_collects():
    t1, t2, m, ln = sp.symbols("theta1 theta2 m l", real=True)
    e = m * ln * sp.cos(t1) * sp.cos(t2) - m * ln * sp.sin(t1) * sp.sin(t2) + m
    assert tidy(e, (m,)) in (m * (ln * sp.cos(t1 + t2) + 1), ln * m * sp.cos(t1 + t2) + m)


# --- the laws of M and C ---------------------------------------------------------------------


@pytest.mark.parametrize("name", ["planar2r", "example1_rrp"])
def test_Mdot_minus_2C_is_skew_symmetric_exactly(name):
    eom = dhsym.load(name).dynamics()
    q, qd = eom.variables, eom.rates
    Mdot = sum((eom.M.diff(x) * v for x, v in zip(q, qd)), sp.zeros(*eom.M.shape))
    N = Mdot - 2 * eom.C
    assert prove_equal(N + N.T, sp.zeros(*N.shape))
    assert eom.M == eom.M.T


def test_christoffel_symbols_are_symmetric_in_i_and_j():
    eom = lagrange(spong_arm())
    c = christoffel_symbols(eom.M, eom.variables)
    n = len(eom.variables)
    for i in range(n):
        for j in range(n):
            for k in range(n):
                assert sp.expand(c[i][j][k] - c[j][i][k]) == 0


def _christoffel_entry_by_entry(M, q, params=()):
    """Spong's c_ijk the plain way: every entry of M differentiated, every symbol tidied."""
    n = len(q)
    dM = [M.diff(x) for x in q]
    return tuple(
        tuple(
            tuple(tidy((dM[i][k, j] + dM[j][k, i] - dM[k][i, j]) / 2, params) for k in range(n))
            for j in range(n)
        )
        for i in range(n)
    )


_Q3 = sp.symbols("theta1:4", real=True)
_M3 = sp.symbols("m1:3", real=True)
_TRIG_TERMS = st.tuples(
    st.integers(-3, 3),
    st.sampled_from([sp.Integer(1), *_M3]),
    st.sampled_from([sp.cos(_Q3[1]), sp.sin(_Q3[2]), sp.cos(_Q3[1] + _Q3[2]), _Q3[2]]),
    st.sampled_from([sp.Integer(1), sp.sin(_Q3[1]), sp.cos(_Q3[2]), sp.cos(_Q3[0])]),
)


@settings(max_examples=30, deadline=None)
@given(
    st.lists(st.lists(_TRIG_TERMS, max_size=4), min_size=9, max_size=9),
    st.booleans(),
)
def test_christoffel_symbols_are_those_of_every_entry_differentiated(cells, symmetric):
    """Each distinct entry differentiated and tidied once: the same expressions (srepr) as
    entry by entry, for a symmetric M and for any other."""
    entries = [sp.Add(*(k * a * b * c for k, a, b, c in cell)) for cell in cells]
    M = sp.Matrix(3, 3, entries)
    if symmetric:
        M = sp.Matrix(3, 3, lambda r, c: M[min(r, c), max(r, c)])
    got = christoffel_symbols(M, _Q3, _M3)
    assert sp.srepr(got) == sp.srepr(_christoffel_entry_by_entry(M, _Q3, _M3))


@settings(max_examples=25, deadline=None)
@given(
    st.lists(st.floats(-3.1, 3.1), min_size=2, max_size=2),
    st.floats(0.1, 5),
    st.floats(0.1, 5),
)
def test_M_is_symmetric_positive_definite(q, m1, m2):
    eom = _spong_eom()
    values = {R("m1"): m1, R("m2"): m2, R("l1"): 1.0, R("lc1"): 0.5, R("lc2"): 0.4}
    values |= {R("I1"): 0.1, R("I2"): 0.05, R("q1"): q[0], R("q2"): q[1]}
    M = np.array(eom.M.subs(values).evalf(), dtype=float)
    assert np.allclose(M, M.T)
    assert np.all(np.linalg.eigvalsh(M) > 0)


_CACHE: list = []


def _spong_eom():
    if not _CACHE:
        _CACHE.append(lagrange(spong_arm()))
    return _CACHE[0]


@pytest.mark.parametrize("cell", ["-theta2", "2*theta2", "pi/2 - theta2"])
def test_a_joint_variable_with_a_rate_other_than_one_moves_its_joint_at_that_rate(cell):
    """With theta = k q + c the joint turns at k q̇ and τ is the generalized force of q:
    M[0, 1] of this arm is k (I2 + m2 a2 (a1 cos θ2 + a2)) with θ2 the cell (−(…) for
    theta = −q2, where the methods once agreed on +(…)), and ``robot.rne`` (the numeric
    recursion) gives Lagrange's τ at a state."""
    text = (
        "convention: standard\nangles: rad\nvalues: {a1: 1.0, a2: 0.8}\njoints:\n"
        "  - {type: R, theta: theta1, d: 0, a: a1, alpha: 0, m: m1, I: [0, 0, I1]}\n"
        f"  - {{type: R, theta: {cell}, d: 0, a: a2, alpha: 0, m: m2, I: [0, 0, I2]}}\n"
    )
    robot = Robot(read_table_text(text))
    k = dynamic_model(robot).cell_rates[1]
    assert k == {"-theta2": -1, "2*theta2": 2, "pi/2 - theta2": -1}[cell]
    eom = lagrange(robot)
    t2 = robot.table.rows[1].theta
    I2, m2, a1, a2 = R("I2"), R("m2"), R("a1"), R("a2")
    assert prove_equal(
        sp.Matrix([eom.M[0, 1]]), sp.Matrix([k * (I2 + m2 * a2 * (a1 * sp.cos(t2) + a2))])
    )
    values = {"m1": 2.0, "m2": 1.5, "I1": 0.1, "I2": 0.05}
    q, qd, qdd = np.array([0.3, -0.7]), np.array([1.1, -0.4]), np.array([0.5, 2.0])
    state = dict(zip(eom.variables, q)) | dict(zip(eom.rates, qd))
    state |= dict(zip(eom.accelerations, qdd)) | {R(n): v for n, v in values.items()}
    state |= {a1: 1.0, a2: 0.8, R("g"): 9.81}
    want = np.array([float(e.xreplace(state)) for e in eom.tau])
    np.testing.assert_allclose(robot.rne(q, qd, qdd, values=values), want, rtol=1e-12)
