"""Cubic and quintic profiles: exact boundary conditions, the lecture's coefficients, and
numbers recorded from roboticstoolbox 1.5.0 (``quintic``, ``jtraj``) and modern_robotics
1.1 (``CubicTimeScaling``, ``QuinticTimeScaling``), no runtime dependency on either."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from dhsym.errors import DHError
from dhsym.trajectory import cubic, quintic
from dhsym.trajectory.profiles import TIME, polynomial_segment

T7 = np.linspace(0, 2, 7)

# roboticstoolbox.quintic(1, 3, linspace(0, 2, 7))
RTB_QUINTIC = (
    [
        1.0,
        1.0709876543209875,
        1.4197530864197527,
        1.9999999999999991,
        2.580246913580246,
        2.9290123456790136,
        3.0,
    ],
    [
        0.0,
        0.578703703703703,
        1.48148148148148,
        1.8749999999999982,
        1.4814814814814792,
        0.5787037037037028,
        0.0,
    ],
    [
        0.0,
        2.777777777777775,
        2.2222222222222188,
        0.0,
        -2.2222222222222188,
        -2.7777777777777737,
        0.0,
    ],
)
# roboticstoolbox.quintic(1, 3, linspace(0, 2, 7), qd0=0.5, qdf=-0.25)
RTB_QUINTIC_V = (
    [
        1.0,
        1.2224151234567902,
        1.6543209876543206,
        2.234374999999999,
        2.7530864197530853,
        3.0148533950617264,
        2.9999999999999982,
    ],
    [
        0.5,
        0.9508101851851848,
        1.6018518518518507,
        1.7656249999999991,
        1.2407407407407396,
        0.3119212962962947,
        -0.25,
    ],
    [
        0.0,
        2.118055555555554,
        1.444444444444444,
        -0.5624999999999982,
        -2.444444444444443,
        -2.743055555555553,
        3.552713678800501e-15,
    ],
)
# modern_robotics.CubicTimeScaling(2, t), QuinticTimeScaling(2, t) at linspace(0, 2, 7)
MR_CUBIC = [
    0.0,
    0.07407407407407407,
    0.25925925925925924,
    0.5,
    0.7407407407407408,
    0.925925925925926,
    1.0,
]
MR_QUINTIC = [
    0.0,
    0.03549382716049382,
    0.2098765432098765,
    0.5,
    0.7901234567901232,
    0.9645061728395059,
    1.0,
]


def test_quintic_symbolic_lecture_coefficients() -> None:
    q0, qf, tf = sp.symbols("q0 qf tf", positive=True)
    a = quintic(q0, qf, tf).coefficients
    assert a[:3] == (q0, 0, 0)
    assert sp.simplify(a[3] - 10 * (qf - q0) / tf**3) == 0
    assert sp.simplify(a[4] + 15 * (qf - q0) / tf**4) == 0
    assert sp.simplify(a[5] - 6 * (qf - q0) / tf**5) == 0
    assert str(a[3]) == "10*(-q0 + qf)/tf**3"


def test_cubic_symbolic_lecture_coefficients() -> None:
    q0, qf, tf, v0, vf = sp.symbols("q0 qf tf v0 vf", real=True)
    a = cubic(q0, qf, tf, v0, vf).coefficients
    assert sp.simplify(a[2] - (3 * (qf - q0) / tf**2 - (2 * v0 + vf) / tf)) == 0
    assert sp.simplify(a[3] - (-2 * (qf - q0) / tf**3 + (v0 + vf) / tf**2)) == 0
    assert str(cubic(q0, qf, tf).coefficients[2]) == "3*(-q0 + qf)/tf**2"


@pytest.mark.parametrize("make", [cubic, quintic])
def test_boundary_conditions_hold_exactly(make) -> None:  # type: ignore[no-untyped-def]
    syms = sp.symbols("q0 qf tf v0 vf a0 af", real=True)
    nargs = 5 if make is cubic else 7
    p = make(*syms[:nargs])
    q = p.expression()
    q0, qf, tf, v0, vf, a0, af = syms
    ends = [(q, 0, q0), (q, tf, qf), (q.diff(TIME), 0, v0), (q.diff(TIME), tf, vf)]
    if make is quintic:
        ends += [(q.diff(TIME, 2), 0, a0), (q.diff(TIME, 2), tf, af)]
    for expr, at, want in ends:
        assert sp.simplify(expr.subs(TIME, at) - want) == 0
    assert p.derivation().check()


def test_quintic_equals_roboticstoolbox() -> None:
    q, qd, qdd = quintic(1, 3, 2).sample(T7)
    np.testing.assert_allclose(q, RTB_QUINTIC[0], atol=1e-12)
    np.testing.assert_allclose(qd, RTB_QUINTIC[1], atol=1e-12)
    np.testing.assert_allclose(qdd, RTB_QUINTIC[2], atol=1e-12)
    q, qd, qdd = quintic(1, 3, 2, v0=0.5, vf=-0.25).sample(T7)
    for got, want in zip((q, qd, qdd), RTB_QUINTIC_V):
        np.testing.assert_allclose(got, want, atol=1e-12)


def test_time_scalings_equal_modern_robotics() -> None:
    np.testing.assert_allclose(cubic(0, 1, 2).sample(T7)[0], MR_CUBIC, atol=1e-15)
    np.testing.assert_allclose(quintic(0, 1, 2).sample(T7)[0], MR_QUINTIC, atol=1e-15)


def test_symbolic_profile_samples_with_values() -> None:
    q0, qf, tf = sp.symbols("q0 qf tf", positive=True)
    p = quintic(q0, qf, tf)
    q, _, _ = p.sample(T7, values={"q0": 1, "qf": 3, "tf": 2})
    np.testing.assert_allclose(q, RTB_QUINTIC[0], atol=1e-12)
    with pytest.raises(DHError, match="no numeric value for q0, qf, tf"):
        p.sample(T7)


def test_vectors_one_profile_per_joint() -> None:
    p = quintic([0, 1, -0.5], [1, -1, 0.5], 3)
    assert not p.scalar and p.n == 3
    q, qd, _ = p.sample(np.linspace(0, 3, 5))
    assert q.shape == (5, 3)
    np.testing.assert_allclose(q[1], [0.103515625, 0.79296875, -0.396484375], atol=1e-15)
    np.testing.assert_allclose(qd[2], [0.625, -1.25, 0.625], atol=1e-15)


def test_exact_decimals_and_positions() -> None:
    p = cubic(0.1, 0.3, 2)
    assert p.coefficients[0] == sp.Rational(1, 10)
    assert p.at(1) == (sp.Rational(1, 5),)


def test_bad_inputs_are_named() -> None:
    with pytest.raises(DHError, match="tf: a duration must be positive"):
        cubic(0, 1, 0)
    with pytest.raises(DHError, match="qf: 2 joint values where the others have 3"):
        quintic([0, 0, 0], [1, 1], 1)
    with pytest.raises(DHError, match="field q0"):
        cubic("__import__('os')", 1, 1)
    with pytest.raises(DHError, match="times outside"):
        cubic(0, 1, 1).sample([-0.5])


def test_polynomial_segment_is_the_least_degree_interpolant() -> None:
    seg, d = polynomial_segment(sp.Integer(2), sp.Integer(1), [1, 0], [2])
    assert len(seg.coefficients) == 3 and d.check()
    assert seg.position(sp.Integer(3)) == 2


def test_derivation_prints_through_sympy() -> None:
    d = quintic(*sp.symbols("q_0 q_f t_f", positive=True)).derivation()
    text = sp.latex(d)
    assert text.startswith(r"\begin{aligned}a_{0} &= q_{0}")
    assert r"a_{3} &= \frac{10 \left(- q_{0} + q_{f}\right)}{t_{f}^{3}}" in text
    assert "a3 = 10*(-q_0 + q_f)/t_f**3" in str(d)
    assert d._repr_latex_().startswith("$\\displaystyle")


def test_a_joint_that_ends_early_rests() -> None:
    from dhsym.trajectory import lspb

    p = lspb([0, 0], [1, 2], 2)
    q, qd, qdd = p.sample([2.0])
    np.testing.assert_allclose(q, [[1.0, 2.0]], atol=1e-15)
    np.testing.assert_allclose(qd, [[0.0, 0.0]], atol=1e-15)
