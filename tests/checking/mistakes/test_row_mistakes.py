"""Two slips in one DH table (issue 34, item 3): each pair of catalogued table mistakes is
named by both its kinds, on the rows it touches, within a count of tables compared."""

from __future__ import annotations

from dataclasses import replace

import pytest
import sympy as sp

import dhsym
from dhsym.checking.comparing.table_match import Chain
from dhsym.checking.comparing.verdict import Verdict
from dhsym.checking.grading.credit import Credit
from dhsym.checking.mistakes._row_mistakes import explain_table_pairs, shifted
from dhsym.checking.mistakes.registry import (
    PAIR_BUDGET,
    TABLE_PAIR_MISTAKES,
    TableCase,
    diagnose_table,
)

from .._keys import check_answer, load_key  # each key prepared once, as a grading worker does

PUMA = dhsym.load_table("puma560")
HEAD = "| j | θ | d | a | α |\n|---|---|---|---|---|\n"
ROWS = (
    "| 1 | θ1 | 0 | 0 | 90° |",
    "| 2 | θ2 | 0 | a2 | 0 |",
    "| 3 | θ3 | d3 | a3 | -90° |",
    "| 4 | θ4 | d4 | 0 | 90° |",
    "| 5 | θ5 | 0 | 0 | -90° |",
    "| 6 | θ6 | 0 | 0 | 0 |",
)


def puma(**changed: str):
    """The PUMA 560 table as a student types it, rows ``r<k>`` replaced, checked."""
    rows = [changed.get(f"r{k}", row) for k, row in enumerate(ROWS, 1)]
    return check_answer(load_key("puma560", "table"), HEAD + "\n".join(rows))


def found(result) -> list[tuple[str, tuple[int, ...]]]:
    return [(d.kind, d.rows) for d in result.diagnoses]


def test_the_typed_table_is_right():
    assert puma().verdict is Verdict.CORRECT


@pytest.mark.parametrize(
    ("changed", "expected"),
    [
        # -90° written 1.5708 in a table in degrees: radians read as degrees, and the sign
        (
            {"r3": "| 3 | θ3 | d3 | a3 | 1.5708 |"},
            [("degrees_as_radians", (3,)), ("wrong_sign", (3,))],
        ),
        # two slips of one kind in two rows
        (
            {"r2": "| 2 | θ2 | 0 | -a2 | 0 |", "r5": "| 5 | θ5 | 0 | 0 | 90° |"},
            [("wrong_sign", (2,)), ("wrong_sign", (5,))],
        ),
        # two rows, each with one wrong entry
        (
            {"r2": "| 2 | θ2 | 0 | 0.5 | 0 |", "r4": "| 4 | θ4 | 0.3 | 0 | 90° |"},
            [("single_wrong_row", (2,)), ("single_wrong_row", (4,))],
        ),
        # a named slip and one wrong entry elsewhere: the named slip is named
        (
            {"r2": "| 2 | θ2 | 0 | -a2 | 0 |", "r4": "| 4 | θ4 | 0.3 | 0 | 90° |"},
            [("wrong_sign", (2,)), ("single_wrong_row", (4,))],
        ),
        # the radians of two rows in a table in degrees
        (
            {"r1": "| 1 | θ1 | 0 | 0 | 1.5708 |", "r4": "| 4 | θ4 | d4 | 0 | 1.5708 |"},
            [("degrees_as_radians", (1,)), ("degrees_as_radians", (4,))],
        ),
    ],
)
def test_two_slips_in_a_typed_table_are_both_named(changed, expected):
    r = puma(**changed)
    assert r.verdict is Verdict.INCORRECT
    assert found(r) == expected
    first, second = r.diagnoses
    assert first.title in r.message and second.detail in r.message
    assert "two slips" in r.message


def test_one_slip_is_still_one_diagnosis():
    # single diagnoses are unchanged: a sign, and one wrong row with two wrong cells
    assert found(puma(r3="| 3 | θ3 | d3 | a3 | 90° |")) == [("wrong_sign", (3,))]
    r = puma(r2="| 2 | θ2 | 0.2 | 0.5 | 0 |")
    assert found(r) == [("single_wrong_row", (2,))]
    assert "two slips" not in r.message
    # a3 for a2 (the example class's grace) is no sign of a2 overwritten by a wrong cell
    assert found(puma(r2="| 2 | θ2 | 0 | a3 | 0 |")) == [("single_wrong_row", (2,))]


def test_three_slips_are_not_forced_into_a_pair():
    r = puma(
        r2="| 2 | θ2 | 0 | 0.5 | 0 |",
        r4="| 4 | θ4 | 0.3 | 0 | 90° |",
        r6="| 6 | θ6 | d6 | 0 | 0 |",
    )
    assert r.verdict is Verdict.INCORRECT
    assert found(r) == [("geometry", ())]


