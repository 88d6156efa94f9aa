"""Reading answers: text, expressions, matrices and tables in every notation."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from dhsym import load_table
from dhsym.checking import Key, check_answer
from dhsym.checking.comparing.verdict import Verdict
from dhsym.checking.reading.answer_names import NameContext
from dhsym.checking.reading.answers import (
    matrix_cells,
    read_answer_file,
    read_answer_table,
    read_expression,
    read_matrix,
    read_text,
)
from dhsym.checking.reading.limits import UnreadableAnswer
from dhsym.errors import DHError
from dhsym.model.table import Convention

SEEDS = Path(__file__).resolve().parents[2] / "data" / "seeds"
S = lambda n: sp.Symbol(n, real=True)  # noqa: E731
t1, t2, a1, a2 = S("theta1"), S("theta2"), S("a1"), S("a2")
P2 = NameContext.from_table(load_table("planar2r"))


@pytest.mark.parametrize(
    "text",
    [
        "a1*cos(theta1) + a2*cos(theta1 + theta2)",
        "a1*c1 + a2*C12",
        "a1 C1 + a2 C_{12}",
        r"p_x = a_1 \cos\theta_1 + a_2 \cos(\theta_1 + \theta_2)",
        "a_1·C1 + a_2·C12",
        r"$a_1 C_1 + a_2 C_{12}$",
        "a1*cos(q1) + a2*cos(q1 + q2)",
        "a1 C1 + a2 C12 = px",  # the answer first, its label last
        r"a_1 c_1 + a_2 c_{12} = p_x",
        "T0_2[0,3] = a1 C1 + a2 C12",
        "a1 C1 + a2 C12;",  # a MATLAB statement's end
        r"\(a_1 C_1 + a_2 C_{12}\)",  # MathJax's inline and display delimiters
        r"\[a_1 C_1 + a_2 C_{12}\]",
        "a1 c_1 + a2 c_{1+2}",  # the sum angle's subscript written as a sum
        r"a_1 C_{\theta_1} + a_2 C_{\theta_1+\theta_2}",
    ],
)
def test_expressions_in_every_notation(text):
    assert read_expression(text, P2) == a1 * sp.cos(t1) + a2 * sp.cos(t1 + t2)


@pytest.mark.parametrize(
    "text",
    [
        "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], "
        "[0, 0, 1, 0], [0, 0, 0, 1]]",
        "Matrix([[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]])",
        "C12, -S12, 0, a1*C1 + a2*C12\nS12, C12, 0, a1*S1 + a2*S12\n0, 0, 1, 0\n0, 0, 0, 1",
        "C12 & -S12 & 0 & a1 C1 + a2 C12 \\\\ S12 & C12 & 0 & a1 S1 + a2 S12 \\\\ 0&0&1&0",
        r"{}^0T_2 = \begin{bmatrix} C_{12} & -S_{12} & 0 & a_1 C_1 + a_2 C_{12} \\ "
        r"S_{12} & C_{12} &"
        r" 0 & a_1 S_1 + a_2 S_{12} \\ 0 & 0 & 1 & 0 \\ 0 & 0 & 0 & 1 \end{bmatrix}",
        "[C12, -S12, 0, a1*C1 + a2*C12; S12, C12, 0, a1*S1 + a2*S12; 0, 0, 1, 0; 0, 0, 0, 1]",
        "[C12, -S12, 0, a1*C1 + a2*C12; S12, C12, 0, a1*S1 + a2*S12; 0, 0, 1, 0; 0, 0, 0, 1]"
        " = T0_2",
        # as Python prints or builds it: numpy's array, a label before sympy's Matrix
        "np.array([[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]])",
        "T0_2 = sp.Matrix([[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12],"
        " [0, 0, 1, 0]])",
    ],
)
def test_matrices_in_every_notation(text):
    M = read_matrix(text, P2)
    assert M.shape == (4, 4)
    assert M[0, 3] == a1 * sp.cos(t1) + a2 * sp.cos(t1 + t2)
    assert M[3, :] == sp.ImmutableMatrix([[0, 0, 0, 1]])


def test_numeric_rows_split_on_spaces():
    cells = matrix_cells("1 0 0 0.4521\n0 1 0 -0.15\n0 0 1 0.4318\n0 0 0 1")
    assert cells[1] == ["0", "1", "0", "-0.15"]


@pytest.mark.parametrize("text", ["C1 -S1", "[[1, 2], [3, 4]]", "1, 2, 3\n4, 5, 6\n7, 8, 9"])
def test_wrong_shapes_are_unreadable(text):
    with pytest.raises(UnreadableAnswer, match="4×4"):
        read_matrix(text, P2)


def _seed_table(seed: str, start: str, rows: int) -> str:
    lines = (SEEDS / seed).read_text(encoding="utf-8").splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith(start))
    return "\n".join(lines[k : k + rows + 1])


@pytest.mark.parametrize(
    ("robot", "start", "rows"),
    [
        ("example1_rrp", "Link\t$\\Theta$", 3),
        ("planar2r", "\t$d$\t$\\theta$", 2),
        ("example4_6dof", "Link\t$a_i$", 6),
        ("puma260", "J\t$\\theta_i$", 6),
        ("puma560", "j\ttheta\td", 6),
    ],
)
def test_the_lecture_tables_read_as_the_built_in_robots(robot, start, rows):
    from dhsym.checking.comparing.table_match import compare_tables

    key = load_table(robot)
    text = _seed_table("001_7792e01642df3866.txt", start, rows)
    answer = read_answer_table(text, NameContext.from_table(key), key.convention)
    assert answer.n == key.n
    assert compare_tables(key, answer).same_robot


def test_columns_in_any_order_csv_yaml_and_modified_headers():
    key = load_table("planar2r")
    ctx = NameContext.from_table(key)
    csv_text = "alpha,a,d,theta\n0,a1,0,theta1\n0,a2,0,theta2\n"
    rows = read_answer_table(csv_text, ctx).rows
    assert [r.params() for r in rows] == [r.params() for r in key.rows]
    yaml_text = (
        "angles: deg\njoints:\n- {type: R, theta: q1, d: 0, a: a_1, alpha: 0}\n"
        "- {type: R, theta: q2, d: 0, a: a_2, alpha: 0}\n"
    )
    t = read_answer_table(yaml_text, ctx)
    assert t.rows[0].a == a1 and t.convention is Convention.STANDARD
    md = (
        "| i | $\\alpha_{i-1}$ | $a_{i-1}$ | $d_i$ | $\\theta_i$ |\n|--|--|--|--|--|\n"
        "| 1 | 0 | 0 | 0 | θ1 |\n| 2 | 0 | a1 | 0 | θ2 |"
    )
    assert read_answer_table(md, ctx).convention is Convention.MODIFIED


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("| θ | d | a |\n| q1 | 0 | 1 |", "missing column"),
        ("| θ | d | a | α | colour |\n| q1 | 0 | 1 | 0 | red |", "unknown column"),
        ("| θ | d | a | α |\n| q1 | 0 | 1 |", "cells"),
        ("just some words", "table"),
    ],
)
def test_bad_tables_say_what_is_wrong(text, match):
    with pytest.raises(DHError, match=match):
        read_answer_table(text, P2)


def test_text_limits(tmp_path):
    with pytest.raises(UnreadableAnswer, match="bytes"):
        read_text("x" * 100_001)
    with pytest.raises(UnreadableAnswer, match="binary"):
        read_text(b"\x7fELF\x00\x01")
    with pytest.raises(UnreadableAnswer, match="UTF-8"):
        read_text(b"\xfa\xff\xfe")  # not UTF-8 (\xff\xfe first would be UTF-16's mark)
    big = tmp_path / "big.txt"
    big.write_bytes(b"1" * 10_000_000)
    with pytest.raises(UnreadableAnswer, match="10000000 bytes"):
        read_answer_file(big)
    assert read_text("\ufeffθ1 − 1") == "θ1 - 1"


@pytest.mark.parametrize(
    ("text", "read"),
    [
        ("d = d3", "d3"),  # two names: the label is on the left
        ("0 = d3", "d3"),  # a bare number is no answer written first
        ("a1 C1 = a1 cos(theta1)", "a1*cos(theta1)"),  # a rewriting: its last form
        ("p_x = x = a1 C1", "a1*cos(theta1)"),
    ],
)
def test_the_answer_side_of_an_equation(text, read):
    assert read_expression(text, P2) == read_expression(read, P2)


@pytest.mark.parametrize(
    "text",
    [
        "```\na1*cos(theta1) + a2*cos(theta1 + theta2)\n```",  # a Markdown answer file
        "```python\na1*cos(theta1) + a2*cos(theta1 + theta2)\n```",
        "# px\na1 C1 + a2 C12",  # a comment line (Python, Markdown) ...
        "% p_x\na1 C1 + a2 C12",  # ... (LaTeX, MATLAB)
        "Answer: a1 C1 + a2 C12",
        "**Solution:** $p_x = a_1 c_1 + a_2 c_{12}$",
        "My answer is $a_1 c_1 + a_2 c_{12}$.",
        r"Multiplying the two link matrices gives \(a_1 C_1 + a_2 C_{12}\) for p_x.",
    ],
)
def test_the_answer_in_a_text_that_holds_more_is_read(text):
    key = Key.load("planar2r", "T0_2[0,3]")
    r = check_answer(key, text)
    assert r.verdict is Verdict.CORRECT, r.message


@pytest.mark.parametrize(
    "text",
    [
        "So $p_x$ is $a_1 c_1 + a_2 c_{12}$ or $-a_1 c_1$.",  # two formulas: no guess
        "Answer: a1 C1 + a2 C12, I think, or maybe minus",
    ],
)
def test_prose_with_no_single_answer_stays_unreadable(text):
    r = check_answer(Key.load("planar2r", "T0_2[0,3]"), text)
    assert r.verdict is Verdict.UNREADABLE, r.message


def test_utf16_with_its_byte_order_mark_is_text_and_nothing_else_is_guessed():
    """Windows PowerShell's `>` writes UTF-16 with a byte-order mark."""
    for encoding in ("utf-16", "utf-16-le", "utf-16-be"):
        data = "a1 C1 + a2 C12".encode(encoding)
        if encoding != "utf-16":
            data = ("\ufeff" + "a1 C1 + a2 C12").encode(encoding)
        assert read_expression(read_text(data), P2) == a1 * sp.cos(t1) + a2 * sp.cos(t1 + t2)
    with pytest.raises(UnreadableAnswer, match="not UTF-16"):
        read_text(b"\xff\xfe\x00")
    with pytest.raises(UnreadableAnswer, match="binary"):
        read_text("a1 C1".encode("utf-16-le"))  # no mark: not guessed
    with pytest.raises(UnreadableAnswer, match="not UTF-8"):
        read_text("90°".encode("cp1252"))


