"""The mistakes students really make, named in feedback (issue 24, item 2), and a sample
of the mutation benchmark (``benchmarks/bench_mutations.py``)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from dhsym.checking import Key
from dhsym.checking.comparing.verdict import Verdict

from .._keys import KEYS, check_answer, load_key  # each key prepared once, as a grading worker does

PX = "T0_6[0,3]"  # p_x of the PUMA 560: C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1


@pytest.fixture(scope="module")
def px() -> Key:
    return load_key("puma560", PX)


@pytest.mark.parametrize(
    ("answer", "kind", "words"),
    [
        ("C1*(a2*C2 - a3*C23 - d4*S23) + d3*S1", "wrong_sign", "a3*C23 has the wrong sign"),
        ("a2*C1*C2 - a3*C1*C23 - d4*C1*S23 + d3*S1", "wrong_sign", "wrong sign"),
        ("C1*(a2*C2 + a3*C23) + d3*S1", "dropped_term", "-d4*S23 is missing"),
        (
            "C1*(a2*C2 + a3*C23 - d4*C23) + d3*S1",
            "sin_cos_swapped",
            "C23 is written where S23 belongs",
        ),
        ("C1*(a2*C2 + a3*C12 - d4*S23) + d3*S1", "wrong_joint_index", "C12 is written where C23"),
        ("C1*(a2*C2 + C23 - d4*S23) + d3*S1", "missing_length", "length a3 is missing"),
    ],
)
def test_a_single_slip_is_named(px, answer, kind, words):
    r = check_answer(px, answer)
    assert r.verdict is Verdict.INCORRECT
    assert r.kinds[0] == kind, r.message
    assert words in r.message, r.message
    assert "none of the usual mistakes" not in r.message


def test_the_transpose_of_one_jacobian_block_is_named():
    import sympy as sp

    key = load_key("puma560", "J")
    J = sp.Matrix(KEYS.get(key).part.expected)
    J[0:3, 0:3] = J[0:3, 0:3].T
    nota = key_notation(key)
    text = "[" + ", ".join("[" + ", ".join(nota.text(x) for x in row) + "]" for row in J.tolist())
    r = check_answer(key, text + "]")
    assert r.verdict is Verdict.INCORRECT
    assert r.kinds[0] == "transposed", r.message
    assert "block of columns 1 to 3" in r.message


def key_notation(key: Key):
    from dhsym.robot import Robot

    return Robot(key.table).notation


@pytest.mark.slow
def test_mutation_benchmark_sample():
    """A seeded sample of the benchmark: every kind named, no correct answer graded wrong."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "benchmarks"))
    import bench_mutations as bm

    mutants = bm.matrix_mutants("planar2r", "T0_2") + bm.matrix_mutants("example1_rrp", "T0_3")
    mutants += bm.degree_mutants("planar2r")
    outcomes = bm.run(mutants)
    correct = [o for o in outcomes if o.mutant.kind is None]
    wrong = [o for o in outcomes if o.mutant.kind is not None]
    assert correct and not [o for o in correct if o.false_wrong]
    assert {o.mutant.kind for o in wrong} >= {"wrong_sign", "dropped_term", "sin_cos_swapped"}
    right = sum(o.right for o in wrong) / len(wrong)
    assert right >= 0.95, [(o.mutant.where, o.mutant.kind, o.kind) for o in wrong if not o.right]


# --- two slips in one place, and one mistake said once (issue 34, item 3) -------------------


@pytest.mark.parametrize(
    ("answer", "kinds", "words"),
    [
        # a sign and S1 for C1 in one entry (the example)
        ("C1*(a2*C2 + a3*C23 + d4*S23) + d3*C1", {"wrong_sign", "sin_cos_swapped"}, "d4*S23"),
        # a dropped term and a missing length
        ("C1*(C2 + a3*C23) + d3*S1", {"dropped_term", "missing_length"}, "a2 is missing"),
        # a wrong joint index and a wrong sign
        ("C1*(a2*C2 - a3*C12 - d4*S23) + d3*S1", {"wrong_joint_index", "wrong_sign"}, "C12"),
    ],
)
def test_two_slips_in_one_entry_are_both_named(px, answer, kinds, words):
    r = check_answer(px, answer)
    assert r.verdict is Verdict.INCORRECT
    assert set(r.kinds) == kinds, r.diagnoses
    assert "none of the usual mistakes" not in " ".join(d.detail for d in r.diagnoses)
    assert words in " ".join(d.detail for d in r.diagnoses)
    assert all(d.entries == ((1, 4),) for d in r.diagnoses)


