"""Mistakes in a Jacobian and in its determinant, each recognised by recomputing the key.

``J`` (the geometric Jacobian, base frame, tool point): written in the tool frame
(``tool_frame``); built with the axis of the next joint, ``z_i`` instead of ``z_{i−1}``
(the other convention's axis, ``next_axis``); a prismatic joint's column left out or
built like a revolute one (``prismatic_column``). ``det J``: a factor left out
(``missing_factor``), or the determinant of one block only (``block_determinant``).
The public names are re-exported by :mod:`dhsym.checking.mistakes.registry`.

Examples
--------
>>> import dhsym
>>> M = next_axis_jacobian(dhsym.load("planar2r"))
>>> M[:2, 0].T  # column 1 built from z_1 and o_1: the lever o_2 - o_1 of joint 2
Matrix([[-a2*sin(theta1 + theta2), a2*cos(theta1 + theta2)]])
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
import sympy as sp

from dhsym.kinematics.jacobian import axis_frame, geometric_jacobian, resolve_frame
from dhsym.model.table import Convention, JointType

from ..comparing.equivalence import values
from ._mistake_base import MatrixCase, Mistake

if TYPE_CHECKING:
    from dhsym.kinematics.singularities import Singularities
    from dhsym.robot import Robot

__all__ = [
    "DET_MISTAKES",
    "JACOBIAN_MISTAKES",
    "BlockDeterminant",
    "MissingFactor",
    "NextAxis",
    "PrismaticColumn",
    "ToolFrame",
    "next_axis_jacobian",
]

Matrix: TypeAlias = sp.ImmutableMatrix


def _robot(case: MatrixCase) -> Robot:
    """The key's robot, which a Jacobian or determinant case carries."""
    if case.robot is None:
        raise ValueError("a Jacobian or determinant case carries the key's robot")
    return case.robot


def _cached(case: MatrixCase, key: str, build: Any) -> np.ndarray:
    """Values of an exact variant at the case's sample: the variant derived once per key
    (the cases of a key's samples share their scratch), its values once per sample."""
    k = (key, case.sample.origin)
    if k not in case.cache:
        exact = case.cache.get((key,))
        if exact is None:
            exact = case.cache[(key,)] = build()
        case.cache[k] = values(exact, case.sample)
    cached: np.ndarray = case.cache[k]
    return cached


def _column(z: Matrix, lever: Matrix, revolute: bool, rate: sp.Expr) -> Matrix:
    top = z.cross(lever) if revolute else z
    bottom = z if revolute else Matrix.zeros(3, 1)
    return Matrix.vstack(Matrix(top), Matrix(bottom)) * rate


def _variant(robot: Any, axis_of: Any, treat_prismatic: str = "") -> Matrix:
    """``J`` with column ``i`` built on frame ``axis_of(row)``; prismatic columns as they are,
    ``zero`` or ``revolute``."""
    k, e = resolve_frame(robot, "base"), resolve_frame(robot, "tool")
    tip = robot.transform(k, e).matrix[:3, 3]
    cols = []
    for c in geometric_jacobian(robot).columns:
        a = axis_of(c.row)
        T = robot.transform(k, a).matrix
        z, o = T[:3, 2], T[:3, 3]
        revolute = c.joint is JointType.REVOLUTE
        if not revolute and treat_prismatic == "zero":
            cols.append(Matrix.zeros(6, 1))
            continue
        cols.append(_column(z, tip - o, revolute or treat_prismatic == "revolute", c.rate))
    return Matrix.hstack(*cols)


def next_axis_jacobian(robot: Any) -> Matrix:
    """``J`` with each joint's column built on the next frame's axis and origin (``z_i``
    instead of ``z_{i−1}`` in the standard convention, ``z_{i−1}`` instead of ``z_i`` in the
    modified one): the other convention's axis."""
    step = 1 if robot.convention is Convention.STANDARD else -1
    return _variant(robot, lambda row: min(max(axis_frame(robot, row) + step, 0), robot.n))