@pytest.mark.parametrize(
    ("question", "text"),
    [
        ("S", "S1 = (0, 0, 1, 0, 0, 0)\nS2 = (0, 0, 1, 0, -a1, 0)"),  # Lynch and Park
        ("S", "S_1 = [0;0;1;0;0;0], S_2 = [0;0;1;0;-a1;0]"),
        ("S", "[0 0; 0 0; 1 1; 0 0; 0 -a1; 0 0]"),  # MATLAB rows of two
        ("S", "[[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -a1, 0]]^T"),  # transposed: 6×2
        ("S2", "(0, 0, 1, 0, -a1, 0)"),
        ("S2", "S2 = [0 0 1 0 -a1 0]^T"),
        ("S2", "[0 0 1 0 -a1 0]'"),
        (
            "J",
            "J1 = (-a1 S1 - a2 S12, a1 C1 + a2 C12, 0, 0, 0, 1)\n"
            "J2 = (-a2 S12, a2 C12, 0, 0, 0, 1)",
        ),  # J column by column
    ],
)
def test_vectors_as_tuples_by_name_and_transposed(question, text):
    r = check_answer(Key.load("planar2r", question), text)
    assert r.verdict is Verdict.CORRECT, r.message


def test_a_transposed_matrix_is_transposed_and_a_wrong_column_named():
    key = Key.load("planar2r", "T0_2")
    rows = "[[C12, S12, 0, 0], [-S12, C12, 0, 0], [0, 0, 1, 0], "
    rows += "[a1 C1 + a2 C12, a1 S1 + a2 S12, 0, 1]]"
    assert check_answer(key, rows + "^T").verdict is Verdict.CORRECT
    assert check_answer(key, rows).verdict is Verdict.INCORRECT  # not transposed: wrong
    r = check_answer(Key.load("planar2r", "S"), "S1 = (0, 0, 1, 0, 0, 0)\nS2 = (0, 0, 1, 0, a1, 0)")
    assert r.verdict is Verdict.INCORRECT and "v = ω × q" in r.message, r.message
