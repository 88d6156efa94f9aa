"""Question tests (tests: right/wrong) and the key's own answer: read, run, refused by grade."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from dhsym.checking.grading.assignment import Assignment
from dhsym.checking.grading.assignment_tests import key_answer, run_assignment_tests
from dhsym.checking.grading.batch import grade
from dhsym.checking.grading.question_tests import QuestionTests, WrongAnswer
from dhsym.checking.judging.checker import check_answer
from dhsym.checking.judging.key import Key, PreparedKeys
from dhsym.errors import DHError

ROOT = Path(__file__).resolve().parents[3]
HW = ROOT / "examples" / "homework"
GUIDE = ROOT / "docs" / "guide" / "assignments.md"


def write(tmp_path: Path, tests: str) -> Path:
    p = tmp_path / "hw.yaml"
    p.write_text(f"key: planar2r\nquestions:\n  - id: q1\n    ask: px\n    tests: {tests}\n")
    return p


def test_parse_and_errors():
    t = QuestionTests.parse(
        {"right": ["a1", 3], "wrong": ["x", {"answer": "y", "mistake": "sign"}]}
    )
    assert t.right == ("a1", "3")
    assert t.wrong == (WrongAnswer("x"), WrongAnswer("y", "wrong_sign"))
    with pytest.raises(DHError, match="mistake: unknown mistake .signs.") as err:
        QuestionTests.parse({"wrong": [{"answer": "y", "mistake": "signs"}]})
    assert err.value.field == "tests.wrong[1].mistake"
    with pytest.raises(DHError, match="expected {right"):
        QuestionTests.parse({"rigth": ["a1"]})
    with pytest.raises(DHError, match="expected an answer"):
        QuestionTests.parse({"right": [None]})


def test_errors_name_the_file_and_question(tmp_path: Path):
    with pytest.raises(DHError) as err:
        Assignment.load(write(tmp_path, "{wrong: [{answer: a1, mistake: nope}]}"))
    assert err.value.file == str(tmp_path / "hw.yaml") and err.value.row == 1
    assert err.value.field == "tests.wrong[1].mistake"


def test_a_failing_test_fails_the_run_and_grade_refuses(tmp_path: Path):
    # a right answer that is wrong, a wrong answer that is right, a mistake misnamed
    hw = write(
        tmp_path,
        "{right: [a1*C1 - a2*C12], wrong: [a1*C1 + a2*C12, {answer: a1*C1 - a2*C12, "
        "mistake: transposed}]}",
    )
    report = run_assignment_tests(Assignment.load(hw))
    assert not report.passed
    assert [r.passed for r in report.rows] == [True, False, False, False]
    assert [r.got for r in report.rows][1:] == [
        "incorrect: wrong_sign",
        "correct",
        "incorrect: wrong_sign",
    ]
    text = report.text()
    assert text.endswith("1 passed, 3 failed\n") and text.count("FAIL") == 3
    subs = tmp_path / "subs"
    (subs / "ann").mkdir(parents=True)
    (subs / "ann" / "q1.txt").write_text("a1*C1 + a2*C12")
    with pytest.raises(DHError, match=r"question tests fail \(3 of 3; first: question q1, right"):
        grade(hw, subs, tmp_path / "out", workers=0, progress=False)
    assert not (tmp_path / "out").exists()  # refused before anything is written


def test_the_shipped_example_passes_its_tests():
    report = run_assignment_tests(Assignment.load(HW / "assignment.yaml"))
    assert report.passed, report.text()
    cases = {(r.question, r.case) for r in report.rows}
    for q in ("q1", "q2", "q3", "q4", "q5"):  # the key and both kinds of test, per question
        assert {(q, "key"), (q, "right"), (q, "wrong")} <= cases


def test_key_answers_of_each_kind_are_graded_correct():
    keys = PreparedKeys()
    for robot, question in [
        ("planar2r", "J"),
        ("planar2r", "det J"),
        ("planar2r", "table"),
        ("planar2r", "ik@0.3,0.5"),
        ("planar2r", "M[0,1]"),
        ("puma560", "T0_3"),
    ]:
        key = Key.load(robot, question, keys=keys)
        text = key_answer(keys.get(key))
        assert check_answer(key, text, keys=keys).correct, (robot, question, text)


def test_the_guides_examples_are_checked(tmp_path: Path):
    """Every assignment YAML block of the assignments guide loads, and its question tests
    and key answers pass (blocks that are a fragment, without 'questions:', are skipped)."""
    blocks = re.findall(r"```yaml\n(.*?)```", GUIDE.read_text(encoding="utf-8"), re.S)
    checked = 0
    for k, block in enumerate(blocks):
        if not block.startswith(("title:", "key:")) or "questions:" not in block:
            continue
        folder = tmp_path / f"b{k}"
        folder.mkdir()
        (folder / "generic_modified_link.yaml").write_bytes(
            (HW / "generic_modified_link.yaml").read_bytes()
        )
        if "secret:" in block:
            (folder / "hw3.secret").write_text("a-secret-for-the-guide-example-0123\n")
        (folder / "hw.yaml").write_text(block)
        report = run_assignment_tests(Assignment.load(folder / "hw.yaml"), samples=1)
        assert report.passed, report.text()
        checked += 1
    assert checked >= 2


def test_trajectory_questions_are_tested_like_the_others(tmp_path):
    (tmp_path / "hw.yaml").write_text(
        "questions:\n"
        '  - id: t1\n    ask: traj a3\n    key: "quintic(q0=q0, qf=qf, tf=tf)"\n'
        "    tests:\n"
        '      right: ["10*(qf - q0)/tf^3", "\\\\frac{10(q_f-q_0)}{t_f^3}"]\n'
        '      wrong: [{answer: "10*(qf - q0)/tf^2", mistake: tf_for_tf_squared}, "0"]\n'
        '  - id: t2\n    ask: kp\n    key: "gains(omega=4)"\n'
        "    tests: {right: ['16', '16.0'], wrong: [{answer: '4', mistake: kp_not_squared}]}\n"
    )
    report = run_assignment_tests(Assignment.load(tmp_path / "hw.yaml"))
    assert report.passed, report.text()
    rows = [(r.question, r.case, r.got) for r in report.rows]
    assert rows == [
        ("t1", "key", "correct"),
        ("t2", "key", "correct"),
        ("t1", "right", "correct"),
        ("t1", "right", "correct"),
        ("t1", "wrong", "incorrect: tf_for_tf_squared"),
        ("t1", "wrong", "incorrect"),
        ("t2", "right", "correct"),
        ("t2", "right", "correct"),
        ("t2", "wrong", "incorrect: kp_not_squared"),
    ]
    # a test naming the wrong mistake fails, and grade refuses the assignment
    (tmp_path / "hw.yaml").write_text(
        (tmp_path / "hw.yaml")
        .read_text()
        .replace("mistake: kp_not_squared", "mistake: kd_without_two")
    )
    report = run_assignment_tests(Assignment.load(tmp_path / "hw.yaml"))
    assert [(r.question, r.got) for r in report.failures] == [("t2", "incorrect: kp_not_squared")]
    (tmp_path / "subs" / "ann").mkdir(parents=True)
    with pytest.raises(DHError, match="question tests fail"):
        grade(tmp_path / "hw.yaml", tmp_path / "subs", tmp_path / "out", workers=0, progress=False)