def test_one_slip_in_several_entries_is_said_once():
    """S1 written for C1 in p_x and p_y of the 2R: one message naming both entries."""
    key = load_key("planar2r", "T0_2")
    r = check_answer(
        key, "[[C12, -S12, 0, a1*S1 + a2*C12], [S12, C12, 0, a1*C1 + a2*S12], [0,0,1,0], [0,0,0,1]]"
    )
    assert r.verdict is Verdict.INCORRECT
    (d,) = r.diagnoses
    assert d.kind == "sin_cos_swapped" and d.entries == ((1, 4), (2, 4))
    assert d.detail.count("entries (1,4) and (2,4)") == 1, d.detail


def test_an_unexplained_entry_stays_unexplained(px):
    """Three slips (or a rewrite no pair of catalogued slips gives) are no pair."""
    r = check_answer(px, "C1*(a2*S2 - a3*C23 - d4*S23) + 7*d3*S1")
    assert r.verdict is Verdict.INCORRECT
    assert r.kinds == ("unexplained",)


@pytest.mark.parametrize(
    ("answer", "kind", "words"),
    [
        # two terms with the wrong sign (one inside the bracket)
        ("C1*(a2*C2 - a3*C23 - d4*S23) - d3*S1", "wrong_sign", ("a3*C23", "d3*S1")),
        # two lengths left out
        ("C1*(C2 + a3*C23 - S23) + d3*S1", "missing_length", ("a2", "d4")),
        # two terms left out
        ("C1*a2*C2 + d3*S1", "dropped_term", ("a3*C23", "-d4*S23")),
    ],
)
def test_two_slips_of_one_kind_in_one_entry_are_both_named(px, answer, kind, words):
    r = check_answer(px, answer)
    assert r.verdict is Verdict.INCORRECT
    assert r.kinds == (kind, kind), r.diagnoses
    details = [d.detail for d in r.diagnoses]
    assert "of this kind" in details[0] and "of this kind" in details[1]
    for word in words:
        assert word in " ".join(details), (word, details)
    assert all(d.entries == ((1, 4),) for d in r.diagnoses)


# --- two slips found by what each changes (issue 34, item 3: the benchmark's double edits) -


def _jacobian_with(robot: str, entry: tuple[int, int], written: str) -> tuple[Key, str]:
    """The key's J of ``robot`` as a student types it, with one entry written otherwise."""
    import sympy as sp

    key = load_key(robot, "J")
    nota = key_notation(key)
    rows = [[nota.text(x) for x in row] for row in sp.Matrix(KEYS.get(key).part.expected).tolist()]
    rows[entry[0]][entry[1]] = written
    return key, "[" + ", ".join("[" + ", ".join(r) + "]" for r in rows) + "]"


@pytest.mark.parametrize(
    ("robot", "entry", "written", "words"),
    [
        # -S1*S23: S23 swapped for C23, and C23 moved to C34
        ("puma560", (4, 3), "-S1*C34", ("C23 is written where S23", "C34 is written where C23")),
        # S23*S4
        ("puma560", (5, 4), "C34*S4", ("C23 is written where S23", "C34 is written where C23")),
        # C1*S234
        ("ur5", (3, 4), "C1*C123", ("C234 is written where S234", "C123 is written where C234")),
        # -C234
        ("ur5", (5, 4), "-S123", ("S234 is written where C234", "S123 is written where S234")),
    ],
)
def test_one_factor_swapped_and_moved_is_named_with_both_kinds(robot, entry, written, words):
    """Two slips in one sine or cosine of a sum angle (the benchmark's double edits that
    3f6d355 left unexplained: its search pruned the first slip, whose factor ``C23`` the
    student's answer no longer has)."""
    key, text = _jacobian_with(robot, entry, written)
    r = check_answer(key, text)
    assert r.verdict is Verdict.INCORRECT
    assert r.kinds == ("sin_cos_swapped", "wrong_joint_index"), r.diagnoses
    where = f"entry ({entry[0] + 1},{entry[1] + 1})"
    for d, word in zip(r.diagnoses, words):
        assert word in d.detail and where in d.detail, d.detail
        assert d.entries == ((entry[0] + 1, entry[1] + 1),)


def _entry_case(robot: str, question: str, text: str):
    """The case a judge builds for a wrong one-entry answer (the key's diagnosis sample)."""
    from dhsym.checking.judging.matrix_judge import _diagnosis_values
    from dhsym.checking.mistakes.registry import MatrixCase
    from dhsym.checking.reading.answer_value import read_answer_value

    key = load_key(robot, question)
    pk = KEYS.get(key)
    answer = read_answer_value(pk.form(), text).matrix
    sample, kv, av = _diagnosis_values(pk.part.diagnosis(key.table, answer), answer, [])
    q = key.question
    return MatrixCase(
        tuple(key.table.rows),
        key.table.convention,
        q.frm,
        q.to,
        q.entry,
        pk.part.expected,
        answer,
        sample,
        kv,
        av,
        ((0, 0),),
        key_notation(key),
    )


