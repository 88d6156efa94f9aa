"""The assignment file: questions, keys relative to the file, points, one error per problem."""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsym.checking.grading.assignment import Assignment
from dhsym.errors import DHError

HW = Path(__file__).resolve().parents[3] / "examples" / "homework"


def test_the_example_assignment_reads_its_questions_and_keys():
    a = Assignment.load(HW / "assignment.yaml")
    assert [q.id for q in a.questions] == ["q1", "q2", "q3", "q4", "q5"]
    assert a.max_score == 10 and a.seconds == 5 and len(a.fingerprint) == 16
    assert a.questions[3].key == Assignment.load(HW / "assignment.yaml").questions[3].key


def test_a_key_file_is_relative_to_the_assignment(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "arm.yaml").write_text((HW / "generic_modified_link.yaml").read_text())
    (tmp_path / "sub" / "hw.yaml").write_text(
        "title: '  Two\n  lines '\nkey: arm.yaml\nquestions: [{id: q1, ask: A1, points: '1.5'}]\n"
    )
    a = Assignment.load(tmp_path / "sub" / "hw.yaml")
    assert a.title == "Two lines" and a.max_score == 1.5


@pytest.mark.parametrize(
    ("text", "row", "field"),
    [
        ("key: puma560\nquestions: [{id: '../x', ask: table}]\n", 1, "id"),
        ("key: puma560\nquestions: [{id: q1, ask: table}, {id: q1, ask: T0_2}]\n", 2, "id"),
        ("key: puma560\nquestions: [{id: q1, ask: table, points: -1}]\n", 1, "points"),
        ("questions: [{id: q1, ask: table}]\n", 1, "key"),
        ("key: puma560\nquestions: [{id: q1, ask: [T0_2]}]\n", 1, "ask"),
    ],
)
def test_every_problem_names_the_file_row_and_field(tmp_path, text, row, field):
    bad = tmp_path / "a.yaml"
    bad.write_text(text, encoding="utf-8")
    with pytest.raises(DHError) as err:
        Assignment.load(bad)
    assert (err.value.file, err.value.row, err.value.field) == (str(bad), row, field)
