"""Exact entries: the one formatter of exact decimals."""

from __future__ import annotations

from decimal import Decimal

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from dhsym.errors import TableError
from dhsym.model.entries import as_expr, exact_decimal
from dhsym.model.tablefile import dump_table, read_table_text


@given(st.decimals(min_value=-1000, max_value=1000, places=12, allow_nan=False))
def test_exact_decimal_prints_what_was_written(d):
    value = as_expr(format(d, "f"))
    printed = exact_decimal(value)
    assert printed is not None and as_expr(printed) == value and Decimal(printed) == d
    assert "." not in printed or not printed.endswith("0")  # the digits written, no more


def test_exact_decimal_refuses_what_is_no_finite_decimal():
    assert exact_decimal(sp.Rational(1, 3)) is None
    assert exact_decimal(sp.sqrt(2)) is None
    assert exact_decimal(sp.Symbol("a")) is None
    assert exact_decimal(sp.Rational(1, 2**30), max_digits=12) is None
    assert exact_decimal(sp.Integer(-7)) == "-7"
    assert exact_decimal(sp.Rational(-1, 20)) == "-0.05"


def test_yaml_keeps_decimals_as_written():
    text = (
        "joints: [{type: P, theta: 0, d: d1 + b, a: 0.4318, alpha: 0, q: d1}]\nvalues: {b: 0.3}\n"
    )
    t = read_table_text(text)
    out = dump_table(t)
    assert "a: 0.4318" in out and "b: 0.3" in out and "/" not in out
    long = read_table_text(text.replace("0.4318", "'0.12345678901234567891'"))  # > 17 digits
    out = dump_table(long)
    assert "0.12345678901234567891" in out and read_table_text(out) == long


def test_angle_bound_in_floats_gives_the_verdict_of_a_symbolic_evaluation():
    """check_radians compares rationals and rational multiples of pi in floats: the same
    verdict as ``abs(float(term)) > 2*pi + 1e-9`` (an evalf), also a hair from the bound."""
    import random

    from dhsym.model.entries import _TURN, _above_turn

    rng = random.Random(7)
    terms = [sp.pi, -2 * sp.pi, sp.Integer(10) ** 400, sp.Integer(10) ** 400 * sp.pi]
    for _ in range(2000):
        r = sp.Rational(rng.randint(-(10**12), 10**12), rng.randint(1, 10**11))
        near = sp.Rational(round(rng.uniform(_TURN - 1e-9, _TURN + 1e-9) * 10**15), 10**15)
        two = sp.Rational(round(rng.uniform(2 - 1e-9, 2 + 1e-9) * 10**15), 10**15)
        terms += [r, r * sp.pi, near, -near, two * sp.pi]
    assert [_above_turn(t) for t in terms] == [abs(float(t)) > _TURN for t in terms]
    assert any(_above_turn(t) for t in terms) and not all(_above_turn(t) for t in terms)


def test_a_rational_times_a_power_of_pi_is_accepted_without_evaluation():
    """pi**2/360 (a table in degrees read as radians) is kept as it is, as check_real
    would; pi**5 and sqrt(2)*pi still go through the checks (and pass)."""
    from dhsym.model.entries import _plainly_finite_real

    for e in (sp.pi**2 / 360, -3 * sp.pi**2, sp.pi**-2, sp.pi**5, sp.sqrt(2) * sp.pi):
        assert as_expr(e) == e
    assert _plainly_finite_real(sp.pi**2 / 360)
    assert not _plainly_finite_real(sp.I * sp.pi**2)
    with pytest.raises(TableError, match="complex"):
        as_expr(sp.I * sp.pi**2)
