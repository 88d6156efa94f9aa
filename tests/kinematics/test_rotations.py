"""The one numeric exponential and logarithm of rotations: inverse of each other at every
angle (0, tiny, generic, near π and π), accurate where ``arccos`` of the trace is not,
and the copy the straight-line paths and the numeric IK share."""

from __future__ import annotations

import numpy as np
import pytest

from dhsym.kinematics.rotations import rotation_exp, rotation_log


def _axes(rng: np.random.Generator, n: int) -> np.ndarray:
    axes = rng.normal(size=(n, 3))
    return axes / np.linalg.norm(axes, axis=1, keepdims=True)


@pytest.mark.parametrize(
    ("low", "high", "tol"),
    [
        (0.0, np.pi - 1e-3, 1e-12),  # generic angles
        (1e-12, 1e-3, 1e-15),  # small: arccos of the trace loses half the digits here
        (np.pi - 1e-3, np.pi - 1e-12, 1e-9),  # near a half turn
    ],
    ids=["generic", "small", "near-pi"],
)
def test_log_recovers_the_rotation_vector(low: float, high: float, tol: float) -> None:
    rng = np.random.default_rng(7)
    w = _axes(rng, 2000) * rng.uniform(low, high, 2000)[:, None]
    R = rotation_exp(w)
    np.testing.assert_allclose(rotation_log(R), w, rtol=0, atol=tol)
    np.testing.assert_allclose(rotation_exp(rotation_log(R)), R, rtol=0, atol=tol)


def test_the_ends_and_the_shapes() -> None:
    np.testing.assert_array_equal(rotation_log(np.eye(3)), np.zeros(3))
    half = rotation_log(np.diag([-1.0, 1.0, -1.0]))  # a half turn about y
    np.testing.assert_allclose(np.abs(half), [0.0, np.pi, 0.0], atol=1e-15)
    # the rotation at π about a general axis: either sign of the axis is the same turn
    axis = np.array([1.0, 2.0, -2.0]) / 3
    R = 2 * np.outer(axis, axis) - np.eye(3)
    w = rotation_log(R)
    assert abs(np.linalg.norm(w) - np.pi) < 1e-15
    np.testing.assert_allclose(rotation_exp(w), R, atol=1e-15)
    batch = rotation_exp(np.zeros((4, 5, 3)))
    assert batch.shape == (4, 5, 3, 3) and rotation_log(batch).shape == (4, 5, 3)
    assert rotation_log(np.eye(3)).shape == (3,)


def test_numeric_ik_measures_its_orientation_error_by_it() -> None:
    from dhsym.ik.levenberg_marquardt import _rotation_error

    rng = np.random.default_rng(8)
    R, goal = rotation_exp(_axes(rng, 2) * [[0.4], [2.0]])
    np.testing.assert_array_equal(_rotation_error(R, goal), rotation_log(goal @ R.T))
    # the error turns R into the goal
    np.testing.assert_allclose(rotation_exp(_rotation_error(R, goal)) @ R, goal, atol=1e-15)
