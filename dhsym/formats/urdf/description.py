"""The URDF model: a robot description's links, joints and inertials as frozen values.

A :class:`UrdfModel` holds what :func:`~dhsym.formats.urdf.read.read_urdf` read, numbers
kept exactly as written (``0.089159`` stays 89159/1000000): each link's
:class:`Inertial`, each :class:`UrdfJoint` with its :class:`Origin`. The model answers
questions about the tree (its root, the links below a link, the chain of joints from one
link to another); reading files is :mod:`.read`'s, the DH table :mod:`.to_dh`'s.

Examples
--------
>>> j1 = UrdfJoint("j1", "revolute", "a", "b", Origin(), (0, 0, 1))
>>> m = UrdfModel("r", (("a", None), ("b", None)), (j1,))
>>> m.root, m.leaves("a"), [j.name for j in m.chain("a", "b")]
('a', ['b'], ['j1'])
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import TypeAlias

import sympy as sp

from dhsym.errors import FormatError, echoed
from dhsym.kinematics.numeric import to_float
from dhsym.kinematics.transforms import plain_product
from dhsym.model.angles import Snapped
from dhsym.model.table import Elementary

__all__ = ["JOINT_KINDS", "MOVING_KINDS", "Inertial", "Origin", "UrdfJoint", "UrdfModel"]

Expr: TypeAlias = sp.Expr
Triple: TypeAlias = tuple[sp.Expr, sp.Expr, sp.Expr]
_ZERO: Triple = (sp.Integer(0), sp.Integer(0), sp.Integer(0))
#: The moving joint kinds, with the DH joint each becomes (revolute R, prismatic P).
MOVING_KINDS = {"revolute": "R", "continuous": "R", "prismatic": "P"}
#: Every joint kind of URDF.
JOINT_KINDS = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")


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

    @cached_property
    def rational_matrix(self) -> sp.ImmutableMatrix:
        """The transform with each measured angle (no rational multiple of π) replaced by the
        nearest angle whose cosine and sine are rational (``tan(θ/2)`` within 1e-13), so the
        rotation stays exactly orthogonal and exact arithmetic stays rational.

        >>> Origin(rpy=(sp.Rational(-9, 5), 0, 0)).rational_matrix[1:3, 1:3]
        Matrix([
        [ -6500857724477/28612666328005, 27864377316636/28612666328005],
        [-27864377316636/28612666328005, -6500857724477/28612666328005]])
        """
        # T(xyz) R: the rotations multiplied, the translation put in its column
        rotation = sp.eye(4)
        for e in self.word:
            if e.kind == "R" and not (e.value / sp.pi).is_rational:
                rotation = rotation * _rational_rotation(e.axis, e.value)
            elif e.kind == "R":
                rotation = rotation * plain_product([e])
        cells = list(rotation)
        cells[3], cells[7], cells[11] = self.xyz
        return sp.ImmutableMatrix(4, 4, cells)


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
        return self.kind in MOVING_KINDS

    @property
    def where(self) -> str:
        """The joint as the field of an error: ``<joint name='elbow'>``.

        >>> UrdfJoint("elbow", "fixed", "a", "b", Origin(), (1, 0, 0)).where
        "<joint name='elbow'>"
        """
        return f"<joint name={self.name[:80]!r}>"


@dataclass(frozen=True)
class UrdfModel:
    """A URDF robot: its links (with inertials) and joints, and the angles read as exact."""

    name: str
    links: tuple[tuple[str, Inertial | None], ...]
    joints: tuple[UrdfJoint, ...]
    file: str | None = None
    snapped: tuple[Snapped, ...] = ()
    physical: bool = True  # False: inertias accepted without the triangle inequality

    @property
    def link_names(self) -> tuple[str, ...]:
        """The link names in file order."""
        return tuple(name for name, _ in self.links)

    @property
    def root(self) -> str:
        """The one link that is no joint's child.

        >>> UrdfModel("r", (("a", None),), ()).root
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

        >>> UrdfModel("r", (("a", None),), ()).leaves("a")
        ['a']
        """
        below = self.below(start)
        parents = {j.parent for j in self.joints}
        return [n for n in self.link_names if n in below and n not in parents]

    def chain(self, base: str, tip: str) -> tuple[UrdfJoint, ...]:
        """The joints from link ``base`` down to link ``tip``, in order.

        >>> j = UrdfJoint("j", "fixed", "a", "b", Origin(), (1, 0, 0))
        >>> [j.name for j in UrdfModel("r", (("a", None), ("b", None)), (j,)).chain("a", "b")]
        ['j']
        """
        for link, what in ((base, "base"), (tip, "tip")):
            if link not in self.link_names:
                raise FormatError(
                    f"no link named {echoed(link)} (links: {_listing(self.link_names)})",
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
                    f"link {echoed(base)} is not above link {echoed(tip)}: the path from the "
                    f"root {echoed(self.root)} to {echoed(tip)} does not pass through it",
                    file=self.file,
                    field="base",
                )
            out.append(joint)
            link = joint.parent
        return tuple(reversed(out))


def _listing(names: Iterable[str], limit: int = 30) -> str:
    items = list(names)
    text = ", ".join(items[:limit])
    return text + (f", … ({len(items)} in all)" if len(items) > limit else "")
