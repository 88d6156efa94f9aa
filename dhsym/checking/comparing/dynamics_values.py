r"""The keys of the dynamics questions, from the dynamics room, once per key.

``M``, ``M[i,j]`` (0-based, like ``J[r,c]``), ``g``, ``C``, ``c_ijk`` (Spong's Christoffel
symbol, 1-based indices as he writes them: ``c_112``), ``tau`` (τ = M q̈ + C q̇ + g, symbolic
in q, q̇, q̈) and ``tau_static`` (τ = Jᵀ F for the tip wrench ``fx … nz`` in the base frame).
Every answer names the robot's inertial symbols (``m1``, ``lc1``, ``I1``, ``g``), its rates
(``qdot1``, also ``thetadot1``) and accelerations (``qddot1``).

Examples
--------
>>> import dhsym
>>> from dhsym.checking.reading.questions import Question
>>> robot = dhsym.load("planar2r")
>>> part_matrix(robot.dynamics(), Question.parse("c_121", 2)).shape
(1, 1)
>>> [s.name for s in question_symbols(robot, Question.parse("tau", 2))][-4:]
['thetadot1', 'thetadot2', 'thetaddot1', 'thetaddot2']
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.dynamics.equations import EquationsOfMotion
from dhsym.dynamics.model import dynamic_model
from dhsym.dynamics.static_forces import WRENCH, statics
from dhsym.errors import DHError
from dhsym.model.table import JointType

from ..reading.questions import Question

if TYPE_CHECKING:
    from dhsym.robot import Robot

__all__ = ["dynamics_key", "part_matrix", "question_symbols", "rate_aliases"]

Matrix: TypeAlias = sp.ImmutableMatrix


def part_matrix(eom: EquationsOfMotion, q: Question) -> Matrix:
    """The part of ``eom`` that question ``q`` asks (``M``, ``g``, ``C``, ``tau``, ``c_ijk``).

    >>> import dhsym
    >>> eom = dhsym.load("planar2r").dynamics()
    >>> [part_matrix(eom, Question.parse(s, 2)).shape for s in ("M[0,1]", "g")]
    [(1, 1), (2, 1)]
    """
    n = len(eom.variables)
    if q.part == "c":
        assert q.index is not None
        if not all(1 <= k <= n for k in q.index):
            raise DHError(f"question {q.spec!r}: the indices of c_ijk are 1 … {n}")
        return Matrix([[eom.c(*q.index)]])
    full = Matrix(getattr(eom, q.part))
    if q.entry is None:
        return full
    r, c = q.entry
    if not (r < full.rows and c < full.cols):
        raise DHError(
            f"question {q.spec!r}: rows are 0 … {full.rows - 1}, columns 0 … {full.cols - 1}"
        )
    return Matrix([[full[r, c]]])


def dynamics_key(robot: Robot, q: Question) -> Matrix:
    """The key's matrix: a part of the Lagrange–Euler equations of motion, or ``Jᵀ F``.

    >>> import dhsym
    >>> dynamics_key(dhsym.load("planar2r"), Question.parse("tau_static", 2))[1]
    -a2*fx*sin(theta1 + theta2) + a2*fy*cos(theta1 + theta2) + nz
    """
    if q.part == "tau_static":
        return Matrix(statics(robot).tau).applyfunc(sp.expand)
    return part_matrix(robot.dynamics(), q)


def question_symbols(robot: Robot, q: Question) -> tuple[sp.Symbol, ...]:
    """The symbols an answer may use beyond the table's: the inertial parameters, gravity,
    rates and accelerations (or the wrench, for ``tau_static``)."""
    if q.part == "tau_static":
        return WRENCH
    dm = dynamic_model(robot)
    return (*dm.parameters, *dm.rates, *dm.accelerations)


def rate_aliases(robot: Robot) -> tuple[tuple[str, sp.Symbol], ...]:
    """Other spellings of the rates: ``qdot<k>``, ``qd<k>``, ``thetadot<k>`` (revolute),
    ``ddot<k>`` (prismatic), code's ``dq<k>``, and the same with ``ddot``/``dd``/``ddq``
    for the accelerations.

    >>> import dhsym
    >>> dict(rate_aliases(dhsym.load("planar2r")))["qdot1"]
    thetadot1
    """
    dm = dynamic_model(robot)
    out = []
    for k, (kind, rate, acc) in enumerate(zip(dm.kinds, dm.rates, dm.accelerations), 1):
        heads = ["q"] + (["theta"] if kind is JointType.REVOLUTE else ["d"])
        for h in heads:
            out += [(f"{h}dot{k}", rate), (f"{h}ddot{k}", acc)]
        out += [(f"qd{k}", rate), (f"qdd{k}", acc), (f"dq{k}", rate), (f"ddq{k}", acc)]
    return tuple(out)
