r"""Paths of an arm: joint-space motion between two configurations (:func:`jtraj`) and a
straight Cartesian line solved by the closed-form inverse kinematics (:func:`ctraj`).

:func:`jtraj` is a :func:`~dhsym.trajectory.profiles.quintic` per joint, all joints
timed to the same end, as roboticstoolbox's ``jtraj`` (and the lectures) do.
:func:`ctraj` moves the tool's origin along the straight line from ``T0`` to ``T1`` and
turns its orientation about one fixed axis, the shortest rotation from ``R0`` to ``R1``
(``R(s) = R0 exp(s log(R0ᵀ R1))``, the same path as quaternion slerp, with the numeric
exponential and logarithm of :mod:`dhsym.kinematics.rotations`; Lynch–Park,
*Modern Robotics*, ch. 9, straight-line paths), with the progress ``s(t)`` a
trapezoidal profile from 0 to 1 (as roboticstoolbox's ``ctraj``); every sample is
solved by the robot's inverse kinematics, keeping the branch nearest the previous
sample, and the path stops with a reason at the first sample without a solution (the
workspace boundary) or near a singular configuration.

Examples
--------
>>> path = jtraj([0, 1], [1, -1], [0.0, 0.5, 1.0])
>>> path.q
array([[ 0. ,  1. ],
       [ 0.5,  0. ],
       [ 1. , -1. ]])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dhsym.errors import DHError
from dhsym.kinematics.rotations import rotation_exp, rotation_log
from dhsym.model.kinds import JointType

from .blends import lspb
from .profiles import Profile, quintic

if TYPE_CHECKING:
    from dhsym.ik.choices import IKCache
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["CartesianPath", "JointPath", "ctraj", "jtraj"]


@dataclass(frozen=True)
class JointPath:
    """Samples of a joint-space motion: times ``t`` ``(N,)``, ``q``, ``qd``, ``qdd``
    ``(N, n)`` and the ``profile`` they were sampled from."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    profile: Profile


def _times(t: object) -> np.ndarray:
    """roboticstoolbox's time argument: an int ``N`` is ``N`` samples over ``[0, 1]`` s…"""
    if isinstance(t, (int, np.integer)) and not isinstance(t, bool):
        if t < 2:
            raise DHError(f"t: at least two samples, got {t}")
        return np.linspace(0.0, 1.0, int(t))
    ts = np.asarray(t, dtype=float).reshape(-1)
    if ts.size < 2 or not np.all(np.isfinite(ts)) or np.any(np.diff(ts) < 0) or ts[0] < 0:
        raise DHError("t: expected times from 0 on, increasing, at least two")
    return ts


def jtraj(
    q0: object,
    qf: object,
    t: object,
    qd0: object = None,
    qd1: object = None,
    *,
    joints: int | None = None,
) -> JointPath:
    """A quintic from ``q0`` to ``qf`` per joint, at rest at both ends unless ``qd0``,
    ``qd1`` are given, ending at ``max(t)`` (``t`` an int: that many samples over one
    second), sampled at ``t``; ``joints`` the number of joints expected.

    >>> jtraj([0, 0], [1, 2], 5).qd[2]
    array([1.875, 3.75 ])
    """
    ts = _times(t)
    if np.ndim(q0) == 0 or np.ndim(qf) == 0:  # type: ignore[arg-type]  # any sequence
        raise DHError("jtraj: q0 and qf are joint vectors (for one joint use quintic)")
    n = len(np.asarray(q0, dtype=object).reshape(-1))
    for name, q in (("q0", q0), ("qf", qf)):
        size = len(np.asarray(q, dtype=object).reshape(-1))
        if joints is not None and size != joints:
            raise DHError(f"jtraj: {name} has {size} values for {joints} joints")
    zero = [0] * n
    profile = quintic(
        q0,
        qf,
        float(ts[-1]),
        zero if qd0 is None else qd0,
        zero if qd1 is None else qd1,
    )
    q, qd, qdd = profile.sample(ts)
    return JointPath(ts, q, qd, qdd, profile)


