"""The equivalent frames of one arm: the senses of x (each frame turned about z), the sense
of the last z of a standard table, and why a twist of 180° between two joint axes stays."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from dhsym.errors import DHError
from dhsym.geometry.frame_choices import reverse_last_z, textbook_frames
from dhsym.kinematics.chain import KinematicChain
from dhsym.model.inertia import LinkInertia
from dhsym.model.table import DHRow, DHTable


def _tool_pose(table: DHTable, q: np.ndarray) -> np.ndarray:
    return KinematicChain(table).fk(q)


def test_the_last_z_of_a_standard_table_is_reversed_when_it_removes_a_half_turn() -> None:
    inertia = LinkInertia(
        m=2, r=(sp.Rational(1, 10), sp.Rational(1, 5), sp.Rational(3, 10)), I=sp.diag(1, 2, 3)
    )
    t = DHTable.from_rows(
        [
            DHRow.revolute("theta1", d=1, alpha=sp.pi / 2),
            DHRow.revolute("theta2", a=2, alpha=sp.pi, inertia=inertia),
        ]
    )
    choice = textbook_frames(t)
    assert choice.last_z_reversed
    assert choice.table.rows[1].alpha == 0 and choice.table.tool  # the tool takes the turn
    assert any("z2 reversed" in s for s in choice.sentences)
    q = np.random.default_rng(2).uniform(-3, 3, (5, 2))
    assert np.abs(_tool_pose(choice.table, q) - _tool_pose(t, q)).max() < 1e-12
    turned = reverse_last_z(t).rows[1].inertia
    assert turned is not None and turned.r == (
        sp.Rational(1, 10),
        -sp.Rational(1, 5),
        -sp.Rational(3, 10),
    )
    # a twist of 90° at the end is left alone: x flips already sign it
    plain = textbook_frames(DHTable.from_rows([DHRow.revolute("theta1", a=1, alpha=-sp.pi / 2)]))
    assert not plain.last_z_reversed and plain.table.rows[0].alpha == sp.pi / 2


def test_the_last_z_of_a_modified_table_is_a_joint_axis() -> None:
    t = DHTable.from_rows([DHRow.revolute("theta1", alpha=sp.pi)], convention="modified")
    with pytest.raises(DHError, match="last joint's axis"):
        reverse_last_z(t)
    assert not textbook_frames(t).last_z_reversed


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_a_half_turn_between_two_joint_axes_stays_and_says_why(convention: str) -> None:
    rows = [
        DHRow.revolute("theta1", d=1, alpha=sp.pi / 2),
        DHRow.revolute("theta2", a=1, alpha=sp.pi),
        DHRow.revolute("theta3", a=1, alpha=sp.pi / 2),
    ]
    if convention == "modified":
        rows = [
            DHRow.revolute("theta1", d=1),
            DHRow.revolute("theta2", alpha=sp.pi / 2),
            DHRow.revolute("theta3", a=1, alpha=sp.pi),
        ]
    choice = textbook_frames(DHTable.from_rows(rows, convention=convention))
    twists = [r.alpha for r in choice.table.rows]
    assert sp.pi in twists  # no frame turned about z changes a twist of 180°
    (why,) = choice.forced
    expected = "α2 = 180° stays: z1 and z2 are the axes of joints 2 and 3"
    if convention == "modified":
        expected = "α2 = 180° stays: z2 and z3 are the axes of joints 2 and 3"
    assert why.startswith(expected) and "θ = −q" in why
    assert why in choice.sentences
