"""Judging matrix answers: what a wrong entry's feedback shows."""

from __future__ import annotations

import pytest

from dhsym.checking import Key, PreparedKeys, check_answer
from dhsym.checking.reading.answer_value import read_answer_value

#: the PUMA 560's 0T2 transposed (every off-diagonal entry is another key entry), with
#: two entries that are no key entry (a sign slip, a 0 for S1)
TRANSPOSED = (
    "[[C1*C2, S1*C2, S2, 0], [-C1*S2, -S1*S2, C2, 0], [S1, -C1, 0, 0], "
    "[a2*C1*C2, a2*S1*C2, a2*S2, 1]]"
)
SLIPS = (
    "[[C1*C2, -C1*S2, S1, -a2*C1*C2], [S1*C2, -S1*S2, -C1, a2*S1*C2], "
    "[S2, C2, 0, a2*S2], [0, 0, 0, 0]]"
)


@pytest.mark.parametrize("text", [TRANSPOSED, SLIPS])
def test_a_wrong_entry_is_shown_as_the_keys_notation_prints_it(text):
    """A wrong entry that is one of the key's entries takes the key's printed forms; the
    text and LaTeX are those the key's notation prints for the student's entry."""
    keys = PreparedKeys()
    key = Key.load("puma560", "T0_2")
    pk = keys.get(key)
    result = check_answer(key, text, keys=keys)
    read = read_answer_value(pk.form(), text).matrix
    nota = pk.robot.notation
    wrong = [e for e in result.entries if not e.correct]
    assert result.verdict.value == "incorrect" and wrong
    for e in wrong:
        entry = read[e.row - 1, e.col - 1]
        assert (e.answer, e.answer_latex) == (nota.text(entry), nota.latex(entry))
