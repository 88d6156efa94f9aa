"""The prepared part of an inverse-kinematics key: the closed form, the pose, the branches.

:func:`prepare_ik` derives the key's inverse kinematics once per worker, before any
answer's clock starts, and compiles its branches; a numeric question (``ik@q1,…``)
keeps its pose, and every branch gets the name the IK results give it (``"elbow up"``).
The random poses at which the mistakes of wrong answers are recomputed are drawn here
too, and the key's values under every catalogued mistake built there
(:func:`~dhsym.checking.mistakes.registry.prepare_ik_variants`), so the part
(:class:`IKPart`) is a frozen value and a wrong answer's diagnosis only compares.
A numeric question's variants and branch names are the same in every process: they are
kept in the disk cache (:mod:`dhsym.cache`) as data, never code (a JSON header with
the slips' expressions in the codec's document, read by its whitelist reader, and a
``.npy`` array read with ``allow_pickle=False``; verified by the store), so a warm
process reads them instead of building them.
Checking an answer is :mod:`~dhsym.checking.judging.ik_check`'s.

Examples
--------
>>> from dhsym.checking.judging.key import Key, prepare
>>> part = prepare(Key.load("planar2r", "ik")).part
>>> sorted(part.branch_names), part.pose is None
(['elbow down', 'elbow up'], True)
"""

from __future__ import annotations

import hashlib
import json
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
from ..mistakes.registry import (
    IK_MISTAKES,
    IKMistake,
    IKStepEdit,
    IKVariants,
    StepEdits,
    Variants,
    prepare_ik_variants,
)
from ..reading.answer_names import NameContext
from ..reading.questions import Question

if TYPE_CHECKING:
    from dhsym.notation.printers import Notation
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
    symbols = frozenset(set(table.constants) | set(pose_symbols()[:3, :]))
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
        # the numeric solver, the key's branches at the pose and the mistakes' variants
        # there (one pose for both kinds of answer) are built here, once per worker,
        # outside every student's time limit (the first build takes seconds), or read
        # back from the disk cache
        branch_names, variants = _kept_variants(robot, ik, pose)
        diagnosis = MappingProxyType({False: variants, True: variants})
        return names, IKPart(ik, pose, branch_names, symbols, diagnosis)
    # the key's branches compiled once, before the first answer's clock starts
    sample = pose_sample(robot, values=table.value_map or None)
    key_values(ik, sample.env, sample.size)
    branch_names = _reference_names(robot, ik)
    poses = {False: pose_sample(robot, values=None)}
    if set(table.constants) <= set(table.value_map):
        poses[True] = pose_sample(robot, values=table.value_map)
    # the mistakes' variants, at each diagnosis pose: a wrong answer's diagnosis only compares
    nota = robot.notation
    built = {k: prepare_ik_variants(ik, s, branch_names, nota) for k, s in poses.items()}
    return names, IKPart(ik, None, branch_names, symbols, MappingProxyType(built))


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


# -- a numeric question's variants, kept in the disk cache -----------------------------------
_FORMAT = "dhsym-ik-variants 1"


def _kept_variants(
    robot: Robot, ik: ClosedForm, pose: PoseSample
) -> tuple[tuple[str, ...], IKVariants]:
    """The key's branch names at a numeric question's ``pose`` and the mistakes' variants
    there (:func:`prepare_ik_variants`), read from the disk cache when a process kept them
    (the entry is named by the table, the versions, the steps, the notation and the
    sample's numbers), else built and kept."""
    from dhsym.cache.codec import CodecError
    from dhsym.cache.keys import entry_name
    from dhsym.cache.store import default_store

    nota = robot.notation
    store = default_store()
    entry = None
    if store is not None:
        entry = entry_name(robot.table, "ik_variants", _variants_text(ik, nota, pose))
        data = store.read(entry)
        if data is not None:
            try:
                found = _read_variants(data, ik, pose)
            except (CodecError, ValueError, TypeError, KeyError, IndexError):
                found = None  # not what this version writes: built again and rewritten
            if found is not None:
                return found
    at_pose = key_values(ik, pose.env, pose.size)
    names = tuple(_numeric_names(robot, ik, pose, at_pose))
    variants = prepare_ik_variants(ik, pose, names, nota)
    if store is not None and entry is not None:
        try:
            store.write(entry, _write_variants(names, variants))
        except CodecError:
            pass  # an expression the codec does not write: kept in this process only
    return names, variants


