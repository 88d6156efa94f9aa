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


@pytest.mark.parametrize(
    ("spec", "label", "part", "latex"),
    [
        ("traj a2", "traj a2", "a2", "a_{2}"),
        ("trajectory a5", "traj a5", "a5", "a_{5}"),
        ("tb", "tb", "tb", "t_b"),
        ("traj t_b", "tb", "tb", "t_b"),
        ("v_max", "vmax", "vmax", r"\dot q_{\max}"),
        ("q@1.5", "q@1.5", "q@1.5", "q(1.5)"),
        ("q @ tf / 2", "q@tf/2", "q@tf/2", "q(tf/2)"),
        ("K_p", "kp", "kp", "K_p"),
        ("k_{d}", "kd", "kd", "K_d"),
    ],
)
def test_trajectory_questions(spec, label, part, latex):
    q = Question.parse(spec, n=0)
    assert (q.kind, q.label, q.part, q.label_latex) == ("trajectory", label, part, latex)


@pytest.mark.parametrize("spec", ["a2", "traj b2", "traj a", "q@", "kq", "traj a12"])
def test_bad_trajectory_questions(spec):
    with pytest.raises(DHError, match="traj a<k>, tb, vmax, q@<t>, kp, kd"):
        Question.parse(spec, n=2)
