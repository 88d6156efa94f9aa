"""Paths of an arm: ``jtraj`` against roboticstoolbox 1.5.0's recorded numbers, the
shortest rotation, and a straight line for the PUMA 560 solved by its closed-form IK."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.kinematics.rotations import rotation_exp, rotation_log
from dhsym.trajectory.paths import interpolate_poses, jtraj

from ._rtb_ctraj import RTB_CTRAJ

# roboticstoolbox.jtraj([0, 1, -0.5], [1, -1, 0.5], linspace(0, 3, 5))
RTB_JTRAJ = (
    [[0.0, 1.0, -0.5], [0.103515625, 0.79296875, -0.396484375], [0.5, 0.0, 0.0],
     [0.896484375, -0.79296875, 0.396484375], [1.0, -1.0, 0.5]],
    [[0.0, 0.0, 0.0], [0.3515625, -0.703125, 0.3515625], [0.625, -1.25, 0.625],
     [0.3515625, -0.703125, 0.3515625], [0.0, 0.0, 0.0]],
    [[0.0, 0.0, 0.0], [0.625, -1.25, 0.625], [0.0, 0.0, 0.0], [-0.625, 1.25, -0.625],
     [0.0, 0.0, 0.0]],
)  # fmt: skip


def test_jtraj_equals_roboticstoolbox() -> None:
    path = jtraj([0, 1, -0.5], [1, -1, 0.5], np.linspace(0, 3, 5))
    for got, want in zip((path.q, path.qd, path.qdd), RTB_JTRAJ):
        np.testing.assert_allclose(got, want, atol=1e-12)
    with pytest.raises(DHError, match="q0 has 2 values for 6 joints"):
        dhsym.load("puma560").jtraj([0, 0], [1, 1], 3)


def test_interpolated_rotation_is_the_shortest_turn() -> None:
    R1 = rotation_exp(np.array([0.0, 0.0, 2.0]))
    T1 = np.eye(4)
    T1[:3, :3] = R1
    mid = interpolate_poses(np.eye(4), T1, np.array([0.5]))[0, :3, :3]
    np.testing.assert_allclose(rotation_log(mid), [0, 0, 1.0], atol=1e-15)


@pytest.mark.slow
def test_puma_straight_line_stays_on_the_line() -> None:
    r = dhsym.load("puma560")
    qa = np.array([0.2, -0.6, 0.4, 0.3, 0.7, -0.2])
    qb = np.array([0.5, -0.3, 0.1, 0.1, 0.9, 0.3])
    A, B = r.fk(qa), r.fk(qb)
    path = r.ctraj(A, B, np.linspace(0, 2, 101), near=qa)
    assert path.complete, path.reason
    np.testing.assert_allclose(path.q[0], qa, atol=1e-9)
    np.testing.assert_allclose(path.q[-1], qb, atol=1e-9)
    T = r.fk(path.q)
    p, a, b = T[:, :3, 3], A[:3, 3], B[:3, 3]
    u = (b - a) / np.linalg.norm(b - a)
    off = (p - a) - ((p - a) @ u)[:, None] * u  # distance from the line
    assert np.abs(off).max() < 1e-9
    along = (p - a) @ u / np.linalg.norm(b - a)
    np.testing.assert_allclose(along, path.s, atol=1e-9)
    np.testing.assert_allclose(T[:, :3, :3], path.T[:, :3, :3], atol=1e-9)
    assert np.abs(np.diff(path.q, axis=0)).max() < 0.1  # one branch, no jumps


@pytest.mark.slow
def test_puma_line_out_of_reach_stops_with_the_sample() -> None:
    r = dhsym.load("puma560")
    q = np.array([0.2, -0.6, 0.4, 0.3, 0.7, -0.2])
    A = r.fk(q)
    B = A.copy()
    B[:3, 3] = A[:3, 3] + 3 * A[:3, 3] / np.linalg.norm(A[:3, 3])  # far out of reach
    path = r.ctraj(A, B, 201, near=q)
    assert not path.complete and 0 < path.stopped < 201
    assert path.reason.startswith(f"sample {path.stopped} (t = ")
    assert len(path.q) == path.stopped
    with pytest.raises(DHError, match="ctraj stopped: sample"):
        path.require()
    # without the jump and singularity stops: the first sample out of reach
    free = r.ctraj(A, B, 201, near=q, max_step=np.inf, singular=False)
    assert free.stopped >= path.stopped and "no solution" in free.reason
    reach = np.linalg.norm(free.T[:, :3, 3], axis=1)
    assert reach[free.stopped] > reach[free.stopped - 1]  # moving outwards, the last reachable


@pytest.mark.parametrize("case", sorted(RTB_CTRAJ))
def test_ctraj_poses_equal_roboticstoolbox(case: str) -> None:
    """The poses asked for along the line equal roboticstoolbox's ``ctraj`` to 1e-9: the
    same trapezoidal time scaling of the progress, the same shortest turn."""
    T0, T1, want, t = RTB_CTRAJ[case]
    times = np.linspace(0, 2, 9) if t == "linspace(0, 2, 9)" else t
    r = dhsym.load("puma560")
    path = r.ctraj(np.array(T0), np.array(T1), times, max_step=np.inf, singular=False)
    assert path.T.shape == (len(want), 4, 4)
    np.testing.assert_allclose(path.T, want, rtol=0, atol=1e-9)
    assert path.complete, path.reason
    np.testing.assert_allclose(r.fk(path.q), want, rtol=0, atol=1e-9)  # and solved


def test_ctraj_case_c_turns_the_short_way_by_nearly_a_half_turn() -> None:
    T0, T1, want, _ = RTB_CTRAJ["C"]
    R0, R1 = np.array(T0)[:3, :3], np.array(T1)[:3, :3]
    angle = np.linalg.norm(rotation_log(R0.T @ R1))
    assert 2.8 < angle < np.pi  # the case that tells the shortest turn from the long one
    steps = [
        np.linalg.norm(rotation_log(np.array(a)[:3, :3].T @ np.array(b)[:3, :3]))
        for a, b in zip(want[:-1], want[1:])
    ]
    assert abs(sum(steps) - angle) < 1e-9  # roboticstoolbox's path turns by that angle only
