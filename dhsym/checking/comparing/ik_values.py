"""The closed-form inverse kinematics in numbers, at many poses at once, for the checker.

A *pose sample* draws configurations (and, for a symbolic answer, lengths) and computes
their poses ``^0T_n`` with the numeric kernel's tree walker (:mod:`dhsym.kinematics.numeric`);
the pose symbols ``n_x … p_z`` of the derivation get those values. :func:`key_values`
evaluates the derivation's steps there for every choice of the branch signs ``σ = ±1``,
optionally rewritten (a mistake recomputed: ``atan`` for ``atan2``, a sign under a root).
Angles are compared modulo 2π.

Examples
--------
>>> import dhsym
>>> robot = dhsym.load("planar2r")
>>> ps = pose_sample(robot, size=4, values=robot.table.value_map, seed=1)
>>> q = key_values(robot.inverse(), ps.env, ps.size)  # (branches, poses, joints)
>>> found = (joint_distance(q, ps.q, ps.revolute) < 1e-9).all(axis=2).any(axis=0)
>>> q.shape, bool(found.all())  # each configuration drawn is one of the two branches
((2, 4, 2), True)
"""

from __future__ import annotations

import itertools
import secrets
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.ik.steps import pose_symbols
from dhsym.model.table import JointType

from .sampled_frames import evaluate_or_nan, frames
from .tolerances import TOLERANCES

if TYPE_CHECKING:
    from dhsym.ik.closed_form import ClosedForm
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "PoseSample",
    "branch_signs",
    "branch_steps",
    "joint_distance",
    "key_values",
    "pose_sample",
    "same_joints",
]

#: Tolerance of a symbolic answer's joint values (radians, or lengths relative to 1 + |q|).
ATOL = TOLERANCES.ik_atol

Rewrite = Callable[[sp.Expr], sp.Expr]


@dataclass(frozen=True, eq=False)
class PoseSample:
    """Configurations ``q`` ``(size, n)``, their poses, and the values of every symbol.

    ``env`` maps the lengths, the joint variables and the pose symbols to arrays of
    ``size`` values; ``revolute`` marks the revolute joints; ``origin`` names the draw.
    """

    q: np.ndarray
    env: dict[sp.Symbol, np.ndarray]
    revolute: np.ndarray
    size: int
    origin: int


def _rng(seed: int | None) -> np.random.Generator:
    return np.random.default_rng(secrets.randbits(128) if seed is None else seed)


def pose_sample(
    robot: KinematicChain,
    size: int = 64,
    *,
    q: np.ndarray | None = None,
    values: Mapping[sp.Symbol, object] | None = None,
    seed: int | None = None,
) -> PoseSample:
    """Poses of ``size`` configurations (random, or the rows of ``q``).

    Revolute joints are drawn in (−π, π], prismatic ones in [0.2, 1.5]; lengths without a
    value in ``values`` in [0.3, 1.5] (positive, as an arm's lengths are).
    """
    rng = _rng(seed)
    rows = [r for r in robot.table.rows if r.variable is not None]
    revolute = np.array([r.joint is JointType.REVOLUTE for r in rows])
    if q is None:
        q = np.where(
            revolute,
            rng.uniform(*TOLERANCES.revolute_range, size=(size, len(rows))),
            rng.uniform(*TOLERANCES.prismatic_range, size=(size, len(rows))),
        )
    q = np.atleast_2d(np.asarray(q, dtype=float))
    size = len(q)
    env: dict[sp.Symbol, np.ndarray] = {}
    for s in robot.table.constants:
        if values is not None and s in values:
            env[s] = np.full(size, float(values[s]))  # type: ignore[arg-type]  # a number; float() refuses the rest
        else:
            env[s] = rng.uniform(*TOLERANCES.length_range, size=size)
    for k, v in enumerate(robot.variables):
        env[v] = q[:, k]
    T = frames(robot.table, env, size)[:, -1]
    P = pose_symbols()
    for i in range(3):
        for j in range(4):
            env[P[i, j]] = T[:, i, j]
    origin = secrets.randbits(63) if seed is None else seed
    return PoseSample(q, env, revolute, size, origin)