class ToolFrame(Mistake):
    """The columns written in the tool frame instead of the base frame."""

    kind, title = "tool_frame", "Jacobian in the wrong frame"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        robot = _robot(case)
        k, n = resolve_frame(robot, "base"), resolve_frame(robot, "tool")
        full = case.expected if case.entry is None else None  # the key itself, when whole
        J = _cached(case, "J", lambda: full if full is not None else robot.jacobian().matrix)
        R = _cached(case, "R tool", lambda: robot.transform(k, n).matrix)[:, :3, :3]
        Rt = np.swapaxes(R, 1, 2)  # the tool frame's vectors: Rᵀ v, for v and ω alike
        vals = np.concatenate([Rt @ J[:, :3], Rt @ J[:, 3:]], axis=1)
        yield (
            case.project(vals),
            f"The columns are written in the tool frame ({n}); the question asks for J in the "
            f"base frame: take z_(i-1) and o_{n} - o_(i-1) from the poses ^0T_(i-1) and ^0T_{n}.",
        )


class NextAxis(Mistake):
    """Each column built on the next joint's axis (``z_i`` for ``z_{i−1}``)."""

    kind, title = "next_axis", "axis of the wrong frame"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        robot = _robot(case)
        vals = _cached(case, "J next axis", lambda: next_axis_jacobian(robot))
        if robot.convention is Convention.STANDARD:
            detail = (
                "Column i uses z_i and o_i, the axis and origin of frame i; in the standard "
                "convention joint i turns about z_(i-1), through o_(i-1) (z_i belongs to the "
                "modified convention)."
            )
        else:
            detail = (
                "Column i uses z_(i-1) and o_(i-1); in the modified (Craig) convention joint "
                "i turns about z_i of frame i, through o_i (z_(i-1) belongs to the standard "
                "convention)."
            )
        yield case.project(vals), detail


class PrismaticColumn(Mistake):
    """A prismatic joint's column left out (zero) or built like a revolute joint's."""

    kind, title = "prismatic_column", "wrong column for a prismatic joint"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        robot = _robot(case)
        if all(c.joint is JointType.REVOLUTE for c in geometric_jacobian(robot).columns):
            return
        same = lambda row: axis_frame(robot, row)  # noqa: E731
        for how, detail in (
            (
                "zero",
                "The column of a prismatic joint is zero or left out: sliding along z_(i-1) "
                "moves the tool with velocity z_(i-1), so its column is [z_(i-1); 0].",
            ),
            (
                "revolute",
                "A prismatic joint's column is built like a revolute joint's, "
                "[z_(i-1) x (o_n - o_(i-1)); z_(i-1)]; sliding does not turn anything, "
                "its column is [z_(i-1); 0].",
            ),
        ):
            vals = _cached(case, f"J prismatic {how}", lambda h=how: _variant(robot, same, h))
            yield case.project(vals), detail


def _singular(case: MatrixCase) -> Singularities:
    """The key's singularities: the prepared key's (derived once per worker), else derived."""
    if case.singularities is not None:
        return case.singularities
    from dhsym.kinematics.singularities import singularities

    return singularities(_robot(case))


class MissingFactor(Mistake):
    """``det J`` with one of its factors left out (a length, or a singular factor)."""

    kind, title = "missing_factor", "factor missing"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        s = _singular(case)
        nota = case.notation
        for f in s.factors:
            short = s.determinant / f.expr
            vals = _cached(case, f"det without {f.expr}", lambda e=short: Matrix([[e]]))
            detail = f"The factor {nota.text(f.expr)} ({f.name}) is missing."
            yield vals, detail
            yield -vals, detail  # the sign of det J is free (the order of the rows)


class BlockDeterminant(Mistake):
    """Only one block's determinant (``det J11`` or ``det J22``) given for ``det J``."""

    kind, title = "block_determinant", "determinant of one block only"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        s = _singular(case)
        if len(s.blocks) != 2:
            return
        other = {"J11": "J22", "J22": "J11"}
        for b in s.blocks:
            vals = _cached(case, f"det {b.name}", lambda e=b.determinant: Matrix([[e]]))
            detail = (
                f"This is det {b.name} alone; at the wrist centre J is block triangular and "
                f"det J = det J11 * det J22: multiply by det {other[b.name]}."
            )
            yield vals, detail
            yield -vals, detail


JACOBIAN_MISTAKES: tuple[Mistake, ...] = (ToolFrame(), NextAxis(), PrismaticColumn())
DET_MISTAKES: tuple[Mistake, ...] = (BlockDeterminant(), MissingFactor())
