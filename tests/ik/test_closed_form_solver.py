"""The compiled closed-form solver: ``raw`` on one pose and on a batch, branch names."""

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
