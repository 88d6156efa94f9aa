"""The prepared part of an inverse-kinematics key: the closed form, the pose, the branches.

:func:`prepare_ik` derives the key's inverse kinematics once per worker, before any
answer's clock starts, and compiles its branches; a numeric question (``ik@q1,…``)
keeps its pose, and every branch gets the name the IK results give it (``"elbow up"``).
The random poses at which the mistakes of wrong answers are recomputed are drawn here
too, and the key's values under every catalogued mistake built there
(:func:`~dhsym.checking.mistakes.registry.prepare_ik_variants`), so the part
(:class:`IKPart`) is a frozen value and a wrong answer's diagnosis only compares.
Checking an answer is :mod:`~dhsym.checking.judging.ik_check`'s.

Examples
--------
>>> from dhsym.checking.judging.key import Key, prepare
>>> part = prepare(Key.load("planar2r", "ik")).part
>>> sorted(part.branch_names), part.pose is None
(['elbow down', 'elbow up'], True)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.ik.closed_form import ClosedForm
from dhsym.ik.steps import pose_symbols
from dhsym.model.table import DHTable

from ..comparing.ik_values import PoseSample, key_values, pose_sample, same_joints
from ..comparing.sampled_frames import frames
from ..comparing.tolerances import TOLERANCES
from ..mistakes.registry import IKVariants, prepare_ik_variants
from ..reading.answer_names import NameContext
from ..reading.questions import Question

if TYPE_CHECKING:
    from dhsym.robot import Robot

__all__ = ["IKPart", "prepare_ik"]


@dataclass(frozen=True, eq=False)
class IKPart:
    """What checking answers to an inverse-kinematics key shares.

    ``ik`` is the key's closed form; ``pose`` the question's pose (``ik@…``; None: random
    poses); ``branch_names`` each key branch's name, at the pose or in general;
    ``symbols`` the symbols an answer may use besides its own (the lengths, the pose);
    ``diagnosis`` the poses a wrong answer's mistakes are recomputed at, with the key's
    values there under each mistake, by whether the answer uses the table's numbers for
    the lengths (True) or their symbols (False); a numeric question's is its pose, for both.
    """

    ik: ClosedForm
    pose: PoseSample | None
    branch_names: tuple[str, ...]
    symbols: frozenset[sp.Symbol]
    diagnosis: Mapping[bool, IKVariants]


def prepare_ik(
    table: DHTable, question: Question, robot: Robot, names: NameContext
) -> tuple[NameContext, IKPart]:
    """Derive the key's inverse kinematics once (and the pose of a numeric question)."""
    q = question
    ik = robot.inverse()
    if not isinstance(ik, ClosedForm):  # the general 6R: an Elimination
        raise DHError(
            f"{robot.name or 'this arm'} is a general 6R: its inverse kinematics is an "
            "eigenproblem, not closed-form steps to grade"
        )
    pose: PoseSample | None = None
    poses: dict[bool, PoseSample] = {}
    if q.pose is not None:
        if len(q.pose) != len(robot.variables):
            raise DHError(
                f"question {q.spec!r}: {robot.name} has {len(robot.variables)} joints, "
                f"got {len(q.pose)} values"
            )
        missing = [str(s) for s in table.constants if s not in table.value_map]
        if missing:
            raise DHError(
                f"question {q.spec!r} needs numbers for {', '.join(missing)} (table values)"
            )
        pose = pose_sample(robot, q=np.array([q.pose]), values=table.value_map)
        # the numeric solver and the key's branches at the pose are built here, once per
        # worker, outside every student's time limit (the first build takes seconds)
        at_pose = key_values(ik, pose.env, pose.size)
        branch_names = tuple(_numeric_names(robot, ik, pose, at_pose))
        poses[False] = poses[True] = pose
    else:  # the key's branches compiled once, before the first answer's clock starts
        sample = pose_sample(robot, values=table.value_map or None)
        key_values(ik, sample.env, sample.size)
        branch_names = _reference_names(robot, ik)
        poses[False] = pose_sample(robot, values=None)
        if set(table.constants) <= set(table.value_map):
            poses[True] = pose_sample(robot, values=table.value_map)
    # the mistakes' variants, at each diagnosis pose: a wrong answer's diagnosis only compares
    nota = robot.notation
    distinct = {id(s): s for s in poses.values()}  # a numeric question: one pose, built once
    built = {i: prepare_ik_variants(ik, s, branch_names, nota) for i, s in distinct.items()}
    diagnosis = MappingProxyType({valued: built[id(s)] for valued, s in poses.items()})
    symbols = frozenset(set(table.constants) | set(pose_symbols()[:3, :]))
    return names, IKPart(ik, pose, branch_names, symbols, diagnosis)


def _reference_names(robot: Robot, ik: ClosedForm) -> tuple[str, ...]:
    """Each key branch named as the IK results name it (``"elbow up"``, ``"right arm"``),
    read at the examples' configuration
    (:func:`~dhsym.explain.inverse_kinematics.default_configuration`) with the table's
    lengths (1 where it gives none), for questions without a pose."""
    from dhsym.explain.inverse_kinematics import default_configuration
    from dhsym.robot import Robot

    table = robot.table
    values = {s: table.value_map.get(s, 1.0) for s in table.constants}
    try:
        named = Robot(table.with_values(values))
        ref = pose_sample(named, q=np.array([default_configuration(named)]), values=values)
        return tuple(_numeric_names(named, ik, ref, key_values(ik, ref.env, ref.size)))
    except (DHError, ValueError, ArithmeticError):
        return tuple(f"branch {k + 1}" for k in range(2 ** len(ik.branches)))


def _numeric_names(robot: Robot, ik: ClosedForm, sample: PoseSample, key: np.ndarray) -> list[str]:
    """Each key branch named as the numeric solver names it at the question's pose."""
    T = frames(robot.table, sample.env, 1)[0, -1]
    position_only = not ik.decoupling.wrist
    sol = robot.ik(T[:3, 3] if position_only else T)
    if sol.batch:  # one pose gives one solution, not a batch
        raise TypeError(f"robot.ik of one pose returned {type(sol).__name__}")
    names = []
    for k in range(len(key)):
        found = [
            name
            for name, q in zip(sol.branches, sol.q, strict=True)
            if same_joints(key[k], q[None, :], sample.revolute, TOLERANCES.reach_atol)
        ]
        names.append(found[0] if found else f"branch {k + 1}")
    return names
