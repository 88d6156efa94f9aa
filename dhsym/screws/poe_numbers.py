r"""The product of exponentials in numbers: twist exponentials, adjoints and the space and
body Jacobians of a batch of configurations, from screw axes given as floats.

The numeric twins of :mod:`dhsym.screws.algebra` and of
:meth:`~dhsym.screws.product.ProductOfExponentials.jacobian_space` /
:meth:`~dhsym.screws.product.ProductOfExponentials.jacobian_body` (Lynch and Park, *Modern
Robotics*, §3.3.3 and §5.1), written for arrays: nothing is derived, so the numbers of an
arm whose exact Jacobian is long (the KUKA LWR4, the Jaco) cost what a short one's do.

* :func:`twist_exp`: ``e^{[S]θ}`` — ``R = e^{[ω]θ}`` (Rodrigues, the one numeric copy of
  :mod:`dhsym.kinematics.rotations`) and ``p = (Iθ + (1 − cos θ)[ω] + (θ − sin θ)[ω]²) v``
  for a revolute axis, ``R = I``, ``p = vθ`` for a prismatic one;
* :func:`adjoint_numbers`: ``[Ad_T] = [[R, 0], [[p]R, R]]``;
* :func:`jacobian_space_numbers`: column ``i`` is ``[Ad_{e^{[S_1]θ_1}⋯e^{[S_{i-1}]θ_{i-1}}}] S_i``;
* :func:`jacobian_body_numbers`: column ``i`` is
  ``[Ad_{e^{-[B_n]θ_n}⋯e^{-[B_{i+1}]θ_{i+1}}}] B_i``.

Examples
--------
The planar 2R with ``a1 = a2 = 1`` at ``q = 0``: the second axis passes through
``(1, 0, 0)``, so ``v = −ω × q = (0, −1, 0)``.

>>> S = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0]], dtype=float).T
>>> jacobian_space_numbers(S, np.zeros(2))[:, 1]
array([ 0.,  0.,  1.,  0., -1.,  0.])
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.rotations import rotation_exp

if TYPE_CHECKING:
    from .product import ProductOfExponentials

__all__ = [
    "adjoint_numbers",
    "jacobian_body_numbers",
    "jacobian_space_numbers",
    "screw_jacobian_function",
    "twist_exp",
]


def _skew(w: np.ndarray) -> np.ndarray:
    """``[w]`` of vectors ``(..., 3)``: ``(..., 3, 3)``."""
    z = np.zeros(w.shape[:-1])
    x, y, t = w[..., 0], w[..., 1], w[..., 2]
    return np.stack(
        [np.stack([z, -t, y], -1), np.stack([t, z, -x], -1), np.stack([-y, x, z], -1)], -2
    )


def twist_exp(S: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """``e^{[S]θ}`` of one screw axis ``S`` ``(6,)`` (rows ``[ω; v]``, ``ω`` a unit vector
    or zero) at the values ``theta`` ``(N,)``: ``(N, 4, 4)``.

    >>> T = twist_exp(np.array([0, 0, 1, 0, -1, 0.0]), np.array([np.pi / 2]))
    >>> np.round(T[0, :3, 3], 12)  # a quarter turn about the vertical line through x = 1
    array([ 1., -1.,  0.])
    """
    S = np.asarray(S, dtype=float)
    theta = np.asarray(theta, dtype=float)
    w, v = S[:3], S[3:]
    out = np.zeros((*theta.shape, 4, 4))
    out[..., 3, 3] = 1.0
    if not np.any(w):  # prismatic: a translation along v
        out[..., :3, :3] = np.eye(3)
        out[..., :3, 3] = theta[..., None] * v
        return out
    out[..., :3, :3] = rotation_exp(theta[..., None] * w)
    W = _skew(w)
    G = (
        np.eye(3) * theta[..., None, None]
        + (1.0 - np.cos(theta))[..., None, None] * W
        + (theta - np.sin(theta))[..., None, None] * (W @ W)
    )
    out[..., :3, 3] = G @ v
    return out


def adjoint_numbers(T: np.ndarray) -> np.ndarray:
    """``[Ad_T]`` of transforms ``(..., 4, 4)``: ``(..., 6, 6)`` acting on ``[ω; v]``.

    >>> T = np.eye(4); T[:3, 3] = [1.0, 0, 0]
    >>> (adjoint_numbers(T) @ np.array([0, 0, 1, 0, 0, 0.0]))[3:]  # v = p × ω
    array([ 0., -1.,  0.])
    """
    R, p = T[..., :3, :3], T[..., :3, 3]
    out = np.zeros((*T.shape[:-2], 6, 6))
    out[..., :3, :3] = R
    out[..., 3:, 3:] = R
    out[..., 3:, :3] = _skew(p) @ R
    return out


def _batch(q: np.ndarray, n: int) -> tuple[np.ndarray, bool]:
    """Joint values as a batch ``(N, n)``, and whether one configuration was given."""
    arr = np.asarray(q, dtype=float)
    single = arr.ndim <= 1
    Q = arr.reshape(1, -1) if single else arr
    if Q.ndim != 2 or Q.shape[-1] != n:
        raise DHError(f"expected {n} joint values per configuration, got shape {arr.shape}")
    return Q, single


def jacobian_space_numbers(S: np.ndarray, q: object) -> np.ndarray:
    """The space Jacobian of screw axes ``S`` ``(6, n)`` at ``q`` ``(n,)`` → ``(6, n)``, or
    ``(N, n)`` → ``(N, 6, n)``."""
    S = np.asarray(S, dtype=float)
    n = S.shape[1]
    Q, single = _batch(np.asarray(q), n)
    J = np.empty((Q.shape[0], 6, n))
    T = np.broadcast_to(np.eye(4), (Q.shape[0], 4, 4))
    for i in range(n):
        J[:, :, i] = adjoint_numbers(T) @ S[:, i]
        T = T @ twist_exp(S[:, i], Q[:, i])
    return J[0] if single else J


def jacobian_body_numbers(B: np.ndarray, q: object) -> np.ndarray:
    """The body Jacobian of body screw axes ``B`` ``(6, n)`` at ``q`` ``(n,)`` → ``(6, n)``,
    or ``(N, n)`` → ``(N, 6, n)``."""
    B = np.asarray(B, dtype=float)
    n = B.shape[1]
    Q, single = _batch(np.asarray(q), n)
    J = np.empty((Q.shape[0], 6, n))
    T = np.broadcast_to(np.eye(4), (Q.shape[0], 4, 4))
    for i in reversed(range(n)):
        J[:, :, i] = adjoint_numbers(T) @ B[:, i]
        T = T @ twist_exp(B[:, i], -Q[:, i])
    return J[0] if single else J


def screw_jacobian_function(
    poe: ProductOfExponentials, frame: str, values: Mapping[sp.Symbol, sp.Expr]
) -> Callable[[object], np.ndarray]:
    """``q -> J_s(q)`` (``frame`` ``"space"``) or ``J_b(q)`` (``"body"``) of ``poe`` with
    ``values`` for its symbolic lengths: the axes made floats once, the Jacobian computed in
    numbers (:func:`jacobian_space_numbers`), nothing derived.

    >>> import dhsym
    >>> r = dhsym.load("planar2r")
    >>> values = r.table.with_values({"a1": 1, "a2": 1}).value_map
    >>> f = screw_jacobian_function(r.poe(), "body", values)
    >>> f([0.0, 0.0])[:, 0]
    array([0., 0., 1., 0., 2., 0.])
    """
    S = poe.screw_matrix(frame).xreplace(dict(values)).xreplace(dict(poe.values))
    missing = S.free_symbols
    if missing:
        names = ", ".join(sorted(str(s) for s in missing))
        raise DHError(f"no numeric value for {names}: give values for these symbols")
    axes = np.array(S.evalf(17).tolist(), dtype=float)
    numbers = jacobian_body_numbers if frame == "body" else jacobian_space_numbers

    def evaluate(q: object) -> np.ndarray:
        return numbers(axes, q)

    return evaluate
