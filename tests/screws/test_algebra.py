"""Screws, exponentials, logarithms and adjoints: the algebraic laws, exactly."""

from __future__ import annotations

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from dhsym.errors import DHError
from dhsym.kinematics.simplification import prove_equal
from dhsym.kinematics.transforms import Rx, Ry, Rz, Tx, Ty, Tz, rigid_inverse
from dhsym.screws.algebra import (
    Exponential,
    ScrewAxis,
    adjoint,
    bracket,
    is_zero,
    matrix_exp,
    matrix_log,
    skew,
    unskew,
)

# unit directions with rational entries (Pythagorean quadruples) and axis directions
_DIRECTIONS = [
    (1, 0, 0),
    (0, -1, 0),
    (0, 0, 1),
    (sp.Rational(1, 3), sp.Rational(2, 3), sp.Rational(2, 3)),
    (sp.Rational(-2, 7), sp.Rational(3, 7), sp.Rational(6, 7)),
    (sp.Rational(3, 5), 0, sp.Rational(-4, 5)),
]
_POINTS = st.tuples(*[st.integers(-3, 3).map(sp.Integer)] * 3)
_ANGLES = st.sampled_from([sp.pi / 6, sp.pi / 4, sp.pi / 3, sp.pi / 2, 2 * sp.pi / 3, sp.pi / 12])


@st.composite
def screws(draw: st.DrawFn) -> ScrewAxis:
    """A revolute axis through a lattice point, or a prismatic axis."""
    w = draw(st.sampled_from(_DIRECTIONS))
    if draw(st.booleans()):
        return ScrewAxis.revolute(w, draw(_POINTS))
    return ScrewAxis.prismatic(w)


@st.composite
def motions(draw: st.DrawFn) -> sp.ImmutableMatrix:
    """An exact rigid transform: the exponential of a screw by an angle (or a length)."""
    return matrix_exp(draw(screws()), draw(_ANGLES))


def _same(A: sp.MatrixBase, B: sp.MatrixBase) -> bool:
    return all(is_zero(a - b) for a, b in zip(sp.Matrix(A), sp.Matrix(B)))


def test_skew_is_the_cross_product() -> None:
    a, b = sp.Matrix([1, -2, 5]), sp.Matrix([4, 0, 3])
    assert skew(a) * b == a.cross(b)
    assert unskew(skew(a)) == a


def test_revolute_axis_v_is_minus_omega_cross_q() -> None:
    # Lynch and Park, Example 3.26 style: axis along z through (0, 2, 0) -> v = (2, 0, 0)
    S = ScrewAxis.revolute((0, 0, 1), (0, 2, 0))
    assert S.vector.T.tolist() == [[0, 0, 1, 2, 0, 0]]
    assert S.point().T.tolist() == [[0, 2, 0]]
    assert S.is_revolute and not ScrewAxis.prismatic((1, 0, 0)).is_revolute


def test_axis_rules_are_enforced() -> None:
    with pytest.raises(DHError, match="unit omega"):
        ScrewAxis.revolute((1, 1, 0), (0, 0, 0))
    with pytest.raises(DHError, match="unit v"):
        ScrewAxis.prismatic((0, 0, 2))
    with pytest.raises(DHError, match="omega·v = 0"):
        ScrewAxis((0, 0, 1), (0, 0, 1)).check(revolute=True)
    with pytest.raises(DHError, match="six numbers"):
        ScrewAxis.from_vector([1, 2, 3])


def test_text_is_never_sympified() -> None:
    with pytest.raises(DHError):
        ScrewAxis.revolute((0, 0, 1), ("__import__('os')", 0, 0))


def test_exponential_of_a_z_rotation_is_the_elementary_rotation() -> None:
    t = sp.Symbol("t", real=True)
    assert matrix_exp(ScrewAxis.revolute((0, 0, 1), (0, 0, 0)), t) == Rz(t)
    assert matrix_exp(ScrewAxis.revolute((1, 0, 0), (0, 0, 0)), t) == Rx(t)
    assert matrix_exp(ScrewAxis.revolute((0, 1, 0), (0, 0, 0)), t) == Ry(t)
    assert matrix_exp(ScrewAxis.prismatic((0, 1, 0)), t) == Ty(t)


