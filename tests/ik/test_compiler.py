"""The compiled IK solver: ``raw`` on one pose and on a batch."""

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError


def test_raw_takes_one_pose_as_a_batch_of_one():
    robot = dhsym.load("planar2r")
    solver = robot.inverse().solver()
    q = np.array([0.4, -0.7])
    T = np.asarray(robot.fk(q), dtype=float)
    one = solver.raw(T)
    batch = solver.raw(T[None])
    assert one.shape == batch.shape == (1, 2, 2)
    np.testing.assert_allclose(one, batch)
    assert any(np.allclose(branch, q) for branch in one[0])


def test_raw_names_the_shape_it_expects():
    solver = dhsym.load("planar2r").inverse().solver()
    with pytest.raises(DHError, match=r"\(N, 4, 4\) or one pose \(4, 4\), not \(3, 3\)"):
        solver.raw(np.eye(3))
