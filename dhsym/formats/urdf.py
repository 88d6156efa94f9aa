"""URDF in and out: a robot description's joint chain as a DH table, and a DH table as a URDF.

**In.** :func:`read_urdf` reads the file through :mod:`.xmlsafe` (no DTD, no entities,
nothing outside the file; meshes and ``package://`` paths are never opened) into a
:class:`UrdfModel` of frozen values, numbers kept exactly as written (``0.089159``
stays 89159/1000000). :func:`import_urdf` follows the chain from the root link (or
``base``) to ``tip``, places each moving joint's axis at the home pose (every joint at
zero) in the base link's coordinates, folds ``fixed`` joints into those placements,
and runs the lectures' frame-assignment algorithm
(:func:`~dhsym.geometry.frames.assign_frames`) on the axes, with the tip link's frame as
the tool. The DH z axes point along the URDF axes and the variables are zero at the
URDF zero, so q means the same in both: ``robot.fk(q)`` is the URDF chain's pose of the
tip link in the base link for every q. ``revolute`` and ``continuous`` joints become
revolute rows, ``prismatic`` ones prismatic rows (``limit`` becomes the row's limits);
``mimic``, ``floating`` and ``planar`` joints on the chain are refused. Each link's
``<inertial>`` becomes part of ``row.inertia`` of the DH link that moves it (links fixed
below it merged by the parallel-axis theorem), in DH frame k; the base's and off-chain
links' inertials are left out with a warning.

Angles in ``rpy`` that are a multiple of π/12 rounded to the digits written
(``1.57079632679``) are read as that multiple, as the table reader does
(:mod:`dhsym.model.angles`), and the table's warnings say so. Other angles
(``-1.8``) are measurements: their cosines are floats (as in the transform kernel),
and positions that depend on them are read as the simplest exact number within 1e-12.

**Out.** :func:`write_urdf` writes one URDF link per DH frame (``link0`` … ``linkn``,
``world`` before a base transform, ``tool`` after a tool transform), joints whose
origins are the constant part of each link matrix, cylinders on the joint axes and boxes
along the links sized from the DH lengths. In the standard convention the joint moves
before the constant ``Tx(a) Rx(α)`` of its row, so the body it moves is one more link,
``link{k}_joint``, fixed to DH frame k. A row's ``inertia`` becomes ``link{k}``'s
``<inertial>``, in DH frame k.

Examples
--------
>>> text = '''<robot name="two">
...   <link name="base"/><link name="upper"/><link name="tip"/>
...   <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
...     <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
...     <limit lower="-3.1" upper="3.1" effort="1" velocity="1"/></joint>
...   <joint name="elbow" type="continuous"><parent link="upper"/><child link="tip"/>
...     <origin xyz="0.25 0 0"/><axis xyz="0 0 1"/></joint>
... </robot>'''
>>> robot = chain_from_urdf(text)
>>> [(r.theta, r.d, r.a, r.alpha) for r in robot.table.rows]
[(theta1, 0, 1/4, 0), (theta2, 1/10, 0, 0)]
>>> robot.table.rows[0].limits, robot.table.rows[1].label
((-31/10, 31/10), 'elbow')
>>> again = chain_from_urdf(write_urdf(robot))
>>> bool(abs(again.fk([0.3, -0.2]) - robot.fk([0.3, -0.2])).max() < 1e-12)
True
"""

from __future__ import annotations

import math
import os
import re
import textwrap
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeAlias
from xml.etree.ElementTree import Element
from xml.sax.saxutils import quoteattr

import numpy as np
import sympy as sp

from dhsym.errors import DHError, FormatError
from dhsym.geometry.axes import JointAxis, Tool, exact_number
from dhsym.geometry.conversion import euler_solution
from dhsym.geometry.frames import FrameAssignment, assign_frames
from dhsym.kinematics.numeric import to_float
from dhsym.kinematics.transforms import chain_word, link_word, plain_product, rigid_inverse
from dhsym.model.angles import AngleSnap, Snapped, snap_angle, snap_note
from dhsym.model.entries import exact_decimal
from dhsym.model.inertia import LinkInertia
from dhsym.model.kinds import Convention, JointType
from dhsym.model.parsing import numeral_problem
from dhsym.model.table import DHTable, Elementary
from dhsym.model.tablefile import dump_table

from .xmlsafe import read_xml, read_xml_file

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "MAX_CHAIN",
    "MAX_LINKS",
    "Inertial",
    "Origin",
    "UrdfImport",
    "UrdfJoint",
    "UrdfModel",
    "chain_from_urdf",
    "import_urdf",
    "is_urdf_source",
    "read_urdf",
    "table_yaml",
    "write_urdf",
]

Expr: TypeAlias = sp.Expr
Triple: TypeAlias = tuple[sp.Expr, sp.Expr, sp.Expr]
_ZERO: Triple = (sp.Integer(0), sp.Integer(0), sp.Integer(0))
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_MOVING = {"revolute": "R", "continuous": "R", "prismatic": "P"}
_KINDS = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
_SUFFIXES = (".urdf", ".xacro")
#: Most joints (fixed and moving) on the chain from base to tip; arms have 6 to 20.
MAX_CHAIN = 100
#: Most links (and most joints) in a URDF; a humanoid with hands has about 100.
MAX_LINKS = 2000


