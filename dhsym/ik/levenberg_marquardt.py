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

from .solution import IKSolution

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["DESCRIPTION", "METHOD", "numeric_ik"]

#: what an :class:`IKSolution` of this solver says it is, and that in a sentence
METHOD = "numeric"
DESCRIPTION = "numeric: Levenberg–Marquardt on the compiled fk (one local solution)"


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
    E = goal @ R.T
    v = 0.5 * np.array([E[2, 1] - E[1, 2], E[0, 2] - E[2, 0], E[1, 0] - E[0, 1]])
    s, c = float(np.linalg.norm(v)), (float(np.trace(E)) - 1.0) / 2.0
    if s > 1e-9:
        rotvec: np.ndarray = np.arctan2(s, c) / s * v
        return rotvec
    if c > 0:
        return v
    k = int(np.argmax(np.linalg.norm(E + np.eye(3), axis=0)))  # a half turn: axis from E + I
    axis = (E + np.eye(3))[:, k]
    half_turn: np.ndarray = np.pi * axis / np.linalg.norm(axis)
    return half_turn


def numeric_ik(
    robot: KinematicChain,
    T: object,
    q0: object = None,
    *,
    tol: float = 1e-12,
    max_iter: int = 100,
    values: Mapping[object, object] | None = None,
) -> IKSolution:
    """Levenberg–Marquardt on the compiled ``fk`` and Jacobian, from ``q0`` (default zeros).

    A numeric solver, clearly not the closed form: it finds one solution near its
    start, or none. The error is the position error and the rotation vector from the
    current orientation to the goal, both in the base frame; the step solves
    ``(JᵀJ + λ diag(JᵀJ)) Δq = Jᵀe`` with λ divided by 10 after a successful step and
    multiplied by 10 after a failed one.

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

    def error(q: np.ndarray) -> np.ndarray:
        M = fk(q)
        return np.concatenate(
            [target[:3, 3] - M[:3, 3], _rotation_error(M[:3, :3], target[:3, :3])]
        )

    e = error(q)
    lam = 1e-2
    it = 0
    for it in range(1, max_iter + 1):
        if e @ e < tol**2:
            return _solution(q, True, it - 1, float(np.sqrt(e @ e)))
        J = np.asarray(robot.jacobian(q, values=values))
        H = J.T @ J
        step = np.linalg.solve(H + lam * np.diag(np.diag(H) + 1e-12), J.T @ e)
        trial = q + step
        e_trial = error(trial)
        if e_trial @ e_trial < e @ e:
            q, e, lam = trial, e_trial, max(lam / 10, 1e-12)
        else:
            lam = min(lam * 10, 1e12)
    err = float(np.sqrt(e @ e))
    return _solution(q, err < tol, it, err)
