"""IK answers judged where the branch exists (issue 34, item 5): the derivations that
``dhsym derive NAME --what ik`` prints, fed back as answers to their own questions, in every
branch form, are graded CORRECT; one slip in a step is INCORRECT with the slip named."""

from __future__ import annotations

import itertools
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.checking import check_answer
from dhsym.checking.comparing.verdict import Verdict
from dhsym.checking.judging.ik_check import MIN_REAL_POSES, _where_real
from dhsym.checking.reading.limits import AnswerLimits
from dhsym.explain.documents import render_derivation

from .._keys import KEYS, load_key  # each key prepared once, as a grading worker does

ROBOTS = ("ur5", "puma560", "stanford")
_STATEMENT = re.compile(r"^ {5}([A-Za-z][A-Za-z0-9_]*) = (.+)$")


def printed_statements(name: str) -> list[str]:
    """The statements ``name = value`` of the printed derivation, as a student copies them
    (continuation lines joined; the prose, the abbreviations table and the special case
    of a singular wrist, printed after "If the wrist is singular … then", left out)."""
    text = render_derivation(dhsym.load(name), fmt="text", what="ik")
    text = text.split("\nAbbreviations")[0]
    out: list[str] = []
    special = False
    for line in text.splitlines():
        m = _STATEMENT.match(line)
        prose = m is not None and (":" in m.group(2) or m.group(1).startswith("sigma"))
        if m and not prose and "  " not in m.group(2).strip():
            if not special:
                out.append(f"{m.group(1)} = {m.group(2).strip()}")
            special = False
        elif out and re.match(r"^ {7,}[-+]", line):  # a long right-hand side, continued
            out[-1] += "" if special else " " + line.strip()
        elif line.rstrip().endswith("then"):  # the singular case's own statement follows
            special = True
    return out


def branch(statements: list[str], choice: dict[str, int]) -> str:
    """One branch: each ``sigma_k`` written as its sign."""
    text = "\n".join(statements)
    for name, sign in choice.items():
        text = re.sub(rf"\b{name}\*", "" if sign > 0 else "-", text)
    return text


def sigmas(statements: list[str]) -> list[str]:
    return sorted(set(re.findall(r"\bsigma_[0-9]+\b", "\n".join(statements))))


@pytest.fixture(scope="module", params=ROBOTS)
def derivation(request) -> tuple[str, list[str]]:
    return request.param, printed_statements(request.param)


def test_every_printed_branch_is_right(derivation):
    name, statements = derivation
    names = sigmas(statements)
    assert len(names) == 3, statements
    key = load_key(name, "ik")
    for signs in itertools.product((1, -1), repeat=len(names)):
        r = check_answer(key, branch(statements, dict(zip(names, signs))), keys=KEYS)
        assert r.verdict is Verdict.CORRECT, (signs, r.message)


def test_the_printed_sigma_form_is_every_solution(derivation):
    name, statements = derivation
    r = check_answer(load_key(name, "ik all"), "\n".join(statements), keys=KEYS)
    assert r.verdict is Verdict.CORRECT, r.message
    assert "8 branches" in r.message


def test_the_plus_minus_form_of_the_ur5():
    """Each sigma_k is written once in the UR5's derivation: ± is the same answer."""
    statements = printed_statements("ur5")
    text = re.sub(r"\bsigma_[0-9]+\*", "±", "\n".join(statements))
    assert text.count("±") == 3
    r = check_answer(load_key("ur5", "ik all"), text, keys=KEYS)
    assert r.verdict is Verdict.CORRECT, r.message
    r = check_answer(load_key("ur5", "ik"), text, keys=KEYS)  # each choice is a solution
    assert r.verdict is Verdict.CORRECT, r.message


def _mutants(statements: list[str]) -> list[tuple[str, int, str]]:
    """(kind, statement, text) per slip: atan2 arguments swapped, the last term of a sum
    with the other sign, left out; in the steps the joints need."""
    out = []
    for i, s in enumerate(statements):
        lhs, rhs = s.split(" = ", 1)
        m = re.search(r"atan2\(([^(),]+), ([^(),]+)\)", rhs)
        if m:
            swapped = rhs[: m.start()] + f"atan2({m.group(2)}, {m.group(1)})" + rhs[m.end() :]
            out.append(("atan2_swapped", i, f"{lhs} = {swapped}"))
        m = re.search(r" ([-+]) ([A-Za-z0-9_]+(\*[A-Za-z0-9_]+)*)$", rhs)
        if m:
            flipped = {"+": "-", "-": "+"}[m.group(1)]
            out.append(("wrong_sign", i, f"{lhs} = {rhs[: m.start()]} {flipped} {m.group(2)}"))
            out.append(("dropped_term", i, f"{lhs} = {rhs[: m.start()]}"))
    return out


