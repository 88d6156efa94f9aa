"""Poses as they come (issue 32): rounded poses are solved at their nearest rigid pose,
checked against the pose as given within a tolerance that follows its accuracy."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.ik.accuracy import FLOOR, nearest_rigid, pose_accuracy, written_decimals
from dhsym.ik.closed_form import ClosedForm
from dhsym.model.library import builtin_names

DATA = Path(__file__).resolve().parents[1] / "data" / "urdf"
#: every built-in arm of six joint variables (the 6R arms and the Stanford arm)
SIX = tuple(n for n in builtin_names() if len(dhsym.load(n).variables) == 6)
#: the URDF examples: the UR5 whole, the Panda with joint 7 given (its closed form)
URDF = {"ur5_robot.urdf": ("tool0", None), "panda.urdf": ("panda_hand", 7)}
#: the general 6R (one eigenproblem per pose) and the Panda (one pose per call, ``free``
#: takes one pose) take well over 10 s for 1,000 poses
SLOW = {"jaco", "panda.urdf"}
POSES = 1000


def _load(name: str) -> tuple[dhsym.Robot, int | None]:
    if name in URDF:
        tip, given = URDF[name]
        return dhsym.from_urdf(DATA / name, tip=tip), given
    return dhsym.load(name), None


def _configurations(robot: dhsym.Robot, count: int = POSES) -> tuple[np.ndarray, np.ndarray]:
    rev = np.array([r.joint.name == "REVOLUTE" for r in robot.table.rows if r.variable is not None])
    rng = np.random.default_rng(32)
    Q = rng.uniform(-np.pi, np.pi, (count, len(rev)))
    Q[:, ~rev] = rng.uniform(0.2, 1.0, (count, int((~rev).sum())))
    return Q, rev


CASES = [
    pytest.param(name, d, marks=[pytest.mark.slow] if name in SLOW else [])
    for name in (*SIX, *URDF)
    for d in (6, 4, 3)
]


@pytest.mark.parametrize(("name", "decimals"), CASES)
def test_every_rounded_pose_is_solved_and_its_branch_found(name: str, decimals: int) -> None:
    """1,000 poses reachable by construction (``fk`` of random joint values), rounded to
    ``decimals``: each gets a solution within its tolerance, and the joint values it came
    from are among the answers to the accuracy the rounding allows.

    That accuracy: rounding moves the pose by at most half a unit of the last decimal in
    each entry, so the joints by at most about ``3·half / σ_min(J)`` to first order (the
    smallest singular value of the Jacobian at the true joints); the bound is ten times
    that (second order near a singularity), at least 1e-6. Near a singularity it allows
    much (the joints there are ill-conditioned), elsewhere a few hundredths of a radian
    at 3 decimals and less than 1e-4 at 6."""
    robot, given = _load(name)
    Q, rev = _configurations(robot)
    T = robot.fk(Q)
    P = np.round(T, decimals)
    half = 0.5 * 10.0**-decimals
    if given is None:
        batch = robot.ik(P)  # the batch: one call for the 1,000 poses
        sols = [batch.solution(i) for i in range(len(P))]
        assert robot.ik(P, tol=1e-9).count.sum() == 0  # at 1e-9 nothing (issue 32)
        if isinstance(robot.inverse(), ClosedForm):
            # and one by one, as a single pose of a closed form is solved: the native
            # program with the rule around it where a C compiler is (robot.ik's own path
            # for the rest)
            sols += [robot.ik(pose) for pose in P]
    else:
        sols = [robot.ik(P[i], free={given: Q[i, given - 1]}) for i in range(len(P))]
    moving = [k for k in range(len(rev)) if k + 1 != given]
    missed = []
    for j, sol in enumerate(sols):
        i = j % len(P)
        tol = pose_accuracy(P[i]).tol
        assert FLOOR <= tol <= 2 * 3 * half  # the rule, within its bound
        if not len(sol):
            missed.append((i, sol.reason))
            continue
        # each residual is the largest entry error against the pose as given, within tol
        err = np.abs(robot.fk(sol.q)[:, :3] - P[i, :3]).reshape(len(sol), -1).max(axis=1)
        # (a single pose's residual is the one its program computes, with its own fk: the
        # same to rounding)
        atol = 1e-15 if j < len(P) or given is not None else 1e-13
        np.testing.assert_allclose(err, sol.residual, rtol=0, atol=atol)
        assert (sol.residual <= tol).all()
        d = sol.q - Q[i]
        d[:, rev] = (d[:, rev] + np.pi) % (2 * np.pi) - np.pi
        sigma = np.linalg.svd(robot.jacob0(Q[i])[:, moving], compute_uv=False)[-1]
        bound = max(10 * 3 * half / sigma, 1e-6)
        if np.abs(d).max(axis=1).min() > bound:
            missed.append((i, f"the branch of the true joints is missing (σ_min {sigma:.2g})"))
    assert not missed, missed


def test_the_ur5_pose_of_the_issue() -> None:
    r = dhsym.load("ur5")
    T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    sol = r.ik(np.round(T, 6))
    assert len(sol) == 8 and sol.reason is None
    assert (sol.residual <= 1e-6).all() and (sol.residual > 1e-9).any()
    # tol= overrides: at 1e-9 nothing, and the reason says why
    strict = r.ik(np.round(T, 6), tol=1e-9)
    assert len(strict) == 0 and "from a rigid pose" in str(strict.reason)


def test_an_exact_pose_is_solved_as_before() -> None:
    r = dhsym.load("puma560")
    T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    a, b = r.ik(T), r.ik(T, tol=1e-9)
    assert np.array_equal(a.q, b.q) and np.array_equal(a.residual, b.residual)
    batch = np.stack([T, np.round(T, 4)])
    sol = r.ik(batch)
    assert sol.count.tolist() == [8, 8]
    # in a batch with a rounded pose the exact one goes through the stretched program (its
    # roots clamped at 0): the same solutions, equal to rounding
    np.testing.assert_allclose(sol.solution(0).q, r.ik(batch[:1]).solution(0).q, atol=1e-12)


@pytest.mark.parametrize("decimals", [6, 3])
def test_an_unreachable_pose_has_no_solution_and_a_reason(decimals: int) -> None:
    r = dhsym.load("puma560")
    T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T[:3, 3] *= 10  # far outside the workspace
    sol = r.ik(np.round(T, decimals))
    assert len(sol) == 0 and "no real value of theta3" in str(sol.reason)
    assert "no real value of theta3" in str(r.ik(T).reason)  # the exact pose too


def test_written_decimals_and_the_nearest_rotation() -> None:
    r = dhsym.load("stanford")
    T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert written_decimals(T) is None and written_decimals(np.round(T, 3)) == 3
    R = nearest_rigid(np.round(T, 3))
    assert np.allclose(R[:3, :3].T @ R[:3, :3], np.eye(3), atol=1e-14)
    assert np.array_equal(R[:3, 3], np.round(T, 3)[:3, 3])
    eye = pose_accuracy(np.eye(4))
    assert eye.decimals == 0 and eye.tol == FLOOR and eye.exact


def test_written_decimals_is_the_least_k_np_round_keeps() -> None:
    """The decimals of a pose are the least k with np.round(T, k) == T, as np.round reads
    them (every k tried at once), on poses rounded to 0 … 13 decimals, scaled, and with NaN
    or inf entries; the tolerance is the same with the nearest rigid pose given or not."""

    def by_definition(T: np.ndarray) -> int | None:
        entries = T[:3].ravel()
        return next((k for k in range(13) if np.array_equal(np.round(entries, k), entries)), None)

    rng = np.random.default_rng(7)
    for _ in range(3000):
        T = rng.uniform(-5, 5, (4, 4)) * rng.choice([1e-3, 1.0, 1e3])
        d = int(rng.integers(0, 14))
        if d < 13:
            T = np.round(T, d)
        if rng.random() < 0.05:
            T[0, 0] = rng.choice([np.nan, np.inf])
        assert written_decimals(T) == by_definition(T)
    T = np.round(dhsym.load("puma560").fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1]), 4)
    assert pose_accuracy(T, nearest_rigid(T)) == pose_accuracy(T)


def test_the_jaco_pose_beside_a_singularity_rounded_to_3_decimals() -> None:
    # pose 479 of the 1,000 (σ_min(J) = 4.5e-4): its exact pose has two solutions 0.0084
    # rad apart, which the rounding to 3 decimals turns into a complex pair of eigenvalues;
    # Newton from their real part wanders 2.6 rad away (6e-3 from the pose), while the real
    # part itself is 4e-4 from it: the general 6R keeps it, between the two exact ones
    r = dhsym.load("jaco")
    q0 = [-1.4380847342990997, 1.3970927393409296, -3.0165028174341266]
    q0 += [-2.6347072642348155, -1.40819622523677, -0.8131605962334625]
    exact = r.ik(r.fk(q0))
    assert len(exact) == 2 and np.abs(exact.q[0] - exact.q[1]).max() > 0.008
    P = np.round(r.fk(q0), 3)
    sol = r.ik(P)
    assert len(sol) == 1 and sol.reason is None
    assert sol.residual[0] <= pose_accuracy(P).tol == 1e-3
    assert np.abs(sol.q[0] - q0).max() < 0.005
