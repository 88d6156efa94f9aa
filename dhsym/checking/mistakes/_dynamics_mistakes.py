r"""Mistakes in the equations of motion, each recognised by recomputing the key under it.

Each variant runs the dynamics room's Lagrange–Euler (:func:`dhsym.dynamics.lagrange`) on
the key robot with one thing changed in its inertial model, the way a student who made the
mistake computes: the centre of mass put at the joint for the kinetic energy
(``parallel_axis``: the ``m·lc²`` term of the parallel-axis theorem dropped); every inertia
set to zero (``rotational_energy`` left out); gravity reversed or along another base axis
(``gravity_direction``); the centre of mass at the far end of the link (``l_for_lc``); the
body-frame inertia used with the base-frame angular velocity (``inertia_frame``: ``I``
instead of ``R I Rᵀ``); and the Christoffel symbols read in the other index convention
(``christoffel_indices``: ``c_kji`` for ``c_ijk``). The kinetic variants are only
derived for at most :data:`KINETIC_JOINTS` joints (each is a full derivation); all of them
are computed when the key is prepared, outside a student's clock.

Examples
--------
>>> import dhsym
>>> from dhsym.checking.reading.questions import Question
>>> robot = dhsym.load("planar2r")
>>> eom = variant_equations(robot, robot.dynamics(), "rotational_energy")
>>> eom.M[1, 1]
m2*(a2**2 + 2*a2*rx2 + rx2**2 + ry2**2)
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, TypeAlias

import numpy as np
import sympy as sp

from dhsym.dynamics.equations import EquationsOfMotion
from dhsym.dynamics.lagrange_euler import (
    christoffel_symbols,
    coriolis_matrix,
    lagrange,
    potential_energies,
    tidy,
)
from dhsym.kinematics.jacobian import axis_frame
from dhsym.model.inertia import LinkInertia
from dhsym.model.table import Convention

from ..comparing.dynamics_values import part_matrix
from ..comparing.equivalence import values
from ..reading.questions import Question
from ._mistake_base import MatrixCase, Mistake

if TYPE_CHECKING:
    from dhsym.robot import Robot

__all__ = [
    "KINETIC_JOINTS",
    "ChristoffelIndices",
    "DynamicsMistake",
    "dynamics_mistakes",
    "variant_equations",
    "variant_matrices",
]

Matrix: TypeAlias = sp.ImmutableMatrix
#: The largest number of joints whose kinetic-energy mistakes are derived.
KINETIC_JOINTS = 3

_KINETIC = ("parallel_axis", "rotational_energy", "l_for_lc", "inertia_frame")
_TITLES = {
    "parallel_axis": "parallel-axis term forgotten",
    "rotational_energy": "rotational kinetic energy left out",
    "gravity_direction": "wrong sign or direction of gravity",
    "l_for_lc": "l used where lc belongs",
    "inertia_frame": "inertia in the wrong frame",
    "christoffel_indices": "Christoffel indices swapped",
}
_DETAILS = {
    "parallel_axis": (
        "The kinetic energy is computed as if each link's mass sat on its joint axis, with "
        "only its inertia about the centre of mass turning: the parallel-axis term m_i*lc_i**2 "
        "(mass times the squared distance from the joint to the centre of mass) is missing. "
        "Take the velocity of the centre of mass, v_ci = J_vci q', in K = 1/2 m_i v_ci^T v_ci."
    ),
    "rotational_energy": (
        "Only the translational kinetic energy 1/2 m_i v_ci^T v_ci is counted; each link also "
        "has the rotational energy 1/2 omega_i^T R_i I_i R_i^T omega_i (the I_i terms of M)."
    ),
    "l_for_lc": (
        "The centre of mass of each link is put at the far end of the link (l_i where lc_i "
        "belongs): use the distance lc_i from the joint to the centre of mass."
    ),
    "inertia_frame": (
        "The inertia I_i, given in link frame i, is used with the angular velocity written in "
        "the base frame: in the base frame it is R_i I_i R_i^T (R_i = ^0R_i), or use omega in "
        "frame i."
    ),
    "christoffel_indices": (
        "The Christoffel symbols are read in the other index order: this is c_kji where "
        "c_ijk = 1/2 (dm_kj/dq_i + dm_ki/dq_j - dm_ij/dq_k) is asked, and C_kj = sum_i c_ijk "
        "q'_i (Spong, Hutchinson and Vidyasagar, Robot Modeling and Control)."
    ),
}


def _far_end(robot: Robot, i: int) -> Matrix | None:
    """The far end of link ``i`` (where the next joint is) in link frame ``i``, or None."""
    if robot.convention is Convention.STANDARD:
        return Matrix([0, 0, 0])
    if i >= robot.n:
        return None
    return Matrix(robot.transform(i, i + 1).matrix[:3, 3])


def _with(
    eom: EquationsOfMotion,
    part: str,
    M: Matrix | None = None,
    g: Matrix | None = None,
    christoffel: tuple[tuple[tuple[sp.Expr, ...], ...], ...] | None = None,
) -> EquationsOfMotion:
    """``eom`` with its M (and so its Christoffel symbols and C), g or Christoffel symbols
    replaced, and what ``part`` depends on rebuilt (the rest is the key's)."""
    dm = eom.model
    params = dm.masses
    c = christoffel
    if c is None and M is not None and part in ("c", "C", "tau"):
        c = christoffel_symbols(M, dm.variables, params)
    M = eom.M if M is None else M
    g = eom.g if g is None else g
    c = eom.christoffel if c is None else c
    C, tau = eom.C, eom.tau
    if part in ("C", "tau"):
        C = coriolis_matrix(c, dm.rates, params)
    if part == "tau":
        qd, qdd = Matrix(dm.rates), Matrix(dm.accelerations)
        tau = Matrix((M * qdd + C * qd + g).applyfunc(lambda e: tidy(e, params)))
    return EquationsOfMotion("lagrange", dm, M, C, g, tau, c)


#: The parts of the equations of motion that each mistake changes.
_CHANGES = {
    "christoffel_indices": ("c", "C", "tau"),
    "gravity_direction": ("g", "tau"),
    "l_for_lc": ("M", "c", "C", "g", "tau"),
    "parallel_axis": ("M", "c", "C", "tau"),
    "rotational_energy": ("M", "c", "C", "tau"),
    "inertia_frame": ("M", "c", "C", "tau"),
}


def variant_equations(
    robot: Robot, eom: EquationsOfMotion, kind: str, part: str = "tau", link: int | None = None
) -> EquationsOfMotion | None:
    """The equations of motion of ``robot`` under the mistake ``kind`` (from the key's
    Lagrange–Euler ``eom``; exact in ``part`` and what it is built from), or None when
    the mistake does not apply; with ``link`` (0-based) the mistake made in that link
    only (``parallel_axis``, ``l_for_lc``: ``l2`` for ``lc2`` alone)."""
    dm = eom.model
    links = list(dm.links)
    if link is not None:
        one = variant_equations(robot, eom, kind, part)
        if one is None or kind not in _PER_LINK:
            return one
        moved = _moved(robot, eom, kind)[link]
        links[link] = moved
        other = lagrange(robot, replace(dm, links=tuple(links)))
        return _with(eom, part, M=other.M, g=other.g if kind == "l_for_lc" else None)
    if kind == "christoffel_indices":
        n = dm.n
        c = eom.christoffel
        swapped = tuple(
            tuple(tuple(c[k][j][i] for k in range(n)) for j in range(n)) for i in range(n)
        )
        return _with(eom, part, christoffel=swapped)
    if kind == "gravity_direction":
        return None  # several variants: see _gravity_variants
    if kind == "parallel_axis":
        links = _moved(robot, eom, kind)
        return _with(eom, part, M=lagrange(robot, replace(dm, links=tuple(links))).M)
    if kind == "rotational_energy":
        links = [replace(L, I=sp.zeros(3, 3)) for L in links]
        return _with(eom, part, M=lagrange(robot, replace(dm, links=tuple(links))).M)
    if kind == "inertia_frame":
        for i, L in enumerate(links):
            R = robot.transform(0, i + 1).matrix[:3, :3]
            links[i] = replace(L, I=(R.T * L.I * R).applyfunc(sp.expand))
        return _with(eom, part, M=lagrange(robot, replace(dm, links=tuple(links))).M)
    if kind == "l_for_lc":
        other = lagrange(robot, replace(dm, links=tuple(_moved(robot, eom, kind))))
        return _with(eom, part, M=other.M, g=other.g)
    raise ValueError(f"unknown dynamics mistake {kind!r}")


#: The mistakes a student may make in one link only (one variant per link, as well).
_PER_LINK = ("parallel_axis", "l_for_lc")


def _moved(robot: Robot, eom: EquationsOfMotion, kind: str) -> list[LinkInertia]:
    """The links with the centre of mass where ``kind`` puts it: on the joint axis
    (``parallel_axis``), at the far end of the link (``l_for_lc``)."""
    links = list(eom.model.links)
    for i, L in enumerate(links):
        if kind == "parallel_axis":
            a = axis_frame(robot, i + 1)
            links[i] = replace(L, r=tuple(robot.transform(i + 1, a).matrix[:3, 3]))
        else:
            end = _far_end(robot, i + 1)
            if end is not None:
                links[i] = replace(L, r=tuple(end))
    return links


def _link_detail(robot: Robot, eom: EquationsOfMotion, kind: str, i: int) -> str:
    """What the student did in link ``i`` (0-based) alone, with ``{entries}`` for where:
    ``l2 written for lc2 in entries (1,1) and (2,1)`` when one symbol of the centre of
    mass written as another puts it where the mistake does."""
    r = Matrix(eom.model.links[i].r)
    goal = Matrix(_moved(robot, eom, kind)[i].r)
    k = i + 1
    table = set(robot.table.constants)  # the lengths written for others: the table's
    for c in sorted(r.free_symbols - table, key=sp.default_sort_key):
        for t in sorted(r.free_symbols & table, key=sp.default_sort_key):
            if (r.xreplace({c: t}) - goal).applyfunc(sp.expand) == sp.zeros(3, 1):
                if kind == "l_for_lc":
                    return (
                        f"{t} written for {c} in {{entries}}: the centre of mass of link {k} "
                        f"is put at the far end of the link; use the distance {c} from joint "
                        f"{k} to the centre of mass."
                    )
                return (
                    f"{t} written for {c} in {{entries}}: link {k}'s mass is put on its joint "
                    f"axis, and its parallel-axis term m{k}*{c}**2 is missing."
                )
    if kind == "l_for_lc":
        return (
            f"In {{entries}} the centre of mass of link {k} is put at the far end of the "
            f"link: use the distance from joint {k} to the centre of mass."
        )
    return (
        f"In {{entries}} the parallel-axis term of link {k} is missing: its kinetic energy is "
        f"computed as if its mass sat on joint axis {k}. Take the velocity of its centre of "
        f"mass, v_c{k} = J_vc{k} q', in K = 1/2 m_{k} v_c{k}^T v_c{k}."
    )


def _gravity_variants(eom: EquationsOfMotion, part: str) -> Iterator[tuple[EquationsOfMotion, str]]:
    """g reversed, and along each other base axis when gravity is along one axis."""
    dm = eom.model
    g0 = dm.gravity
    options = [(tuple(-x for x in g0), "Gravity points the other way: ")]
    axes = [k for k in range(3) if g0[k] != 0]
    if len(axes) == 1:
        size = -g0[axes[0]]  # the magnitude, with the sign of "downwards"
        for k in range(3):
            for sign in (1, -1):
                axis = [sp.Integer(0)] * 3
                axis[k] = -sign * size
                if tuple(axis) != tuple(g0) and tuple(axis) != options[0][0]:
                    options.append(
                        (tuple(axis), f"Gravity is taken along {'-+'[sign < 0]}{'xyz'[k]}: ")
                    )
    for vec, head in options:
        P = sum(potential_energies(replace(dm, gravity=vec)), sp.Integer(0))
        g = Matrix([tidy(sp.diff(P, x), dm.masses) for x in dm.variables])
        shown = ", ".join(sp.sstr(x) for x in g0)
        yield (
            _with(eom, part, g=g),
            head + f"the table's gravity is [{shown}] in the base frame, and "
            "g(q) = dP/dq with P = -sum m_i g^T p_ci.",
        )


def variant_matrices(
    robot: Robot, eom: EquationsOfMotion, q: Question
) -> tuple[tuple[str, Matrix, str], ...]:
    """Every variant of the key of ``q``: ``(kind, matrix, detail)`` triples.

    >>> import dhsym
    >>> robot = dhsym.load("planar2r")
    >>> found = variant_matrices(robot, robot.dynamics(), Question.parse("g", 2))
    >>> sorted({k for k, _, _ in found})
    ['gravity_direction', 'l_for_lc']
    """
    out: list[tuple[str, Matrix, str]] = []
    kinds = ["christoffel_indices"] + (list(_KINETIC) if eom.model.n <= KINETIC_JOINTS else [])
    for kind in kinds:
        if q.part not in _CHANGES[kind]:
            continue
        v = variant_equations(robot, eom, kind, q.part)
        if v is not None:
            out.append((kind, part_matrix(v, q), _DETAILS[kind]))
        if v is not None and kind in _PER_LINK and eom.model.n > 1:
            for i in range(eom.model.n):
                one = variant_equations(robot, eom, kind, q.part, link=i)
                if one is not None:
                    detail = _link_detail(robot, eom, kind, i)
                    out.append((kind, part_matrix(one, q), detail))
    if q.part in _CHANGES["gravity_direction"]:
        for v, detail in _gravity_variants(eom, q.part):
            out.append(("gravity_direction", part_matrix(v, q), detail))
    return tuple(out)


@dataclass(frozen=True)
class DynamicsMistake(Mistake):
    """One of the catalogued dynamics mistakes; its variants come from the prepared key."""

    which: str = ""

    @property
    def kind(self) -> str:  # type: ignore[override]  # one class, its instances are the kinds
        return self.which

    @property
    def title(self) -> str:  # type: ignore[override]  # per instance, like kind
        return _TITLES[self.which]

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        for kind, matrix, detail in case.dynamics_variants:
            if kind == self.which:
                k = ("dynamics variant", kind, detail, case.sample.origin)
                if k not in case.cache:
                    case.cache[k] = values(matrix, case.sample)
                yield case.cache[k], detail


ChristoffelIndices = DynamicsMistake("christoffel_indices")


def dynamics_mistakes() -> tuple[Mistake, ...]:
    """The catalogue, in the order a diagnosis tries them.

    >>> [m.kind for m in dynamics_mistakes()][:2]
    ['christoffel_indices', 'gravity_direction']
    """
    return tuple(
        DynamicsMistake(k) for k in ("christoffel_indices", "gravity_direction", *_KINETIC)
    )