def test_one_slip_in_a_step_is_named(derivation):
    name, statements = derivation
    names = sigmas(statements)
    key = load_key(name, "ik")
    right = branch(statements, dict.fromkeys(names, 1))
    lines = right.splitlines()
    tried = 0
    for kind, i, line in _mutants(lines):
        text = "\n".join([*lines[:i], line, *lines[i + 1 :]])
        # the diagnosis is tested here, not the time: the machine running the suite is shared
        r = check_answer(key, text, keys=KEYS, limits=AnswerLimits(seconds=120))
        if r.verdict is Verdict.CORRECT:
            # the step is not used by any joint, or the slip gives another branch (a sign
            # of a whole atan2 term): the answer is right, and must be
            assert _unused_or_other_branch(name, lines, i, line), (kind, line)
            continue
        tried += 1
        assert r.verdict is Verdict.INCORRECT
        assert kind in r.kinds, (kind, line, r.message)
    assert tried >= 10


def _unused_or_other_branch(name: str, lines: list[str], i: int, line: str) -> bool:
    lhs = lines[i].split(" = ")[0]
    used = any(re.search(rf"\b{lhs}\b", s.split(" = ", 1)[1]) for s in lines[i + 1 :])
    if not used:
        return True
    # another branch: the answer reaches the pose at every sample (check_answer said so)
    return "atan2" in line


# --- where the branch exists: the rule, as a property ------------------------------------------


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.booleans(), min_size=16, max_size=16),
    st.lists(st.booleans(), min_size=16, max_size=16),
)
def test_an_answer_is_a_branch_only_where_it_exists(exists, answered):
    """A row that equals branch 0 wherever branch 0 is real is judged branch 0 exactly when
    it has no value elsewhere (or a value that reaches the pose there); a value where the
    branch has none that does not reach the pose, or none where it exists, is wrong."""
    real = np.array([exists, [False] * 16])
    has = np.array(answered)
    row = np.where(has[:, None], 0.5, np.nan) * np.ones((16, 2))
    hits = np.array([real[0] & has, [False] * 16])
    got = _where_real(hits, real, row, lambda: np.zeros(16, dtype=bool))
    expected = (
        real[0].sum() >= MIN_REAL_POSES and (has == real[0]).all()  # exactly where it exists
    )
    assert (got == 0) is bool(expected)
    reaches = _where_real(hits, real, row, lambda: np.ones(16, dtype=bool))
    assert (reaches == 0) is bool(real[0].sum() >= MIN_REAL_POSES and (has | ~real[0]).all())


def test_a_branch_that_never_exists_accepts_nothing():
    real = np.zeros((1, 16), dtype=bool)
    row = np.full((16, 2), np.nan)
    assert _where_real(np.zeros((1, 16), dtype=bool), real, row, lambda: np.zeros(16, bool)) is None


@pytest.mark.parametrize(
    ("theta3", "words"),
    [
        # |1 - D3^2| under the root: real where the elbow has no solution
        ("atan2(sqrt(sqrt(Q_3)), D_3)", "where the branch does not exist"),
        # NaN wherever x_4 < 0, also where the branch exists
        ("atan2(sqrt(1 - D_3**2), D_3) + E_3 - sqrt(x_4)", "has no value at"),
    ],
)
def test_a_value_where_the_branch_has_none_or_none_where_it_has_one_is_wrong(theta3, words):
    statements = printed_statements("ur5")
    text = branch(statements, dict.fromkeys(sigmas(statements), 1))
    right = "theta3 = atan2(sqrt(1 - D_3**2), D_3)"
    assert right in text
    helpers = "E_3 = sqrt(x_4)\nQ_3 = (1 - D_3**2)**2"
    text = text.replace(right, f"{helpers}\ntheta3 = {theta3}")
    r = check_answer(load_key("ur5", "ik"), text, keys=KEYS, limits=AnswerLimits(seconds=60))
    assert r.verdict is Verdict.INCORRECT, r.message
    assert r.kinds[0] == "branch_domain", r.message
    assert words in r.message
