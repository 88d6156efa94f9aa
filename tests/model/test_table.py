"""The table model from Python: values, conversion, validation."""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

import dhsym
from dhsym.model.table import (
    AngleUnit,
    Convention,
    DHRow,
    DHTable,
    JointType,
    as_expr,
    to_radians,
)

S = lambda n: sp.Symbol(n, real=True)  # noqa: E731


def test_rows_and_tables_are_frozen_values():
    r = DHRow.revolute("theta1", a="a1")
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.a = 1  # type: ignore[misc]
    assert r == DHRow.revolute("theta1", a="a1")
    t = DHTable.from_rows([r])
    assert hash(t) == hash(DHTable.from_rows([DHRow.revolute("theta1", a="a1")]))


def test_degree_conversion_is_exact():
    for deg, rad in [
        (90, sp.pi / 2),
        (180, sp.pi),
        (-90, -sp.pi / 2),
        (45, sp.pi / 4),
        (30.5, sp.Rational(61, 360) * sp.pi),
    ]:
        assert to_radians(as_expr(deg), "deg") == rad


def test_enums_parse_synonyms():
    assert Convention.parse("proximal") is Convention.MODIFIED
    assert Convention.parse("distal") is Convention.STANDARD
    assert AngleUnit.parse("radians") is AngleUnit.RAD
    assert JointType.parse("revolute") is JointType.REVOLUTE


def test_variable_inference_prefers_the_rows_own_name():
    t = DHTable.from_rows(
        [DHRow.revolute("theta1"), DHRow.revolute("theta2"), DHRow.prismatic("a5 + d3")]
    )
    assert t.variables == (S("theta1"), S("theta2"), S("d3"))
    assert t.constants == (S("a5"),)


def test_explicit_variable_must_be_in_its_column():
    with pytest.raises(dhsym.TableError, match="row 1, field d: joint variable x"):
        DHTable.from_rows([DHRow.prismatic("a + b", variable="x")])


def test_with_values_and_substituted():
    t = dhsym.planar_chain(2).with_values({"a1": 1, "a2": "1/2"})
    assert t.value_map[S("a2")] == sp.Rational(1, 2)
    sub = t.substituted()
    assert sub.rows[1].a == sp.Rational(1, 2) and sub.values == ()


def test_fixed_rows_have_no_variable():
    t = DHTable.from_rows([DHRow.revolute("q1"), DHRow.fixed(d="L")])
    assert t.variables == (S("q1"),)
    assert t.joint_rows == (1,)


def test_as_expr_refuses_non_numbers():
    for bad in (True, None, [1], {"a": 1}, float("nan"), float("inf")):
        with pytest.raises(dhsym.TableError):
            as_expr(bad)
