"""Question specs."""

from __future__ import annotations

import pytest

from dhsym.checking.reading.questions import Question
from dhsym.errors import DHError


@pytest.mark.parametrize(
    ("spec", "label", "kind"),
    [
        ("table", "table", "table"),
        ("T0_2", "T0_2", "matrix"),
        ("A3", "T2_3", "matrix"),
        ("T0_6[0,3]", "T0_6[0,3]", "entry"),
        ("^0T_6", "T0_6", "matrix"),
        ("arm", "T0_6", "matrix"),
        ("pz", "T0_6[2,3]", "entry"),
        ("T3_1", "T3_1", "matrix"),
    ],
)
def test_parse(spec, label, kind):
    q = Question.parse(spec, n=6)
    assert (q.label, q.kind) == (label, kind)


@pytest.mark.parametrize("spec", ["T0_9", "A0", "T2_2", "T0_6[4,0]", "matrix please"])
def test_bad_questions(spec):
    with pytest.raises(DHError):
        Question.parse(spec, n=6)