def test_index_shift_and_offset_missing():
    key = dhsym.load_table("example4_6dof")  # theta3 + pi/2 in row 3
    rows = list(shifted(tuple(key.rows), 1, ("alpha", "a")))
    rows[2] = replace(rows[2], theta=rows[2].variable)
    d = diagnose_table(TableCase(key, Chain(tuple(rows), key.convention)))
    assert [x.kind for x in d] == ["index_shift", "offset_missing"]
    assert d[1].rows == (3,) and "theta3 + pi/2" in d[1].detail
    assert "the other: joint offset missing" in d[0].detail


def test_the_second_slip_is_told_against_the_key():
    # degrees as radians in every row, and a sign of a length: the length is the key's
    rows = [replace(r, alpha=r.alpha * 180 / sp.pi) for r in PUMA.rows]
    rows[2] = replace(rows[2], d=-rows[2].d)
    d = diagnose_table(TableCase(PUMA, Chain(tuple(rows), PUMA.convention)))
    assert [x.kind for x in d] == ["degrees_as_radians", "wrong_sign"]
    assert "Row 3: d has the wrong sign; it is d3 (= 0.15005)." in d[1].detail


def test_the_search_is_bounded_by_a_count():
    rows = list(PUMA.rows)
    rows[1], rows[4] = replace(rows[1], a=-rows[1].a), replace(rows[4], alpha=sp.pi / 2)
    case = TableCase(PUMA, Chain(tuple(rows), PUMA.convention))
    assert len(explain_table_pairs(case, TABLE_PAIR_MISTAKES, PAIR_BUDGET)) == 2
    assert explain_table_pairs(case, TABLE_PAIR_MISTAKES, 0) == ()
    assert explain_table_pairs(TableCase(PUMA, PUMA), TABLE_PAIR_MISTAKES) == ()


def test_credit_by_rows_of_a_table_with_two_slips():
    r = puma(r2="| 2 | θ2 | 0 | -a2 | 0 |", r4="| 4 | θ4 | 0.3 | 0 | 90° |")
    assert Credit("entries").award(6.0, r) == (
        4.0,
        "partial credit: 4 of 6 rows right, 4 of 6 points",
    )


def test_deductions_of_a_table_with_two_slips():
    r = puma(r2="| 2 | θ2 | 0 | -a2 | 0 |", r4="| 4 | θ4 | 0.3 | 0 | 90° |")
    # the rows the two slips name are the wrong rows (credit: entries counts them)
    assert {k for d in r.diagnoses for k in d.rows} == {2, 4}
    # deducted only when every mistake named is a deducted kind
    assert Credit(deduct=(("wrong_sign", 0.25),)).award(4.0, r) == (0.0, "")
    both = Credit(deduct=(("wrong_sign", 0.25), ("single_wrong_row", 0.25)))
    assert both.award(4.0, r)[0] == 2.0
    signs = puma(r2="| 2 | θ2 | 0 | -a2 | 0 |", r5="| 5 | θ5 | 0 | 0 | 90° |")
    assert Credit(deduct=(("wrong_sign", 0.25),)).award(4.0, signs)[0] > 0


def test_a_sign_after_a_shift_is_told_as_a_second_slip():
    # α and a from the previous row, and the sign of the α that moved into row 5
    rows = list(shifted(tuple(PUMA.rows), -1, ("alpha", "a")))
    rows[4] = replace(rows[4], alpha=-rows[4].alpha)
    d = diagnose_table(TableCase(PUMA, Chain(tuple(rows), PUMA.convention)))
    assert [x.kind for x in d] == ["index_shift", "wrong_sign"]
    assert d[1].rows == (5,) and "Row 5: alpha has the wrong sign too." in d[1].detail


def test_every_row_in_radians_is_one_slip_not_a_pair():
    cartesian = dhsym.load_table("cartesian")  # prismatic joints, fixed angles in two rows
    rows = [
        replace(r, theta=r.theta * sp.pi / 180, alpha=r.alpha * sp.pi / 180) for r in cartesian.rows
    ]
    d = diagnose_table(TableCase(cartesian, Chain(tuple(rows), cartesian.convention)))
    assert [x.kind for x in d] == ["degrees_as_radians"]
    rows[1] = cartesian.rows[1]  # row 1 alone in radians: the slip of one row
    d = diagnose_table(TableCase(cartesian, Chain(tuple(rows), cartesian.convention)))
    assert [(x.kind, x.rows) for x in d] == [("degrees_as_radians", (1,))]
