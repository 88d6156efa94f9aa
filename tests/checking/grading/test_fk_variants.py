"""A transform at joint values drawn per student (issue 34, item 2): ``T0_2@q1,q2`` in an
assignment with ``variants:``, each student graded against the matrix at their own joint
values, shown in the class listing, the feedback and the problem sheets."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from dhsym.checking import Key, check_answer
from dhsym.checking.grading.assignment import Assignment
from dhsym.checking.grading.batch import grade
from dhsym.checking.grading.sheets import student_sheets
from dhsym.checking.grading.variants import ClassList, class_variants, list_variants, variant_id
from dhsym.checking.reading.questions import Question

HW = """title: HW forward kinematics
key: planar2r
secret: hw.secret
variants:
  q1: {values: [30, 45, 60], unit: deg}
  q2: {values: [0, 90, -45], unit: deg}
questions:
  - {id: fk, ask: "T0_2@q1,q2", points: 2}
"""
STUDENTS = ("alice", "bob", "carol")


@pytest.fixture
def hw(tmp_path: Path) -> Path:
    (tmp_path / "hw.secret").write_text("s3cret-for-the-tests-0123456789\n")
    (tmp_path / "hw.yaml").write_text(HW)
    return tmp_path / "hw.yaml"


def planar2r(q1: float, q2: float, a1: float, a2: float) -> str:
    """``^0T_2`` of the planar 2R arm in numbers to three decimals, as a student writes it
    (the textbook's closed form, computed here independently of dhsym)."""
    c1, s1 = math.cos(q1), math.sin(q1)
    c12, s12 = math.cos(q1 + q2), math.sin(q1 + q2)
    rows = [
        [c12, -s12, 0, a1 * c1 + a2 * c12],
        [s12, c12, 0, a1 * s1 + a2 * s12],
        [0, 0, 1, 0],
        [0, 0, 0, 1],
    ]
    return "[" + ", ".join("[" + ", ".join(f"{x:.3f}" for x in r) + "]" for r in rows) + "]"


def lengths() -> tuple[float, float]:
    table = Key.load("planar2r", "table").table
    by_name = {str(s): float(v) for s, v in table.value_map.items()}
    return by_name["a1"], by_name["a2"]


def test_a_transform_at_joint_values_is_a_question():
    q = Question.parse("T0_2@pi/6, pi/2", 2)
    assert (q.kind, q.frm, q.to, q.label) == (
        "matrix",
        0,
        2,
        "T0_2@0.523598775598299,1.5707963267949",
    )
    assert Question.parse("fk@0,0", 2).label == "T0_2@0,0"
    assert Question.parse("T0_2[0,3]@0,0", 2).entry == (0, 3)
    with pytest.raises(Exception, match="joint values follow a transform"):
        Question.parse("J@0,0", 2)
    with pytest.raises(Exception, match="2 joint values"):
        check_answer(Key.load("planar2r", "T0_2@0"), "[[1,0,0,1.8],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")


def test_the_matrix_at_the_joint_values_is_graded_to_the_digits():
    a1, a2 = lengths()
    key = Key.load("planar2r", "T0_2@pi/6,pi/3")
    assert check_answer(key, planar2r(math.pi / 6, math.pi / 3, a1, a2)).correct
    # the matrix at other joint values, or a wrong digit, is wrong
    assert not check_answer(key, planar2r(math.pi / 3, math.pi / 6, a1, a2)).correct
    wrong = planar2r(math.pi / 6, math.pi / 3, a1, a2).replace("0.866", "0.876", 1)
    assert not check_answer(key, wrong).correct


def test_each_student_draws_their_own_joint_values_reproducibly(hw: Path):
    a = Assignment.load(hw)
    assert a.variants is not None and a.variants.names == ("q1", "q2")
    drawn = class_variants(a.variants, STUDENTS)
    assert len({v.values for v in drawn.values()}) == 3  # no duplicates: 9 combinations
    poses = {}
    for s in STUDENTS:
        mine = a.for_variant(drawn[variant_id(s)])
        (q,) = mine.questions
        values = dict(drawn[variant_id(s)].values)
        assert q.key.question.pose == pytest.approx((float(values["q1"]), float(values["q2"])))
        poses[s] = q.key.question.pose
    assert len(set(poses.values())) == 3
    again = Assignment.load(hw)
    assert again.variants is not None
    assert class_variants(again.variants, STUDENTS) == drawn  # the same on a second load


def test_the_class_listing_and_the_sheets_show_the_joint_values(hw: Path):
    a = Assignment.load(hw)
    assert a.variants is not None
    roster = ClassList(tuple((s, s.title()) for s in STUDENTS))
    drawn = class_variants(a.variants, STUDENTS)
    listing = list_variants(a.variants, roster, "csv").splitlines()
    assert listing[0] == "student,name,q1,q2"
    for s, line in zip(STUDENTS, listing[1:], strict=True):
        shown = dict(drawn[variant_id(s)].shown)
        assert line == f"{s},{s.title()},{shown['q1']},{shown['q2']}"
    for sheet in student_sheets(a, roster):
        v = drawn[variant_id(sheet.student)]
        values = dict(v.values)
        assert sheet.pose == pytest.approx((float(values["q1"]), float(values["q2"])))
        assert v.text().startswith("q1 = ") and "°" in v.text()


def test_grade_checks_each_student_against_their_own_joint_values(hw: Path, tmp_path: Path):
    a1, a2 = lengths()
    roster = tmp_path / "class.csv"
    roster.write_text("student\n" + "\n".join(STUDENTS) + "\n")
    a = Assignment.load(hw)
    assert a.variants is not None
    drawn = class_variants(a.variants, STUDENTS)

    def at(student: str) -> tuple[float, float]:
        values = dict(drawn[variant_id(student)].values)
        return float(values["q1"]), float(values["q2"])

    subs = tmp_path / "subs"
    answers = {
        "alice": planar2r(*at("alice"), a1, a2),  # her own values
        "bob": planar2r(*at("bob"), a1, a2),  # his own values
        "carol": planar2r(*at("alice"), a1, a2),  # alice's answer copied
    }
    for who, text in answers.items():
        (subs / who).mkdir(parents=True)
        (subs / who / "fk.txt").write_text(text)
    report = grade(hw, subs, tmp_path / "out", workers=0, progress=False, variants=roster)
    rec = {r.student: r for r in report.records}
    assert rec["alice"].verdicts["fk"] == "correct"
    assert rec["bob"].verdicts["fk"] == "correct"
    assert rec["carol"].verdicts["fk"] == "incorrect"
    for who in STUDENTS:
        page = (tmp_path / "out" / "feedback" / f"{who}.md").read_text()
        assert f"**Your values:** {drawn[variant_id(who)].text()}" in page
