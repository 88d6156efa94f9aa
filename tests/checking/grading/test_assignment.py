"""The assignment file: questions, keys relative to the file, points, one error per problem."""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsym.checking.grading.assignment import Assignment
from dhsym.checking.judging.trajectory_key import TrajectoryKey
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


def test_a_trajectory_question_has_a_profile_for_its_key(tmp_path):
    (tmp_path / "hw.yaml").write_text(
        "key: planar2r\nrounding: digits=4\nquestions:\n"
        "  - {id: q1, ask: px}\n"
        '  - {id: t1, ask: traj a2, key: "cubic(q0=0, qf=pi/2, tf=2)", points: 2}\n'
        '  - {id: t2, ask: kd, key: "gains(omega=omega, zeta=1)", rounding: off}\n'
    )
    a = Assignment.load(tmp_path / "hw.yaml")
    t1, t2 = a.questions[1].key, a.questions[2].key
    assert isinstance(t1, TrajectoryKey) and isinstance(t2, TrajectoryKey)
    assert t1.name == "cubic(q0=0, qf=pi/2, tf=2)" and str(t1.rounding) == "digits=4"
    assert str(t2.rounding) == "off" and a.max_score == 4
    # the fingerprint follows the profile
    (tmp_path / "hw.yaml").write_text((tmp_path / "hw.yaml").read_text().replace("tf=2)", "tf=3)"))
    assert Assignment.load(tmp_path / "hw.yaml").fingerprint != a.fingerprint


@pytest.mark.parametrize(
    ("question", "message", "field"),
    [
        ("{id: t1, ask: traj a2}", "asks about a profile", "key"),
        ('{id: t1, ask: tb, key: "cubic(q0=0, qf=1, tf=2)"}', "lspb or minimum_time", "ask"),
        ('{id: t1, ask: T0_2, key: "cubic(q0=0, qf=1, tf=2)"}', "not one a profile", "ask"),
        ('{id: t1, ask: traj a2, key: "cubic(q0=0, qf=1, tf=X)"}', "unknown name X", "key.tf"),
        ('{id: t1, ask: traj a2, key: "cubic(q0=0, qf=1, tf=0)"}', "positive", "key"),
        ('{id: t1, ask: vmax, key: "lspb(q0=0, qf=1, tf=2, V=5)"}', "too large", "key"),
        (
            '{id: t1, ask: kd, key: "gains(omega=1)", deduct: {kd_twice: 10%}}',
            "catalogue",
            "credit",
        ),
    ],
)
def test_a_bad_trajectory_question_names_the_file_row_and_field(tmp_path, question, message, field):
    (tmp_path / "hw.yaml").write_text(f"key: planar2r\nquestions:\n  - {question}\n")
    with pytest.raises(DHError, match=message) as err:
        Assignment.load(tmp_path / "hw.yaml")
    assert (err.value.file, err.value.row, err.value.field) == (
        str(tmp_path / "hw.yaml"),
        1,
        field,
    )