# --- the model: frozen values -----------------------------------------------------------


@dataclass(frozen=True)
class Origin:
    """A URDF ``<origin xyz rpy>``: translation, then ``Rz(yaw) Ry(pitch) Rx(roll)``.

    >>> Origin((0, 0, sp.Rational(1, 10)), (sp.pi / 2, 0, 0)).word
    (Tz(1/10), Rx(pi/2))
    """

    xyz: Triple = _ZERO
    rpy: Triple = _ZERO

    @property
    def word(self) -> tuple[Elementary, ...]:
        """The non-trivial elementary transforms, in multiplication order."""
        (x, y, z), (roll, pitch, yaw) = self.xyz, self.rpy
        word = [Elementary("T", "x", x), Elementary("T", "y", y), Elementary("T", "z", z)]
        word += [Elementary("R", "z", yaw), Elementary("R", "y", pitch), Elementary("R", "x", roll)]
        return tuple(e for e in word if e.value != 0)

    @property
    def matrix(self) -> sp.ImmutableMatrix:
        """The 4×4 transform, from the one kernel (``plain_product``)."""
        return plain_product(self.word)

    @property
    def rational_matrix(self) -> sp.ImmutableMatrix:
        """The transform with each measured angle (no rational multiple of π) replaced by the
        nearest angle whose cosine and sine are rational (``tan(θ/2)`` within 1e-13), so the
        rotation stays exactly orthogonal and exact arithmetic stays rational.

        >>> Origin(rpy=(sp.Rational(-9, 5), 0, 0)).rational_matrix[1:3, 1:3]
        Matrix([
        [ -6500857724477/28612666328005, 27864377316636/28612666328005],
        [-27864377316636/28612666328005, -6500857724477/28612666328005]])
        """
        out = sp.eye(4)
        for e in self.word:
            if e.kind == "R" and not (e.value / sp.pi).is_rational:
                out = out * _rational_rotation(e.axis, e.value)
            else:
                out = out * plain_product([e])
        return sp.ImmutableMatrix(out)


