"""The compiled closed-form solver: ``raw`` on one pose and on a batch, branch names."""

import re

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.ik.closed_form_solver import ClosedFormSolver


def test_raw_takes_one_pose_as_a_batch_of_one():
    robot = dhsym.load("planar2r")
    solver = robot.ik_cache().solver()
    q = np.array([0.4, -0.7])
    T = np.asarray(robot.fk(q), dtype=float)
    one = solver.raw(T)
    batch = solver.raw(T[None])
    assert one.shape == batch.shape == (1, 2, 2)
    np.testing.assert_allclose(one, batch)
    assert any(np.allclose(branch, q) for branch in one[0])


def test_raw_names_the_shape_it_expects():
    solver = dhsym.load("planar2r").ik_cache().solver()
    with pytest.raises(DHError, match=r"\(N, 4, 4\) or one pose \(4, 4\), not \(3, 3\)"):
        solver.raw(np.eye(3))


def test_the_programs_are_built_on_first_use_and_kept():
    from dataclasses import replace

    import dhsym

    # a table of its own: equal tables share what they derived (dhsym.cache.memo)
    r = dhsym.Robot(replace(dhsym.load("planar2r").table, name="first use"))
    solver = ClosedFormSolver(r.inverse(), r.table.value_map)
    assert solver._programs.checked is None and solver._programs.raw is None
    solver.solve(r.fk([[0.4, 0.9], [0.1, -0.3]]), check="position")
    built = solver._programs.checked
    assert built is not None and solver._program("checked") is built
    assert solver._programs.raw is None  # only what was asked for


@pytest.mark.parametrize("name", ["puma560", "ur5"])
def test_an_unreachable_pose_says_how_far_and_how_far_the_arm_reaches(name) -> None:
    # issue 32, item 2: the reason in the robot's words, with distances
    r = dhsym.load(name)
    T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T[:3, 3] *= 5
    sol = r.ik(T)
    assert len(sol) == 0
    m = re.search(
        r"the wrist centre is ([\d.]+) from the origin of frame 0; this arm "
        r"reaches at most about ([\d.]+)",
        sol.reason,
    )
    assert m is not None, sol.reason
    away, reach = float(m[1]), float(m[2])
    assert away > reach
    # the reach is the farthest wrist centre: a stretched arm comes close to it from below
    dec = r.inverse().decoupling
    centre = r.fk_function(0, dec.centre)
    q = np.random.default_rng(3).uniform(-np.pi, np.pi, (2000, 6))
    assert np.linalg.norm(centre(q)[:, :3, 3], axis=1).max() <= reach * 1.001