def branch_signs(ik: ClosedForm) -> np.ndarray:
    """Every choice of the signs ``σ`` (rows, in the solver's order: ``+1`` first)."""
    B = len(ik.branches)
    return np.array(list(itertools.product([1, -1], repeat=B)), dtype=float).reshape(2**B, B)


def key_values(
    ik: ClosedForm,
    env: Mapping[sp.Symbol, np.ndarray],
    size: int,
    rewrite: Rewrite | None = None,
    choices: tuple[int, ...] | None = None,
) -> np.ndarray:
    """The joint values of every branch, ``(K, size, n)`` (NaN where a step is not real).

    ``rewrite`` changes each step's right-hand side first (a mistake, recomputed);
    ``choices`` keeps those branches only (rows of :func:`branch_signs`), in that order.
    """
    variables = list(ik.robot.variables)
    signs = branch_signs(ik)
    if choices is not None:
        signs = signs[list(choices)]
    rhs = [rewrite(st.rhs) if rewrite else st.rhs for st in ik.steps]
    out = np.full((len(signs), size, len(variables)), np.nan)
    for k, choice in enumerate(signs):
        local = dict(env)
        for b, sign in zip(ik.branches, choice, strict=True):
            local[b.symbol] = np.full(size, sign)
        memo: dict[object, np.ndarray] = {}
        for st, e in zip(ik.steps, rhs, strict=True):
            local[st.lhs] = evaluate_or_nan(e, local, size, memo)
        for j, v in enumerate(variables):
            out[k, :, j] = local[v]
    return out


def branch_steps(
    ik: ClosedForm,
    env: Mapping[sp.Symbol, np.ndarray],
    size: int,
    k: int,
    edit: tuple[int, sp.Expr] | None = None,
    known: Mapping[sp.Symbol, np.ndarray] | None = None,
) -> dict[sp.Symbol, np.ndarray]:
    """The values of every step of branch ``k`` (a row of :func:`branch_signs`), by left-hand
    side; with ``edit`` = (step index, new right-hand side) and the unedited values
    ``known``, only that step and those after it are computed (a mistake in one step,
    recomputed)."""
    local = dict(env)
    for b, sign in zip(ik.branches, branch_signs(ik)[k], strict=True):
        local[b.symbol] = np.full(size, sign)
    start = 0
    changed: set[sp.Symbol] = set()
    if edit is not None and known is not None:
        start = edit[0]
        local.update({st.lhs: known[st.lhs] for st in ik.steps[:start]})
        changed.add(ik.steps[start].lhs)
    memo: dict[object, np.ndarray] = {}
    for i, st in enumerate(ik.steps[start:], start):
        if known is not None and i > start and not (st.rhs.free_symbols & changed):
            local[st.lhs] = known[st.lhs]  # a step the edit does not reach
            continue
        if i > start:
            changed.add(st.lhs)
        e = edit[1] if edit is not None and i == edit[0] else st.rhs
        local[st.lhs] = evaluate_or_nan(e, local, size, memo)
    return {st.lhs: local[st.lhs] for st in ik.steps}


def joint_distance(a: np.ndarray, b: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """``|a − b|`` joint by joint, angles modulo 2π (NaN where either is NaN)."""
    d: np.ndarray = a - b
    with np.errstate(invalid="ignore"):
        d = np.where(revolute, np.abs(np.remainder(d + np.pi, 2 * np.pi) - np.pi), np.abs(d))
    return d


def same_joints(
    a: np.ndarray,
    b: np.ndarray,
    revolute: np.ndarray,
    tol: np.ndarray | float = ATOL,
    nan: bool = False,
) -> bool:
    """True when ``a`` and ``b`` (``(size, n)``) agree at every point, angles modulo 2π.

    ``tol`` is absolute for angles and relative to ``1 + |b|`` for lengths; with ``nan``
    a NaN matches a NaN (a mistake that takes the root of a negative number).
    """
    d = joint_distance(a, b, revolute)
    scale = np.where(revolute, 1.0, 1.0 + np.abs(np.nan_to_num(b)))
    with np.errstate(invalid="ignore"):
        ok = d <= np.asarray(tol) * scale
    if nan:
        ok = ok | (np.isnan(a) & np.isnan(b))
    return bool(ok.all())
