"""The chain read backwards, and roboticstoolbox's six-joint models."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.ik import classify
from dhsym.ik.inverted import reversed_table

from ._roundtrip import DATA, random_q, recovered


@pytest.mark.slow
def test_a_chain_whose_first_three_axes_meet_is_solved_backwards() -> None:
    puma = dhsym.load("puma560")
    back = dhsym.Robot(reversed_table(puma.table))
    assert classify(back).family == "inverted chain"
    ik = back.inverse()
    assert ik.family == "inverted chain" and ik.count == 8
    q = random_q(back, 1000, seed=2)
    assert recovered(back, q).mean() > 0.999
    # and the reversed chain's pose is the inverse of the arm's
    qa = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert np.allclose(back.fk(-qa[::-1]), np.linalg.inv(puma.fk(qa)))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["irb140", "kr5", "puma560", "ur3", "ur5", "ur10"])
def test_roboticstoolbox_six_joint_models_are_solved(name: str) -> None:
    r = dhsym.load(DATA / f"{name}.yaml")
    q = random_q(r, 200, seed=3)
    assert recovered(r, q).mean() > 0.99


@pytest.mark.slow
def test_axes_3_4_5_parallel_are_solved_backwards_as_a_ur() -> None:
    back = dhsym.Robot(reversed_table(dhsym.load("ur5").table))
    assert str(classify(back)) == "axes 3, 4, 5 parallel"
    ik = back.inverse()
    assert ik.family == "inverted chain" and "three parallel axes" in ik.structure
    q = random_q(back, 1000, seed=6)
    assert recovered(back, q).all()
