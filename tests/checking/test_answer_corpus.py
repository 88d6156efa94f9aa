"""The answer corpus (tests/data/answers): every answer gets its expected verdict."""

from __future__ import annotations

import pytest

from tests.checking.answer_corpus import VERDICTS, load_corpus, run_case

from ._keys import KEYS  # each key prepared once, as a grading worker does

CASES = load_corpus()


def test_corpus_is_large_and_covers_every_verdict():
    assert len(CASES) >= 150
    assert {c.verdict for c in CASES} == set(VERDICTS)
    kinds = {c.mistake for c in CASES if c.mistake}
    assert kinds >= {
        "wrong_sign",
        "sin_cos_swapped",
        "transposed",
        "other_convention",
        "degrees_as_radians",
        "index_shift",
        "offset_missing",
        "reverse_order",
        "single_wrong_row",
    }


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_corpus_answer(case):
    outcome = run_case(case, KEYS)
    assert outcome.ok, f"{case.answer!r}: {outcome.why}"
