r"""Writing a URDF: a DH table as one URDF link per DH frame, built with ElementTree.

:func:`write_urdf` writes one URDF link per DH frame (``link0`` … ``linkn``, ``world``
before a base transform, ``tool`` after a tool transform), joints whose origins are the
constant part of each link matrix, cylinders on the joint axes and boxes along the links
sized from the DH lengths. In the standard convention the joint moves before the constant
``Tx(a) Rx(α)`` of its row, so the body it moves is one more link, ``link{k}_joint``, fixed
to DH frame k. A row's ``inertia`` becomes ``link{k}``'s ``<inertial>``, in DH frame k.

The document is an :mod:`xml.etree.ElementTree` tree (names and values escaped by the
serializer), laid out two spaces an indent with a material's colour and a visual's shape
on one line; the same table gives the same bytes.

Examples
--------
>>> from dhsym.robot import load
>>> text = write_urdf(load("planar2r").table.with_values({"a1": 1, "a2": 0.5}))
>>> print("\n".join(text.splitlines()[3:6]))
<robot name="Planar_2R">
  <material name="dhsym_grey"><color rgba="0.6 0.6 0.65 1" /></material>
  <material name="dhsym_orange"><color rgba="0.95 0.5 0.1 1" /></material>
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.geometry.conversion import euler_solution
from dhsym.kinematics.numeric import to_float
from dhsym.kinematics.transforms import link_word, plain_product
from dhsym.model.entries import exact_decimal
from dhsym.model.inertia import LinkInertia
from dhsym.model.kinds import JointType
from dhsym.model.table import DHTable, Elementary

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["write_urdf"]

Expr: TypeAlias = sp.Expr
#: Elements whose children stay on their line: a material's colour, a visual's shape.
_INLINE = ("material", "geometry")
_MATERIALS = (("dhsym_grey", "0.6 0.6 0.65 1"), ("dhsym_orange", "0.95 0.5 0.1 1"))


@dataclass(frozen=True)
class _Joint:
    name: str
    kind: str  # revolute, continuous, prismatic, fixed
    parent: str
    child: str
    origin: sp.ImmutableMatrix
    limits: tuple[Expr, Expr] | None = None
    sign: int = 1  # -1: the variable turns about (slides along) -z (a flipped joint)


def write_urdf(robot: KinematicChain | DHTable, *, name: str | None = None) -> str:
    """A URDF of a DH table: one link per DH frame, joints on the DH z axes, simple visuals.

    Symbolic lengths need numbers (the table's ``values``). The joint variables keep
    their meaning: URDF joint k at q is the table's variable k at q.

    >>> from dhsym.robot import load
    >>> text = write_urdf(load("planar2r").table.with_values({"a1": 1, "a2": 0.5}))
    >>> print(text.splitlines()[3])
    <robot name="Planar_2R">
    >>> for line in text.splitlines():
    ...     if "<joint " in line:
    ...         print(line.strip())
    <joint name="joint1" type="revolute">
    <joint name="link1_joint_to_link1" type="fixed">
    <joint name="joint2" type="revolute">
    <joint name="link2_joint_to_link2" type="fixed">
    <joint name="link2_to_tool" type="fixed">
    """
    table = robot if isinstance(robot, DHTable) else robot.table
    table = table.substituted()
    if table.constants:
        missing = ", ".join(str(s) for s in table.constants)
        raise DHError(
            f"{table.name or 'the table'} has symbolic lengths {missing}: give them numbers "
            "(table.with_values({...}) or values: in the table file) to write a URDF"
        )
    joints = _urdf_joints(table)
    links = ["world" if table.base else "link0"] + [j.child for j in joints]
    return _render(_robot_name(name or table.name), links, joints, table)


def _urdf_joints(table: DHTable) -> list[_Joint]:
    """The URDF joints of a table: base, each row (moving, maybe a fixed rest), tool."""
    out: list[_Joint] = []
    if table.base:
        out.append(_Joint("world_to_link0", "fixed", "world", "link0", plain_product(table.base)))
    parent = "link0"
    for k, row in enumerate(table.rows, start=1):
        word = list(link_word(row, table.convention))
        if row.variable is None:  # a fixed row: one fixed joint
            out.append(_Joint(f"joint{k}", "fixed", parent, f"link{k}", plain_product(word)))
            parent = f"link{k}"
            continue
        at = next(i for i, e in enumerate(word) if row.variable in e.value.free_symbols)
        motion, pre, post = word[at], word[:at], word[at + 1 :]
        while post and post[0].axis == "z":  # Rz and Tz commute with a motion about/along z
            pre.append(post.pop(0))
        slope = sp.expand(motion.value).coeff(row.variable)
        if slope not in (1, -1):
            raise DHError(
                f"row {k}: {motion.value} is not ±{row.variable} plus a constant; a URDF joint "
                "moves by its variable"
            )
        fixed_part = Elementary(motion.kind, "z", sp.expand(motion.value).subs(row.variable, 0))
        origin = plain_product([*pre[:at], fixed_part, *pre[at:]])
        kind = "prismatic" if row.joint is JointType.PRISMATIC else "revolute"
        if row.limits is None and kind == "revolute":
            kind = "continuous"
        body = f"link{k}" if not post else f"link{k}_joint"
        out.append(_Joint(f"joint{k}", kind, parent, body, origin, row.limits, int(slope)))
        if post:
            out.append(_Joint(f"{body}_to_link{k}", "fixed", body, f"link{k}", plain_product(post)))
        parent = f"link{k}"
    if table.tool:
        out.append(_Joint(f"{parent}_to_tool", "fixed", parent, "tool", plain_product(table.tool)))
    else:  # a tool link all the same, so that the last arm link gets its box
        out.append(
            _Joint(f"{parent}_to_tool", "fixed", parent, "tool", sp.ImmutableMatrix(sp.eye(4)))
        )
    return out


def _robot_name(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name.strip()) or "dhsym_robot"


def _text(value: Expr) -> str:
    """An exact number as its decimal when it has one, else the float's shortest repr."""
    value = sp.nsimplify(value) if isinstance(value, sp.Float) else value
    return exact_decimal(value) or repr(to_float(value))


def _xyz_rpy(T: sp.MatrixBase) -> tuple[str, str]:
    xyz = " ".join(_text(sp.simplify(T[i, 3])) for i in range(3))
    R = np.array([[to_float(T[i, j]) for j in range(3)] for i in range(3)])
    found = euler_solution(R, (2, 1, 0), exact=False)
    yaw, pitch, roll = (0.0, 0.0, 0.0) if found is None else found[0]
    rpy = " ".join(repr(float(a) + 0.0) if abs(a) > 1e-15 else "0" for a in (roll, pitch, yaw))
    return xyz, rpy


def _render(name: str, links: list[str], joints: list[_Joint], table: DHTable) -> str:
    """The URDF text: the XML declaration, two comments on what it is, the robot."""
    robot = _robot(name, links, joints, table)
    _layout(robot)
    about = (
        f" {re.sub('-{2,}', '-', name)}: written by dhsym from its {table.convention.value} DH "
        "table; one link per DH frame (linkK = DH frame K) "
    )  # a comment cannot hold "--"
    parts = [
        '<?xml version="1.0"?>',
        ET.tostring(ET.Comment(about), encoding="unicode"),
        ET.tostring(
            ET.Comment(" cylinders sit on the joint axes, boxes run along the links; no meshes "),
            encoding="unicode",
        ),
        ET.tostring(robot, encoding="unicode"),
    ]
    return "\n".join(parts) + "\n"


def _robot(name: str, links: list[str], joints: list[_Joint], table: DHTable) -> ET.Element:
    """The ``<robot>`` element: the two materials, links with visuals, then joints."""
    offsets: dict[str, list[np.ndarray]] = {link: [] for link in links}
    for j in joints:
        M = np.array([[to_float(x) for x in row] for row in j.origin.tolist()])
        offsets[j.parent].append(M[:3, 3])
    reach = sum(float(np.linalg.norm(p)) for ps in offsets.values() for p in ps)
    r = max(reach, 0.2) * 0.03
    moved = {j.child: j.kind for j in joints if j.kind != "fixed"}
    inertias = {f"link{k}": row.inertia for k, row in enumerate(table.rows, start=1)}
    robot = ET.Element("robot", name=name)
    if not table.physical:  # read back with the triangle inequality off, as the table says
        robot.set("physical", "false")
    for material, rgba in _MATERIALS:
        ET.SubElement(ET.SubElement(robot, "material", name=material), "color", rgba=rgba)
    for link in links:
        el = ET.SubElement(robot, "link", name=link)
        if link in moved:
            shape = (
                ET.Element("cylinder", radius=_f(r), length=_f(3 * r))
                if moved[link] != "prismatic"
                else ET.Element("box", size=f"{_f(1.6 * r)} {_f(1.6 * r)} {_f(3 * r)}")
            )
            el.append(_visual(np.zeros(3), "0 0 0", shape, "dhsym_orange"))
        for p in offsets[link]:
            length = float(np.linalg.norm(p))
            if length < 1e-9:
                continue
            u = p / length
            yaw, pitch = math.atan2(u[1], u[0]), math.atan2(-u[2], math.hypot(u[0], u[1]))
            shape = ET.Element("box", size=f"{_f(length)} {_f(r)} {_f(r)}")
            el.append(_visual(p / 2, f"0 {_f(pitch)} {_f(yaw)}", shape, "dhsym_grey"))
        inertia = inertias.get(link)
        if inertia is not None:
            el.append(_inertial(inertia))
    for j in joints:
        xyz, rpy = _xyz_rpy(j.origin)
        el = ET.SubElement(robot, "joint", name=j.name, type=j.kind)
        ET.SubElement(el, "parent", link=j.parent)
        ET.SubElement(el, "child", link=j.child)
        ET.SubElement(el, "origin", xyz=xyz, rpy=rpy)
        if j.kind != "fixed":
            ET.SubElement(el, "axis", xyz=f"0 0 {j.sign}")
        if j.kind in ("revolute", "prismatic"):
            lo, hi = j.limits if j.limits is not None else (sp.Integer(-1), sp.Integer(1))
            ET.SubElement(el, "limit", lower=_text(lo), upper=_text(hi), effort="0", velocity="0")
            if j.limits is None:
                el.append(ET.Comment(" no limits in the DH table "))
    return robot


def _layout(el: ET.Element, level: int = 0) -> None:
    """Line breaks and indents (two spaces a level) as the element's text and tails: each
    child on its own line, except inside a material or a geometry (one line) and a comment,
    which follows its element on the same line; an empty link still closes on its own line.

    >>> el = ET.fromstring('<link name="a"><visual><geometry><box size="1 1 1"/></geometry>'
    ...                    '</visual></link>')
    >>> _layout(el)
    >>> print(ET.tostring(el, encoding="unicode"))
    <link name="a">
      <visual>
        <geometry><box size="1 1 1" /></geometry>
      </visual>
    </link>
    """
    if el.tag in _INLINE:
        return
    if len(el) == 0:
        if el.tag == "link":
            el.text = "\n" + "  " * level
        return
    inside = "\n" + "  " * (level + 1)
    el.text = inside
    for child, after in zip(el, [*el[1:], None], strict=True):
        _layout(child, level + 1)
        # typeshed types tag as str, but a comment's tag is the ET.Comment factory itself
        comment = after is not None and after.tag is ET.Comment  # type: ignore[comparison-overlap]
        child.tail = "  " if comment else inside
    el[-1].tail = "\n" + "  " * level


def _inertial(inertia: LinkInertia) -> ET.Element:
    r"""``<inertial>`` of a DH link: the centre of mass and the inertia about it, both in the
    link's own frame (DH frame k), so the origin has no rotation. Motor inertia, gearing and
    friction have no place in URDF and are left out.

    >>> L = LinkInertia(sp.Rational(3, 2), (0, 0, sp.Rational(1, 10)), sp.diag(1, 2, 3))
    >>> el = _inertial(L)
    >>> _layout(el)
    >>> print(ET.tostring(el, encoding="unicode"))
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 0" />
      <mass value="1.5" />
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3" />
    </inertial>
    """
    I = inertia.I  # noqa: E741 (the inertia)
    if inertia.free_symbols:
        names = ", ".join(sorted(str(s) for s in inertia.free_symbols))
        raise DHError(f"symbolic inertial parameters {names}: give them numbers to write a URDF")
    values = {
        "ixx": I[0, 0], "ixy": I[0, 1], "ixz": I[0, 2],
        "iyy": I[1, 1], "iyz": I[1, 2], "izz": I[2, 2],
    }  # fmt: skip
    el = ET.Element("inertial")
    ET.SubElement(el, "origin", xyz=" ".join(_text(v) for v in inertia.r), rpy="0 0 0")
    ET.SubElement(el, "mass", value=_text(inertia.m))
    ET.SubElement(el, "inertia", {k: _text(v) for k, v in values.items()})
    return el


def _f(x: float) -> str:
    return f"{x:.6g}"


def _visual(xyz: np.ndarray, rpy: str, shape: ET.Element, material: str) -> ET.Element:
    """A ``<visual>``: where the shape sits, the shape, its material."""
    el = ET.Element("visual")
    ET.SubElement(el, "origin", xyz=" ".join(_f(v) for v in xyz), rpy=rpy)
    ET.SubElement(el, "geometry").append(shape)
    ET.SubElement(el, "material", name=material)
    return el
