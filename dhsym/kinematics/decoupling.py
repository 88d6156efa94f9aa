"""Kinematic structure read from a DH table: the wrist centre and the arm that places it.

Closed-form inverse kinematics and the factored Jacobian determinant both rest on
*kinematic decoupling*: when the last three axes meet in one point (a spherical
wrist, Pieper's condition) the first joints place that point and the wrist turns about
it; with one last revolute joint (planar 3R, SCARA) a point on its axis plays the
same part. Everything here is detected from the compact transforms of the table,
never from a robot's name.

Examples
--------
>>> import dhsym
>>> d = decouple(dhsym.load("puma560"), 3)
>>> d.arm, d.wrist, d.centre, d.centre_in_last.T
((1, 2, 3), (4, 5, 6), 4, Matrix([[0, 0, 0]]))
>>> g = arm_geometry(dhsym.load("puma560"), d)
>>> g.first.value, g.offset, g.radial
(theta1, -d3, a2*cos(theta2) + a3*cos(theta2 + theta3) - d4*sin(theta2 + theta3))
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.table import Elementary, JointType

from .simplification import compose, normalize_word, prove_equal
from .transforms import chain_word

if TYPE_CHECKING:
    from .chain import KinematicChain

__all__ = ["ArmGeometry", "Decoupling", "StructureError", "arm_geometry", "decouple"]

Matrix: TypeAlias = sp.ImmutableMatrix


class StructureError(DHError):
    """The table lacks the structure a closed form needs (named in the message)."""


@dataclass(frozen=True)
class Decoupling:
    """How a chain splits into an arm (placing a point) and a wrist (turning about it).

    ``arm`` and ``wrist`` are 1-based table rows; ``centre`` is the DH frame whose origin
    is the wrist centre (for a chain without wrist: the last frame, the tool point);
    ``centre_in_last`` is that point in frame n, a constant vector.
    """

    arm: tuple[int, ...]
    wrist: tuple[int, ...]
    centre: int
    centre_in_last: Matrix


def _joint_rows(robot: KinematicChain) -> list[int]:
    return [i for i, r in enumerate(robot.table.rows, start=1) if r.variable is not None]


def _independent(expr: Matrix, variables: set[sp.Symbol]) -> bool:
    """True when ``expr`` does not depend on ``variables`` (by symbols, else by proof)."""
    hit = expr.free_symbols & variables
    if not hit:
        return True
    return all(prove_equal(expr.diff(v), Matrix.zeros(*expr.shape)) for v in hit)


def decouple(robot: KinematicChain, size: int) -> Decoupling:
    """Split ``robot`` into an arm and a wrist of ``size`` revolute joints (0, 1, 2 or 3).

    A wrist of 2 is a pair of last axes that meet (the point where they meet is fixed in
    the link before them and in the last link).

    The wrist centre is the first frame origin, from the first wrist axis on, that
    stays fixed both in the link before the wrist and in the last link: then it lies on
    every wrist axis.

    Raises
    ------
    StructureError
        Naming what is missing (a prismatic wrist joint, axes that do not meet).

    >>> import dhsym
    >>> decouple(dhsym.load("planar3r"), 1).centre
    2
    >>> decouple(dhsym.load("puma560_modified"), 3).centre
    4
    >>> decouple(dhsym.load("planar4r"), 3)
    Traceback (most recent call last):
    ...
    dhsym.kinematics.decoupling.StructureError: no spherical wrist: the axes of joints 2, 3, 4 ...
    """
    rows = _joint_rows(robot)
    n = robot.n
    if size == 0:
        return Decoupling(tuple(rows), (), n, Matrix.zeros(3, 1))
    if len(rows) < size:
        raise StructureError(f"a wrist of {size} joints needs at least {size} joints")
    wrist = tuple(rows[-size:])
    arm = tuple(rows[:-size])
    table = robot.table
    names = ", ".join(str(rows.index(r) + 1) for r in wrist)
    kind = {3: "spherical wrist", 2: "meeting last two axes"}.get(size, "revolute last joint")
    for r in wrist:
        if table.rows[r - 1].joint is not JointType.REVOLUTE:
            raise StructureError(
                f"no {kind}: joint {rows.index(r) + 1} (row {r}) is prismatic; "
                "a wrist turns about a point"
            )
    variables = {table.rows[r - 1].variable for r in wrist}
    start = wrist[0] - 1 if robot.convention.value == "standard" else wrist[0]
    for f in range(start, n + 1):
        in_base = robot.transform(0, f).position
        in_last = robot.transform(n, f).position
        if _independent(in_base, variables) and _independent(in_last, variables):
            const = Matrix(in_last.subs({v: 0 for v in variables}))
            return Decoupling(arm, wrist, f, const)
    before = arm[-1] if arm else 0
    what = (
        f"the axes of joints {names} do not meet in one point"
        if size in (2, 3)
        else (f"joint {names} has no axis point")
    )
    raise StructureError(
        f"no {kind}: {what} (no frame origin from frame {start} on stays fixed in "
        f"link {before} and in link {n})"
    )


@dataclass(frozen=True)
class ArmGeometry:
    """The wrist centre as ``prefix · first(q1) · point(q2, q3)``.

    ``prefix`` are the constant elementaries before joint 1 (``Rx(α0) Tx(a0)`` of a
    modified table); ``first`` is joint 1's ``Rz(θ1)`` or ``Tz(d1)``; ``point`` is the
    wrist centre in the frame after it, a function of the other arm joints only.
    When ``first`` is a rotation and one horizontal coordinate of ``point`` is
    constant (the shoulder ``offset``), the other one is the ``radial`` reach.
    """

    prefix: tuple[Elementary, ...]
    first: Elementary
    point: Matrix
    offset_axis: int | None = None
    offset: sp.Expr | None = None
    radial: sp.Expr | None = None

    @property
    def prefix_matrix(self) -> Matrix:
        """The constant 4×4 transform of ``prefix``."""
        return compose(self.prefix)


def arm_geometry(robot: KinematicChain, dec: Decoupling) -> ArmGeometry:
    """Read the arm part of ``dec`` as ``prefix · first(q1) · point``.

    >>> import dhsym
    >>> g = arm_geometry(dhsym.load("stanford"), decouple(dhsym.load("stanford"), 3))
    >>> g.point.T, g.offset_axis
    (Matrix([[d3*sin(theta2), d2, d3*cos(theta2)]]), 1)
    >>> arm_geometry(dhsym.load("planar2r"), decouple(dhsym.load("planar2r"), 0)).radial is None
    True
    """
    if not dec.arm:
        raise StructureError("the chain has no arm joints before the wrist")
    table = robot.table
    q1 = table.rows[dec.arm[0] - 1].variable
    word = chain_word(table, 0, dec.centre)
    k = next(i for i, e in enumerate(word) if q1 in e.value.free_symbols)
    prefix, first, rest = normalize_word(word[:k]), word[k], word[k + 1 :]
    point = Matrix(compose(rest)[:3, 3])
    if q1 in point.free_symbols:
        raise StructureError(f"joint 1 ({q1}) appears twice in the chain")
    if first.kind == "T" or len(dec.arm) == 1:
        return ArmGeometry(tuple(prefix), first, point)
    others = {table.rows[r - 1].variable for r in dec.arm[1:]}
    for axis in (1, 0):
        if not (point[axis].free_symbols & others) and point[1 - axis].free_symbols & others:
            return ArmGeometry(tuple(prefix), first, point, axis, point[axis], point[1 - axis])
    return ArmGeometry(tuple(prefix), first, point)
