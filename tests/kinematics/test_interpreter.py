"""The tree walker: one-off expressions at many points agree entry by entry."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import dhsym
from dhsym.kinematics.interpreter import EvaluationError, evaluate, evaluate_many

from ..strategies import dh_tables


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(table=dh_tables(max_rows=3), data=st.data())
def test_evaluate_many_agrees_with_evaluate_entry_by_entry(table, data):
    """The matrix walk (one memo, all entries) gives each entry's own walk, to the bit."""
    robot = dhsym.Robot(table)
    M = robot.transform(0, table.n).matrix
    syms = sorted(M.free_symbols, key=sp.default_sort_key)
    size = data.draw(st.integers(1, 8))
    env = {s: np.asarray(data.draw(arrays(float, size, elements=st.floats(-3, 3)))) for s in syms}
    many = evaluate_many(list(M), env, size)
    one = np.array([evaluate(e, env, size) for e in M])
    assert many.shape == (16, size)
    np.testing.assert_array_equal(many, one)


@pytest.mark.parametrize(
    ("expr", "message"),
    [
        (sp.Symbol("y") + sp.Symbol("x"), "no value for symbol y"),
        (sp.gamma(sp.Symbol("x")), "cannot evaluate gamma"),
        (sp.Symbol("x") + sp.zoo, "not a real number"),
    ],
)
def test_what_has_no_value_is_an_evaluation_error(expr: sp.Basic, message: str) -> None:
    with pytest.raises(EvaluationError, match=message) as err:
        evaluate(expr, {sp.Symbol("x"): np.array([0.5, 1.0])}, 2)
    assert isinstance(err.value, dhsym.DHError) and isinstance(err.value, ValueError)
