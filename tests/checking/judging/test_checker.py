"""check_answer: verdicts, proofs, rounding, unknown symbols, never raises on bad answers."""

from __future__ import annotations

from pathlib import Path

import dhsym
from dhsym.checking import Key, check_answer

ROOT = Path(__file__).resolve().parents[3]

KEY = Key.load("planar2r", "T0_2")
RIGHT = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]"


def test_right_answers_in_other_forms_are_exactly_proven():
    expanded = (
        "[[c1*c2 - s1*s2, -s1*c2 - c1*s2, 0, a1*c1 + a2*(c1*c2 - s1*s2)],"
        " [s1*c2 + c1*s2, c1*c2 - s1*s2, 0, a1*s1 + a2*(s1*c2 + c1*s2)], [0,0,1,0]]"
    )
    r = check_answer(KEY, expanded)
    assert r.correct and {e.proof for e in r.entries} == {"exact"}


def test_numbers_for_lengths_and_rounding():
    key = Key.load("puma560", "T0_1")
    r = check_answer(key, "[[c1, 0, s1, 0], [s1, 0, -c1, 0], [0, 1, 0, 0]]")
    assert r.correct
    puma = dhsym.load("puma560")
    pz = puma.arm_matrix().matrix[2, 3].subs(puma.table.value_map)  # lengths as numbers
    r = check_answer(Key.load("puma560", "T0_6[2,3]"), puma.notation.text(pz))
    assert r.correct, r.message
    approx = check_answer(Key.load("planar2r", "T0_2[0,0]"), "0.70711*1.41421*C12")
    assert approx.correct and approx.entries[0].proof == "rounding"


def test_unknown_symbols_are_named():
    r = check_answer(Key.load("planar2r", "T0_2[0,3]"), "a1*C1 + a3*C12")
    assert not r.correct and r.kinds[0] == "unknown_symbol" and "a3" in r.diagnoses[0].detail


def test_wrong_answer_lists_wrong_entries_in_key_notation():
    r = check_answer(KEY, RIGHT.replace("a1*S1 + a2*S12", "a1*S1 + a2*C12"))
    wrong = [e for e in r.entries if not e.correct]
    assert [(e.row, e.col) for e in wrong] == [(2, 4)]
    assert wrong[0].expected == "a1*S1 + a2*S12" and wrong[0].answer == "a1*S1 + a2*C12"
    assert wrong[0].expected_latex == "a_{1} S_{1} + a_{2} S_{12}"


def test_table_answers_report_both_tables():
    r = check_answer(Key.load("planar2r", "table"), "theta,d,a,alpha\nq1,0,a1,0\nq2,0,a2,0")
    assert r.correct and r.answer_table[0][0] == "i" and len(r.expected_table) == 3


def test_a_bug_in_dhsym_is_raised_not_graded_unreadable(monkeypatch):
    from dhsym.checking.judging import checker

    def bug(*args, **kwargs):
        raise TypeError("a bug of dhsym")

    monkeypatch.setattr(checker, "check_matrix", bug)
    key = Key.load("planar2r", "T0_2[0,3]")
    try:
        check_answer(key, "a1*C1 + a2*C12")
    except TypeError as err:
        assert "a bug of dhsym" in str(err)
    else:  # pragma: no cover - the test fails here
        raise AssertionError("a TypeError inside dhsym was turned into a verdict")
    monkeypatch.undo()
    assert check_answer(key, "a1*C1 + (").verdict.value == "unreadable"  # parse errors still are


def test_a_key_that_cannot_be_checked_against_is_refused_not_blamed_on_answers():
    import pytest

    from dhsym.errors import DHError

    with pytest.raises(DHError, match="2 joints, got 3 values"):
        Key.load("planar2r", "ik@1,2,3")


def test_one_wrong_entry_of_several_is_singular():
    """Issue 34, item 8: "1 of 4 entries is wrong", "2 of 4 entries are wrong"."""
    key = Key.load("planar2r", "T0_2")
    one = check_answer(
        key, "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 - a2*S12], [0, 0, 1, 0]]"
    )
    assert one.message.startswith("1 of 16 entries is wrong."), one.message
    two = check_answer(
        key, "[[C12, -S12, 0, a1*C1 - a2*C12], [S12, C12, 0, a1*S1 - a2*S12], [0, 0, 1, 0]]"
    )
    assert two.message.startswith("2 of 16 entries are wrong."), two.message


def test_the_guides_example_answers_are_right():
    """Issue 34, item 8: each example answer of the guide's table of question kinds is
    graded right against the example assignment's key (the PUMA 560 for T0_6[0,3])."""
    guide = (ROOT / "docs" / "guide" / "assignments.md").read_text(encoding="utf-8")
    row = next(line for line in guide.splitlines() if line.startswith("| `T0_6[0,3]`"))
    answer = row.rsplit("|", 2)[-2].strip().strip("`")
    assert check_answer(Key.load("puma560", "T0_6[0,3]"), answer).correct, answer
