"""Numbers come from the symbolic result: they agree with it, and batch equals single."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import dhsym
from dhsym.kinematics.numeric import compile_pose

from ..strategies import dh_tables

FAST = settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _values(table):
    return {s: sp.Rational(k + 2, 7) for k, s in enumerate(table.constants)}


@FAST
@given(dh_tables(max_rows=5), st.data())
def test_numeric_equals_symbolic(table, data):
    robot = dhsym.Robot(table)
    vals = _values(table)
    f = robot.fk_function(values=vals)
    q = data.draw(arrays(float, len(table.variables), elements=st.floats(-3, 3)))
    subs = {**vals, **dict(zip(table.variables, q))}
    expected = np.array(robot.plain_transform(0, table.n).evalf(subs=subs), dtype=float)
    np.testing.assert_allclose(f(q), expected, atol=1e-10)


@FAST
@given(dh_tables(max_rows=5), st.integers(1, 40), st.data())
def test_batch_equals_single(table, N, data):
    robot = dhsym.Robot(table)
    f = robot.fk_function(values=_values(table))
    Q = data.draw(arrays(float, (N, len(table.variables)), elements=st.floats(-3, 3)))
    batch = f(Q)
    assert batch.shape == (N, 4, 4)
    for k in range(N):
        np.testing.assert_allclose(batch[k], f(Q[k]), atol=1e-12)


def test_compiled_function_is_cached_per_robot_and_values():
    robot = dhsym.load("puma560")
    assert robot.fk_function() is robot.fk_function()
    assert robot.fk_function(values={"a2": 1}) is not robot.fk_function()


def test_wrong_number_of_joint_values():
    robot = dhsym.load("planar2r")
    with pytest.raises(dhsym.DHError, match="expected 2 joint values"):
        robot.fk([1, 2, 3])


def test_constant_entries_broadcast_in_batches():
    q1 = sp.Symbol("q1", real=True)
    f = compile_pose(sp.ImmutableMatrix(sp.eye(4)).row_insert(0, sp.zeros(0, 4)), (q1,))
    out = f(np.zeros((3, 1)))
    np.testing.assert_array_equal(out, np.broadcast_to(np.eye(4), (3, 4, 4)))
