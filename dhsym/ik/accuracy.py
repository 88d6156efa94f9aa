"""Poses as they come: how accurate a measured, rounded or typed pose is, its nearest rigid
pose, and the tolerance its inverse kinematics is checked with.

A pose typed from a teach pendant or rounded to a few decimals is not exactly a rigid
motion: its rotation ``R`` is a little off the rotations (``RᵀR ≠ I``), and no joint
values reproduce it to 1e-9. :func:`pose_accuracy` measures it and says what to do:

* ``off``: the distance of ``R`` from the nearest rotation ``R̂`` (polar decomposition,
  by SVD: ``R = U S Vᵀ``, ``R̂ = U diag(1, 1, det U Vᵀ) Vᵀ``), as the largest entry of
  ``R − R̂``;
* ``decimals``: the decimals the pose was written with, when its 12 entries look rounded
  (the smallest ``k ≤ 12`` with every entry equal to its rounding to ``k`` decimals),
  and ``half_unit`` = half a unit of the last decimal, ``0.5·10⁻ᵏ`` (0 when none);
* ``tol``: the tolerance the solutions are checked with against the pose *as given*
  (largest entry error of ``fk``, as ``Robot.ik``'s residual), ``max(1e-9, 2·max(off,
  min(half_unit, 3·off)))`` when the rotation is off by more than :data:`EXACT`, else
  1e-9 (an exact float pose is solved exactly as before).

Why this rule: the branches are computed from the nearest rigid pose ``(R̂, p)`` (same
position). A true solution of it reproduces ``R̂`` and ``p`` to rounding, so against the
pose as given its largest entry error is ``off`` (the rotation entries) and about 1e-15
(the position). ``off`` is below about three half-units of the last decimal of a
rounded rotation; twice the larger of the two leaves room and stays far below the error
of a wrong branch (whole radians). The half-unit counts only up to ``3·off``: a pose
written with few decimals whose rotation is nearly exact (``np.eye(4)``, 0 decimals) is
not loosened by them. The position's own rounding needs no room: the position is
reproduced as given.

Near the workspace boundary or a singularity the rounded pose may lie a little out of
reach: the closed form then reads a negative radicand as 0 (the arm stretched) and the
general 6R keeps a pair of roots that rounding made complex; such a branch lands near the
pose, not on it. A branch within :data:`REFINE` tolerances is refined by
Levenberg–Marquardt towards the nearest rigid pose before it is judged (restarted beside
a stretched, singular arm), so that every pose reached by ``fk`` and rounded to 6, 4 or 3
decimals gets its solutions (``tests/ik/test_accuracy.py``: 1,000 poses of every built-in
six-joint arm and of the UR5 and Panda URDFs).

Examples
--------
>>> import dhsym
>>> r = dhsym.load("ur5")
>>> T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
>>> exact = pose_accuracy(T)
>>> exact.decimals, exact.tol, bool(exact.off < EXACT)
(None, 1e-09, True)
>>> typed = pose_accuracy(np.round(T, 6))
>>> typed.decimals, typed.half_unit, typed.tol
(6, 5e-07, 1e-06)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "EXACT",
    "FLOOR",
    "MOST_DECIMALS",
    "PoseAccuracy",
    "REFINE",
    "REFINE_STEPS",
    "SAME",
    "STUCK",
    "nearest_rigid",
    "pose_accuracy",
    "written_decimals",
]

#: a rotation off the rotations by at most this (largest entry) is exact: solved as given
EXACT = 1e-12
#: the tolerance of an exact pose, and the least tolerance of any
FLOOR = 1e-9
#: the most decimals looked for in a pose's entries
MOST_DECIMALS = 12
#: a branch of a pose that is not exact within this many tolerances of it (but not within
#: one) is refined against it before it is judged: near a boundary or a singularity the
#: rounding moves the pose a little out of reach, and the arm stretched towards it lands
#: near it (a few tolerances: up to 14 on the PUMA's shoulder in 1,000 poses), not on it
REFINE = 30
#: the most Levenberg–Marquardt steps such a branch is refined by
REFINE_STEPS = 12
#: a Jacobian whose smallest singular value is below this fraction of its largest holds
#: Levenberg–Marquardt at a stretched arm (the refinement starts again beside it, along the
#: Jacobian's null direction, ``√res`` away)
STUCK = 1e-3
#: two refined solutions closer than this (angles by cosine and sine) are one
SAME = 1e-6

#: 10ᵏ for k = 0 … MOST_DECIMALS, a column (written_decimals tries every k at once)
_SCALES = 10.0 ** np.arange(MOST_DECIMALS + 1, dtype=float)[:, None]


@dataclass(frozen=True)
class PoseAccuracy:
    """How accurate one pose is (see the module): ``off`` from the rotations, the
    ``decimals`` it was written with (None: not rounded), ``half_unit`` of its last
    decimal, and the ``tol`` its solutions are checked with."""

    off: float
    decimals: int | None
    half_unit: float
    tol: float

    @property
    def exact(self) -> bool:
        """Whether the rotation is a rotation to :data:`EXACT` (the pose is solved as given)."""
        return self.off <= EXACT


def written_decimals(T: np.ndarray) -> int | None:
    """The decimals the 12 entries of ``T`` ``(4, 4)`` were written with: the smallest
    ``k ≤ 12`` with every entry equal to its rounding to ``k`` decimals (None when none).

    >>> written_decimals(np.round(np.array([[0.123456789, 0, 0, 1.5]] * 4), 4))
    4
    >>> written_decimals(np.eye(4)), written_decimals(np.full((4, 4), np.pi))
    (0, None)
    """
    entries = np.asarray(T, dtype=float)[:3].ravel()
    # every k at once, by numpy's own rule for np.round(x, k): x·10ᵏ, rint, ÷10ᵏ
    with np.errstate(invalid="ignore", over="ignore"):
        same = (np.rint(entries * _SCALES) / _SCALES == entries).all(axis=1)
    return int(np.argmax(same)) if same.any() else None


def nearest_rigid(T: np.ndarray) -> np.ndarray:
    """``T`` ``(4, 4)`` or ``(N, 4, 4)`` with each rotation replaced by the nearest rotation
    (polar decomposition by SVD), the position kept.

    >>> R = np.round(np.array([[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]]) + 1e-4, 4)
    >>> T = np.eye(4)
    >>> T[:3, :3] = R
    >>> Q = nearest_rigid(T)[:3, :3]
    >>> bool(np.allclose(Q.T @ Q, np.eye(3), atol=1e-15)), bool(np.linalg.det(Q) > 0)
    (True, True)
    """
    out = np.array(T, dtype=float)
    R = out[..., :3, :3]
    finite = np.isfinite(R).all(axis=(-2, -1))[..., None, None]  # NaN, inf: kept as they are
    U, _, Vt = np.linalg.svd(np.where(finite, R, np.eye(3)))
    d = np.sign(np.linalg.det(U @ Vt))
    U[..., :, 2] *= d[..., None]
    out[..., :3, :3] = np.where(finite, U @ Vt, R)
    return out


def pose_accuracy(T: np.ndarray, rigid: np.ndarray | None = None) -> PoseAccuracy:
    """How accurate the pose ``T`` ``(4, 4)`` is, and its tolerance (the rule: see the
    module); ``rigid``: its :func:`nearest_rigid` pose when already known."""
    arr = np.asarray(T, dtype=float)
    if rigid is None:
        rigid = nearest_rigid(arr)
    with np.errstate(invalid="ignore"):  # a pose of NaNs: no solution, said by its step
        off = float(np.abs(rigid[:3, :3] - arr[:3, :3]).max())
    if not np.isfinite(off):
        return PoseAccuracy(off, None, 0.0, FLOOR)
    k = written_decimals(arr)
    half = 0.0 if k is None else 0.5 * 10.0**-k
    if off <= EXACT:
        return PoseAccuracy(off, k, half, FLOOR)
    return PoseAccuracy(off, k, half, max(FLOOR, 2 * max(off, min(half, 3 * off))))
