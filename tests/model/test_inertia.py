"""Inertial parameters in rows and table files: reading, checking, writing back."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.errors import DHError, TableError
from dhsym.model.inertia import LinkInertia
from dhsym.model.tablefile import dump_table, read_table_text

ROW = "{type: R, theta: q1, d: 0, a: l1, alpha: 0, %s}"


def table(extra: str, top: str = ""):
    return read_table_text(f"{top}\njoints: [{ROW % extra}]", file="arm.yaml")


def test_values_are_exact_and_expressions_go_through_the_parser():
    t = table(
        "m: m1, r: [lc1 - l1, 0, 0], I: [0.1, 0.2, 0.25, 0, 0, 0.01], Tc: 0.4",
        "gravity: [0, -g, 0]",
    )
    L = t.rows[0].inertia
    assert L.r[0] == sp.Symbol("lc1", real=True) - sp.Symbol("l1", real=True)
    assert L.I[0, 2] == L.I[2, 0] == sp.Rational(1, 100)
    assert L.Tc == (sp.Rational(2, 5), -sp.Rational(2, 5))
    assert t.gravity == (0, -sp.Symbol("g", real=True), 0)


def test_three_by_three_inertia_and_default_gravity():
    t = table("m: 1, I: [[1, 0, 0], [0, 1, 0], [0, 0, 1.5]]")
    assert t.rows[0].inertia.I == sp.diag(1, 1, sp.Rational(3, 2))
    assert t.gravity == (0, 0, sp.Rational(-981, 100))


@pytest.mark.parametrize(
    ("extra", "field", "words"),
    [
        ("m: -2", "m", "negative"),
        ("m: 1, I: [1, 1, -1]", "I", "semi-definite"),
        ("m: 1, I: [1, 1, 3]", "I", "triangle"),
        ("m: 1, I: [[1, 0.2, 0], [0, 1, 0], [0, 0, 1]]", "I", "not symmetric"),
        ("m: 1, r: [1, 2]", "r", "3 values"),
        ("m: 1, I: [1, 2, 3, 4]", "I", "6 values"),
        ("m: 1, Tc: [1, 2, 3]", "Tc", "2 values"),
        ("m: __import__('os')", "m", ""),
    ],
)
def test_bad_values_name_file_row_and_field(extra, field, words):
    with pytest.raises(DHError) as err:  # a TableError, or the parser's ParseError
        table(extra)
    assert err.value.file == "arm.yaml" and err.value.row == 1 and err.value.field == field
    assert words in str(err.value)


def test_unknown_key_is_refused():
    with pytest.raises(TableError, match="unknown column 'mass'"):
        table("mass: 2")


def test_published_data_that_breaks_the_triangle_inequality():
    t = table("m: 1, I: [1, 1, 3]", "physical: false")
    assert not t.physical and t.rows[0].inertia.I[2, 2] == 3
    with pytest.raises(TableError, match="semi-definite"):
        table("m: 1, I: [1, 1, -3]", "physical: false")


def test_writing_a_table_back_keeps_the_inertial_parameters():
    t = table(
        "m: 17.4, r: [-0.3638, 0.006, lc2], I: [0.13, 0.524, 0.539, 0, 0, 0], Jm: 200e-6, "
        "G: -62.6111, B: 1.48e-3, Tc: [0.395, -0.435]",
        "gravity: [0, -g, 0]",
    )
    text = dump_table(t)
    assert "m: 17.4" in text and "Jm: 0.0002" in text and "gravity: [0, -g, 0]" in text
    assert read_table_text(text) == t


def test_puma560_carries_the_published_parameters():
    from dhsym.model.library import builtin_table

    t = builtin_table("puma560")
    assert [r.inertia.m for r in t.rows] == [
        0,
        sp.Rational(87, 5),
        sp.Rational(24, 5),
        sp.Rational(41, 50),
        sp.Rational(17, 50),
        sp.Rational(9, 100),
    ]
    assert read_table_text(dump_table(t)) == t


def test_textbook_set_and_substitution():
    L = LinkInertia.textbook(3)
    assert L.m == sp.Symbol("m3", real=True) and L.I.is_symmetric()
    num = L.subs({s: 1 for s in L.free_symbols})
    assert num.m == 1 and num.I[0, 1] == 1
