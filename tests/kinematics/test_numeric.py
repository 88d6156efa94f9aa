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


# --- compiled code: floats only, evaluated in chunks ---------------------------------------


def test_compiled_code_sees_floats_only():
    from dhsym.kinematics.numeric import compile_exprs, float_constants

    x = sp.Symbol("x", real=True)
    huge = sp.sqrt(sp.Integer(10) ** 40 + 1)  # numpy's sqrt fails on Python ints > 2**63
    e = huge * x / 10**20 + sp.Rational(1, 3) * sp.cos(x + sp.sqrt(2))
    folded = float_constants(e)
    assert all(a.is_Float or (a.is_Integer and abs(a) < 2**53) for a in folded.atoms(sp.Number))
    for fn in (compile_exprs([e], [x]), compile_exprs([e], [x], floats=True)):
        assert float(np.asarray(fn(0.5)[0])) == pytest.approx(0.5 + np.cos(0.5 + 2**0.5) / 3)


def test_one_configuration_takes_the_float_path_and_equals_the_batch():
    robot = dhsym.load("puma560")
    f = robot.fk_function()
    q = [0.1, -0.4, 0.3, 1.2, -0.5, 2.0]
    batch = f.batch(np.array([q, q]))
    for single in (f(q), f(tuple(q)), f(np.array(q)), robot.fk(q), f([int(x) for x in q])):
        assert single.shape == (4, 4) and single.dtype == float
    np.testing.assert_allclose(f(q), batch[0], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(f(np.array(q)), f(q))


def test_printed_poses_have_no_negative_zeros():
    for q in ([0.0] * 6, [-0.0] * 6):
        single, batch = dhsym.load("puma560").fk(q), dhsym.load("puma560").fk([q])
        assert not np.signbit(single[single == 0]).any()
        assert not np.signbit(batch[batch == 0]).any()


def test_non_finite_joint_values_behave_like_numpy():
    f = dhsym.load("planar2r").fk_function()
    with np.errstate(invalid="ignore"):
        out = f([np.inf, 0.0])
        assert np.isnan(out[0, 0]) and out[3, 3] == 1.0
        assert np.isnan(f([np.nan, 0.0])[0, 3])


def test_the_cache_is_keyed_by_what_changes():
    robot = dhsym.load("puma560")
    assert robot.fk_function(values={"a2": 1}) is robot.fk_function(values={"a2": 1})
    assert robot.fk_function(0, 3) is robot.fk_function(0, 3)
    assert robot.fk_function(0, 3) is not robot.fk_function(0, 4)
    q = [0.1] * 6
    np.testing.assert_allclose(
        robot.fk(q, values={"a2": 1.0})[:3, 3], robot.fk_function(values={"a2": 1})(q)[:3, 3]
    )


def test_compile_word_multiplies_elementaries_numerically():
    from dhsym.kinematics.numeric import compile_word
    from dhsym.kinematics.transforms import chain_word

    robot = dhsym.load("stanford")
    word = chain_word(robot.table, -1, robot.n + 1)
    f = compile_word(word, robot.variables, robot.table.value_map)
    Q = np.random.default_rng(0).uniform(-1, 1, (7, robot.n))
    np.testing.assert_allclose(f(Q), robot.fk(Q), atol=1e-12)
    np.testing.assert_allclose(f(Q[0]), robot.fk(Q[0]), atol=1e-12)
    prefixes = compile_word(word, robot.variables, robot.table.value_map, prefixes=True)(Q)
    assert prefixes.shape == (7, len(word) + 1, 4, 4)
    np.testing.assert_allclose(prefixes[:, -1], f(Q))
    np.testing.assert_array_equal(prefixes[:, 0], np.broadcast_to(np.eye(4), (7, 4, 4)))


def test_chunked_evaluation_equals_one_pass_at_every_chunk_size():
    from dhsym.kinematics.numeric import compile_exprs, evaluate_chunked

    x, y = sp.symbols("x y", real=True)
    f = compile_exprs([x * y, sp.cos(x) - y, sp.Integer(3)], (x, y))
    rng = np.random.default_rng(2)
    X, Y = rng.uniform(-2, 2, (11, 1)), rng.uniform(-2, 2, (11, 1))
    whole = evaluate_chunked(f, X, Y, out=np.empty((11, 3)), chunk=11)
    np.testing.assert_array_equal(whole[:, 2], 3.0)  # a constant is broadcast
    np.testing.assert_allclose(whole[:, 0], (X * Y)[:, 0], rtol=0, atol=0)
    for chunk in (1, 2, 4, 10, 12):
        np.testing.assert_array_equal(
            evaluate_chunked(f, X, Y, out=np.empty((11, 3)), chunk=chunk), whole
        )
    assert evaluate_chunked(f, X[:0], Y[:0], out=np.empty((0, 3))).shape == (0, 3)
    with pytest.raises(ValueError, match="11 points expected"):
        evaluate_chunked(f, X, Y[:5], out=np.empty((11, 3)))


def test_chunked_evaluation_fills_a_view_and_drops_negative_zeros():
    from dhsym.kinematics.numeric import compile_exprs, evaluate_chunked

    x = sp.Symbol("x", real=True)
    f = compile_exprs([-x, 2 * x], (x,))
    poses = np.full((5, 3), 7.0)
    out = evaluate_chunked(f, np.zeros((5, 1)), out=poses[:, :2], chunk=2, plus_zero=True)
    assert out.base is poses and not np.signbit(poses[:, :2]).any()
    np.testing.assert_array_equal(poses[:, 2], 7.0)  # the rest of the rows untouched
    assert np.signbit(evaluate_chunked(f, np.zeros((5, 1)), out=np.empty((5, 2)))[:, 0]).all()


def test_batches_longer_than_a_chunk_equal_their_configurations():
    from dhsym.kinematics.numeric import CHUNK

    robot = dhsym.load("stanford")
    Q = np.random.default_rng(4).uniform(-1, 1, (CHUNK + 3, robot.n))
    poses, jacobians = robot.fk(Q), robot.jacob0(Q)
    for k in (0, CHUNK - 1, CHUNK, CHUNK + 2):
        np.testing.assert_allclose(poses[k], robot.fk(Q[k]), rtol=0, atol=1e-15)
        np.testing.assert_array_equal(jacobians[k], robot.jacob0(Q[k]))
