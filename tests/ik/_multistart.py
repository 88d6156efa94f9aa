"""A multi-start Levenberg–Marquardt on the pose residual: the reference the general 6R solver
is checked against for completeness (every solution it finds, the solver must have)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def multistart_lm(
    fk: Callable[[np.ndarray], np.ndarray],
    T: np.ndarray,
    starts: int = 200,
    *,
    iterations: int = 150,
    seed: int = 0,
) -> np.ndarray:
    """Distinct solutions ``(k, 6)`` found from ``starts`` random starts (all run at once).

    The residual is the 3×4 part of ``fk(q) − T``; the Jacobian is by central differences;
    λ is divided by 3 after a step that lowers the residual and multiplied by 4 otherwise.
    A start counts when its residual is below 1e-10.
    """
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (starts, 6))
    goal = T[:3, :].ravel()

    def residual(Q: np.ndarray) -> np.ndarray:
        return fk(Q)[:, :3, :].reshape(len(Q), 12) - goal

    e = residual(q)
    cost = (e**2).sum(axis=1)
    lam = np.full(starts, 1e-2)
    h = 1e-6
    for _ in range(iterations):
        J = np.empty((starts, 12, 6))
        for j in range(6):
            dq = np.zeros(6)
            dq[j] = h
            J[:, :, j] = (residual(q + dq) - residual(q - dq)) / (2 * h)
        JtJ = J.transpose(0, 2, 1) @ J
        g = (J.transpose(0, 2, 1) @ e[..., None])[..., 0]
        A = JtJ + lam[:, None, None] * np.eye(6)
        step = -np.linalg.solve(A, g[..., None])[..., 0]
        trial = q + step
        e_trial = residual(trial)
        cost_trial = (e_trial**2).sum(axis=1)
        better = cost_trial < cost
        q[better], e[better], cost[better] = trial[better], e_trial[better], cost_trial[better]
        lam = np.where(better, np.maximum(lam / 3, 1e-12), np.minimum(lam * 4, 1e8))
        if (cost < 1e-26).all():
            break
    found = q[np.sqrt(cost) < 1e-10]
    found = np.remainder(found + np.pi, 2 * np.pi) - np.pi
    out: list[np.ndarray] = []
    for row in found:
        if all(wrapped_distance(row, k) > 1e-6 for k in out):
            out.append(row)
    return np.array(out).reshape(-1, 6)


def wrapped_distance(a: np.ndarray, b: np.ndarray) -> float:
    """The largest joint difference modulo 2π."""
    return float(np.abs(np.remainder(a - b + np.pi, 2 * np.pi) - np.pi).max())


def contains(Q: np.ndarray, q: np.ndarray, tol: float = 1e-6) -> bool:
    """Whether ``q`` is among the rows of ``Q`` (modulo 2π)."""
    return any(wrapped_distance(row, q) < tol for row in Q)
