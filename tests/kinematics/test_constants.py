"""Exact constants as floats: safe for huge integers, nested roots and multiples of π."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.kinematics.constants import to_float


def test_to_float_is_safe_for_huge_integers_nested_roots_and_pi():
    big = sp.Integer(10) ** 30 + 7
    assert to_float(sp.sqrt(big**2 + 1) / big) == 1.0
    assert to_float(sp.sqrt(2 + sp.sqrt(3)) - (sp.sqrt(6) + sp.sqrt(2)) / 2) == pytest.approx(0)
    assert to_float(sp.Rational(2**70 + 1, 2**70)) == 1.0
    assert to_float(sp.pi / 2) == np.pi / 2
    with pytest.raises(dhsym.DHError, match="too large"):
        to_float(sp.Integer(10) ** 400)
    with pytest.raises(dhsym.DHError, match="not a real number"):
        to_float(sp.sqrt(-2))
    with pytest.raises(dhsym.DHError, match="no numeric value for x"):
        to_float(sp.Symbol("x") + 1)


def test_rational_multiples_of_pi_round_as_the_30_digit_value():
    rng = np.random.default_rng(7)
    for p, q in rng.integers(1, 721, size=(200, 2)):
        e = sp.Rational(int(p) - 360, int(q)) * sp.pi
        assert to_float(e) == float(sp.N(e, 30)), e
