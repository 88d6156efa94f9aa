"""An answer is read once (reading.answer_value) and then judged: the counts of the readers'
entry points while a whole check runs, and the typed values themselves."""

from __future__ import annotations

from collections import Counter

import pytest
import sympy as sp

from dhsym.checking import Key, check_answer, prepare
from dhsym.checking.reading import _table_text, answer_value, answers
from dhsym.checking.reading.answer_value import (
    IKAnswer,
    MatrixAnswer,
    TableAnswer,
    read_answer_value,
)


class Calls:
    """The reading entry points, counted while a check runs."""

    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        self.read_text = 0
        self.latex: Counter[str] = Counter()
        self.exact: Counter[str] = Counter()  # whitelist parses of a cell's exact value
        self.literal: Counter[str] = Counter()  # parses with a placeholder per literal
        self.table_cells: Counter[str] = Counter()
        real_read, real_latex = answers.read_text, answers.latex_to_text
        real_parse, real_table_parse = answers.parse_expression, _table_text.parse_expression

        def read_text(*a, **kw):
            self.read_text += 1
            return real_read(*a, **kw)

        def latex_to_text(src, *a, **kw):
            self.latex[src] += 1
            return real_latex(src, *a, **kw)

        def parse(text, *a, **kw):
            (self.literal if kw.get("literal") else self.exact)[text] += 1
            return real_parse(text, *a, **kw)

        def table_parse(text, *a, **kw):
            self.table_cells[text] += 1
            return real_table_parse(text, *a, **kw)

        for module in (answers, answer_value):
            monkeypatch.setattr(module, "read_text", read_text)
            monkeypatch.setattr(module, "latex_to_text", latex_to_text)
        monkeypatch.setattr(_table_text, "latex_to_text", latex_to_text)
        monkeypatch.setattr(answers, "parse_expression", parse)
        monkeypatch.setattr(_table_text, "parse_expression", table_parse)


WRONG_T02 = "[[C12, -S12, 0, a1*C1 - a2*C12], [S12, C12, 0, a1*S1 + 0.50*a2*S12], [0, 0, 1, 0.0]]"


def test_a_matrix_answer_is_read_once(monkeypatch):
    key = Key.load("planar2r", "T0_2")
    prepare(key)
    calls = Calls(monkeypatch)
    r = check_answer(key, WRONG_T02)  # wrong: the diagnosis runs too, and reads nothing
    assert r.verdict.value == "incorrect"
    assert calls.read_text == 1
    written = [c.strip() for c in WRONG_T02.replace("[", "").replace("]", "").split(",")]
    assert calls.exact == Counter(written)  # the 12 cells written, each once
    # only the two cells written with decimals are read for their literals, once each
    assert sorted(calls.literal) == ["0.0", "a1*S1 + 0.50*a2*S12"]
    assert set(calls.literal.values()) == {1}


def test_a_latex_matrix_is_translated_once_per_cell(monkeypatch):
    key = Key.load("planar2r", "T0_2")
    prepare(key)
    calls = Calls(monkeypatch)
    r = check_answer(
        key,
        r"\begin{bmatrix} \cos(\theta_1 + \theta_2) & -S_{12} & 0 & a_1 C_1 + a_2 C_{12} \\"
        r" S_{12} & \cos(\theta_1 + \theta_2) & 0 & a_1 \sin\theta_1 + 0.5 a_2 S_{12} \\"
        r" 0&0&1&0 \\ 0&0&0&1 \end{bmatrix}",
    )
    assert r.verdict.value == "incorrect"
    assert calls.read_text == 1
    cos12, pos = r"\cos(\theta_1 + \theta_2)", r"a_1 \sin\theta_1 + 0.5 a_2 S_{12}"
    assert calls.latex == Counter({cos12: 2, pos: 1})  # each LaTeX cell (two alike) once
    assert sum(calls.exact.values()) == 16  # each cell parsed once
    assert list(calls.literal.values()) == [1]  # the one cell with a decimal, once more


