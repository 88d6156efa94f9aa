"""Property tests of the search of two slips (issue 34, item 3): a correct rewriting is never
graded wrong, an answer with two slips that change its value is never graded right, and
a pair the diagnosis names reproduces the answer."""

from __future__ import annotations

import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dhsym.checking import check_answer
from dhsym.checking.comparing.verdict import Verdict
from dhsym.checking.mistakes.registry import ENTRY_MISTAKES
from dhsym.robot import Robot

from .._keys import KEYS, load_key  # each key prepared once, as a grading worker does

KEY = load_key("puma560", "T0_6[0,3]")  # C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1
PK = KEYS.get(KEY)
E = PK.part.expected[0, 0]
NOTA = Robot(KEY.table).notation
KINDS = {m.kind: m for m in ENTRY_MISTAKES}


def _sample_value(e: sp.Expr) -> float:
    point = {s: 0.3 + 0.17 * k for k, s in enumerate(sorted(e.free_symbols, key=str))}
    return float(e.xreplace(point))


@st.composite
def two_slips(draw: st.DrawFn) -> tuple[str, str, sp.Expr]:
    a, b = draw(st.lists(st.sampled_from(sorted(KINDS)), min_size=2, max_size=2, unique=True))
    first = list(KINDS[a].candidates(E, _case()))
    cand, _ = draw(st.sampled_from(first))
    second = list(KINDS[b].candidates(cand, _case()))
    if not second:
        return a, a, cand
    cand2, _ = draw(st.sampled_from(second))
    return a, b, cand2


def _case():
    from dhsym.checking.judging.matrix_judge import _diagnosis_values
    from dhsym.checking.mistakes.registry import MatrixCase

    answer = sp.ImmutableMatrix([[E]])
    sample, kv, av = _diagnosis_values(PK.part.diagnosis(KEY.table, answer), answer, [])
    return MatrixCase(
        tuple(KEY.table.rows),
        KEY.table.convention,
        0,
        6,
        (0, 3),
        PK.part.expected,
        sp.ImmutableMatrix([[E]]),
        sample,
        kv,
        av,
        (),
        NOTA,
    )


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(two_slips())
def test_two_slips_are_never_graded_right_and_a_named_pair_reproduces(slips):
    _, _, wrong = slips
    r = check_answer(KEY, NOTA.text(wrong), keys=KEYS)
    same = abs(_sample_value(wrong) - _sample_value(E)) < 1e-9 and sp.simplify(wrong - E) == 0
    if same:  # the two edits cancel: a correct answer
        assert r.verdict is Verdict.CORRECT, r.message
        return
    assert r.verdict is Verdict.INCORRECT, r.message
    named = [d for d in r.diagnoses if d.kind in KINDS]
    if len(named) == 2:  # a pair: the two kinds' slips composed give the answer
        assert named[0].entries == named[1].entries


@settings(max_examples=15, deadline=None)
@given(st.sampled_from([sp.expand, sp.factor_terms, sp.trigsimp, lambda e: sp.expand_trig(e)]))
def test_correct_rewritings_are_never_graded_wrong(rewrite):
    r = check_answer(KEY, NOTA.text(rewrite(E)), keys=KEYS)
    assert r.verdict is Verdict.CORRECT, r.message
