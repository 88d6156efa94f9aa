"""A numeric inverse kinematics: Levenberg–Marquardt on the compiled ``fk`` and Jacobian.

Clearly not the closed form: it finds one solution near its start, or none. It is the
reference the closed forms are tested against, and the fallback for arms no family
solves. It returns the :class:`~dhsym.ik.solution.IKSolution` of every solver: one row,
valid when it converged, with ``method="numeric"`` and its ``iterations``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from dhsym.errors import DHError
from dhsym.kinematics.rotations import rotation_log
from dhsym.model.table import JointType

from .solution import IKSolution

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "CONVERGED",
    "DAMPING",
    "DAMPING_RANGE",
    "DAMPING_STEP",
    "DESCRIPTION",
    "DIAGONAL_FLOOR",
    "METHOD",
    "SELF_MOTION",
    "numeric_ik",
    "numeric_solutions",
]

#: what an :class:`IKSolution` of this solver says it is, and that in a sentence
METHOD = "numeric"
#: the singularity a numeric solution may be near: the free joints move the tool in fewer
#: than six directions (the Jacobian of the joints left free short of rank)
SELF_MOTION = "self-motion"
DESCRIPTION = "numeric: Levenberg–Marquardt on the compiled fk (one local solution)"
#: the damping λ a solve starts with; divided by :data:`DAMPING_STEP` after a step that
#: lowers the error, multiplied by it after one that does not, kept within
#: :data:`DAMPING_RANGE` (the exported IK's refinement takes the same numbers)
DAMPING = 1e-2
DAMPING_STEP = 10.0
DAMPING_RANGE = (1e-12, 1e12)
#: a solve has converged when the error's length (position and rotation vector) is below this
CONVERGED = 1e-12
#: added to the diagonal of ``JᵀJ`` the damping scales (a zero column stays solvable)
DIAGONAL_FLOOR = 1e-12


def _solution(q: np.ndarray, converged: bool, iterations: int, error: float) -> IKSolution:
    """The one local solution as an :class:`IKSolution` (valid when it converged)."""
    return IKSolution(
        q[None, :],
        np.array([converged]),
        np.array([error]),
        np.zeros((1, 0), dtype=bool),
        (),
        np.zeros((1, 0), dtype=int),
        METHOD,
        None if converged else f"did not converge in {iterations} iterations",
        iterations,
    )


def _rotation_error(R: np.ndarray, goal: np.ndarray) -> np.ndarray:
    """The rotation vector (axis times angle) that turns ``R`` into ``goal``, base frame."""
    return rotation_log(goal @ R.T)


def numeric_ik(
    robot: KinematicChain,
    T: object,
    q0: object = None,
    *,
    tol: float = CONVERGED,
    max_iter: int = 100,
    values: Mapping[object, object] | None = None,
    fixed: Mapping[int, float] | None = None,
) -> IKSolution:
    """Levenberg–Marquardt on the compiled ``fk`` and Jacobian, from ``q0`` (default zeros).

    A numeric solver, clearly not the closed form: it finds one solution near its
    start, or none. The error is the position error and the rotation vector from the
    current orientation to the goal, both in the base frame; the step solves
    ``(JᵀJ + λ diag(JᵀJ)) Δq = Jᵀe`` with λ divided by 10 after a successful step and
    multiplied by 10 after a failed one. ``fixed={joint: value}`` (1-based) holds those
    joints at their values (their columns of J left out): a seven-joint arm with one
    joint given.

    >>> import dhsym
    >>> r = dhsym.load("planar2r")
    >>> sol = numeric_ik(r, r.fk([0.4, 0.9]), [0.3, 0.8])
    >>> sol.method, sol.converged, np.round(sol.q, 9).tolist(), sol.branches
    ('numeric', True, [[0.4, 0.9]], ('solution 1',))
    """
    fk = robot.fk_function(values=values)
    target = np.asarray(T, dtype=float)
    n = len(robot.variables)
    q = np.zeros(n) if q0 is None else np.asarray(q0, dtype=float).copy()
    held = sorted(fixed or {})
    if any(not 1 <= k <= n for k in held):
        raise DHError(f"fixed: joints are 1 … {n}, got {held}")
    for k in held:
        q[k - 1] = float((fixed or {})[k])
    moving = np.array([k not in held for k in range(1, n + 1)])

    def error(q: np.ndarray) -> np.ndarray:
        M = fk(q)
        return np.concatenate(
            [target[:3, 3] - M[:3, 3], _rotation_error(M[:3, :3], target[:3, :3])]
        )

    e = error(q)
    lam = DAMPING
    it = 0
    for it in range(1, max_iter + 1):
        if e @ e < tol**2:
            return _solution(q, True, it - 1, float(np.sqrt(e @ e)))
        J = np.asarray(robot.jacobian(q, values=values))[:, moving]
        H = J.T @ J
        trial = q.copy()
        trial[moving] += np.linalg.solve(H + lam * np.diag(np.diag(H) + DIAGONAL_FLOOR), J.T @ e)
        e_trial = error(trial)
        if e_trial @ e_trial < e @ e:
            q, e, lam = trial, e_trial, max(lam / DAMPING_STEP, DAMPING_RANGE[0])
        else:
            lam = min(lam * DAMPING_STEP, DAMPING_RANGE[1])
    err = float(np.sqrt(e @ e))
    return _solution(q, err < tol, it, err)


def numeric_solutions(
    robot: KinematicChain,
    T: object,
    *,
    starts: int = 24,
    tol: float = 1e-12,
    values: Mapping[object, object] | None = None,
    fixed: Mapping[int, float] | None = None,
    seed: int = 0,
) -> IKSolution:
    """The distinct solutions :func:`numeric_ik` finds from several starts: all joints
    zero, then ``starts − 1`` starts drawn (``seed``) within the joint limits (±π for a
    revolute joint without limits, [0, 1] for a prismatic one).

    What an arm without a closed form gets (the Panda with joint 4 given, say): a set of
    local solutions, not a guarantee that every branch is found. The result is one
    :class:`~dhsym.ik.solution.IKSolution` with ``method="numeric"``, one row per
    distinct converged solution (angles compared modulo 2π), ``iterations`` the steps
    taken over all starts, and a ``reason`` naming the smallest error reached when no
    start converged.

    >>> import dhsym
    >>> r = dhsym.load("planar2r")
    >>> sol = numeric_solutions(r, r.fk([0.4, 0.9]), starts=8)  # the whole pose: one
    >>> sol.method, len(sol), sol.branches, np.round(sol.q, 9).tolist()
    ('numeric', 1, ('numeric solution 1',), [[0.4, 0.9]])
    """
    n = len(robot.variables)
    rows = [r for r in robot.table.rows if r.variable is not None]
    revolute = np.array([r.joint is JointType.REVOLUTE for r in rows])
    lo, hi = np.full(n, -np.pi), np.full(n, np.pi)
    values_map = robot.table.value_map
    for k, r in enumerate(rows):
        if r.limits is not None:
            lo[k], hi[k] = (float(x.xreplace(values_map)) for x in r.limits)
        elif not revolute[k]:
            lo[k], hi[k] = 0.0, 1.0
    rng = np.random.default_rng(seed)
    mid = np.where(np.isfinite(lo + hi), (lo + hi) / 2, 0.0)
    first = np.clip(np.zeros(n), lo, hi) if np.isfinite(lo + hi).all() else mid
    guesses = [first] + [rng.uniform(lo, hi) for _ in range(max(starts, 1) - 1)]
    found: list[np.ndarray] = []
    errors: list[float] = []
    steps = 0
    best = np.inf
    for q0 in guesses:
        one = numeric_ik(robot, T, q0, tol=tol, values=values, fixed=fixed)
        steps += one.iterations or 0
        best = min(best, float(one.residual[0]))
        if not one.converged:
            continue
        q = one.q[0].copy()
        q[revolute] = (q[revolute] + np.pi) % (2 * np.pi) - np.pi  # angles in [−π, π)
        d = [q - other for other in found]
        same = [np.abs(np.where(revolute, np.angle(np.exp(1j * x)), x)).max() < 1e-6 for x in d]
        if not any(same):
            found.append(q)
            errors.append(float(one.residual[0]))
    k = len(found)
    # where the joints left free still move the tool in fewer than six directions (J of
    # the moving joints short of rank), the solution is one of a continuum: said so
    held = sorted(fixed or {})
    moving = np.array([j not in held for j in range(1, n + 1)])
    flat = np.zeros((k, 1), dtype=bool)
    for i, q in enumerate(found):
        J = np.asarray(robot.jacobian(q, values=values))[:, moving]
        sv = np.linalg.svd(J, compute_uv=False)
        flat[i, 0] = int(moving.sum()) > sv.size or sv[-1] < 1e-9 * max(sv[0], 1.0)
    names = tuple(
        f"numeric solution {i}" + (", one of a continuum (self-motion)" if flat[i - 1, 0] else "")
        for i in range(1, k + 1)
    )
    reason = None
    if not k:
        reason = (
            f"{DESCRIPTION}: no start of {len(guesses)} converged (smallest error {best:.3g}; "
            "the pose may be out of reach)"
        )
    return IKSolution(
        np.array(found).reshape(k, n),
        np.ones(k, dtype=bool),
        np.array(errors),
        flat,
        (SELF_MOTION,),
        np.zeros((k, 0), dtype=int),
        METHOD,
        reason,
        steps,
        names=names,
    )
