"""Writing a DH table as a URDF: read back with the same fk, valid for yourdfpy, the layout
and the escaping of ElementTree."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.formats.urdf.read import read_urdf
from dhsym.formats.urdf.to_dh import chain_from_urdf
from dhsym.formats.urdf.write import write_urdf
from dhsym.model.inertia import LinkInertia
from dhsym.model.table import DHRow, DHTable

from .support import DATA, ROBOTS


@pytest.mark.parametrize(("file", "tip", "n"), ROBOTS)
def test_round_trip_keeps_fk(file: str, tip: str, n: int) -> None:
    robot = chain_from_urdf(DATA / file, tip=tip)
    for convention in ("standard", "modified"):
        again = chain_from_urdf(write_urdf(dhsym.convert(robot.table, convention)), tip="tool")
        q = np.random.default_rng(3).uniform(-math.pi, math.pi, (5, n))
        assert np.abs(again.fk(q) - robot.fk(q)).max() < 1e-9


def test_written_urdf_is_valid_for_yourdfpy() -> None:
    import yourdfpy  # in the test extra: a missing validator is a failure, not a skip

    robot = chain_from_urdf(DATA / "panda.urdf", tip="panda_hand")
    for convention in ("standard", "modified"):
        text = write_urdf(dhsym.convert(robot.table, convention))
        import io

        model = yourdfpy.URDF.load(io.StringIO(text), load_meshes=False, build_scene_graph=True)
        assert model.validate()
        q = np.random.default_rng(1).uniform(-1, 1, 7)
        names = [f"joint{k}" for k in range(1, 8)]
        model.update_cfg(dict(zip(names, q, strict=True)))
        T = model.get_transform("tool", model.base_link)
        assert np.abs(T - robot.fk(q)).max() < 1e-9
        links = {link.name for link in model.robot.links}
        assert {f"link{k}" for k in range(8)} <= links


def test_robot_to_urdf_method_and_visuals() -> None:
    r = dhsym.load("puma560")
    out = dhsym.Robot(r.table.with_values({s: 0.3 for s in r.table.constants})).to_urdf()
    assert out.count("<cylinder") == 6 and "<box" in out
    with pytest.raises(dhsym.DHError, match="symbolic lengths a1, a2, a3"):
        dhsym.Robot(dhsym.planar_chain(3)).to_urdf()


def test_fixed_rows_and_flipped_joints_are_written() -> None:
    from dhsym.model.table import DHRow, DHTable

    rows = [
        DHRow.revolute("pi/2 - q1", d=0.3, a=0.2, alpha="pi/2"),
        DHRow.fixed(theta="pi/6", d=0.1),
        DHRow.prismatic("0.1 - d3", a=0.1, alpha="-pi/2"),
    ]
    for convention in ("standard", "modified"):
        robot = dhsym.Robot(DHTable.from_rows(rows, convention=convention, name="odd"))
        text = robot.to_urdf()
        assert '<axis xyz="0 0 -1" />' in text and 'name="joint2" type="fixed"' in text
        again = chain_from_urdf(text, tip="tool")
        for q in ([0.3, 0.2], [-1.0, 0.6]):
            assert np.abs(again.fk(q) - robot.fk(q)).max() < 1e-12


@pytest.mark.slow
def test_written_inertials_come_back() -> None:
    """Puma 560 with its published inertial parameters: the URDF holds m, r and I (not the
    motor inertia, gearing or friction, which URDF has no place for)."""
    from dataclasses import replace

    from dhsym.robot import Robot

    table = dhsym.load("puma560").table.substituted()
    rigid = replace(
        table,
        rows=tuple(
            replace(row, inertia=replace(row.inertia, Jm=0, G=1, B=0, Tc=(0, 0)))
            for row in table.rows
        ),
    )
    text = write_urdf(rigid)
    assert text.count("<inertial>") == 6 and '<mass value="17.4" />' in text
    again = dhsym.from_urdf(text, tip="tool")
    assert again.table.rows[1].inertia.m == sp.Rational(87, 5)
    robot = Robot(rigid)
    rng = np.random.default_rng(3)
    for _ in range(3):
        q, qd, qdd = (rng.uniform(-1.5, 1.5, 6) for _ in range(3))
        np.testing.assert_allclose(again.rne(q, qd, qdd), robot.rne(q, qd, qdd), atol=1e-9, rtol=0)


# --- the layout: ElementTree's, two spaces an indent, as a person would write it -------------

ABOUT = (
    "<!-- slide_co: written by dhsym from its standard DH table; one link per DH frame "
    "(linkK = DH frame K) -->"
)
SLIDE = f"""\
<?xml version="1.0"?>
{ABOUT}
<!-- cylinders sit on the joint axes, boxes run along the links; no meshes -->
<robot name="slide_co">
  <material name="dhsym_grey"><color rgba="0.6 0.6 0.65 1" /></material>
  <material name="dhsym_orange"><color rgba="0.95 0.5 0.1 1" /></material>
  <link name="link0">
  </link>
  <link name="link1_joint">
    <visual>
      <origin xyz="0 0 0" rpy="0 0 0" />
      <geometry><box size="0.024 0.024 0.045" /></geometry>
      <material name="dhsym_orange" />
    </visual>
    <visual>
      <origin xyz="0.25 0 0" rpy="0 -0 0" />
      <geometry><box size="0.5 0.015 0.015" /></geometry>
      <material name="dhsym_grey" />
    </visual>
  </link>
  <link name="link1">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 0" />
      <mass value="1.5" />
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3" />
    </inertial>
  </link>
  <link name="tool">
  </link>
  <joint name="joint1" type="prismatic">
    <parent link="link0" />
    <child link="link1_joint" />
    <origin xyz="0 0 0" rpy="0 0 0" />
    <axis xyz="0 0 1" />
    <limit lower="-1" upper="1" effort="0" velocity="0" />  <!-- no limits in the DH table -->
  </joint>
  <joint name="link1_joint_to_link1" type="fixed">
    <parent link="link1_joint" />
    <child link="link1" />
    <origin xyz="0.5 0 0" rpy="1.5707963267948966 0 0" />
  </joint>
  <joint name="link1_to_tool" type="fixed">
    <parent link="link1" />
    <child link="tool" />
    <origin xyz="0 0 0" rpy="0 0 0" />
  </joint>
