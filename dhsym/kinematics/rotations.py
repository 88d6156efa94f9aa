r"""Rotations in numbers: the exponential and the logarithm of rotation matrices.

The numeric twins of the exact matrix exponential and logarithm of
:mod:`dhsym.screws.algebra` (Lynch and Park, *Modern Robotics*, §3.2.3), restricted to
rotations and written for arrays ``(..., 3, 3)``:

* :func:`rotation_exp`: Rodrigues' formula :math:`R = I + \frac{\sin\theta}{\theta}[w]
  + \frac{1 - \cos\theta}{\theta^2}[w]^2` of a rotation vector ``w = θ ω``;
* :func:`rotation_log`: the rotation vector ``θ ω`` (``θ`` in ``[0, π]``) with
  ``θ = atan2(sin θ, cos θ)`` from the antisymmetric part
  :math:`(R - R^T)/2 = \sin\theta\,[\omega]` and the trace
  :math:`\cos\theta = (\operatorname{tr} R - 1)/2` (accurate at every angle, where
  ``arccos`` of the trace alone loses digits near 0 and π); near ``θ = π`` the axis
  comes from the symmetric part, :math:`((R + R^T)/2 + I)/2 = \omega\omega^T` at ``π``
  exactly, its sign from the antisymmetric part.

The one numeric copy: the straight-line paths of :mod:`dhsym.trajectory.paths` turn the
tool by it, and the numeric inverse kinematics
(:mod:`dhsym.ik.levenberg_marquardt`) measures its orientation error by it.

Examples
--------
>>> w = np.array([0.3, -0.2, 0.9])
>>> np.allclose(rotation_log(rotation_exp(w)), w)
True
"""

from __future__ import annotations

import numpy as np

__all__ = ["rotation_exp", "rotation_log"]

#: below this ``sin θ`` the angle is 0 (``w`` is the antisymmetric part) or π (the axis
#: from the symmetric part)
_SMALL_SIN = 1e-9
#: below this ``sin θ`` and with ``cos θ < 0`` the axis comes from the symmetric part
_NEAR_PI_SIN = 1e-6


def rotation_log(R: np.ndarray) -> np.ndarray:
    """The rotation vector ``θ ω`` (``θ`` in ``[0, π]``) of rotation matrices ``(..., 3, 3)``.

    >>> rotation_log(rotation_exp(np.array([0.0, 0.0, 3.0])))
    array([0., 0., 3.])
    >>> rotation_log(np.diag([1.0, -1.0, -1.0]))  # a half turn about x
    array([3.14159265, 0.        , 0.        ])
    """
    R = np.asarray(R, dtype=float)
    flat = R.reshape(-1, 3, 3)
    v = 0.5 * np.stack(
        [
            flat[:, 2, 1] - flat[:, 1, 2],
            flat[:, 0, 2] - flat[:, 2, 0],
            flat[:, 1, 0] - flat[:, 0, 1],
        ],
        axis=-1,
    )
    s = np.linalg.norm(v, axis=-1)
    c = (np.trace(flat, axis1=-2, axis2=-1) - 1.0) / 2.0
    theta = np.arctan2(s, c)
    turning = s > _SMALL_SIN
    ratio = np.where(turning, theta / np.where(turning, s, 1.0), 1.0)
    w = v * ratio[:, None]
    near_pi = (s < _NEAR_PI_SIN) & (c < 0)
    if np.any(near_pi):  # θ ≈ π: the axis from the symmetric part (R + Rᵀ)/2 + I ≈ 2 ω ωᵀ
        P = flat[near_pi]
        B = ((P + np.swapaxes(P, -1, -2)) / 2 + np.eye(3)) / 2
        k = np.argmax(np.diagonal(B, axis1=-2, axis2=-1), axis=-1)
        col = np.take_along_axis(B, k[:, None, None], axis=-1)[..., 0]
        axis = col / np.linalg.norm(col, axis=-1, keepdims=True)
        # the sign of the axis from the small antisymmetric part
        sign = np.where(np.einsum("...i,...i->...", axis, v[near_pi]) < 0, -1.0, 1.0)
        w[near_pi] = axis * (sign * theta[near_pi])[:, None]
    out: np.ndarray = w.reshape(*R.shape[:-2], 3)
    return out


def rotation_exp(w: np.ndarray) -> np.ndarray:
    """Rodrigues' formula: the rotations ``exp([w])`` of rotation vectors ``(..., 3)``.

    >>> np.round(rotation_exp(np.array([0.0, 0.0, np.pi / 2])), 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    w = np.asarray(w, dtype=float)
    theta = np.linalg.norm(w, axis=-1)
    small = theta < 1e-8
    safe = np.where(small, 1.0, theta)
    a = np.where(small, 1 - theta**2 / 6, np.sin(theta) / safe)
    b = np.where(small, 0.5 - theta**2 / 24, (1 - np.cos(theta)) / safe**2)
    K = np.zeros((*w.shape[:-1], 3, 3))
    K[..., 0, 1], K[..., 0, 2], K[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    K = K - np.swapaxes(K, -1, -2)
    R: np.ndarray = np.eye(3) + a[..., None, None] * K + b[..., None, None] * (K @ K)
    return R
