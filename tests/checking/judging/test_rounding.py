"""Rounding the instructor controls: the rule, the test, per check and per assignment."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dhsym.checking import Assignment, Key, check_answer
from dhsym.checking.judging.key import PreparedKeys
from dhsym.checking.judging.rounding import DEFAULT_ROUNDING, Rounding
from dhsym.errors import DHError

from .test_dynamics_questions import TABLE as SPONG

CORPUS = Path(__file__).resolve().parents[2] / "data" / "answers"
TWIST45 = CORPUS / "tables" / "twist45.yaml"  # entry T0_1[2,1] is sqrt(2)/2 = 0.70710678…


def check(answer: str, rounding: object = None, question: str = "T0_1[2,1]"):
    return check_answer(Key.load(TWIST45, question, rounding=rounding), answer)


@pytest.mark.parametrize(
    ("spec", "text"),
    [
        (None, "digits=3"),
        ("digits=4", "digits=4"),
        ("4 digits", "digits=4"),
        ({"digits": 2}, "digits=2"),
        ("abs=1e-3", "abs=0.001"),
        ({"rel": 0.01}, "rel=0.01"),
        ("off", "off"),
        (False, "off"),  # YAML reads 'rounding: off' as false
        (Rounding("abs", tolerance=0.5), "abs=0.5"),
    ],
)
def test_rounding_rules_are_read(spec, text):
    assert str(Rounding.parse(spec)) == text


@pytest.mark.parametrize("spec", ["digits=0", "digits=x", "abs=-1", "rel=0", "sometimes", 3])
def test_bad_rounding_rules_are_refused(spec):
    with pytest.raises(DHError, match="rounding"):
        Rounding.parse(spec)


@pytest.mark.parametrize(
    ("answer", "verdict"),
    [
        ("0.7071", "correct"),  # rounded to 4 digits
        ("0.707", "correct"),  # rounded and truncated to 3 digits
        ("0.70711", "correct"),
        ("0.7072", "incorrect"),  # neither rounded nor truncated
        ("0.71", "incorrect"),  # 2 significant digits: must be exact
        ("0.7", "incorrect"),
        ("sqrt(2)/2", "correct"),
    ],
)
def test_default_rule_digits_written_and_at_least_three(answer, verdict):
    assert DEFAULT_ROUNDING == Rounding("digits", 3)
    assert check(answer).verdict.value == verdict


@pytest.mark.parametrize(
    ("answer", "verdict"),
    [
        # the toolbox printout of IRob2305 Lecture 5 (fkine of the PUMA 560 at zero), as
        # numpy and MATLAB print it: -0.15005 to 4 decimals, its trailing zeros dropped
        ("[[1, 0, 0, 0.4521], [0, 1, 0, -0.15], [0, 0, 1, 0.4318], [0, 0, 0, 1]]", "correct"),
        (
            "[[1., 0., 0., 0.4521], [0., 1., 0., -0.15], [0., 0., 1., 0.4318], [0., 0., 0., 1.]]",
            "correct",
        ),
        ("[[1, 0, 0, 0.4521], [0, 1, 0, -0.1501], [0, 0, 1, 0.4318], [0, 0, 0, 1]]", "correct"),
        # to 4 decimals, -0.16 and -0.1 are -0.1600 and -0.1000: wrong
        ("[[1, 0, 0, 0.4521], [0, 1, 0, -0.16], [0, 0, 1, 0.4318], [0, 0, 0, 1]]", "incorrect"),
        ("[[1, 0, 0, 0.4521], [0, 1, 0, -0.1], [0, 0, 1, 0.4318], [0, 0, 0, 1]]", "incorrect"),
        # every entry to 2 decimals: 2 significant digits are too few, as before
        ("[[1, 0, 0, 0.45], [0, 1, 0, -0.15], [0, 0, 1, 0.43], [0, 0, 0, 1]]", "incorrect"),
    ],
)
def test_a_printed_matrix_keeps_its_decimals_with_trailing_zeros_dropped(answer, verdict):
    assert check_answer(Key.load("puma560", "fk@0,0,0,0,0,0"), answer).verdict.value == verdict


def test_the_issue_examples():
    puma = "puma560"
    pi_half = check_answer(Key.load(puma, "T0_3[0,1]"), "cos(theta1 + 1.5708)")
    assert pi_half.correct and pi_half.entries[0].proof == "rounding"
    a3 = check_answer(Key.load(puma, "T0_3[2,3]"), "0.4318 S2 + 0.02 S23")  # a3 = 0.0203
    assert not a3.correct


def test_feedback_says_up_to_rounding_and_to_how_many_digits():
    r = check("0.7071")
    assert r.message == "The entry is right up to rounding (to 4 significant digits)."
    assert r.entries[0].rounding == "to 4 significant digits"
    assert r.to_json()["entries"][0]["rounding"] == "to 4 significant digits"
    m = check(
        "[[C1, -0.707*S1, 0.7071*S1, a1*C1], [S1, 0.7071*C1, -0.7071*C1, a1*S1],"
        " [0, 0.7071, 0.7071, 0]]",
        question="T0_1",
    )
    assert m.correct
    assert m.message == (
        "All 16 entries are right; 6 of them up to rounding "
        "(to 3 significant digits; to 4 significant digits)."
    )
    assert check("0.71", "abs=0.01").message.endswith("(within an absolute tolerance of 0.01).")


@pytest.mark.parametrize(
    ("answer", "rounding", "verdict"),
    [
        ("0.71", "digits=2", "correct"),
        ("0.71", None, "incorrect"),
        ("0.7071", "digits=5", "incorrect"),
        ("0.71", "abs=0.01", "correct"),
        ("0.72", "abs=0.01", "incorrect"),
        ("0.7075", "rel=0.001", "correct"),
        ("0.7", "rel=0.001", "incorrect"),
        ("0.7071", "off", "incorrect"),
        ("sqrt(2)/2", "off", "correct"),
    ],
)
def test_the_instructor_sets_the_rounding_both_ways(answer, rounding, verdict):
    assert check(answer, rounding).verdict.value == verdict


def test_rounding_in_the_assignment_and_per_question(tmp_path):
    (tmp_path / "twist45.yaml").write_text(TWIST45.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "hw.yaml").write_text(
        "key: twist45.yaml\nrounding: digits=2\nquestions:\n"
        "  - {id: q1, ask: 'T0_1[2,1]'}\n"
        "  - {id: q2, ask: 'T0_1[2,1]', rounding: off}\n"
        "  - {id: q3, ask: 'T0_1[2,1]', rounding: {abs: 0.1}}\n",
        encoding="utf-8",
    )
    a = Assignment.load(tmp_path / "hw.yaml")
    assert [str(q.key.rounding) for q in a.questions] == ["digits=2", "off", "abs=0.1"]
    verdicts = [check_answer(q.key, "0.71").verdict.value for q in a.questions]
    assert verdicts == ["correct", "incorrect", "correct"]
    (tmp_path / "bad.yaml").write_text(
        "key: twist45.yaml\nrounding: roughly\nquestions: [{id: q1, ask: A1}]\n", encoding="utf-8"
    )
    with pytest.raises(DHError, match="bad.yaml.*unknown rounding 'roughly'"):
        Assignment.load(tmp_path / "bad.yaml")


# Spong's two-link planar elbow arm (Robot Modeling and Control): M[1,1] = m2 lc2² + I2 and
# the tip's x = l1 C1 + l2 C12.
# The keys are loaded by the worker that runs these tests, not by every worker at collection.
SPONG_QUESTIONS = {"M22": "M[1,1]", "PX": "T0_2[0,3]"}


@pytest.fixture(scope="module")
def spong() -> dict[str, Key]:
    return {name: Key.load(SPONG, q) for name, q in SPONG_QUESTIONS.items()}


@pytest.fixture(scope="module")
def prepared() -> PreparedKeys:
    """The keys prepared once for the many answers of a property (as a grading worker does)."""
    return PreparedKeys()


@pytest.mark.parametrize(
    ("key", "answer"),
    [
        ("M22", "1.00*(m2*lc2**2 + I2)*(1 + S2/300)"),
        ("M22", "1.00**64*1.00**64*1.00**64*(m2*lc2**2 + I2)*(2 + S2)"),
        ("PX", "1.00*(l1*C1 + l2*C12)*(1 + S1/300)"),
        ("PX", "1.00**64*1.00**64*1.00**64*(l1*C1 + l2*C12)*(1 + S1/3)"),
        ("PX", "1.000*l1*C1 + 1.00*l2*C12*(1 + S2/400)"),
    ],
)
def test_decimals_cannot_absorb_an_error_that_varies_with_q(key, answer, spong):
    """Issue 34, item 4: each decimal stands for one value, the same at every point."""
    assert check_answer(spong[key], answer).verdict.value == "incorrect"


@pytest.mark.parametrize(
    ("key", "answer"),
    [
        ("M22", "1.00*(m2*lc2**2 + I2)"),
        ("M22", "1.00**64*1.000**8*(m2*lc2**2 + I2)"),
        ("PX", "l1*cos(q1 + 0.000) + l2*cos(q1 + q2)"),
        ("PX", "l1*sin(q1 + 1.5708) + l2*0.7071**2*2*C12"),
    ],
)
def test_honestly_rounded_decimals_stay_right(key, answer, spong):
    r = check_answer(spong[key], answer)
    assert r.correct, r.message


FACTORS = st.sampled_from(["S2", "C2", "S1", "C12", "q2", "S2**2", "lc2", "m1"])
DECIMALS = st.sampled_from(["1.00", "1.000", "0.999", "1.001", "1.00**64", "1.000**16", "1.01"])


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    factor=FACTORS,
    size=st.fractions(min_value=Fraction(1, 2000), max_value=Fraction(2)),
    decimals=st.lists(DECIMALS, min_size=1, max_size=4),
    where=st.sampled_from(["outside", "inside"]),
)
def test_key_times_a_varying_factor_is_never_right(spong, prepared, factor, size, decimals, where):
    """key × (1 + f(q)), f not constant, whatever decimals are added: never correct."""
    scale = "*".join(decimals)
    f = f"({size.numerator}/{size.denominator})*{factor}"
    if where == "outside":
        answer = f"{scale}*(m2*lc2**2 + I2)*(1 + {f})"
    else:
        answer = f"(m2*{scale}*lc2**2 + I2*{scale})*(1 + {f})"
    r = check_answer(spong["M22"], answer, keys=prepared)
    assert not r.correct, (answer, r.message)


def test_a_long_rounding_rule_is_not_echoed_in_full():
    """Issue 34, item 8: user input echoed in an error is cut short."""
    with pytest.raises(DHError) as err:
        Rounding.parse("roughly " * 12_500)
    assert len(str(err.value)) < 300 and "roughly" in str(err.value)