</robot>
"""


def _slide() -> DHTable:
    row = DHRow.prismatic("d1", a=0.5, alpha="pi/2")
    inertia = LinkInertia(sp.Rational(3, 2), (0, 0, sp.Rational(1, 10)), sp.diag(1, 2, 3))
    return DHTable.from_rows([replace(row, inertia=inertia)], name="slide & co")


def test_the_whole_text_of_a_small_arm() -> None:
    """Every rule of the layout once: a prismatic joint's box, a joint without limits and its
    comment, an inertial, empty links. The same bytes as the f-string writer that came before,
    but for ElementTree's space before ``/>`` in an empty element."""
    assert write_urdf(_slide()) == SLIDE


def test_a_robot_name_is_an_xml_name_and_comments_stay_well_formed() -> None:
    text = write_urdf(_slide(), name="a--b -->")
    assert "<!-- a-b_-_: written by dhsym" in text  # a comment cannot hold "--"
    model = read_urdf(text)
    assert model.name == "a--b_--_" and model.link_names[0] == "link0"


def test_a_table_marked_not_physical_reads_back_as_such() -> None:
    # the Puma 560's published inertias break the triangle inequality (physical: false)
    from dhsym import load_table
    from dhsym.errors import FormatError
    from dhsym.formats.urdf import import_urdf, write_urdf

    text = write_urdf(load_table("puma560"))
    assert '<robot name="PUMA_560" physical="false">' in text
    assert import_urdf(text, tip="tool").table.physical is False
    strict = text.replace(' physical="false"', "")
    with pytest.raises(FormatError, match="triangle inequality"):
        import_urdf(strict, tip="tool")
    with pytest.raises(FormatError, match="physical must be true or false"):
        import_urdf(text.replace('physical="false"', 'physical="maybe"'), tip="tool")