def _rational_rotation(axis: str, angle: Expr) -> sp.Matrix:
    """Rotation about x, y or z by the angle with ``tan(angle/2) = t`` rational (Weierstrass:
    ``cos = (1 - t²)/(1 + t²)``, ``sin = 2t/(1 + t²)``), t within about 1e-13 of the true one."""
    t = Fraction(math.tan(to_float(angle) / 2)).limit_denominator(10**7)
    t = sp.Rational(t.numerator, t.denominator)
    c, s = (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    M = sp.eye(4)
    M[i, i], M[i, j], M[j, i], M[j, j] = c, -s, s, c
    return M


@dataclass(frozen=True)
class Inertial:
    """A link's ``<inertial>``: mass, centre-of-mass origin, inertia (ixx ixy ixz iyy iyz izz)
    about the centre of mass in the origin's axes, as written."""

    mass: Expr
    origin: Origin
    inertia: tuple[Expr, Expr, Expr, Expr, Expr, Expr]


@dataclass(frozen=True)
class UrdfJoint:
    """One ``<joint>``: kind, parent and child links, origin, unit axis, limits, mimic."""

    name: str
    kind: str
    parent: str
    child: str
    origin: Origin
    axis: Triple
    limits: tuple[Expr, Expr] | None = None
    mimic: str | None = None
    snapped: tuple[Snapped, ...] = ()

    @property
    def moving(self) -> bool:
        """True for revolute, continuous and prismatic joints."""
        return self.kind in _MOVING


@dataclass(frozen=True)
class UrdfModel:
    """A URDF robot: its links (with inertials) and joints, and the angles read as exact."""

    name: str
    links: tuple[tuple[str, Inertial | None], ...]
    joints: tuple[UrdfJoint, ...]
    file: str | None = None
    snapped: tuple[Snapped, ...] = ()

    @property
    def link_names(self) -> tuple[str, ...]:
        """The link names in file order."""
        return tuple(name for name, _ in self.links)

    @property
    def root(self) -> str:
        """The one link that is no joint's child.

        >>> read_urdf("<robot name='r'><link name='a'/></robot>").root
        'a'
        """
        children = {j.child for j in self.joints}
        roots = [n for n in self.link_names if n not in children]
        if len(roots) != 1:
            what = (
                "every link is some joint's child: the links form a cycle"
                if not roots
                else f"links {', '.join(roots)} are no joint's child: the tree is not connected"
            )
            raise FormatError(f"a URDF has one root link; {what}", file=self.file, field="robot")
        return roots[0]

    def parent_joint(self, link: str) -> UrdfJoint | None:
        """The joint whose child is ``link`` (None for the root)."""
        return next((j for j in self.joints if j.child == link), None)

    def below(self, start: str) -> dict[str, int]:
        """Every link below ``start`` (inclusive), with the number of moving joints from
        ``start`` to it (one pass down the tree)."""
        children: dict[str, list[UrdfJoint]] = {}
        for j in self.joints:
            children.setdefault(j.parent, []).append(j)
        counts, todo = {start: 0}, [start]
        while todo:
            link = todo.pop()
            for j in children.get(link, ()):
                if j.child not in counts:  # the tree is checked when read; be safe anyway
                    counts[j.child] = counts[link] + int(j.moving)
                    todo.append(j.child)
        return counts

    def leaves(self, start: str) -> list[str]:
        """Links below ``start`` (inclusive) that are no joint's parent, in file order.

        >>> read_urdf("<robot name='r'><link name='a'/></robot>").leaves("a")
        ['a']
        """
        below = self.below(start)
        parents = {j.parent for j in self.joints}
        return [n for n in self.link_names if n in below and n not in parents]

    def chain(self, base: str, tip: str) -> tuple[UrdfJoint, ...]:
        """The joints from link ``base`` down to link ``tip``, in order.

        >>> m = read_urdf('''<robot name="r"><link name="a"/><link name="b"/>
        ...   <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>''')
        >>> [j.name for j in m.chain("a", "b")]
        ['j']
        """
        for link, what in ((base, "base"), (tip, "tip")):
            if link not in self.link_names:
                raise FormatError(
                    f"no link named {link!r} (links: {_listing(self.link_names)})",
                    file=self.file,
                    field=what,
                )
        parent = {j.child: j for j in self.joints}
        out: list[UrdfJoint] = []
        link = tip
        while link != base:
            joint = parent.get(link)
            if joint is None or len(out) > len(parent):
                raise FormatError(
                    f"link {base!r} is not above link {tip!r}: the path from the root "
                    f"{self.root!r} to {tip!r} does not pass through it",
                    file=self.file,
                    field="base",
                )
            out.append(joint)
            link = joint.parent
        return tuple(reversed(out))


@dataclass(frozen=True)
class UrdfImport:
    """A URDF chain read as a DH table: the chain, the frame assignment, the table, inertials.

    ``inertials`` are the links' ``<inertial>`` as written (in each URDF link's own
    frame), from the base link to the tip link; the table's rows carry them converted
    into the DH link frames (``row.inertia``, see :func:`import_urdf`).
    """

    model: UrdfModel
    base: str
    tip: str
    joints: tuple[UrdfJoint, ...]
    assignment: FrameAssignment
    table: DHTable
    inertials: tuple[tuple[str, Inertial], ...]

    @property
    def moving(self) -> tuple[UrdfJoint, ...]:
        """The joints that became DH rows, in order."""
        return tuple(j for j in self.joints if j.moving)

    @property
    def steps(self) -> list[str]:
        """The frame-assignment sentences, one per choice."""
        return self.assignment.step_texts

    def chain(self, **kw: Any) -> KinematicChain:  # its keywords: compact, style
        """A :class:`~dhsym.kinematics.chain.KinematicChain` of the table (``compact``,
        ``style``)."""
        from dhsym.kinematics.chain import KinematicChain

        return KinematicChain(self.table, **kw)


# --- reading ---------------------------------------------------------------------------------


def is_urdf_source(source: object) -> bool:
    """True for a URDF or xacro path (by suffix) or URDF text (starts with ``<``).

    >>> is_urdf_source("ur5.urdf"), is_urdf_source("<robot/>"), is_urdf_source("puma560")
    (True, True, False)
    """
    if isinstance(source, os.PathLike):
        return Path(source).suffix.lower() in _SUFFIXES
    return isinstance(source, str) and (
        source.lstrip().startswith("<") or Path(source).suffix.lower() in _SUFFIXES
    )


def read_urdf(
    source: str | os.PathLike[str], *, snap_angles: AngleSnap | bool | float | None = True
) -> UrdfModel:
    """Read a URDF file (a path) or URDF text (starting with ``<``) into a :class:`UrdfModel`.

    >>> m = read_urdf('''<robot name="r"><link name="a"/><link name="b"/>
    ...   <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    ...   <origin xyz="0 0 0.089159" rpy="0 1.57079632679 0"/></joint></robot>''')
    >>> m.joints[0].origin, m.joints[0].axis
    (Origin(xyz=(0, 0, 89159/1000000), rpy=(0, pi/2, 0)), (1, 0, 0))
    >>> read_urdf("<robot name='r'><link name='a'/><link name='a'/></robot>")
    Traceback (most recent call last):
    ...
    dhsym.errors.FormatError: field <link name='a'>: a second link with this name
    """
    rule = AngleSnap.parse(snap_angles)
    if isinstance(source, str) and source.lstrip().startswith("<"):
        root, file = read_xml(source), None
    else:
        if Path(source).suffix.lower() == ".xacro":
            raise FormatError(
                "a .xacro file is a macro that expands to a URDF: expand it first with the "
                "xacro command (pip install 'dhsym[urdf]' installs it), e.g. "
                "`xacro robot.urdf.xacro > robot.urdf`, then read robot.urdf; dhsym does not "
                "run xacro itself, because xacro evaluates the file's ${...} expressions as "
                "Python",
                file=str(source),
            )
        root, file = read_xml_file(source)
    return _model(root, file, rule)


def _model(root: Element, file: str | None, rule: AngleSnap) -> UrdfModel:
    if root.tag != "robot":
        raise FormatError(
            f"the root element is <{root.tag}>, expected <robot>", file=file, field=f"<{root.tag}>"
        )
    for tag in ("link", "joint"):
        count = sum(1 for _ in root.iterfind(tag))
        if count > MAX_LINKS:
            raise FormatError(
                f"the robot has {count} {tag}s: at most {MAX_LINKS} are read",
                file=file,
                field=f"<{tag}>",
            )
    snapped: list[Snapped] = []
    links: list[tuple[str, Inertial | None]] = []
    names: set[str] = set()
    for el in root.findall("link"):
        name = _name(el, file)
        if name in names:
            raise FormatError("a second link with this name", file=file, field=_where(el))
        names.add(name)
        inertial = el.find("inertial")
        links.append(
            (name, None if inertial is None else _inertial(inertial, el, file, rule, snapped))
        )
    joints: list[UrdfJoint] = []
    joint_names: set[str] = set()
    parent_of: dict[str, UrdfJoint] = {}  # child link -> its joint (local to this read)
    for el in root.findall("joint"):
        joint = _joint(el, file, rule, snapped)
        where = _where(el)
        if joint.name in joint_names:
            raise FormatError("a second joint with this name", file=file, field=where)
        joint_names.add(joint.name)
        for role in ("parent", "child"):
            link = getattr(joint, role)
            if link not in names:
                raise FormatError(f"{role} link {link!r} is not defined", file=file, field=where)
        if joint.parent == joint.child:
            raise FormatError(
                "the joint's parent and child are the same link", file=file, field=where
            )
        other = parent_of.get(joint.child)
        if other is not None:
            raise FormatError(
                f"link {joint.child!r} is already the child of joint {other.name!r}: a URDF is a "
                "tree (each link has one parent joint); closed loops are not supported",
                file=file,
                field=where,
            )
        joints.append(joint)
        parent_of[joint.child] = joint
    model = UrdfModel(root.get("name", ""), tuple(links), tuple(joints), file, tuple(snapped))
    if links:
        _check_acyclic(model)
    return model


def _check_acyclic(model: UrdfModel) -> None:
    """Each link has at most one parent, so the links form a forest plus cycles: walk up from
    every link once, marking links already known to reach the root (linear time)."""
    parent = {j.child: j for j in model.joints}
    reaches_root: set[str] = set()
    for start in model.link_names:
        path, on_path, link = [], set(), start
        while link in parent and link not in reaches_root:
            if link in on_path:
                raise FormatError(
                    f"the links form a cycle through link {link!r}: a URDF is a tree",
                    file=model.file,
                    field=_where_joint(parent[link].name),
                )
            path.append(link)
            on_path.add(link)
            link = parent[link].parent
        reaches_root.update(path)
        reaches_root.add(link)
    _ = model.root  # exactly one root


def _name(el: Element, file: str | None) -> str:
    name = el.get("name")
    if not name or not name.strip():
        raise FormatError("missing the name attribute", file=file, field=f"<{el.tag}>")
    if len(name) > 200:
        raise FormatError("a name longer than 200 characters", file=file, field=f"<{el.tag}>")
    return name


def _where(el: Element, child: str = "", attr: str = "") -> str:
    head = f"<{el.tag} name={el.get('name', '')[:80]!r}>"
    return head + (f" <{child}>" if child else "") + (f" {attr}" if attr else "")


def _where_joint(name: str) -> str:
    return f"<joint name={name[:80]!r}>"


def _numbers(
    text: str | None, count: int, where: str, file: str | None, default: str | None = None
) -> tuple[Expr, ...]:
    """``count`` exact numbers from a whitespace-separated attribute (decimals kept exact)."""
    if text is None:
        if default is None:
            raise FormatError("missing attribute", file=file, field=where)
        text = default
    parts = text.split()
    if len(parts) != count:
        raise FormatError(
            f"expected {count} number{'s' if count > 1 else ''}, got {text[:80]!r}",
            file=file,
            field=where,
        )
    out = []
    for part in parts:
        if not _NUMBER.fullmatch(part):
            hint = (
                "; xacro expressions must be expanded first (xacro robot.urdf.xacro > robot.urdf)"
                if "$" in part
                else ""
            )
            raise FormatError(
                f"{part[:40]!r} is not a finite decimal number{hint}", file=file, field=where
            )
        if problem := numeral_problem(part):
            raise FormatError(f"{problem[0]}: {problem[1]}", file=file, field=where)
        out.append(sp.Rational(part))
    return tuple(out)


def _origin(parent: Element, file: str | None, rule: AngleSnap, snapped: list[Snapped]) -> Origin:
    el = parent.find("origin")
    if el is None:
        return Origin()
    xyz = _numbers(el.get("xyz"), 3, _where(parent, "origin", "xyz"), file, "0 0 0")
    rpy = []
    for value in _numbers(el.get("rpy"), 3, _where(parent, "origin", "rpy"), file, "0 0 0"):
        found = snap_angle(value, rule)
        if found is not None:
            snapped.append(Snapped("origin rpy", None, value, found[0], found[1]))
            value = found[0]
        rpy.append(value)
    return Origin(xyz, tuple(rpy))


def _inertial(
    el: Element, link: Element, file: str | None, rule: AngleSnap, snapped: list[Snapped]
) -> Inertial:
    mass_el = el.find("mass")
    where = _where(link, "inertial")
    mass = _numbers(None if mass_el is None else mass_el.get("value"), 1, where + " <mass>", file)[
        0
    ]
    inertia_el = el.find("inertia")
    keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    if inertia_el is None:
        raise FormatError("missing <inertia>", file=file, field=where)
    inertia = tuple(_numbers(inertia_el.get(k), 1, f"{where} <inertia> {k}", file)[0] for k in keys)
    return Inertial(mass, _origin(el, file, rule, snapped), inertia)


def _joint(el: Element, file: str | None, rule: AngleSnap, snapped: list[Snapped]) -> UrdfJoint:
    name = _name(el, file)
    where = _where(el)
    kind = el.get("type", "")
    if kind not in _KINDS:
        raise FormatError(
            f"unknown joint type {kind[:40]!r}: expected one of {', '.join(_KINDS)}",
            file=file,
            field=where,
        )
    links = []
    for role in ("parent", "child"):
        tag = el.find(role)
        if tag is None or not tag.get("link"):
            raise FormatError(f"missing <{role} link=...>", file=file, field=where)
        links.append(tag.get("link", ""))
    own: list[Snapped] = []
    origin = _origin(el, file, rule, own)
    snapped += own
    axis: Triple = (sp.Integer(1), sp.Integer(0), sp.Integer(0))
    axis_el = el.find("axis")
    if kind in _MOVING and axis_el is not None:
        axis = _numbers(axis_el.get("xyz"), 3, _where(el, "axis", "xyz"), file, "1 0 0")
        if all(v == 0 for v in axis):
            raise FormatError(
                "the axis has zero length: a moving joint needs a direction",
                file=file,
                field=_where(el, "axis", "xyz"),
            )
    limits = None
    limit_el = el.find("limit")
    if kind in ("revolute", "prismatic") and limit_el is not None:
        lo = _numbers(limit_el.get("lower"), 1, _where(el, "limit", "lower"), file, "0")[0]
        hi = _numbers(limit_el.get("upper"), 1, _where(el, "limit", "upper"), file, "0")[0]
        if lo > hi:
            raise FormatError(
                f"lower {lo} is above upper {hi}", file=file, field=_where(el, "limit")
            )
        limits = None if lo == hi == 0 else (lo, hi)
    mimic_el = el.find("mimic")
    mimic = None if mimic_el is None else mimic_el.get("joint", "?")
    return UrdfJoint(name, kind, links[0], links[1], origin, axis, limits, mimic, tuple(own))


def _listing(names: Iterable[str], limit: int = 30) -> str:
    items = list(names)
    text = ", ".join(items[:limit])
    return text + (f", … ({len(items)} in all)" if len(items) > limit else "")


# --- the chain as a DH table -------------------------------------------------------------


def import_urdf(
    source: str | os.PathLike[str] | UrdfModel,
    tip: str | None = None,
    base: str | None = None,
    convention: Convention | str = "standard",
    *,
    snap_angles: AngleSnap | bool | float | None = True,
) -> UrdfImport:
    """Read a URDF and derive the DH table of the chain from ``base`` (default: the root)
    to ``tip`` (default: the one leaf link), with the frame-assignment sentences.

    >>> imp = import_urdf('''<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
    ...   <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    ...     <axis xyz="0 0 -1"/></joint>
    ...   <joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint></robot>''')
    Traceback (most recent call last):
    ...
    dhsym.errors.FormatError: field tip: the tree branches below link 'a': give the tip ... b ...
    """
    model = source if isinstance(source, UrdfModel) else read_urdf(source, snap_angles=snap_angles)
    if not model.links:
        raise FormatError("the robot has no links", file=model.file, field="<robot>")
    start = base or model.root
    if tip is None:
        leaves = model.leaves(start)
        if len(leaves) != 1:
            below = model.below(start)
            counts = [below[leaf] for leaf in leaves]
            choices = ", ".join(
                f"{leaf} ({c} moving joint{'s' if c != 1 else ''})"
                for leaf, c in zip(leaves, counts, strict=True)
            )
            raise FormatError(
                f"the tree branches below link {start!r}: give the tip link (tip=, --tip), one of "
                f"{choices}",
                file=model.file,
                field="tip",
            )
        tip = leaves[0]
    joints = model.chain(start, tip)
    if len(joints) > MAX_CHAIN:
        raise FormatError(
            f"the chain from {start!r} to {tip!r} has {len(joints)} joints: at most {MAX_CHAIN} "
            "are read (choose base= and tip= closer together)",
            file=model.file,
            field="tip",
        )
    moving = [j for j in joints if j.moving]
    for j in joints:
        if j.kind in ("floating", "planar"):
            raise FormatError(
                f"a {j.kind} joint has {'six' if j.kind == 'floating' else 'three'} degrees of "
                "freedom and no single axis: a DH row describes one revolute or prismatic "
                "joint; choose base= below it",
                file=model.file,
                field=_where_joint(j.name),
            )
        if j.mimic is not None and j.moving:
            raise FormatError(
                f"the joint mimics joint {j.mimic!r} (its value follows another joint's): a DH "
                "table has one independent variable per joint; choose a tip above it",
                file=model.file,
                field=_where_joint(j.name),
            )
    if not moving:
        raise FormatError(
            f"no revolute, continuous or prismatic joint between {start!r} and {tip!r}",
            file=model.file,
            field="tip",
        )
    axes, tool = _geometry(joints, model.file)
    try:
        fa = assign_frames(axes, convention=convention, tool=tool, name=model.name)
    except DHError as err:
        raise err.located(file=model.file) from None
    rows = tuple(
        replace(row, limits=j.limits if j.kind != "continuous" else None)
        for row, j in zip(fa.table.rows, moving, strict=True)
    )
    inertias, dropped = _dh_inertias(model, start, moving, replace(fa.table, rows=rows))
    rows = tuple(
        replace(row, inertia=inertia) if inertia is not None else row
        for row, inertia in zip(rows, inertias, strict=True)
    )
    snapped = [s for j in joints for s in j.snapped]
    note = snap_note(snapped, "snap_angles=False") if snapped else ""
    notes = [note] if note else []
    if dropped:
        notes.append("inertials not in the DH table: " + "; ".join(dropped))
    table = replace(
        fa.table,
        rows=rows,
        name=model.name or (Path(model.file).stem if model.file else "URDF robot"),
        source=f"URDF {Path(model.file).name if model.file else 'text'}, chain {start} -> {tip}",
        notes=(
            f"Read from {model.file or 'URDF text'}: links {start} to {tip}, joints "
            + ", ".join(j.name for j in moving)
            + "; DH z axes along the URDF axes, variables zero at the URDF zero."
        ),
        warnings=tuple(notes),
    )
    inertials = tuple(
        (name, inertial)
        for name, inertial in model.links
        if inertial is not None and (name == start or any(j.child == name for j in joints))
    )
    return UrdfImport(model, start, tip, joints, fa, table, inertials)


def chain_from_urdf(
    source: str | os.PathLike[str],
    tip: str | None = None,
    base: str | None = None,
    convention: Convention | str = "standard",
    *,
    snap_angles: AngleSnap | bool | float | None = True,
    **kw: object,
) -> KinematicChain:
    """A :class:`~dhsym.kinematics.chain.KinematicChain` from a URDF file or text (see
    :func:`import_urdf`).

    >>> r = chain_from_urdf('''<robot name="slide"><link name="a"/><link name="b"/>
    ...   <joint name="s" type="prismatic"><parent link="a"/><child link="b"/>
    ...     <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
    ... </robot>''', convention="modified")
    >>> r.table.rows[0], r.fk([0.2])[0, 3]
    (DHRow(P: theta=0, d=d1, a=0, alpha=0), np.float64(0.2))
    """
    imp = import_urdf(source, tip, base, convention, snap_angles=snap_angles)
    return imp.chain(**kw)


def _dh_inertias(
    model: UrdfModel, start: str, moving: Sequence[UrdfJoint], table: DHTable
) -> tuple[list[LinkInertia | None], list[str]]:
    """Each DH link's inertia (link k moves with row k) in DH frame k, and what was dropped.

    Every link below ``start`` joins the body of its nearest moving ancestor on the chain:
    links hung on by ``fixed`` joints (a hand, a flange, a tool-centre link) merge into the
    link they hang on (masses add, centres of mass combine, the parallel-axis theorem moves
    each inertia to the common centre). Links before the first moving joint form the base,
    which has no row; links behind a moving joint off the chain (fingers) are not on the
    chain. Both are named in the returned notes. Rotations stay exact where the ``rpy``
    angles are (snapped or rational multiples of π); measured angles use
    :attr:`Origin.rational_matrix`.
    """
    rows = {j.name: k for k, j in enumerate(moving, start=1)}
    children: dict[str, list[UrdfJoint]] = {}
    for j in model.joints:
        children.setdefault(j.parent, []).append(j)
    inertial = dict(model.links)
    bodies: list[list[tuple[sp.Matrix, Inertial]]] = [[] for _ in range(len(moving) + 1)]
    base: list[str] = []
    off: list[str] = []
    stack: list[tuple[str, sp.Matrix, int]] = [(start, sp.eye(4), 0)]
    while stack:
        link, T, body = stack.pop()
        found = inertial.get(link)
        if found is not None and (found.mass != 0 or any(v != 0 for v in found.inertia)):
            bodies[body].append((T * found.origin.rational_matrix, found))
            if body == 0:
                base.append(link)
        for j in children.get(link, []):
            if j.moving and j.name not in rows or j.kind in ("floating", "planar"):
                off.extend(_subtree(children, j.child, inertial))
                continue
            stack.append((j.child, T * j.origin.rational_matrix, rows.get(j.name, body)))
    zero = {v: 0 for v in table.variables}
    out: list[LinkInertia | None] = []
    for k in range(1, len(moving) + 1):
        if not bodies[k]:
            out.append(None)
            continue
        to_frame = rigid_inverse(plain_product(chain_word(table, -1, k)).subs(zero))
        parts = []
        for T, found in bodies[k]:
            M = to_frame * T
            xx, xy, xz, yy, yz, zz = found.inertia
            Ic = sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
            R = M[:3, :3]
            parts.append((found.mass, M[:3, 3], R * Ic * R.T))
        out.append(_combine(parts))
    dropped = []
    if base:
        dropped.append(", ".join(sorted(base)) + " (the base: it does not move and has no row)")
    if off:
        dropped.append(", ".join(off) + " (behind a moving joint that is not on the chain)")
    return out, dropped


def _subtree(
    children: dict[str, list[UrdfJoint]], link: str, inertial: dict[str, Inertial | None]
) -> list[str]:
    """The links with mass in the subtree of ``link`` (``link`` included)."""
    out, stack = [], [link]
    while stack:
        name = stack.pop()
        found = inertial.get(name)
        if found is not None and found.mass != 0:
            out.append(name)
        stack.extend(j.child for j in children.get(name, []))
    return out


def _combine(parts: Sequence[tuple[Expr, sp.MatrixBase, sp.MatrixBase]]) -> LinkInertia:
    """One rigid body of several: masses add, the centre of mass is the mass-weighted mean,
    each inertia moves to it by the parallel-axis theorem ``I + m (|d|² E − d dᵀ)``.

    >>> half = (sp.Integer(1), sp.Matrix([1, 0, 0]), sp.zeros(3))
    >>> both = _combine([half, (sp.Integer(1), sp.Matrix([-1, 0, 0]), sp.zeros(3))])
    >>> both.m, both.r, both.I.diagonal()
    (2, (0, 0, 0), Matrix([[0, 2, 2]]))
    """
    m = sum((p[0] for p in parts), sp.Integer(0))
    if m == 0:
        c = sp.zeros(3, 1)
    else:
        c = sum((p[0] * p[1] for p in parts), sp.zeros(3, 1)) / m
    total = sp.zeros(3)
    for mass, p, Ic in parts:
        d = sp.Matrix(p) - c
        total += Ic + mass * ((d.T * d)[0, 0] * sp.eye(3) - d * d.T)
    clean = [_tidy(v) for v in total]
    return LinkInertia(_tidy(m), tuple(_tidy(v) for v in c), sp.ImmutableMatrix(3, 3, clean))


def _tidy(value: Expr) -> Expr:
    """An exact entry, expanded; sums with float cosines read as exact within 1e-12."""
    value = sp.expand(value)
    return exact_number(to_float(value)) if value.has(sp.Float) else value


def _geometry(joints: Iterable[UrdfJoint], file: str | None) -> tuple[list[JointAxis], Tool]:
    """The moving joints' axes at home and the tip frame as a tool, in the base link's frame."""
    T = sp.eye(4)
    axes = []
    for j in joints:
        T = T * j.origin.rational_matrix
        if j.moving:
            direction = T[:3, :3] * sp.Matrix(j.axis)
            try:
                axes.append(JointAxis(_exact(T[:3, 3]), _exact(direction), _MOVING[j.kind], j.name))
            except DHError as err:
                raise FormatError(err.message, file=file, field=_where_joint(j.name)) from None
    return axes, Tool(_exact(T[:3, 3]), _exact(T[:3, 2]), _exact(T[:3, 1]))


def _exact(column: sp.MatrixBase) -> list[Expr]:
    """Entries as exact numbers; sums with float cosines (measured angles) read within 1e-12."""
    out = []
    for v in column:
        v = sp.expand(v)
        out.append(exact_number(to_float(v)) if v.has(sp.Float) else v)
    return out


def table_yaml(imp: UrdfImport) -> str:
    """The table as a YAML table file, headed by comments on where it came from and the
    frame-assignment sentences.

    >>> imp = import_urdf('''<robot name="r"><link name="a"/><link name="b"/>
    ...   <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
    ...   <axis xyz="0 0 1"/></joint></robot>''')
    >>> print(table_yaml(imp).splitlines()[0])
    # DH table (standard convention) of the URDF chain a -> b in URDF text, joints: j. Derived
    """
    where = imp.model.file or "URDF text"
    head = (
        f"DH table ({imp.table.convention.value} convention) of the URDF chain {imp.base} -> "
        f"{imp.tip} in {where}, joints: {', '.join(j.name for j in imp.moving)}. Derived by "
        "dhsym from the joint axes at the URDF zero pose with the frame-assignment algorithm; "
        "the variables keep the URDF's zero and direction, so fk(q) is the URDF pose of the "
        "tip link in the base link for every q."
    )
    lines = textwrap.wrap(head, 88)
    lines.append("Frame assignment:")
    for k, text in enumerate(imp.steps, start=1):
        lines += textwrap.wrap(f"{k}. {text}", 88, subsequent_indent="   ")
    lines += [w for note in imp.table.warnings for w in textwrap.wrap(f"Note: {note}", 88)]
    return "".join(f"# {line}\n" for line in lines) + dump_table(imp.table)


# --- writing ----------------------------------------------------------------------------------


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
    """The URDF text: links with visuals, then joints."""
    home = {links[0]: np.eye(4)}
    offsets: dict[str, list[np.ndarray]] = {link: [] for link in links}
    for j in joints:
        M = np.array([[to_float(x) for x in row] for row in j.origin.tolist()])
        home[j.child] = home[j.parent] @ M
        offsets[j.parent].append(M[:3, 3])
    reach = sum(float(np.linalg.norm(p)) for ps in offsets.values() for p in ps)
    r = max(reach, 0.2) * 0.03
    moved = {j.child: j.kind for j in joints if j.kind != "fixed"}
    inertias = {f"link{k}": row.inertia for k, row in enumerate(table.rows, start=1)}
    lines = [
        '<?xml version="1.0"?>',
        f"<!-- {name}: written by dhsym from its {table.convention.value} DH table; "
        "one link per DH frame (linkK = DH frame K) -->",
        "<!-- cylinders sit on the joint axes, boxes run along the links; no meshes -->",
        f"<robot name={quoteattr(name)}>",
        '  <material name="dhsym_grey"><color rgba="0.6 0.6 0.65 1"/></material>',
        '  <material name="dhsym_orange"><color rgba="0.95 0.5 0.1 1"/></material>',
    ]
    for link in links:
        lines.append(f"  <link name={quoteattr(link)}>")
        if link in moved:
            shape = (
                f'<cylinder radius="{_f(r)}" length="{_f(3 * r)}"/>'
                if moved[link] != "prismatic"
                else f'<box size="{_f(1.6 * r)} {_f(1.6 * r)} {_f(3 * r)}"/>'
            )
            lines += _visual(np.zeros(3), "0 0 0", shape, "dhsym_orange")
        for p in offsets[link]:
            length = float(np.linalg.norm(p))
            if length < 1e-9:
                continue
            u = p / length
            yaw, pitch = math.atan2(u[1], u[0]), math.atan2(-u[2], math.hypot(u[0], u[1]))
            shape = f'<box size="{_f(length)} {_f(r)} {_f(r)}"/>'
            lines += _visual(p / 2, f"0 {_f(pitch)} {_f(yaw)}", shape, "dhsym_grey")
        inertia = inertias.get(link)
        if inertia is not None:
            lines += _inertial_lines(inertia)
        lines.append("  </link>")
    for j in joints:
        xyz, rpy = _xyz_rpy(j.origin)
        lines += [
            f"  <joint name={quoteattr(j.name)} type={quoteattr(j.kind)}>",
            f"    <parent link={quoteattr(j.parent)}/>",
            f"    <child link={quoteattr(j.child)}/>",
            f'    <origin xyz="{xyz}" rpy="{rpy}"/>',
        ]
        if j.kind != "fixed":
            lines.append(f'    <axis xyz="0 0 {j.sign}"/>')
        if j.kind in ("revolute", "prismatic"):
            lo, hi = j.limits if j.limits is not None else (sp.Integer(-1), sp.Integer(1))
            note = "" if j.limits is not None else "  <!-- no limits in the DH table -->"
            lines.append(
                f'    <limit lower="{_text(lo)}" upper="{_text(hi)}" effort="0" velocity="0"/>'
                + note
            )
        lines.append("  </joint>")
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


def _inertial_lines(inertia: LinkInertia) -> list[str]:
    r"""``<inertial>`` of a DH link: the centre of mass and the inertia about it, both in the
    link's own frame (DH frame k), so the origin has no rotation. Motor inertia, gearing and
    friction have no place in URDF and are left out.

    >>> L = LinkInertia(sp.Rational(3, 2), (0, 0, sp.Rational(1, 10)), sp.diag(1, 2, 3))
    >>> print("\n".join(_inertial_lines(L)))
        <inertial>
          <origin xyz="0 0 0.1" rpy="0 0 0"/>
          <mass value="1.5"/>
          <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>
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
    moments = " ".join(f'{k}="{_text(v)}"' for k, v in values.items())
    return [
        "    <inertial>",
        f'      <origin xyz="{" ".join(_text(v) for v in inertia.r)}" rpy="0 0 0"/>',
        f'      <mass value="{_text(inertia.m)}"/>',
        f"      <inertia {moments}/>",
        "    </inertial>",
    ]


def _f(x: float) -> str:
    return f"{x:.6g}"


def _visual(xyz: np.ndarray, rpy: str, shape: str, material: str) -> list[str]:
    return [
        "    <visual>",
        f'      <origin xyz="{" ".join(_f(v) for v in xyz)}" rpy="{rpy}"/>',
        f"      <geometry>{shape}</geometry>",
        f'      <material name="{material}"/>',
        "    </visual>",
    ]
