"""Seed 003's pick-and-place chain, checked against a computation done by hand."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.errors import ChainError
from dhsym.geometry.chains import FrameChain, step
from dhsym.kinematics.transforms import Rx, Rz, Tx, Tz

R = sp.Rational
M = sp.Matrix


def translation(x, y, z):
    return M([[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]])


# The scene (metres). {1} global frame at the robot base.
# ^1T_2: the part lies on the table at (0.6, -0.2, 0.1), turned 90° about the vertical.
T12 = translation(R(3, 5), R(-1, 5), R(1, 10)) * Rz(sp.pi / 2)
# ^2T_3: the gripper holds the part 0.15 above the point (0.05, 0.02) of the part, z3 pointing
# down into the part (a half turn about x).
T23 = translation(R(1, 20), R(1, 50), R(3, 20)) * Rx(sp.pi)
# ^1T_4: the inclined plane's corner at (-0.2, 0.6, 0.3), the plane tilted about its x axis
# by the angle with cos = 4/5, sin = 3/5.
C, S_ = R(4, 5), R(3, 5)
T14 = translation(R(-1, 5), R(3, 5), R(3, 10)) * M(
    [[1, 0, 0, 0], [0, C, -S_, 0], [0, S_, C, 0], [0, 0, 0, 1]]
)
# ^4T_5: the part's final place, 0.1 along x and 0.05 along y of the plane, same orientation.
T45 = translation(R(1, 10), R(1, 20), 0)


def pick_and_place() -> FrameChain:
    return (
        FrameChain()
        .known(1, 2, T12, "part on the table")
        .known(2, 3, T23, "grip")
        .known(1, 4, T14, "inclined plane")
        .known(4, 5, T45, "final place of the part")
        .same_as(5, 6, 2, 3, "the grip does not change")
    )


def test_gripper_at_the_pick_pose_matches_the_hand_computation():
    # By hand: R = Rz(90°) Rx(180°) = [[0,-1,0],[1,0,0],[0,0,1]] [[1,0,0],[0,-1,0],[0,0,-1]]
    #            = [[0,1,0],[1,0,0],[0,0,-1]]
    #          p = (0.6, -0.2, 0.1) + Rz(90°)(0.05, 0.02, 0.15) = (0.6 - 0.02, -0.2 + 0.05, 0.25)
    expected = M(
        [[0, 1, 0, R(58, 100)], [1, 0, 0, R(-15, 100)], [0, 0, -1, R(25, 100)], [0, 0, 0, 1]]
    )
    d = pick_and_place().derive(1, 3)
    assert d.pose.matrix == expected
    assert d.text == "T1_3 = T1_2 T2_3"
    assert d.path == ("1", "2", "3")


def test_gripper_at_the_place_pose_matches_the_hand_computation():
    # ^5T_6 = ^2T_3 (the grip is kept), so
    # ^4T_6 = Trans(0.1, 0.05, 0) Trans(0.05, 0.02, 0.15) Rx(180°)
    #       = Trans(0.15, 0.07, 0.15) Rx(180°).
    # Tilt · (0.15, 0.07, 0.15) = (0.15, 0.8·0.07 − 0.6·0.15, 0.6·0.07 + 0.8·0.15)
    #                            = (0.15, −0.034, 0.162); plus the corner (−0.2, 0.6, 0.3):
    # p = (−0.05, 0.566, 0.462).  R = Tilt · Rx(180°) = [[1,0,0],[0,−0.8,0.6],[0,−0.6,−0.8]].
    expected = M(
        [
            [1, 0, 0, R(-5, 100)],
            [0, R(-4, 5), R(3, 5), R(566, 1000)],
            [0, R(-3, 5), R(-4, 5), R(462, 1000)],
            [0, 0, 0, 1],
        ]
    )
    chain = pick_and_place()
    d = chain.derive(1, 6)
    assert d.pose.matrix == expected
    assert d.text == "T1_6 = T1_4 T4_5 T5_6"
    assert chain[1, 6].matrix == expected  # T[1←6] by indexing
    assert chain.transforms[-1].note == "the grip does not change"


def test_approach_and_depart_frames_are_translations_along_the_tool_z():
    chain = pick_and_place().approach(3, R(1, 10), "lift").approach(6, R(1, 10), "above place")
    # lift: ^1T_3 Tz(−0.1); z3 = (0, 0, −1), so the gripper rises by 0.1: p = (0.58, −0.15, 0.35)
    assert chain.depart(3, R(1, 10))[1, "3_depart"].matrix == chain[1, "lift"].matrix
    lift = chain[1, "lift"].matrix
    assert lift[:3, 3] == M([R(58, 100), R(-15, 100), R(35, 100)])
    assert lift[:3, :3] == chain[1, 3].matrix[:3, :3]
    # above place: p6 − 0.1 z6 = (−0.05, 0.566, 0.462) − 0.1 (0, 0.6, −0.8) = (−0.05, 0.506, 0.542)
    assert chain[1, "above place"].matrix[:3, 3] == M([R(-5, 100), R(506, 1000), R(542, 1000)])
    assert chain.derive("lift", "above place").text == (
        "Tlift_above place = (T3_lift)^-1 (T2_3)^-1 (T1_2)^-1 T1_4 T4_5 T5_6 T6_above place"
    )


def test_inverse_and_unknown_in_a_loop():
    chain = pick_and_place()
    d = chain.derive(3, 1)
    assert d.text == "T3_1 = (T2_3)^-1 (T1_2)^-1"
    assert sp.simplify(d.pose.matrix * chain[1, 3].matrix) == sp.eye(4)
    # solve the loop 1 → 2 → 3 for T[3←5]: where the part must go, seen from the gripper
    solved, d35 = chain.solve(3, 5)
    assert d35.text == "T3_5 = (T2_3)^-1 (T1_2)^-1 T1_4 T4_5"
    assert solved.transforms[-1].note.startswith("solved: T3_5 =")


def test_a_consistent_loop_closes_and_an_inconsistent_one_is_named():
    chain = pick_and_place()
    closed = chain.known(1, 3, chain[1, 3].matrix, "measured")  # consistent: accepted
    assert len(closed.transforms) == 6
    measured = sp.Matrix(chain[1, 3].matrix)
    measured[0, 3] += sp.Float(1e-12)  # a measured pose with a rounding error still closes
    assert len(chain.known(1, 3, measured).transforms) == 6
    with pytest.raises(ChainError, match="the loop 1 → 2 → 3 → 1 does not close"):
        chain.known(1, 3, Tz(1) * chain[1, 3].matrix)


def test_missing_links_and_unknown_frames_are_named():
    chain = FrameChain().known("world", "table", Tx(1)).known("part", "gripper", Tz(2))
    with pytest.raises(
        ChainError,
        match="no chain of known transforms from frame 'world' to 'gripper'.*reaches only table",
    ):
        chain.derive("world", "gripper")
    with pytest.raises(ChainError, match="unknown frame 'camera'"):
        chain["world", "camera"]
    assert chain["world←table"].matrix == Tx(1)
    with pytest.raises(ChainError, match="write T\\[from←to\\]"):
        chain["world"]
    with pytest.raises(ChainError, match="not a rotation"):
        chain.known("a", "b", sp.diag(2, 1, 1, 1))
    with pytest.raises(ChainError, match="itself"):
        chain.known("a", "a", sp.eye(4))


def test_symbolic_chains_stay_exact():
    h, t = sp.symbols("h theta", real=True)
    chain = FrameChain().known("base", "shoulder", Tz(h)).known("shoulder", "hand", Rz(t) * Tx(1))
    pose = chain["hand", "base"].matrix
    # (Rz(θ) Tx(1))⁻¹ Tz(h)⁻¹ = Tx(−1) Rz(−θ) Tz(−h): the base origin is at (−1, 0, −h)
    assert pose[:3, 3] == M([-1, 0, -h])
    assert pose[:3, :3] == Rz(-t)[:3, :3]
    assert sp.simplify(pose * chain["base", "hand"].matrix) == sp.eye(4)


def test_derivations_render_as_markdown():
    d = pick_and_place().derive(1, 6)
    md = d._repr_markdown_()
    assert "{}^{1}T_{6} = {}^{1}T_{4}\\,{}^{4}T_{5}\\,{}^{5}T_{6}" in md
    assert "T[5←6] (the grip does not change)" in md
    assert step("x", "{a}", a=sp.Symbol("z1")).markdown == "$z_{1}$"
