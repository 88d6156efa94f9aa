"""LaTeX math reader: translation to whitelist-parser text, matrices, refusals."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from dhsym.checking.reading.latex_input import (
    flatten_subscripts,
    is_latex,
    latex_matrix_cells,
    latex_to_text,
)
from dhsym.errors import ParseError
from dhsym.model.parsing import parse_expression

SEED002 = Path(__file__).resolve().parents[2] / "data" / "seeds" / "002_8d4894e47f2048cf.txt"
t = sp.Symbol("theta_1", real=True)


@pytest.mark.parametrize(
    ("src", "text"),
    [
        (r"\cos\theta_1", "cos(theta_1)"),
        (r"\cos(\theta_1 + \theta_2)", "cos(theta_1 + theta_2)"),
        (r"C_{12}", "C_12"),
        (r"\alpha_{i-1}", "alpha_im1"),
        (r"\frac{\pi}{2}", "((pi)/(2))"),
        (r"\left( a_1 + a_2 \right) \cdot C_1", "(a_1 + a_2) * C_1"),
        (r"a^{2}", "a^(2)"),
        (r"\cos^2\theta", "cos(theta)^(2)"),
        (r"90^\circ", "90°"),
        (r"\mathbf{p}_x = d_3", "d_3"),
        (r"\sqrt{2}", "sqrt(2)"),
        (r"\Theta_1", "theta_1"),
    ],
)
def test_translation(src, text):
    assert latex_to_text(src) == text


def test_translated_text_parses_to_the_right_expression():
    e = parse_expression(latex_to_text(r"\cos(\theta_1 + \frac{\pi}{2})"))
    assert e == -sp.sin(t)


@pytest.mark.parametrize(
    "src",
    [
        r"\input{/etc/passwd}",
        r"\write18{rm -rf /}",
        r"\def\x{1}",
        r"\cos",
        r"\frac{1}",
        r"(a",
        r"\left| x \right|",
        r"x_",
    ],
)
def test_refused_latex_raises_parse_error(src):
    with pytest.raises(ParseError):
        latex_to_text(src)


def test_matrix_cells_take_the_last_matrix_and_skip_the_trailing_row_break():
    src = (
        r"T = \begin{bmatrix} n & s \end{bmatrix} = \begin{pmatrix} 1 & 2 \\ 3 & 4 \\ \end{pmatrix}"
    )
    assert latex_matrix_cells(src) == [["1", "2"], ["3", "4"]]
    assert latex_matrix_cells("no matrix here") is None


def test_seed_002_slide_reads_as_a_4x4_matrix():
    line = SEED002.read_text(encoding="utf-8").splitlines()[166]
    cells = latex_matrix_cells(line)
    assert [len(r) for r in cells] == [4, 4, 4, 4]
    assert latex_to_text(cells[1][3]) == "d_i sin(alpha_im1)"


def test_helpers():
    assert is_latex(r"\theta") and is_latex("$x$") and not is_latex("cos(x)")
    assert flatten_subscripts("alpha_{i-1} + a_{i+1} + C_{1,2}") == "alpha_im1 + a_ip1 + C_12"


@pytest.mark.parametrize(
    "src",
    [
        r"\sin 90°",
        r"\sin 90^\circ",
        r"\sin 90^{\circ}",
        r"\sin 90\degree",
        r"\sin 90\textdegree",
        r"\sin(90^o)",
        r"\sin(90^{o})",
        r"\sin(90\,^{\circ})",
        r"\sin\frac{\pi}{2}",
        r"\sin\tfrac{\pi}{2}",
        r"\sin\dfrac\pi2",
        r"\sin{\tfrac{\pi}{2}}",
        r"\sin\bigl(\tfrac{\pi}{2}\bigr)",
    ],
)
def test_degree_signs_and_fractions_as_function_arguments(src):
    assert parse_expression(latex_to_text(src), textbook=True) == 1


def test_degrees_only_where_written():
    assert parse_expression(latex_to_text(r"\sin 90"), textbook=True) == sp.sin(90)
    text = latex_to_text(r"\frac{x}{90^\circ}")
    assert parse_expression(text, textbook=True) == 2 * sp.Symbol("x", real=True) / sp.pi
    assert latex_to_text(r"x^o") == "x^(o)"  # ^o is degrees after a number only


def test_craig_c_theta_and_powers_of_functions():
    assert latex_to_text(r"c\theta_1 s\alpha_{i-1}") == "c_theta_1 s_alpha_im1"
    assert latex_to_text(r"\cos(\theta_1)^2") == "cos(theta_1)^(2)"
    assert latex_to_text(r"\cos^2\frac{\theta}{2}") == "cos(((theta)/(2)))^(2)"
    assert latex_to_text(r"\sin^{-1}\theta") == "asin(theta)"  # the inverse function
    assert latex_to_text(r"\cos^{-1}(x)") == "acos(x)"
    assert latex_to_text(r"\operatorname{Atan2}(y, x)").startswith("atan2(")
    with pytest.raises(ParseError, match="inverse function"):
        latex_to_text(r"\sin^{-2}\theta")


def test_matrix_rows_with_spacing_and_left_right_brackets():
    src = r"\left[ \begin{matrix} 1 & 0 \\[2pt] 0 & 1 \end{matrix} \right]"
    assert latex_matrix_cells(src) == [["1", "0"], ["0", "1"]]


def test_inverse_functions_and_plus_minus_for_inverse_kinematics():
    assert latex_to_text(r"\operatorname{atan2}(p_y, p_x)") == "atan2(p_y , p_x)"
    assert latex_to_text(r"\arctan\frac{p_y}{p_x}") == "atan(((p_y)/(p_x)))"
    assert latex_to_text(r"\arccos x") == "acos(x)"
    assert latex_to_text(r"a \pm b \mp c") == "a ± b ∓ c"
    with pytest.raises(ParseError, match="unknown operator 'argh'"):
        latex_to_text(r"\operatorname{argh}(x)")
