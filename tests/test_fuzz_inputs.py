"""Fuzz: text for the parser, the LaTeX reader and the table loaders is answered or refused
within a second.  A fixed budget (``max_examples`` per test, a 1 s ``deadline`` per input)
so that it runs in CI; the inputs mix numerals with huge exponents, LaTeX, Unicode and
names the checker resolves."""

from __future__ import annotations

from datetime import timedelta

import sympy as sp
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dhsym import load_table
from dhsym.checking.reading.answer_names import NameContext
from dhsym.checking.reading.answers import normalize_unicode, read_answer_table
from dhsym.checking.reading.latex_input import latex_to_text
from dhsym.errors import DHError
from dhsym.model.parsing import parse_expression
from dhsym.model.table import DHTable
from dhsym.model.tablefile import read_table_text

BUDGET = settings(
    max_examples=150,
    deadline=timedelta(seconds=1),
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
CTX = NameContext.from_table(load_table("puma560"))

NUMERALS = st.from_regex(r"[0-9]{0,3}(\.[0-9]{0,3})?([eE][+-]?[0-9]{1,14})?", fullmatch=True)
PIECES = [
    *"0123456789.eE+-*/^(),_ {}[]&°",
    "**",
    "sin",
    "cos",
    "tan",
    "sqrt",
    "atan2",
    "pi",
    "π",
    "θ1",
    "θ₁",
    "²",
    "−",
    "·",
    "×",
    "theta1",
    "a2",
    "d3",
    "C12",
    "c_1",
    "s_{23}",
    "a_1c_1",
    "lc1",
    "q1",
    "^o",
    "^{-1}",
    r"\frac",
    r"\tfrac",
    r"\sin",
    r"\cos",
    r"\theta",
    r"\alpha_{i-1}",
    r"^\circ",
    r"^{\circ}",
    r"\degree",
    r"\left(",
    r"\right)",
    r"\cdot",
    r"\sqrt",
    r"\\",
    r"\begin{bmatrix}",
    r"\end{bmatrix}",
    r"\mathrm{C}_{12}",
    r"\,",
    "$",
    "=",
    "\x00",
    "√",
    "½",
    # issue 25: the spellings of textbooks and numpy, and the campaign's hostile pieces
    "Atan2",
    "arctan2",
    "acos",
    "arccos",
    "^-1",
    r"\cos^{-1}",
    r"\operatorname{Atan2}",
    "0*100.0",
    "100.1 - 100.0",
    "10^13",
    ":30",
]
TEXT = st.one_of(
    st.text(max_size=60),
    st.lists(st.one_of(st.sampled_from(PIECES), NUMERALS), max_size=40).map("".join),
)


@BUDGET
@given(TEXT, st.booleans())
def test_parser_answers_or_refuses(text, textbook):
    try:
        assert isinstance(parse_expression(text, textbook=textbook, resolve=CTX.resolve), sp.Expr)
    except DHError as err:
        assert "\n" not in str(err)


@BUDGET
@given(TEXT)
def test_latex_reader_answers_or_refuses(text):
    try:
        parsed = parse_expression(
            latex_to_text(normalize_unicode(text)), textbook=True, resolve=CTX.resolve
        )
        assert isinstance(parsed, sp.Expr)
    except DHError as err:
        assert str(err)


CELL = st.one_of(NUMERALS, st.lists(st.sampled_from(PIECES), max_size=8).map("".join))


@BUDGET
@given(st.lists(st.tuples(CELL, CELL, CELL, CELL), min_size=1, max_size=4))
def test_table_file_loader_answers_or_refuses(rows):
    joints = [{"type": "R", "theta": t, "d": d, "a": a, "alpha": al} for t, d, a, al in rows]
    try:
        assert isinstance(read_table_text(yaml.safe_dump({"joints": joints})), DHTable)
    except DHError as err:
        assert str(err)


@BUDGET
@given(st.one_of(st.text(max_size=200), st.lists(CELL, max_size=30).map(" ".join)))
def test_table_file_loader_on_any_text(text):
    try:
        read_table_text("joints:\n  - {type: R, theta: q1, d: 0, a: 1, alpha: 0}\n" + text)
    except DHError as err:
        assert str(err)


@BUDGET
@given(st.lists(st.tuples(CELL, CELL, CELL, CELL), min_size=1, max_size=4))
def test_pasted_table_reader_answers_or_refuses(rows):
    text = "| θ | d | a | α |\n|---|---|---|---|\n" + "\n".join(
        "| " + " | ".join(c.replace("|", " ").replace("\n", " ") for c in row) + " |"
        for row in rows
    )
    try:
        assert isinstance(read_answer_table(text, CTX), DHTable)
    except DHError as err:
        assert str(err)
