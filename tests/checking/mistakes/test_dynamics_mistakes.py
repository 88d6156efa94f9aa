"""The dynamics mistakes made in one link only, named once with the entries they explain
(issue 34, item 3)."""

from __future__ import annotations

import pytest

from dhsym.checking import Key
from dhsym.checking.comparing.verdict import Verdict

from .._keys import check_answer, load_key  # each key prepared once, as a grading worker does


@pytest.fixture(scope="module")
def spong_m() -> Key:
    return load_key("spong2r", "M")


def test_l2_for_lc2_throughout_is_one_diagnosis_naming_its_entries(spong_m):
    r = check_answer(
        spong_m,
        "[[I1 + I2 + lc1**2*m1 + m2*(l1**2 + 2*l1*l2*C2 + l2**2), I2 + m2*(l1*l2*C2 + l2**2)],"
        " [I2 + m2*(l1*l2*C2 + l2**2), I2 + l2**2*m2]]",
    )
    assert r.verdict is Verdict.INCORRECT
    (d,) = r.diagnoses
    assert d.kind == "l_for_lc"
    assert d.entries == ((1, 1), (1, 2), (2, 1), (2, 2))
    assert d.detail.startswith("l2 written for lc2 in entries (1,1), (1,2), (2,1) and (2,2)")


def test_a_missing_m1_lc1_squared_is_the_parallel_axis_mistake(spong_m):
    r = check_answer(
        spong_m,
        "[[I1 + I2 + m2*(l1**2 + 2*l1*lc2*C2 + lc2**2), I2 + m2*(l1*lc2*C2 + lc2**2)],"
        " [I2 + m2*(l1*lc2*C2 + lc2**2), I2 + lc2**2*m2]]",
    )
    assert r.verdict is Verdict.INCORRECT
    assert r.kinds == ("parallel_axis",), r.diagnoses
    assert "link 1" in r.diagnoses[0].detail
