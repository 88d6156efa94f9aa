"""Exact entries: the one formatter of exact decimals."""

from __future__ import annotations

from decimal import Decimal

import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

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