# --- the shortest turn ----------------------------------------------------------------
def interpolate_poses(T0: np.ndarray, T1: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Poses ``(N, 4, 4)`` at progress ``s`` ``(N,)``: the origin on the straight line,
    the rotation about the one axis of the shortest turn from ``R0`` to ``R1``.

    >>> T1 = np.eye(4); T1[:3, 3] = [1, 2, 3]
    >>> interpolate_poses(np.eye(4), T1, np.array([0.5]))[0, :3, 3]
    array([0.5, 1. , 1.5])
    """
    w = rotation_log(T0[:3, :3].T @ T1[:3, :3])
    out = np.zeros((len(s), 4, 4))
    out[:, :3, :3] = T0[:3, :3] @ rotation_exp(s[:, None] * w)
    out[:, :3, 3] = (1 - s)[:, None] * T0[:3, 3] + s[:, None] * T1[:3, 3]
    out[:, 3, 3] = 1.0
    return out


# --- the straight line, solved ---------------------------------------------------------
@dataclass(frozen=True)
class CartesianPath:
    """A straight-line path solved sample by sample.

    ``t`` ``(N,)`` the times, ``s`` the progress along the line, ``T`` ``(N, 4, 4)`` the
    poses asked for; ``q`` ``(M, n)`` the joint values of the first ``M`` samples, each
    on the branch nearest the previous one. ``stopped`` is the index of the first sample
    not solved (None when all are) and ``reason`` says why (no solution: outside the
    workspace; near a singular configuration; a jump of the branch).
    """

    t: np.ndarray
    s: np.ndarray
    T: np.ndarray
    q: np.ndarray
    residual: np.ndarray
    stopped: int | None = None
    reason: str | None = None

    @property
    def complete(self) -> bool:
        """True when every sample was solved."""
        return self.stopped is None

    def require(self) -> CartesianPath:
        """The path itself when complete, else :class:`~dhsym.errors.DHError` with the reason.

        >>> CartesianPath(np.zeros(2), np.zeros(2), np.zeros((2, 4, 4)), np.zeros((1, 1)),
        ...               np.zeros(1), 1, "sample 1 (t = 0.5): no solution").require()
        Traceback (most recent call last):
        ...
        dhsym.errors.DHError: ctraj stopped: sample 1 (t = 0.5): no solution
        """
        if self.stopped is not None:
            raise DHError(f"ctraj stopped: {self.reason}")
        return self


def _wrap(d: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """Joint differences with revolute angles brought into ``(−π, π]``."""
    wrapped = np.where(revolute, np.mod(d + np.pi, 2 * np.pi) - np.pi, d)
    return np.asarray(wrapped)


def ctraj(
    robot: KinematicChain,
    T0: object,
    T1: object,
    t: object,
    *,
    near: object = None,
    cache: IKCache | None = None,
    max_step: float = 0.5,
    singular: bool = True,
    check: str = "pose",
) -> CartesianPath:
    """The straight line from pose ``T0`` to pose ``T1`` (see the module docstring),
    solved at the times ``t`` (an int: that many samples, roboticstoolbox's steps).

    The poses asked for are roboticstoolbox's ``ctraj(T0, T1, t)`` (tested to 1e-9 on
    recorded numbers): the same time scaling, the progress ``s`` the trapezoidal
    profile :func:`~dhsym.trajectory.blends.lspb` from 0 to 1 with ``V = 1.5/t_f`` over
    the steps ``0, 1, …, t − 1`` (an int ``t``) or over ``[0, max t]``, and the same
    rotation (the shortest turn, as its quaternion slerp).

    Parameters
    ----------
    near
        The start configuration's neighbourhood: the first sample takes the solution
        nearest it (default: the first solution the IK lists).
    cache
        The robot's IK cache (``Robot.ctraj`` passes its own).
    max_step
        The largest change of any joint between two samples (radians or length) before
        the path stops as a jump of branch.
    singular
        Stop at the first sample whose solution is near a singular configuration.
    check
        What every solution must reach: ``"pose"``, or ``"position"`` for an arm without
        a wrist (the line of its tool point; the orientation follows the arm).
    """
    from dhsym.ik.choices import solve

    if isinstance(t, (int, np.integer)) and not isinstance(t, bool):
        if t < 2:
            raise DHError(f"t: at least two samples, got {t}")
        ts = np.arange(int(t), dtype=float)  # roboticstoolbox's steps
    else:
        ts = _times(t)
    A, B = (np.asarray(x, dtype=float) for x in (T0, T1))
    if A.shape != (4, 4) or B.shape != (4, 4):
        raise DHError(f"ctraj: T0 and T1 are 4×4 poses, got {A.shape} and {B.shape}")
    s = lspb(0, 1, float(ts[-1])).sample(ts)[0]
    poses = interpolate_poses(A, B, s)
    sol = solve(robot, poses, cache=cache, check=check)
    table = robot.table
    revolute = np.array([table.rows[r - 1].joint is JointType.REVOLUTE for r in table.joint_rows])
    qs: list[np.ndarray] = []
    res: list[float] = []
    reason = None
    for i in range(len(ts)):
        where = f"sample {i} (t = {ts[i]:g}, s = {s[i]:.6g})"
        ok = sol.valid[i]
        if not ok.any():
            why = sol.reason or "outside the workspace or at its boundary"
            reason = f"{where}: no solution ({why})"
            break
        cand = sol.q[i][ok]
        ref = (
            np.asarray(near if i == 0 else qs[-1], dtype=float) if (near is not None or i) else None
        )
        if ref is None:
            k = 0
        else:
            k = int(np.argmin(np.abs(_wrap(cand - ref, revolute)).max(axis=-1)))
        q = cand[k]
        if i:
            step = _wrap(q - qs[-1], revolute)
            if np.abs(step).max() > max_step:
                j = int(np.argmax(np.abs(step)))
                reason = (
                    f"{where}: joint {j + 1} would jump by {step[j]:.3g} "
                    f"(more than max_step = {max_step}): the branch is lost"
                )
                break
            q = qs[-1] + step  # continuous angles, no 2π jumps
        if singular and sol.near[i][ok][k].any():
            kinds = [f for f, hit in zip(sol.factor_kinds, sol.near[i][ok][k]) if hit]
            reason = f"{where}: near the {', '.join(kinds)} singularity"
            break
        qs.append(q)
        res.append(float(sol.residual[i][ok][k]))
    n = len(revolute)
    q_arr = np.array(qs).reshape(-1, n)
    stopped = None if reason is None else len(qs)
    return CartesianPath(ts, s, poses, q_arr, np.array(res), stopped, reason)
