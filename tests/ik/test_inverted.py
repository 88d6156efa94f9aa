"""The chain read backwards, and roboticstoolbox's six-joint models."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.ik import classify
from dhsym.ik.inverted import reversed_table

DATA = Path(__file__).parents[1] / "data" / "rtb"


def _random_q(robot: dhsym.Robot, n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(-np.pi, np.pi, (n, len(robot.variables)))


def _recovered(robot: dhsym.Robot, q: np.ndarray, **kw: object) -> np.ndarray:
    """For each row of q: True when a solution of ik(fk(q)) equals it modulo 2π."""
    batch = robot.ik(robot.fk(q), **kw)
    d = batch.q - q[:, None, :]
    d = np.abs(np.angle(np.exp(1j * d)))  # angle differences modulo 2π
    return np.nan_to_num(d, nan=np.inf).max(axis=-1).min(axis=-1) < 1e-7


@pytest.mark.slow
def test_a_chain_whose_first_three_axes_meet_is_solved_backwards() -> None:
    puma = dhsym.load("puma560")
    back = dhsym.Robot(reversed_table(puma.table))
    assert classify(back).family == "inverted chain"
    ik = back.inverse()
    assert ik.family == "inverted chain" and ik.count == 8
    q = _random_q(back, 1000, seed=2)
    assert _recovered(back, q).mean() > 0.999
    # and the reversed chain's pose is the inverse of the arm's
    qa = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert np.allclose(back.fk(-qa[::-1]), np.linalg.inv(puma.fk(qa)))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["irb140", "kr5", "puma560", "ur3", "ur5", "ur10"])
def test_roboticstoolbox_six_joint_models_are_solved(name: str) -> None:
    r = dhsym.load(DATA / f"{name}.yaml")
    q = _random_q(r, 200, seed=3)
    assert _recovered(r, q).mean() > 0.99


@pytest.mark.slow
def test_axes_3_4_5_parallel_are_solved_backwards_as_a_ur() -> None:
    back = dhsym.Robot(reversed_table(dhsym.load("ur5").table))
    assert str(classify(back)) == "axes 3, 4, 5 parallel"
    ik = back.inverse()
    assert ik.family == "inverted chain" and "three parallel axes" in ik.structure
    q = _random_q(back, 1000, seed=6)
    assert _recovered(back, q).all()