def test_a_table_answer_is_read_once(monkeypatch):
    key = Key.load("planar2r", "table")
    prepare(key)
    calls = Calls(monkeypatch)
    text = "| Link | θ | d | a | α |\n|---|---|---|---|---|\n| 1 | θ1 | 0 | a1 | 0 |\n"
    r = check_answer(key, text + "| 2 | θ2 | 0 | a2 | 90° |")
    assert r.verdict.value == "incorrect"
    assert calls.read_text == 1
    assert calls.table_cells and max(calls.table_cells.values()) <= 4  # "0" is written 4 times
    assert calls.table_cells["a2"] == 1


def test_an_ik_answer_is_read_once(monkeypatch):
    key = Key.load("planar2r", "ik")
    prepare(key)
    calls = Calls(monkeypatch)
    answer = (
        "c2 = (px^2 + py^2 - a1^2 - a2^2)/(2*a1*a2)\n"
        "theta2 = atan2(-sqrt(1 - c2^2), c2)\n"
        "theta1 = atan(py/px) - atan2(a2*S2, a1 + 1.000*a2*C2)"
    )
    r = check_answer(key, answer)
    assert r.verdict.value == "incorrect"  # atan for atan2: the diagnosis reads nothing
    assert calls.read_text == 1
    assert sum(calls.exact.values()) == 3 and set(calls.exact.values()) == {1}
    assert sum(calls.literal.values()) == 1


def test_the_values_read():
    pk = prepare(Key.load("planar2r", "T0_2"))
    m = read_answer_value(pk.form(), WRONG_T02)
    assert isinstance(m, MatrixAnswer) and m.shape == (4, 4) and m.missing_column is None
    assert m.texts[-4:] == ["0", "0", "0", "1"]  # the bottom row the answer left out
    assert m.cells[7].template is not None and [x.text for x in m.cells[7].literals] == ["0.50"]
    assert m.cells[0].template is None and m.matrix[1, 3] == m.cells[7].value

    pk = prepare(Key.load("stanford", "J"))
    n = pk.part.expected.cols
    rows = ["; ".join(", ".join("0" for _ in range(n - 1)) for _ in range(6))]
    j = read_answer_value(pk.form(), rows[0])
    assert isinstance(j, MatrixAnswer) and j.shape == (6, n)
    assert j.missing_column == pk.form().prismatic[0]

    pk = prepare(Key.load("planar2r", "table"))
    t = read_answer_value(pk.form(), "theta, d, a, alpha\ntheta1, 0, a1, 0\ntheta2, 0, a2, 180")
    assert isinstance(t, TableAnswer) and t.degrees and len(t.table.rows) == 2

    pk = prepare(Key.load("planar2r", "ik"))
    ik = read_answer_value(pk.form(), "theta1 = ±0.5°\ntheta2 = 1")
    assert isinstance(ik, IKAnswer) and len(ik.signs) == 1
    st = ik.solutions[0][0]
    assert st.degrees and st.text == "±0.5°" and st.expr.has(sp.pi)


@pytest.mark.parametrize(
    "text",
    [
        "q = [0.3000, 0.7000]",  # the joint vector, labelled
        "theta = (0.3, 0.7)",
        "theta1 = 0.3 rad\ntheta2 = 0.7 rad",  # a unit after the number
        "θ1 = 17.19 deg, θ2 = 40.11 degrees",
        "elbow down: θ1 = 0.3, θ2 = 0.7",  # the branch's name first
        "Solution 1: [0.3, 0.7]",
    ],
)
def test_numeric_ik_answers_as_students_label_them(text):
    r = check_answer(Key.load("planar2r", "ik@0.3,0.7"), text)
    assert r.verdict.value == "correct", r.message


def test_a_unit_is_read_only_after_a_number_and_a_wrong_vector_stays_wrong():
    key = Key.load("planar2r", "ik@0.3,0.7")
    assert check_answer(key, "q = [0.3, 0.8]").verdict.value == "incorrect"
    assert check_answer(key, "theta1 = 0.3 deg, theta2 = 0.7 deg").verdict.value == "incorrect"
    assert check_answer(key, "q = [0.3, 0.7, 0.1]").verdict.value == "unreadable"
