"""Numeric literals as written: their significant digits and the unit of their last digit."""

from __future__ import annotations

import sympy as sp

from dhsym import load_table
from dhsym.checking.reading.answer_names import NameContext
from dhsym.checking.reading.answers import cell_literals
from dhsym.checking.reading.literals import Literal, decimal_places


def test_digits_and_unit_of_a_decimal_as_written():
    assert decimal_places("0.0203") == (3, 1e-4)
    assert decimal_places("1.50") == (3, 0.01)
    assert decimal_places("7.071e-1") == (4, 1e-4)
    assert decimal_places("12") == (0, 0.0)


def test_the_reader_keeps_each_decimal_as_written():
    ctx = NameContext.from_table(load_table("planar2r"))
    _, literals = cell_literals("0.7071*a1 + 1.50", ctx)
    assert [(x.text, x.digits) for x in literals] == [("0.7071", 4), ("1.50", 3)]
    assert all(isinstance(x, Literal) and isinstance(x.value, sp.Rational) for x in literals)
