"""Formula layout: line breaking that follows the nesting, in LaTeX and text."""

from __future__ import annotations

import re

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings

import dhsym
from dhsym.notation.layout import (
    LATEX_WIDTH,
    TEXT_WIDTH,
    Math,
    as_decimal,
    equation,
    fill,
    math_width,
    pieces,
)
from dhsym.notation.printers import Notation

from ..strategies import dh_tables

S = lambda n: sp.Symbol(n, real=True)  # noqa: E731
ANCHOR = math_width("{}={}")


def _unindent(line: str, latex: bool) -> str:
    """A line without its indent and the ``{}`` that makes its sign binary."""
    if not latex:
        return line.strip()
    while True:
        if line.startswith(r"\quad "):
            line = line[len(r"\quad ") :]
        elif line.startswith(r"\phantom{"):
            depth, k = 0, len(r"\phantom")
            while True:  # to the end of the balanced group (\{ is a brace, not a group)
                if line[k] == "\\":
                    k += 2
                    continue
                depth += {"{": 1, "}": -1}.get(line[k], 0)
                k += 1
                if depth == 0:
                    break
            line = line[k:]
        else:
            return line[2:] if line.startswith("{}") else line


def _joined(lines: list[str], latex: bool) -> str:
    out = " ".join(_unindent(x, latex) for x in lines)
    return re.sub(r"\\(Big[lr]|left|right)", "", out).replace(" ", "")


def test_px_breaks_inside_its_bracket_under_the_bracket():
    r = dhsym.load("puma560_modified")
    px = r.arm_matrix().matrix[0, 3]
    ps = pieces(px, r.notation)
    assert fill(ps, 21, latex=False) == [
        "C1*(a2*C2 + a3*C23",
        "    - d4*S23) - d3*S1",
    ]
    assert fill(ps, 18, latex=True) == [
        r"C_{1}(a_{2} C_{2} + a_{3} C_{23}",
        r"\phantom{{}={}C_{1}(}{}- d_{4} S_{23}) - d_{3} S_{1}",
    ]


def test_the_outermost_sum_breaks_first():
    r = dhsym.load("puma560_modified")
    r11 = r.arm_matrix().matrix[0, 0]
    lines = fill(pieces(r11, r.notation), 48, latex=False)
    assert lines == [
        "C1*(C23*(C4*C5*C6 - S4*S6) - S23*S5*C6)",
        "  + S1*(S4*C5*C6 + C4*S6)",
    ]
    latex = fill(pieces(r11, r.notation), 40, latex=True)
    assert latex[1] == r"\quad {}+ S_{1}(S_{4} C_{5} C_{6} + C_{4} S_{6})"


def test_nested_continuations_are_indented_under_their_own_bracket():
    r = dhsym.load("stanford", compact=False)
    r12 = r.arm_matrix().matrix[0, 1]
    lines = fill(pieces(r12, r.notation), TEXT_WIDTH - 12, latex=False)
    assert lines == [
        "cos(theta1)*(sin(theta2)*sin(theta5)*sin(theta6)",
        "             - cos(theta2)*(cos(theta4)*cos(theta5)*sin(theta6)",
        "                            + sin(theta4)*cos(theta6)))",
        "  - sin(theta1)*(cos(theta4)*cos(theta6) - sin(theta4)*cos(theta5)*sin(theta6))",
    ]
    # each continuation starts right under the character after its bracket
    assert lines[1].index("-") == lines[0].index("*(") + 2
    assert lines[2].index("+") == lines[1].index("*(") + 2


def test_a_tall_bracket_that_spans_lines_uses_fixed_size_delimiters():
    t1, t2 = S("theta1"), S("theta2")
    nota = Notation.from_variables([t1, t2])
    e = sp.cos(t1) * (sum(S(f"a{k}") * sp.sqrt(k) / 2 for k in (2, 3, 5, 6, 7)) + sp.sin(t2))
    lines = fill(pieces(e, nota), 20, latex=True)
    assert len(lines) > 1 and lines[0].startswith(r"C_{1}\Bigl(")
    assert lines[-1].endswith(r"\Bigr)") and r"\left(" not in "".join(lines)
    assert nota.latex(e).startswith(r"C_{1}\left(")  # on one line: \left( … \right)


def test_equation_splits_only_what_is_too_wide():
    r = dhsym.load("puma560_modified")
    px = r.arm_matrix().matrix[0, 3]
    whole = Math(r.notation.latex(px), r.notation.text(px))
    name = Math("p_{x}", "p_x")
    assert equation(name, px, whole, r.notation, LATEX_WIDTH).latex_lines == (whole.latex,)
    assert len(equation(name, px, whole, r.notation, 20).latex_lines) == 2


def test_math_width_of_indents_and_delimiters():
    assert math_width(r"\phantom{C_{1}}") == math_width("C_{1}")
    assert math_width(r"\quad") == 2
    assert math_width(r"\Bigl[x\Bigr]") == math_width("[x]")
    assert math_width(r"\{x\}") == math_width("(x)")


def test_decimals_come_from_the_one_formatter():
    assert as_decimal(sp.Rational(3001, 20000), Notation()).text == "0.15005"
    assert as_decimal(sp.Rational(1, 3), Notation()).latex == r"\frac{1}{3}"


@pytest.mark.parametrize("width", [18, 30])
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(table=dh_tables(max_rows=4))
def test_lines_rejoin_to_the_formula_each_continuation_led_by_its_sign(table, width):
    r = dhsym.Robot(table)
    for e in r.arm_matrix().matrix:
        ps = pieces(e, r.notation)
        for latex, one in ((True, r.notation.latex(e)), (False, r.notation.text(e))):
            lines = fill(ps, width, latex=latex)
            assert _joined(lines, latex) == re.sub(r"\\(left|right)", "", one).replace(" ", "")
            assert all(re.match(r"[-+] ", _unindent(x, latex)) for x in lines[1:]), lines


@pytest.mark.parametrize("name", [*dhsym.builtin_names(), "planar8r"])
@pytest.mark.parametrize("compact", [True, False])
def test_every_line_of_every_built_in_derivation_fits(name, compact):
    from dhsym.explain.derivation import derive

    d = derive(name, compact=compact)
    blocks = [*d.links, *(s.block for s in d.products), d.result]
    for e in (e for b in blocks for e in b.entries):
        assert math_width(e.latex_lines[0]) <= LATEX_WIDTH, e.latex_lines
        assert all(math_width(x) <= LATEX_WIDTH + ANCHOR for x in e.latex_lines[1:])
        assert all(len(x) <= TEXT_WIDTH - 12 for x in e.text_lines), e.text_lines
