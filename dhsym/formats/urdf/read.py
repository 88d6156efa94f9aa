"""Reading a URDF: the file or text, through the safe XML reader, into a :class:`.UrdfModel`.

The text goes through :mod:`dhsym.formats.xmlsafe` (no DTD, no entities, nothing outside
the file; meshes and ``package://`` paths are never opened). Numbers are read exactly as
written (``0.089159`` stays 89159/1000000); angles in ``rpy`` that are a multiple of π/12
rounded to the digits written (``1.57079632679``) are read as that multiple, as the table
reader does (:mod:`dhsym.model.angles`), and recorded in the model's ``snapped``. A
broken or hostile file raises one :class:`~dhsym.errors.FormatError` naming the element.

Examples
--------
>>> m = read_urdf('''<robot name="r"><link name="a"/><link name="b"/>
...   <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>''')
>>> m.root, m.joints[0].kind, m.joints[0].axis
('a', 'continuous', (1, 0, 0))
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from xml.etree.ElementTree import Element

import sympy as sp

from dhsym.errors import DHError, FormatError, TableError
from dhsym.model.angles import AngleSnap, Snapped, snap_angle
from dhsym.model.entries import as_expr
from dhsym.model.inertia import LinkInertia
from dhsym.model.parsing import numeral_problem

from ..xmlsafe import read_xml, read_xml_file
from .description import (
    JOINT_KINDS,
    MOVING_KINDS,
    Expr,
    Inertial,
    Origin,
    Triple,
    UrdfJoint,
    UrdfModel,
)

__all__ = ["MAX_LINKS", "is_urdf_source", "read_urdf"]

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_SUFFIXES = (".urdf", ".xacro")
#: Most links (and most joints) in a URDF; a humanoid with hands has about 100.
MAX_LINKS = 2000


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
    source: str | os.PathLike[str],
    *,
    snap_angles: AngleSnap | bool | float | None = True,
    physical: bool = True,
) -> UrdfModel:
    """Read a URDF file (a path) or URDF text (starting with ``<``) into a :class:`UrdfModel`.

    Each ``<inertial>`` is checked as the table reader checks a link's inertia
    (:meth:`~dhsym.model.inertia.LinkInertia.check`: no negative mass, an inertia that is
    symmetric positive semi-definite). The triangle inequality belongs to the rigid bodies
    the dynamics see, a link with the links fixed to it:
    :func:`~dhsym.formats.urdf.to_dh.import_urdf` checks it on them unless
    ``physical=False`` here or there, or ``<robot physical="false">``, as
    :func:`~dhsym.formats.urdf.write.write_urdf` writes a table marked ``physical: false``.

    >>> m = read_urdf('''<robot name="r"><link name="a"/><link name="b"/>
    ...   <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    ...   <origin xyz="0 0 0.089159" rpy="0 1.57079632679 0"/></joint></robot>''')
    >>> m.joints[0].origin, m.joints[0].axis
    (Origin(xyz=(0, 0, 89159/1000000), rpy=(0, pi/2, 0)), (1, 0, 0))
    >>> read_urdf("<robot name='r'><link name='a'/><link name='a'/></robot>")
    Traceback (most recent call last):
    ...
    dhsym.errors.FormatError: field <link name='a'>: a second link with this name
    >>> read_urdf('''<robot name="r"><link name="a"><inertial><mass value="-1"/>
    ...   <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>''')
    Traceback (most recent call last):
    ...
    dhsym.errors.FormatError: field <link name='a'> <inertial>: a mass cannot be negative (got -1)
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
    return _model(root, file, rule, physical)


def _model(root: Element, file: str | None, rule: AngleSnap, physical: bool) -> UrdfModel:
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
    declared = root.get("physical", "true").strip().lower()
    if declared not in ("true", "false"):
        raise FormatError(
            f"physical must be true or false, got {declared[:20]!r}", file=file, field="<robot>"
        )
    physical = physical and declared == "true"
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
            (
                name,
                None if inertial is None else _inertial(inertial, el, file, rule, snapped),
            )
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
    model = UrdfModel(
        root.get("name", ""), tuple(links), tuple(joints), file, tuple(snapped), physical
    )
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
                    field=parent[link].where,
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
        try:  # the tables' check: within a double's range (1e309 would be inf in code)
            out.append(as_expr(sp.Rational(part)))
        except TableError as err:
            raise FormatError(err.message, file=file, field=where) from None
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
    el: Element,
    link: Element,
    file: str | None,
    rule: AngleSnap,
    snapped: list[Snapped],
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
    xx, xy, xz, yy, yz, zz = inertia
    body = LinkInertia(mass, (0, 0, 0), sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]))
    try:  # the table reader's checks: mass, symmetry, semi-definiteness; the triangle
        # inequality is the rigid bodies' (import_urdf: a link with those fixed to it)
        body.check(physical=False)
    except DHError as err:
        raise FormatError(err.message, file=file, field=where) from None
    return Inertial(mass, _origin(el, file, rule, snapped), inertia)


def _joint(el: Element, file: str | None, rule: AngleSnap, snapped: list[Snapped]) -> UrdfJoint:
    name = _name(el, file)
    where = _where(el)
    kind = el.get("type", "")
    if kind not in JOINT_KINDS:
        raise FormatError(
            f"unknown joint type {kind[:40]!r}: expected one of {', '.join(JOINT_KINDS)}",
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
    if kind in MOVING_KINDS and axis_el is not None:
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
