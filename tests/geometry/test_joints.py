"""Seed 000's pairs, multi-DOF joints written as 1-DOF joints, Grübler–Kutzbach mobility."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import GeometryError
from dhsym.geometry.axes import JointAxis
from dhsym.geometry.frames import assign_frames
from dhsym.geometry.joints import (
    PAIRS,
    Joint,
    Mechanism,
    decompose,
    four_bar,
    joint_axes,
    mobility,
    pair,
    planar_five_bar,
    serial_6r,
    stewart_platform,
)
from dhsym.robot import Robot


def test_the_table_of_pairs_is_seed_000s():
    table = {p.symbol: (p.name, p.dof, p.constraints) for p in PAIRS.values()}
    assert table == {
        "H": ("screw", 1, 5),
        "R": ("revolute", 1, 5),
        "P": ("prismatic", 1, 5),
        "C": ("cylindrical", 2, 4),
        "S": ("spherical", 3, 3),
        "E": ("planar pair", 3, 3),
        "U": ("Hooke (universal)", 2, 4),
    }
    assert pair("T") is PAIRS["U"] and pair("universal") is PAIRS["U"]
    with pytest.raises(TypeError):
        PAIRS["X"] = PAIRS["R"]  # frozen data
    with pytest.raises(GeometryError, match="unknown joint type 'Q'"):
        pair("Q")


def test_multi_dof_joints_become_intersecting_or_coincident_1dof_joints():
    c = Joint("C", (0, 0, 1), (0, 0, 1), name="C1").axes()
    assert [(a.joint, tuple(a.point), tuple(a.direction)) for a in c] == [
        ("R", (0, 0, 1), (0, 0, 1)),
        ("P", (0, 0, 1), (0, 0, 1)),
    ]
    u = Joint("T", (1, 0, 0), (0, 0, 1), second=(0, 1, 0)).axes()
    assert [a.joint for a in u] == ["R", "R"] and tuple(u[1].direction) == (0, 1, 0)
    s = Joint("S", (0, 0, 0), (1, 0, 0), second=(0, -1, 0), euler=True).axes()
    assert [tuple(a.direction) for a in s] == [(1, 0, 0), (0, -1, 0), (1, 0, 0)]
    assert all(tuple(a.point) == (0, 0, 0) for a in s)
    e = Joint("E", (0, 0, 0), (0, 0, 1), second=(1, 0, 0)).axes()
    assert [(a.joint, tuple(a.direction)) for a in e] == [
        ("P", (1, 0, 0)),
        ("P", (0, 1, 0)),
        ("R", (0, 0, 1)),
    ]
    assert [a.name for a in s] == ["S.1", "S.2", "S.3"]


def test_bad_multi_dof_joints_are_refused():
    with pytest.raises(GeometryError, match="must be perpendicular"):
        Joint("U", (0, 0, 0), (0, 0, 1), second=(1, 0, 1)).axes()
    with pytest.raises(GeometryError, match="screw pair"):
        Joint("H", (0, 0, 0), (0, 0, 1)).axes()


def test_a_robot_with_a_spherical_wrist_gets_the_puma_table():
    """PUMA 560 in the stretched-out pose of seed 003, wrist written as one S joint."""
    a2, a3, d3, d4 = 0.4318, 0.0203, 0.15005, 0.4318
    wrist = (a2 + d4, -d3, -a3)
    joints = [
        Joint("R", (0, 0, 0), (0, 0, 1)),
        Joint("R", (0, 0, 0), (0, -1, 0)),
        Joint("R", (a2, 0, 0), (0, -1, 0)),
        Joint("S", wrist, (1, 0, 0), second=(0, -1, 0), euler=True),
    ]
    axes = decompose(joints)
    assert len(axes) == 6 and joint_axes([*joints[:3], *axes[3:]]) == axes
    fa = assign_frames(axes, tool=(wrist, (1, 0, 0), (0, 1, 0)))
    corke = dhsym.load_table("puma560")
    q = np.random.default_rng(5).uniform(-3, 3, (10, 6))
    assert np.allclose(
        Robot(fa.table).fk(q), Robot(corke).fk(q - [0, 0, np.pi / 2, 0, 0, 0]), atol=1e-12
    )


def test_a_cylindrical_joint_gives_the_cylindrical_robot():
    """C (lift and turn about z) then a radial P: the built-in cylindrical robot (d1 = 0.4)."""
    joints = [Joint("C", (0, 0, 0), (0, 0, 1)), JointAxis((0, 0, 0.4), (0, 1, 0), "P")]
    fa = assign_frames(joint_axes(joints), tool=((0, 0, 0.4), (0, 1, 0), (0, 0, -1)))
    assert "cylindrical pair" in " ".join(fa.step_texts)
    builtin = dhsym.load_table("cylindrical")
    q = np.random.default_rng(2).uniform(-1, 1, (10, 3))
    assert np.allclose(Robot(fa.table).fk(q), Robot(builtin).fk(q), atol=1e-12)


def test_mobility_of_textbook_mechanisms():
    assert four_bar().mobility == 1 and four_bar().loops == 1
    assert serial_6r().mobility == 6 and serial_6r().loops == 0
    assert planar_five_bar().mobility == 2
    sp6 = stewart_platform()
    assert (len(sp6.links), len(sp6.joints), sp6.freedoms) == (14, 18, 42)
    assert sp6.mobility == 6 and sp6.loops == 5
    assert mobility(14, "SPS" * 6) == 12  # without removing the six idle leg spins
    assert mobility(14, "UPS" * 6) == 6  # 6-UPS has no idle spin
    assert mobility(4, "RRRP", "planar") == 1  # slider-crank
    assert mobility(3, [1, 1, 1], "planar") == 0  # a triangle of links is a structure
    assert sp6.equation == "M = 6(N - 1 - J) + Σf - idle = 6(14 - 1 - 18) + 42 - 6 = 6"


def test_bad_mechanisms_name_the_joint():
    with pytest.raises(GeometryError, match="joint 2 .* unknown link 'l9'"):
        Mechanism("m", ("g", "l1"), (("R", "g", "l1"), ("R", "l1", "l9")))
    with pytest.raises(GeometryError, match="joint 1 .* not a planar pair"):
        Mechanism("m", ("g", "l1"), (("S", "g", "l1"),), "planar")
    with pytest.raises(GeometryError, match="connects link 'g' to itself"):
        Mechanism("m", ("g", "l1"), (("R", "g", "g"),))
    with pytest.raises(GeometryError, match="'spatial' or 'planar'"):
        mobility(4, "RRRR", "curved")
    assert sp.Integer(mobility(7, "RRRRRR")) == 6
