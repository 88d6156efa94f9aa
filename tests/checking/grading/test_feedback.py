"""Feedback pages: content a student can act on, everything escaped."""

from __future__ import annotations

from dhsym.checking import Key, check_answer
from dhsym.checking.grading.feedback import (
    QuestionFeedback,
    md_code,
    render_check,
    render_feedback,
)
from dhsym.notation.escape import escape_markdown

from .._keys import KEYS, load_key  # the PUMA's key prepared once, as a worker does

BAD = "[[C12, -S12, 0, a1*C1 - a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]"


def test_markdown_shows_entry_correct_entry_and_diagnosis():
    md = render_check(check_answer(Key.load("planar2r", "T0_2"), BAD))
    assert "**INCORRECT.**" in md and "wrong sign" in md
    assert "| (1,4) | $a_{1} C_{1} - a_{2} C_{12}$ | $a_{1} C_{1} + a_{2} C_{12}$ |" in md
    assert "The other 15 entries are right." in md


def test_html_escapes_names_and_answers():
    r = check_answer(Key.load("planar2r", "T0_2[0,3]"), "<img src=x onerror=alert(1)>")
    student = {"id": "<script>alert(1)</script>", "name": "\\input{/etc/passwd} <b>"}
    html = render_feedback(student, [QuestionFeedback("q1", "T0_2[0,3]", 1, 0, r)], fmt="html")
    assert "<script>" not in html and "<img" not in html and "<b>" not in html
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in html
    md = render_feedback(student, [QuestionFeedback("q1", "T0_2[0,3]", 1, 0, r)], fmt="md")
    assert "<script>" not in md and "&lt;script&gt;" in md


def test_markdown_helpers():
    assert escape_markdown("[x](javascript:1) $\\input$") == "\\[x\\](javascript:1) \\$\\\\input\\$"
    assert md_code("a|b") == "`a\\|b`"


def test_absolute_value_bars_do_not_break_the_markdown_table():
    answer = BAD.replace("a1*C1 - a2*C12", "sqrt(a1^2)*C1 + a2*C12")  # |a1|: printed with bars
    md = render_check(check_answer(Key.load("planar2r", "T0_2"), answer))
    rows = [line for line in md.splitlines() if line.startswith("| (")]
    assert rows == [
        r"| (1,4) | $C_{1} \left\vert {a_{1}}\right\vert  + a_{2} C_{12}$ | "
        r"$a_{1} C_{1} + a_{2} C_{12}$ |"
    ]
    assert all(row.count("|") == 4 for row in rows)


def test_a_one_cell_answer_is_worded_as_one_answer():
    from dhsym.checking.grading.feedback import check_text

    r = check_answer(Key.load("planar2r", "det J"), "a1*a2*C2")
    text = check_text(r)
    assert r.message.startswith("Your determinant is wrong.")
    assert "(entries" not in text and "entry (1,1)" not in text
    assert "In your answer sin and cos are swapped" in text


def test_ik_feedback_shows_no_internal_branch_symbols():
    key = Key.load("planar2r", "ik")
    right = check_answer(
        key,
        "theta2 = acos((p_x**2 + p_y**2 - a1**2 - a2**2)/(2*a1*a2))\n"
        "theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)",
    )
    assert right.correct and "sigma" not in right.message and "elbow" in right.message
    wrong = check_answer(load_key("puma560", "ik"), "theta1 = atan(p_y/p_x)", keys=KEYS)
    assert "sigma" not in wrong.message
    for d in wrong.diagnoses:
        assert "sigma" not in d.detail


def test_summary_chart_counts_whole_students(tmp_path):
    from collections import Counter
    from types import SimpleNamespace as NS

    from dhsym.checking.grading import report as _report
    from dhsym.checking.grading.records import GradeRecord

    a = NS(questions=[NS(id="q1", ask="A1", points=2)], max_score=2.0)
    recs = [
        GradeRecord(s, s, s, f"{s}/", (), "graded", {"q1": p}, {"q1": "correct"}, (), p, 2)
        for s, p in (("ann", 2), ("bo", 0), ("cy", 2))
    ]
    kinds = Counter({"wrong_sign": 1, "<b>&": 3})
    path = _report._chart(tmp_path, a, recs, kinds)
    assert path.name == "summary.svg"
    svg = path.read_text(encoding="utf-8")
    assert svg.startswith("<svg ") and "<b>" not in svg and "&lt;b&gt;&amp;" in svg
    data = _report.chart_data(a, recs, kinds)
    # counts of students and answers: whole-number ticks, the axes reaching the largest count
    assert [t["label"] for t in data["bins_y"]] == ["0", "1", "2"]
    assert [t["label"] for t in data["bars_x"]] == ["0", "1", "2", "3"]
    assert [b["count"] for b in data["bins"]] == [1, 2]  # the maximum score in the last bin
    assert [(b["label"], b["count"]) for b in data["bars"]] == [("<b>&", 3), ("wrong_sign", 1)]
    tall = [b["height"] for b in data["bins"]]
    assert tall[1] == 2 * tall[0] > 0
    many = _report.chart_data(a, recs * 40, Counter({"k": 41}))
    assert [t["label"] for t in many["bins_y"]][-1] == "80"
    assert [t["label"] for t in many["bars_x"]] == [str(t) for t in range(0, 51, 10)]
