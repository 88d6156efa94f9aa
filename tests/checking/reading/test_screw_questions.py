"""PoE questions (S, S3, B, Mhome, Js, Jb, T(theta)): every written form, the errors, and the
reading of their answers (axes as columns or one per row, LaTeX)."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.checking.reading.answer_names import NameContext
from dhsym.checking.reading.answer_value import AnswerForm, read_answer_value
from dhsym.checking.reading.limits import UnreadableAnswer
from dhsym.checking.reading.questions import Question
from dhsym.errors import DHError
from dhsym.model.library import load_table


@pytest.mark.parametrize(
    ("spec", "part", "label", "column", "entry"),
    [
        ("S", "S", "S", None, None),
        ("S3", "S", "S3", 3, None),
        ("S_3", "S", "S3", 3, None),
        ("S_{3}", "S", "S3", 3, None),
        ("B", "B", "B", None, None),
        ("B_{2}[4,0]", "B", "B2[4,0]", 2, (4, 0)),
        ("Mhome", "Mhome", "Mhome", None, None),
        ("M_home", "Mhome", "Mhome", None, None),
        ("M0", "Mhome", "Mhome", None, None),
        ("M_{0}[0, 3]", "Mhome", "Mhome[0,3]", None, (0, 3)),
        ("Js", "Js", "Js", None, None),
        ("J_s", "Js", "Js", None, None),
        ("J_{b}", "Jb", "Jb", None, None),
        ("Jb[5,2]", "Jb", "Jb[5,2]", None, (5, 2)),
        ("T(theta)", "T", "T(theta)", None, None),
        ("T(θ)", "T", "T(theta)", None, None),
        ("T_poe", "T", "T(theta)", None, None),
        ("poe[0,3]", "T", "T(theta)[0,3]", None, (0, 3)),
    ],
)
def test_every_written_form(spec, part, label, column, entry):
    q = Question.parse(spec, n=3)
    assert (q.kind, q.part, q.label, q.column, q.entry) == ("screw", part, label, column, entry)
    again = Question.parse(q.label, n=3)  # the label is read back as the same question
    assert (again.part, again.column, again.entry, again.label) == (part, column, entry, label)


def test_m_stays_the_inertia_matrix_and_other_kinds_are_untouched():
    assert Question.parse("M", 3).kind == "dynamics"
    assert Question.parse("M[0,1]", 3).part == "M"
    assert [Question.parse(s, 3).kind for s in ("J", "T0_3", "A2", "det J", "table")] == [
        "jacobian",
        "matrix",
        "matrix",
        "det",
        "table",
    ]


def test_headings_in_latex():
    assert [
        Question.parse(s, 3).label_latex for s in ("S", "B2", "Mhome", "Js[0,1]", "T(theta)")
    ] == [
        r"\mathcal{S}",
        r"\mathcal{B}_{2}",
        "M",
        "J_s[1,2]",
        r"T(\theta)",
    ]


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("S4", "the screw axes are S1 … S3"),
        ("S0", "the screw axes are S1 … S3"),
        ("Js[6,0]", "rows and columns are 0-based"),
        ("Js[0,3]", "rows and columns are 0-based"),
        ("Mhome[4,0]", "rows and columns are 0-based"),
        ("S2[0,1]", "rows and columns are 0-based"),
    ],
)
def test_out_of_range_questions_are_refused(spec, message):
    with pytest.raises(DHError, match=message):
        Question.parse(spec, n=3)


def _form(spec: str, shape: tuple[int, int]) -> AnswerForm:
    table = load_table("planar2r")
    return AnswerForm(Question.parse(spec, 2), NameContext.from_table(table), shape)


def test_axes_as_columns_as_rows_and_in_latex_read_the_same():
    a1 = sp.Symbol("a1", real=True)
    want = sp.Matrix([[0, 0], [0, 0], [1, 1], [0, 0], [0, -a1], [0, 0]])
    form = _form("S", (6, 2))
    columns = "[[0,0],[0,0],[1,1],[0,0],[0,-a1],[0,0]]"
    rows = "[[0,0,1,0,0,0],[0,0,1,0,-a_1,0]]"
    latex = r"\begin{bmatrix} 0&0&1&0&0&0 \\ 0&0&1&0&-a_{1}&0 \end{bmatrix}"
    for text in (columns, rows, latex):
        read = read_answer_value(form, text)
        assert read.matrix == want, text
    assert read_answer_value(form, rows).cells[9].text == "-a_1"  # entry (5,2) as written


def test_one_axis_as_a_column_or_a_row():
    form = _form("S2", (6, 1))
    for text in ("[0, 0, 1, 0, -a1, 0]", "[[0], [0], [1], [0], [-a1], [0]]"):
        assert read_answer_value(form, text).matrix.T.tolist()[0][4] == -sp.Symbol("a1", real=True)


def test_a_jacobian_is_read_in_its_own_shape_only():
    with pytest.raises(UnreadableAnswer, match="expected a 6×2 matrix"):
        read_answer_value(_form("Js", (6, 2)), "[[0,0,1,0,0,0],[0,0,1,0,-a1,0]]")


def test_a_six_joint_arm_reads_six_rows_as_the_rows():
    form = AnswerForm(Question.parse("S", 6), NameContext.from_table(load_table("puma560")), (6, 6))
    read = read_answer_value(form, "[" + ",".join(f"[{k},0,0,0,0,0]" for k in range(6)) + "]")
    assert read.matrix[:, 0].T.tolist() == [[0, 1, 2, 3, 4, 5]]


def test_unsafe_text_is_never_evaluated():
    with pytest.raises(DHError):
        read_answer_value(
            _form("S", (6, 2)),
            "[[__import__('os').system('ls'),0],[0,0],[1,1],[0,0],[0,-a1],[0,0]]",
        )
