"""The polynomial ring of sines and cosines: normal form, derivatives, what it refuses."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.simplification import prove_equal
from dhsym.kinematics.trig_ring import TrigRing, lecture_form

t1, t2, t3, d, a = sp.symbols("theta1 theta2 theta3 d a", real=True)
S, C = sp.sin, sp.cos


def ring(*exprs: sp.Expr) -> TrigRing:
    return TrigRing.of(exprs, (t1, t2, t3, d))


def test_pythagorean_relatives_vanish_in_the_normal_form():
    r = ring(S(t2 + t3), C(t2 + t3), S(t1), C(t1))
    e = a * C(t2 + t3) ** 2 * S(t1) ** 2 + a * S(t2 + t3) ** 2 * S(t1) ** 2 + a * C(t1) ** 2
    assert r.expr(r.reduce(r.poly(e))) == a


def test_the_normal_form_is_unique():
    r = ring(S(t1), C(t1), S(t2), C(t2))
    one = C(t1) ** 4 - S(t1) ** 4 + S(t2) ** 2
    other = 2 * C(t1) ** 2 - C(t2) ** 2
    assert r.reduce(r.poly(one)) == r.reduce(r.poly(other))
    assert r.reduce(r.poly(one)) != r.reduce(r.poly(other + S(t2)))


def test_derivatives_follow_the_chain_rule_on_sum_angles_and_prismatic_variables():
    e = a * S(t2 + t3) * C(t2) ** 2 + d**2 * C(t1) * S(t3)
    r = ring(e)
    for j, q in enumerate((t1, t2, t3, d)):
        assert prove_equal(sp.Matrix([r.expr(r.diff(r.poly(e), j))]), sp.Matrix([sp.diff(e, q)]))


def test_lecture_form_writes_a_cosine_pair_as_a_sine_square():
    r = ring(S(t2 + t3), C(t2 + t3), C(t1))
    p = r.reduce(r.poly(a * C(t1) * S(t2 + t3) ** 2))
    assert r.expr(p) == a * C(t1) - a * C(t1) * C(t2 + t3) ** 2
    assert lecture_form(r, p) == a * C(t1) * S(t2 + t3) ** 2


def test_angles_must_be_linear_in_the_joint_variables():
    with pytest.raises(DHError, match="not linear"):
        ring(C(t1 * t2))
    r = ring(C(t1))
    with pytest.raises(DHError, match="not a polynomial"):
        r.poly(C(2 * t2))
