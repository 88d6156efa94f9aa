"""LSPB and the minimum-time profile: the feasibility conditions, exact blend times and
numbers recorded from roboticstoolbox 1.5.0's ``trapezoidal`` (no runtime dependency)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from dhsym.errors import DHError
from dhsym.trajectory import lspb, minimum_time, trapezoidal

T7 = np.linspace(0, 2, 7)
# roboticstoolbox.trapezoidal(1, 3, linspace(0, 2, 7)): tblend 2/3
RTB_TRAP = (
    [1.0, 1.125, 1.5, 2.0, 2.5, 2.8749999999999996, 3.0],
    [0.0, 0.75, 1.5, 1.5, 1.5, 0.7500000000000004, 0.0],
    [2.25, 2.25, 2.25, 0.0, 0.0, -2.25, -2.25],
)
# roboticstoolbox.trapezoidal(1, 3, linspace(0, 2, 7), V=1.8): tblend 0.888…
RTB_TRAP_V = (
    [1.0, 1.1125, 1.45, 2.0, 2.55, 2.8875, 3.0],
    [0.0, 0.6749999999999999, 1.3499999999999999, 1.8, 1.35, 0.6750000000000003, 0.0],
    [2.025, 2.025, 2.025, 0.0, -2.025, -2.025, -2.025],
)


def test_trapezoidal_equals_roboticstoolbox() -> None:
    p = trapezoidal(1, 3, 2)
    assert p.derivation().pairs[0] == (sp.Symbol("t_b", real=True), sp.Rational(2, 3))
    for got, want in zip(p.sample(T7), RTB_TRAP):
        np.testing.assert_allclose(got, want, atol=1e-12)
    p = lspb(1, 3, 2, v=1.8)
    assert p.derivation().solution[0] == sp.Rational(8, 9)
    for got, want in zip(p.sample(T7), RTB_TRAP_V):
        np.testing.assert_allclose(got, want, atol=1e-12)


def test_given_acceleration_gives_the_smaller_root() -> None:
    p = lspb(0, 1, 2, a=2)
    tb, V = p.derivation().solution
    assert tb == 1 - sp.sqrt(2) / 2 and sp.simplify(V - 2 * tb) == 0
    assert p.derivation().check()
    q, qd, _ = p.sample([0.0, 1.0, 2.0])
    np.testing.assert_allclose(q, [0, 0.5, 1], atol=1e-15)
    # downwards: the same times, the signs turned
    q, qd, qdd = lspb(1, 0, 2, a=2).sample([0.1])
    np.testing.assert_allclose([q[0], qd[0], qdd[0]], [0.99, -0.2, -2], atol=1e-15)


def test_feasibility_conditions() -> None:
    with pytest.raises(DHError, match=r"V = 2 too large: needs \|V\| ≤ 2\|q_f − q_0\|/t_f = 1"):
        lspb(0, 1, 2, v=2)
    with pytest.raises(DHError, match="V = 1/4 too small"):
        lspb(0, 1, 2, v=0.25)
    with pytest.raises(DHError, match=r"a = 1/2 too small: needs \|a\| ≥ 4\|q_f − q_0\|/t_f² = 1"):
        lspb(0, 1, 2, a=0.5)
    with pytest.raises(DHError, match="not both"):
        lspb(0, 1, 2, v=1, a=1)
    # the limits themselves are feasible: a triangle, and a line at the mean velocity
    assert len(lspb(0, 1, 2, v=1).joints[0]) == 2
    assert lspb(0, 1, 2, v=sp.Rational(1, 2)).derivation().solution[0] == 0


def test_symbolic_blend_keeps_its_conditions() -> None:
    q0, qf, tf, V = sp.symbols("q0 qf tf V", positive=True)
    p = lspb(q0, qf, tf, v=V)
    tb = p.derivation().solution[0]
    assert sp.simplify(tb - (q0 - qf + V * tf) / V) == 0
    assert sp.Gt(qf, q0) in p.conditions and len(p.conditions) == 3
    assert p.derivation().check()


def test_minimum_time() -> None:
    p = minimum_time(0, 2, 1, 1)  # cruise: t_f = D/v + v/a
    assert p.duration == 3
    _, qd, qdd = p.sample(np.linspace(0, 3, 301))
    assert np.abs(qd).max() <= 1 + 1e-12 and np.abs(qdd).max() <= 1 + 1e-12
    p = minimum_time(0, 1, 2, 1)  # triangle: t_f = 2 sqrt(D/a)
    assert p.duration == 2
    p = minimum_time([0, 0], [1, 4], 1, 4)  # timed to the slowest joint
    assert p.duration == sp.Rational(17, 4)
    _, qd, qdd = p.sample(np.linspace(0, 4.25, 500))
    assert np.abs(qd).max() <= 1 + 1e-12 and np.abs(qdd).max() <= 4 + 1e-12
    with pytest.raises(DHError, match="vmax must be positive"):
        minimum_time(0, 1, -1, 1)
