"""Numeric comparison at random points, then exact proof under limits."""

from __future__ import annotations

import numpy as np
import sympy as sp

from dhsym.checking.equivalence import Sample, close, has_decimals, prove_entry, values

x, y = sp.symbols("x y", real=True)


def test_values_and_close():
    s = Sample.random([x, y], size=16)
    assert close(values(sp.sin(x) ** 2 + sp.cos(x) ** 2, s), np.ones(16))
    assert not close(values(sp.sin(x), s), values(sp.cos(x), s))
    M = values(sp.Matrix([[x, y]]), s)
    assert M.shape == (16, 1, 2)
    assert not close(values(sp.zoo, s), np.ones(16))  # non-finite is never equal


def test_sample_fixed_and_extended():
    s = Sample.random([x, y], fixed={y: 0.5})
    assert (s.env[y] == 0.5).all()
    z = sp.Symbol("z")
    assert z in s.extended([z]).env and s.extended([x]) is s


def test_prove_entry_exact_false_and_skipped():
    assert prove_entry(sp.cos(x + y), sp.cos(x) * sp.cos(y) - sp.sin(x) * sp.sin(y)) is True
    assert prove_entry(sp.cos(x), sp.cos(x) + sp.Rational(1, 10**30)) is False
    huge = (sp.cos(x) ** 2 + sp.sin(x) ** 2 + sp.cos(y) ** 2 + sp.sin(y) ** 2 - 1) ** 60
    assert prove_entry(huge, sp.Integer(1)) is None  # too large to expand: numbers decide
    assert prove_entry(sp.tan(x) * sp.cos(x), sp.sin(x)) is None  # not a trig polynomial


def test_has_decimals():
    assert has_decimals(sp.Rational(7071, 10000) * x) and not has_decimals(x / 3)
