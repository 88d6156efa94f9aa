"""Reading submissions: the student's YAML file in every documented form."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from dhsym.checking import grade
from dhsym.checking.grading.submissions import read_submission_file

HW = Path(__file__).resolve().parents[3] / "examples" / "homework"
QIDS = ["q1", "q2", "q3", "q4", "q5"]

TABLE_ROWS = """
    - {theta: theta1, d: 0, a: 0, alpha: 90}
    - {theta: theta2, d: 0, a: a2, alpha: 0}
    - {theta: theta3, d: d3, a: a3, alpha: -90}
    - {theta: theta4, d: d4, a: 0, alpha: 90}
    - {theta: theta5, d: 0, a: 0, alpha: -90}
    - {theta: theta6, d: 0, a: 0, alpha: 0}"""
T0_2 = """
    - [C1*C2, -S2*C1, S1, a2*C1*C2]
    - [S1*C2, -S1*S2, -C1, a2*S1*C2]
    - [S2, C2, 0, a2*S2]
    - [0, 0, 0, 1]"""
Q3 = "[[-S3, 0, C3, 0], [C3, 0, S3, 0], [0, 1, 0, 0], [0, 0, 0, 1]]"
Q5 = "d3*S1 + (a2*C2 + a3*C23 - d4*S23)*C1"


def _answers(indent: str) -> str:
    return (
        f"{indent}q1:{TABLE_ROWS.replace(chr(10), chr(10) + indent)}\n"
        f"{indent}q2:{T0_2.replace(chr(10), chr(10) + indent)}\n"
        f"{indent}q3: {Q3}\n"
        f"{indent}q5: {Q5}\n"
    )


@pytest.mark.parametrize(
    "text",
    [
        "name: Alice\nanswers:\n" + _answers("  "),  # under answers:
        "name: Alice\n" + _answers(""),  # as the guide shows it: q1: … at the top
    ],
)
def test_yaml_answers_in_every_documented_form_are_graded(tmp_path, text):
    """Issue 34, item 7: a table as a YAML list of rows, a matrix as a list of lists."""
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "alice.yaml").write_text(text, encoding="utf-8")
    sub = read_submission_file(subs / "alice.yaml", QIDS)
    assert [q for q, _ in sub.answers] == ["q1", "q2", "q3", "q5"] and not sub.problems
    out = tmp_path / "out"
    grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    (row,) = csv.DictReader((out / "gradebook.csv").open(encoding="utf-8"))
    assert (row["q1"], row["q2"], row["q3"], row["q4"], row["q5"]) == ("4", "2", "1", "0", "1")
    assert row["name"] == "Alice"


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("answers: {q5: true}\n", "true"),
        ("answers: {q5: [[a, [b]]]}\n", "list"),
        ("answers: {q5: {x: 1}}\n", "mapping"),
        ("answers: {q5: [{theta: q1}, 3]}\n", "row"),
        ("q5: [a, {b: 1}]\n", "list"),
    ],
)
def test_an_answer_present_but_unreadable_says_why(tmp_path, text, reason):
    (tmp_path / "bob.yaml").write_text(text, encoding="utf-8")
    sub = read_submission_file(tmp_path / "bob.yaml", QIDS)
    assert not sub.answers
    ((qid, why),) = sub.problems
    assert qid == "q5" and reason in why


def test_a_file_that_is_not_a_mapping_is_a_problem_of_every_question(tmp_path):
    (tmp_path / "eve.yaml").write_text("- q5\n- x\n", encoding="utf-8")
    sub = read_submission_file(tmp_path / "eve.yaml", QIDS)
    assert [q for q, _ in sub.problems] == QIDS and not sub.answers
