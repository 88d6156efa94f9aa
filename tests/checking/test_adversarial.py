"""The findings of a hostile grading campaign (issue 25), one test (or more) each.

Each test failed on the code before its fix: wrong answers graded right, right answers
graded wrong, grades lost in class runs, tracebacks instead of errors.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.checking import Key, check_answer
from dhsym.errors import DHError

HOMEWORK = Path(__file__).resolve().parents[2] / "examples" / "homework"


def verdict(robot: str, question: str, answer: object) -> str:
    return check_answer(Key.load(robot, question), answer).verdict.value


# --- 5: the notations of textbooks and numpy ------------------------------------------------


@pytest.mark.parametrize(
    "answer",
    [
        "cos(Atan2(S12, C12))",  # Craig
        "cos(arctan2(S12, C12))",  # numpy
        "cos(atan2(S12, C12))",
        r"\cos(\cos^{-1}(C12))",
        r"\cos\left(\operatorname{Atan2}(S_{12}, C_{12})\right)",
        "cos(cos^-1(C12))",
        "cos(arccos(C12))",
        "cos(acos(C12))",
        "tan(tan^-1(C12))",
        "sin(sin^-1 C12)",
    ],
)
def test_inverse_function_spellings_are_read(answer):
    assert verdict("planar2r", "T0_2[0,0]", answer) == "correct"


# --- 15, 16: errors, not tracebacks ---------------------------------------------------------


@pytest.mark.parametrize("address", ["garbage://x", "", "tcp://[::1", 5])
def test_dask_address_is_checked_before_anything_runs(address, tmp_path):
    from dhsym.checking import grade

    with pytest.raises(DHError, match="--dask"):
        grade(HOMEWORK / "assignment.yaml", tmp_path, tmp_path / "out", dask=address)


x = sp.Symbol("theta1", real=True)


@pytest.mark.parametrize(
    ("answer", "expected"),
    [
        (5, "incorrect"),
        (sp.cos(x), "incorrect"),
        (sp.Symbol("a1", positive=True) * sp.cos(x) + 0, "incorrect"),
        ([1, 2], "unreadable"),
        (np.float64(0.5), "incorrect"),
        ({1: 2}, "unreadable"),
        (True, "unreadable"),
        (object(), "unreadable"),
    ],
)
def test_check_takes_numbers_and_sympy_objects_or_refuses_clearly(answer, expected):
    result = dhsym.check(answer, key="planar2r", question="px").result
    assert result.verdict.value == expected
    if expected == "unreadable":
        assert "expected" in result.reason or "matrix" in result.reason


def test_check_reads_a_sympy_matrix_and_a_list_of_statements():
    a1, a2 = sp.symbols("a1 a2", positive=True)
    t2 = sp.Symbol("theta2", real=True)
    px = a1 * sp.cos(x) + a2 * sp.cos(x + t2)
    assert dhsym.check(px, key="planar2r", question="px").result.verdict.value == "correct"
    key = Key.load("planar2r", "T0_2")
    matrix = dhsym.Robot(key.table).transform(0, 2).matrix  # the key's own, a sympy matrix
    assert check_answer(key, matrix).verdict.value == "correct"
    assert check_answer(key, matrix.tolist()).verdict.value == "correct"


def test_a_key_of_the_wrong_type_is_refused_clearly():
    with pytest.raises(DHError, match="got int"):
        dhsym.check("C1", key=5, question="px")
