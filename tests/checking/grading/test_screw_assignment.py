"""A PoE homework end to end: the assignment with partial credit, deductions and question
tests, ``dhsym check-assignment``, a tiny class graded, and variants."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from dhsym.checking import grade
from dhsym.checking.grading.assignment import Assignment
from dhsym.checking.grading.assignment_tests import key_answer, run_assignment_tests
from dhsym.checking.judging.checker import check_answer
from dhsym.checking.judging.key import PreparedKeys
from dhsym.cli.main import main
from dhsym.errors import DHError

HOMEWORK = """\
title: "Homework 7: the planar 2R arm as a product of exponentials"
key: planar2r
questions:
  - id: s
    ask: S
    points: 3
    credit: entries
    tests:
      right: ["[[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -a1, 0]]"]
      wrong:
        - {answer: "[[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, a1, 0]]", mistake: omega_cross_q}
        - {answer: "[[0, 0, 1, 0, a1 + a2, 0], [0, 0, 1, 0, a2, 0]]", mistake: body_for_space}
        - {answer: "[[0, 0, 0, 0, 0, 1], [0, -a1, 0, 0, 0, 1]]", mistake: rows_swapped}
  - id: b
    ask: B
    points: 2
    deduct: {space_for_body: 50%}
  - id: home
    ask: Mhome
    points: 1
    tests:
      wrong: [{answer: "[[1, 0, 0, a1], [0, 1, 0, 0], [0, 0, 1, 0]]", mistake: wrong_home}]
  - id: js
    ask: Js
    points: 2
  - id: fk
    ask: T(theta)
    points: 2
    tests:
      right:
        - "[[cos(theta1+theta2), -S12, 0, a1*C1+a2*C12], [S12, C12, 0, a1*S1+a2*S12], [0,0,1,0]]"
"""

RIGHT = {
    "s": "[[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -a1, 0]]",
    "b": "[[0, 0, 1, 0, a1 + a2, 0], [0, 0, 1, 0, a2, 0]]",
    "home": "[[1, 0, 0, a1 + a2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]",
    "js": "[[0, 0], [0, 0], [1, 1], [0, a1*S1], [0, -a1*C1], [0, 0]]",
    "fk": "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]",
}
SLIPS = {  # v = omega x q in S (1 of 12 entries), S for B (50% off), M of frame 1, J_b for J_s
    "s": "[[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, a1, 0]]",
    "b": "[[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -a1, 0]]",
    "home": "[[1, 0, 0, a1], [0, 1, 0, 0], [0, 0, 1, 0]]",
    "js": "[[0, 0], [0, 0], [1, 1], [a1*S2, 0], [a1*C2 + a2, a2], [0, 0]]",
    "fk": RIGHT["fk"],
}


def _write(folder: Path, text: str = HOMEWORK) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "hw.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_check_assignment_passes_the_key_and_the_question_tests(tmp_path: Path, capsys):
    hw = _write(tmp_path)
    report = run_assignment_tests(Assignment.load(hw))
    assert report.passed, report.text()
    got = [(r.question, r.case, r.got) for r in report.rows if r.case == "wrong"]
    assert got == [
        ("s", "wrong", "incorrect: omega_cross_q"),
        ("s", "wrong", "incorrect: body_for_space"),
        ("s", "wrong", "incorrect: rows_swapped"),
        ("home", "wrong", "incorrect: wrong_home"),
    ]
    assert main(["check-assignment", str(hw)]) == 0
    assert capsys.readouterr().out.endswith("11 passed, 0 failed\n")


def test_a_misnamed_mistake_fails_check_assignment(tmp_path: Path, capsys):
    hw = _write(
        tmp_path,
        "key: planar2r\nquestions:\n  - id: s\n    ask: S\n    tests:\n      wrong:\n"
        '        - {answer: "[[0,0,1,0,0,0],[0,0,1,0,a1,0]]", mistake: body_for_space}\n',
    )
    assert main(["check-assignment", str(hw)]) == 1
    out = capsys.readouterr().out
    assert "incorrect: omega_cross_q" in out and out.endswith("1 passed, 1 failed\n")


def test_a_tiny_class_is_graded_with_partial_credit_and_named_mistakes(tmp_path: Path):
    hw = _write(tmp_path / "hw")
    subs = tmp_path / "subs"
    for student, answers in {
        "ann": RIGHT,
        "ben": SLIPS,
        "eve": {"s": "__import__('os').system('echo hacked')", "fk": "T0_2"},
    }.items():
        (subs / student).mkdir(parents=True)
        for qid, text in answers.items():
            (subs / student / f"{qid}.txt").write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    report = grade(hw, subs, out, workers=0, progress=False)
    assert report.graded == 3 and report.failed == 0
    rows = {r["student"]: r for r in csv.DictReader((out / "gradebook.csv").open(encoding="utf-8"))}
    # ben: S 11 of 12 entries (2.75 of 3), B 1 of 2 (deducted), M and J_s 0, T(theta) 2
    assert {s: float(r["total"]) for s, r in rows.items()} == {"ann": 10.0, "ben": 5.75, "eve": 0.0}
    feedback = (out / "feedback" / "ben.md").read_text(encoding="utf-8")
    for title in (
        "v = ω × q for v = −ω × q",
        "space frame for body frame",
        "home configuration M read wrongly",
        "body frame for space frame",
    ):
        assert title in feedback, title
    assert not (tmp_path / "hacked").exists()


def test_variants_draw_the_lengths_and_the_keys_follow(tmp_path: Path):
    hw = _write(
        tmp_path,
        "key: planar2r\nsecret: hw.secret\nvariants: {a1: [1, 2, 3], a2: [0.5, 0.25]}\n"
        "questions:\n  - {id: s, ask: S}\n  - {id: fk, ask: T(theta)}\n  - {id: home, ask: M0}\n",
    )
    (tmp_path / "hw.secret").write_text("a-secret-for-the-screw-variants-0123\n")
    a = Assignment.load(hw)
    report = run_assignment_tests(a, samples=2)
    assert report.passed, report.text()
    assert len(report.rows) == 9 and all(r.variant for r in report.rows)  # 3 variants
    assert a.variants is not None
    mine = a.for_variant(a.variants.draw("ann"))
    keys = PreparedKeys()
    home = next(q for q in mine.questions if q.id == "home")
    text = key_answer(keys.get(home.key))
    assert "a1" not in text and "a2" not in text  # the student's numbers
    assert check_answer(home.key, text, keys=keys).correct


def test_a_bad_poe_question_names_the_file_row_and_field(tmp_path: Path):
    hw = _write(tmp_path, "key: planar2r\nquestions:\n  - {id: s, ask: S}\n  - {id: t, ask: S3}\n")
    with pytest.raises(DHError, match="the screw axes are S1 … S2") as err:
        Assignment.load(hw)
    assert (err.value.file, err.value.row, err.value.field) == (str(hw), 2, "ask")