def _variants_text(ik: ClosedForm, nota: Notation, pose: PoseSample) -> str:
    """What the variants are computed from, as a SHA-256: the steps and branch signs, the
    notation of the feedback, and every number of the sample (symbol by symbol)."""
    digest = hashlib.sha256()
    for st in ik.steps:
        digest.update(f"{st.lhs} = {st.rhs}\n".encode())
    digest.update(f"{[b.symbol for b in ik.branches]}\n{nota!r}\n".encode())
    for sym, values in sorted(pose.env.items(), key=lambda item: str(item[0])):
        array = np.ascontiguousarray(values, dtype=float)
        digest.update(f"{sym} {array.shape}\n".encode())
        digest.update(array.tobytes())
    digest.update(np.ascontiguousarray(pose.q, dtype=float).tobytes())
    return digest.hexdigest()


def _write_variants(names: tuple[str, ...], variants: IKVariants) -> bytes:
    """A JSON header (the names; each mistake's kind with its texts; the slips' steps as
    the codec's document) and one ``.npy`` array of every value in order: the key, the
    whole variants, the slips' values."""
    from dhsym.cache.codec import write_array, write_exprs

    whole = [[m.kind, [detail for _, detail in found]] for m, found in variants.whole.items()]
    steps = [[m.kind, [edit[3] for edit in found.edits]] for m, found in variants.steps.items()]
    edits = [sp.Tuple(*e[:3]) for found in variants.steps.values() for e in found.edits]
    arrays = [variants.key.ravel()]
    arrays += [vals.ravel() for found in variants.whole.values() for vals, _ in found]
    arrays += [found.values.ravel() for found in variants.steps.values()]
    header = {
        "format": _FORMAT,
        "names": list(names),
        "whole": whole,
        "steps": steps,
        "edits": write_exprs(edits),
    }
    return json.dumps(header).encode() + b"\n" + write_array(np.concatenate(arrays))


def _read_variants(
    data: bytes, ik: ClosedForm, pose: PoseSample
) -> tuple[tuple[str, ...], IKVariants] | None:
    """What :func:`_write_variants` wrote, checked against this process: the mistakes of
    :data:`IK_MISTAKES` in order, each slip a step's left-hand side and two expressions,
    every array of the key's shape; ``None`` when anything differs."""
    from dhsym.cache.codec import read_array, read_exprs

    head, _, rest = data.partition(b"\n")
    header = json.loads(head)
    if not isinstance(header, dict) or header.get("format") != _FORMAT:
        return None
    names = header["names"]
    flat = read_array(rest)
    K, n = 2 ** len(ik.branches), len(ik.robot.variables)
    shape = (K, pose.size, n)
    per = K * pose.size * n
    if not isinstance(names, list) or len(names) != K or not all(isinstance(x, str) for x in names):
        return None
    if flat.dtype != np.float64 or flat.ndim != 1:
        return None
    whole_kinds = [
        m
        for m in IK_MISTAKES
        if not isinstance(m, IKStepEdit) and type(m).ik_variants is not IKMistake.ik_variants
    ]
    step_kinds = [m for m in IK_MISTAKES if isinstance(m, IKStepEdit)]
    kept_whole, kept_steps = header["whole"], header["steps"]
    if [k for k, _ in kept_whole] != [m.kind for m in whole_kinds]:
        return None
    if [k for k, _ in kept_steps] != [m.kind for m in step_kinds]:
        return None
    texts = [t for _, found in kept_steps for t in found] + [
        d for _, found in kept_whole for d in found
    ]
    lhs = {st.lhs for st in ik.steps}
    edits = read_exprs(header["edits"])
    if not all(isinstance(t, str) for t in texts) or not all(
        isinstance(e, sp.Tuple) and len(e) == 3 and e[0] in lhs for e in edits
    ):
        return None
    key = flat[:per].reshape(shape)
    at = per
    whole: dict[IKMistake, Variants] = {}
    for m, (_, details) in zip(whole_kinds, kept_whole):
        found = []
        for detail in details:
            found.append((flat[at : at + per].reshape(shape), detail))
            at += per
        whole[m] = tuple(found)
    steps: dict[IKStepEdit, StepEdits] = {}
    e = 0
    for m, (_, details) in zip(step_kinds, kept_steps):
        mine = tuple((*edits[e + i].args, d) for i, d in enumerate(details))
        if len(mine) != len(details):
            return None
        steps[m] = StepEdits(mine, flat[at : at + len(mine) * per].reshape((len(mine), *shape)))
        at, e = at + len(mine) * per, e + len(mine)
    if at != len(flat) or e != len(edits):
        return None
    variants = IKVariants(pose, key, MappingProxyType(whole), MappingProxyType(steps))
    return tuple(names), variants