@pytest.mark.parametrize(
    ("robot", "question", "answer", "kinds", "words"),
    [
        # C1*(S23*S5*S6 - C23*(C4*C5*S6 + S4*C6)) - S1*(C4*C6 - S4*C5*S6): a term of the
        # bracket left out, and C1 written for S1 in the other product (two places of a sum)
        (
            "puma560",
            "T0_6[0,1]",
            "C1*S23*S5*S6 - C1*(C4*C6 - S4*C5*S6)",
            ("sin_cos_swapped", "dropped_term"),
            ("C1 is written where S1 belongs", "-C23*(C4*C5*S6 + S4*C6) is missing"),
        ),
        # C1*(a2*C2 + a3*C23 + d5*S234 - d6*C234*S5) + S1*(d4 + d6*C5): a sign in the
        # bracket and S5 for C5 in the other bracket
        (
            "ur5",
            "T0_6[0,3]",
            "C1*(a2*C2 - a3*C23 + d5*S234 - d6*C234*S5) + S1*(d4 + d6*S5)",
            ("wrong_sign", "sin_cos_swapped"),
            ("a3*C23 has the wrong sign", "S5 is written where C5 belongs"),
        ),
        # C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1: a sign, and S23 for C23 inside that term
        (
            "puma560",
            "T0_6[0,3]",
            "C1*(a2*C2 - a3*S23 - d4*S23) + d3*S1",
            ("wrong_sign", "sin_cos_swapped"),
            ("a3*C23 has the wrong sign", "S23 is written where C23 belongs"),
        ),
        # C1*(C23*(C4*C5*C6 - S4*S6) - S23*S5*C6) - S1*(...): two factors of one product
        (
            "puma560",
            "T0_6[0,0]",
            "S1*(C23*(C4*C5*C6 + S4*S6) - S23*S5*C6) - S1*(S4*C5*C6 + C4*S6)",
            ("wrong_sign", "sin_cos_swapped"),
            ("-S4*S6 has the wrong sign", "S1 is written where C1 belongs"),
        ),
        # a length left out of a3*C23, and S23 for C23 inside that product
        (
            "puma560",
            "T0_6[0,3]",
            "C1*(a2*C2 + S23 - d4*S23) + d3*S1",
            ("sin_cos_swapped", "missing_length"),
            ("S23 is written where C23 belongs", "a3 is missing from a3*C23"),
        ),
        # -C234*S5: C234 swapped and moved
        (
            "ur5",
            "T0_6[2,2]",
            "-C345*S5",
            ("sin_cos_swapped", "wrong_joint_index"),
            ("C234 is written where S234", "C345 is written where C234"),
        ),
    ],
)
def test_two_slips_are_found_by_what_each_changes(robot, question, answer, kinds, words):
    """The pair is found without composing slips (a budget of one candidate leaves the
    search by composition nothing): the answer minus the key is the two slips' changes."""
    from dhsym.checking.mistakes._entry_mistakes import explain_pairs
    from dhsym.checking.mistakes.registry import ENTRY_MISTAKES

    found = explain_pairs(_entry_case(robot, question, answer), ENTRY_MISTAKES, budget=1)
    assert tuple(d.kind for d in found) == kinds, found
    for d, word in zip(found, words):
        assert word in d.detail, d.detail
    # the full check names the same pair
    r = check_answer(load_key(robot, question), answer)
    assert r.verdict is Verdict.INCORRECT and r.kinds == kinds, r.diagnoses


def test_a_sum_of_changes_that_is_no_pair_of_slips_stays_unexplained():
    """Three slips in one entry: no two catalogued slips give it, whatever adds up."""
    from dhsym.checking.mistakes._entry_mistakes import explain_pairs
    from dhsym.checking.mistakes.registry import ENTRY_MISTAKES

    case = _entry_case("puma560", "T0_6[0,1]", "C1*S23*S5*C6 - C1*(C4*C6 + S4*C5*S6)")
    assert explain_pairs(case, ENTRY_MISTAKES) == ()
    assert explain_pairs(case, ENTRY_MISTAKES, same=True) == ()


def test_an_answer_too_large_for_floats_is_no_pair_of_slips_and_warns_nothing():
    """((x+1)^64+1)^64 … overflows at the sample points: the search by changes stops at
    once (it warned "invalid value encountered in matmul" and compared NaNs)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        r = check_answer(load_key("planar2r", "T0_2[0,3]"), "((((a1+1)^64+1)^64+1)^64)")
    assert r.verdict is not Verdict.CORRECT