def test_exponential_about_an_offset_axis_is_a_conjugated_rotation() -> None:
    t = sp.Symbol("t", real=True)
    S = ScrewAxis.revolute((0, 0, 1), (2, 1, 0))
    assert prove_equal(matrix_exp(S, t), Tx(2) * Ty(1) * Rz(t) * Ty(-1) * Tx(-2))


def test_exponential_of_a_non_unit_twist_rescales() -> None:
    t = sp.Symbol("t", real=True)
    assert prove_equal(matrix_exp([0, 0, 3, 0, 0, 0], t), Rz(3 * t))


def test_bracket_and_exponential_series_agree() -> None:
    # e^{[S]t} = I + [S]t + ... : its derivative at t = 0 is [S]
    t = sp.Symbol("t", real=True)
    for w in _DIRECTIONS:
        S = ScrewAxis.revolute(w, (1, -2, 3))
        d = sp.Matrix(matrix_exp(S, t)).diff(t).subs(t, 0)
        assert d == bracket(S)


def test_log_special_cases() -> None:
    L = matrix_log(sp.eye(4))
    assert L.theta == 0 and L.twist == sp.zeros(6, 1)
    L = matrix_log(Tx(3) * Ty(4))
    assert L.theta == 5 and L.screw.v.T.tolist() == [[sp.Rational(3, 5), sp.Rational(4, 5), 0]]
    for R in (Rx(sp.pi), Ry(sp.pi), Rz(sp.pi)):
        L = matrix_log(R * Tz(1))
        assert L.theta == sp.pi
        assert _same(matrix_exp(L.screw, L.theta), R * Tz(1))
    with pytest.raises(DHError, match="4×4"):
        matrix_log(sp.eye(3))


def test_log_of_a_general_rotation_by_pi() -> None:
    S = ScrewAxis.revolute(_DIRECTIONS[3], (1, 0, 2))
    T = matrix_exp(S, sp.pi)
    L = matrix_log(T)
    assert L.theta == sp.pi
    assert _same(matrix_exp(L.screw, L.theta), T)


@settings(max_examples=25, deadline=None)
@given(motions())
def test_exp_of_log_is_the_identity(T: sp.ImmutableMatrix) -> None:
    L = matrix_log(T)
    L.screw.check() if L.theta != 0 else None
    assert _same(matrix_exp(L.screw, L.theta), T)


@settings(max_examples=25, deadline=None)
@given(motions(), motions())
def test_adjoint_of_a_product_is_the_product_of_adjoints(
    T1: sp.ImmutableMatrix, T2: sp.ImmutableMatrix
) -> None:
    assert _same(adjoint(T1 * T2), adjoint(T1) * adjoint(T2))


@settings(max_examples=25, deadline=None)
@given(motions())
def test_adjoint_of_the_inverse_is_the_inverse_of_the_adjoint(T: sp.ImmutableMatrix) -> None:
    assert _same(adjoint(rigid_inverse(T)) * adjoint(T), sp.eye(6))


@settings(max_examples=25, deadline=None)
@given(screws(), motions())
def test_adjoint_carries_the_bracket(S: ScrewAxis, T: sp.ImmutableMatrix) -> None:
    # [Ad_T S] = T [S] T^-1
    carried = ScrewAxis.from_vector(adjoint(T) * S.vector)
    assert _same(bracket(carried), T * bracket(S) * rigid_inverse(T))


@settings(max_examples=20, deadline=None)
@given(screws())
def test_exponentials_of_one_axis_add_their_angles(S: ScrewAxis) -> None:
    t1, t2 = sp.symbols("t1 t2", real=True)
    assert prove_equal(matrix_exp(S, t1) * matrix_exp(S, t2), matrix_exp(S, t1 + t2))
    assert prove_equal(matrix_exp(S, t1) * matrix_exp(S, -t1), sp.eye(4))


def test_exponential_prints_in_lecture_notation() -> None:
    t = sp.Symbol("theta2", real=True)
    E = Exponential.of(ScrewAxis.revolute((0, 0, 1), (1, 0, 0)), t, 2, letter="B")
    assert sp.latex(E) == r"e^{[\mathcal{B}_{2}]\theta_{2}}"
    assert str(E) == "e^([B2]*theta2)"
    text = E.notation.text(E.matrix)
    assert "C2" in text and "S2" in text and "cos" not in text
    assert E._repr_latex_().startswith(r"$$e^{[\mathcal{B}_{2}]\theta_{2}} = \begin{bmatrix}C_{2}")
