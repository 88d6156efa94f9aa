"""Standard ↔ modified conversion keeps the tool pose; rigid transforms as exact words."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.cli.main import main
from dhsym.errors import TableError
from dhsym.geometry.conversion import (
    check_conversion,
    convert,
    rotation_word,
    to_modified,
    to_standard,
    transform_word,
)
from dhsym.kinematics.transforms import (
    Rx,
    Ry,
    Rz,
    Tx,
    Ty,
    Tz,
    chain_word,
    elementary_matrix,
    plain_product,
)
from dhsym.model.table import Convention, DHRow, DHTable, Elementary
from dhsym.model.tablefile import read_table
from dhsym.robot import Robot

pi = sp.pi


def max_fk_difference(a: DHTable, b: DHTable, samples: int = 25, seed: int = 1) -> float:
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, (samples, len(a.variables)))
    free = {s: 0.7 for s in a.constants if s not in a.value_map}  # e.g. a symbolic base step
    return float(np.max(np.abs(Robot(a).fk(q, values=free) - Robot(b).fk(q, values=free))))


@pytest.mark.parametrize("name", dhsym.builtin_names())
def test_round_trip_keeps_the_tool_pose_of_every_builtin_robot(name):
    table = dhsym.load_table(name)
    other = Convention.MODIFIED if table.convention is Convention.STANDARD else Convention.STANDARD
    there = convert(table, other)
    back = convert(there, table.convention)
    assert there.convention is other and back.convention is table.convention
    assert max_fk_difference(table, there) < 1e-12
    assert max_fk_difference(table, back) < 1e-12
    assert back == table  # Rx/Tx moved into base or tool come back into their row


def test_standard_to_modified_moves_each_twist_and_length_one_row_down():
    t = dhsym.load_table("example4_6dof")
    m = to_modified(t)
    assert [(r.alpha, r.a) for r in m.rows] == [(0, 0)] + [(r.alpha, r.a) for r in t.rows[:-1]]
    assert [(r.theta, r.d) for r in m.rows] == [(r.theta, r.d) for r in t.rows]
    assert m.tool == () and m.base == ()  # row 6 has a6 = 0 and alpha6 = 0


def test_modified_to_standard_puts_the_first_twist_into_the_base():
    rows = [DHRow.revolute("q1", alpha=pi / 2, a=2), DHRow.revolute("q2", a=3, alpha=pi)]
    m = DHTable.from_rows(rows, convention="modified")
    s = to_standard(m)
    assert s.base == (Elementary("R", "x", pi / 2), Elementary("T", "x", 2))
    assert [(r.a, r.alpha) for r in s.rows] == [(3, pi), (0, 0)]
    assert max_fk_difference(m, s) < 1e-12
    assert to_modified(s) == m


def test_conversion_of_a_table_in_the_target_convention_is_the_identity():
    t = dhsym.load_table("planar2r")
    assert convert(t, "standard") is t


def test_check_conversion_catches_a_different_robot():
    a = dhsym.load_table("planar2r")
    b = a.with_values({"a2": 0.5})
    with pytest.raises(TableError, match="differs by"):
        check_conversion(a, b)
    with pytest.raises(TableError, match="different joint variables"):
        check_conversion(a, dhsym.load_table("planar4r"))


_angles = st.sampled_from([0, 15, -30, 45, 90, -90, 120, 180]).map(lambda d: sp.pi * d / 180)
_lengths = st.sampled_from([0, 1, sp.Rational(1, 2), -2, sp.Rational(3, 10)])
_step_values = st.sampled_from([0, 1, -2, sp.pi / 2, sp.Symbol("b", real=True)])


@st.composite
def random_tables(draw):
    n = draw(st.integers(1, 4))
    rows = []
    for k in range(1, n + 1):
        theta, d, a, alpha = draw(_angles), draw(_lengths), draw(_lengths), draw(_angles)
        if draw(st.booleans()):
            rows.append(
                DHRow.revolute(sp.Symbol(f"q{k}", real=True) + theta, d=d, a=a, alpha=alpha)
            )
        else:
            rows.append(
                DHRow.prismatic(sp.Symbol(f"q{k}", real=True) + d, theta=theta, a=a, alpha=alpha)
            )
    axes = st.sampled_from("xxxyz")  # x steps often: they meet the row's own Rx, Tx
    elem = st.builds(Elementary, st.sampled_from("RT"), axes, _step_values)
    base = tuple(draw(st.lists(elem, max_size=3)))
    tool = tuple(draw(st.lists(elem, max_size=3)))
    convention = draw(st.sampled_from(["standard", "modified"]))
    return DHTable(tuple(rows), convention, base=base, tool=tool)


def word_pose(table: DHTable, q: np.ndarray) -> np.ndarray:
    """World → tool by multiplying the elementary matrices numerically (independent of fk)."""
    at = {**dict(zip(table.variables, q, strict=True)), sp.Symbol("b", real=True): 0.7}
    out = np.eye(4)
    for e in chain_word(table, -1, table.n + 1):
        out = out @ np.array(
            elementary_matrix(Elementary(e.kind, e.axis, e.value.subs(at))).evalf(), dtype=float
        )
    return out


@settings(max_examples=40, deadline=None)
@given(random_tables(), st.integers(0, 2**16))
def test_random_tables_keep_their_tool_pose_both_ways(table, seed):
    other = "modified" if table.convention is Convention.STANDARD else "standard"
    there = convert(table, other)
    back = convert(there, table.convention)
    assert there.convention.value == other and there.variables == table.variables
    for q in np.random.default_rng(seed).uniform(-np.pi, np.pi, (3, table.n)):
        q = [sp.Float(x) for x in q]
        reference = word_pose(table, q)
        assert np.max(np.abs(word_pose(there, q) - reference)) < 1e-12
        assert np.max(np.abs(word_pose(back, q) - reference)) < 1e-12
    assert back.rows[1:-1] == table.rows[1:-1]


def _zero_step_at_the_row_end(table: DHTable) -> bool:
    """True when the base (standard) ends / the tool (modified) starts with an explicit zero step
    ``Rx(0)`` or ``Tx(0)`` next to the row (a step that does nothing: the round trip drops it)."""
    word = list(reversed(table.base)) if table.convention is Convention.STANDARD else table.tool
    head = [e for e in word[:2] if e.axis == "x"]
    if head and head[0].kind == "R":
        head = head[:1]
    elif len(head) == 2 and head[1].kind != "R":
        head = head[:1]
    return any(e.value == 0 for e in head)


@settings(max_examples=150, deadline=None)
@given(random_tables())
def test_round_trip_gives_back_every_table_with_its_base_and_tool(table):
    """to_standard(to_modified(t)) == t and to_modified(to_standard(m)) == m, base and tool
    included (tool Tx with a zero last twist, base Rx with a zero first twist, ...)."""
    assume(not _zero_step_at_the_row_end(table))
    other = "modified" if table.convention is Convention.STANDARD else "standard"
    there = convert(table, other)
    back = convert(there, table.convention)
    assert back == table
    assert back.base == table.base and back.tool == table.tool  # the very same words
    # the pose of the converted table, by the elementary matrices in numbers (word_pose):
    # no closed form derived for each of the 150 random tables (Robot.fk's closed forms
    # are proven equal to this product by their own tests)
    for q in np.random.default_rng(1).uniform(-np.pi, np.pi, (3, table.n)):
        q = [sp.Float(x) for x in q]
        assert np.max(np.abs(word_pose(there, q) - word_pose(table, q))) < 1e-12


def test_round_trip_of_the_cases_that_used_to_move_into_a_row():
    q1, q2, t, b = sp.symbols("q1 q2 t b", real=True)
    # standard: a tool Tx with a2 = alpha2 = 0 used to come back as a2 = t
    std = DHTable((DHRow.revolute(q1, a=1), DHRow.revolute(q2)), tool=(Elementary("T", "x", t),))
    mod = to_modified(std)
    assert mod.tool == (Elementary("T", "x", 0), Elementary("T", "x", t))  # Tx(0) marks a2 = 0
    assert to_standard(mod) == std
    # modified: a base Rx with alpha0 = 0 used to come back as alpha0 = b
    m = DHTable((DHRow.revolute(q1), DHRow.revolute(q2, a=1)), "modified", base=(Rx_(b),))
    s = to_standard(m)
    assert s.base == (Rx_(b), Rx_(0)) and to_modified(s) == m
    assert max_fk_difference(m, s) < 1e-12 and max_fk_difference(std, mod) < 1e-12


def Rx_(angle: object) -> Elementary:
    return Elementary("R", "x", angle)


def test_an_explicit_zero_step_at_the_row_end_is_dropped_by_a_round_trip():
    std = DHTable((DHRow.revolute("q1", a=1),), base=(Elementary("T", "z", 1), Rx_(0)))
    back = to_standard(to_modified(std))
    assert back.base == (Elementary("T", "z", 1),) and back.rows == std.rows
    assert _zero_step_at_the_row_end(std)


@settings(max_examples=40, deadline=None)
@given(
    st.lists(st.tuples(st.sampled_from([Rx, Ry, Rz]), _angles), min_size=0, max_size=4),
    st.tuples(_lengths, _lengths, _lengths),
)
def test_transform_word_is_exact(rotations, p):
    T = Tx(p[0]) * Ty(p[1]) * Tz(p[2])
    for R, angle in rotations:
        T = T * R(angle)
    word = transform_word(T)
    assert len([e for e in word if e.kind == "R"]) <= 3
    assert sp.simplify(plain_product(word) - T) == sp.zeros(4)


def test_rotation_word_prefers_short_words():
    assert rotation_word((Rz(pi / 2) * Rx(pi / 2))[:3, :3]) == (
        Elementary("R", "z", pi / 2),
        Elementary("R", "x", pi / 2),
    )
    assert rotation_word(Ry(-pi / 3)[:3, :3]) == (Elementary("R", "y", -pi / 3),)
    gimbal = (Rz(pi / 4) * Ry(pi / 2) * Rx(pi / 3))[:3, :3]
    w = rotation_word(gimbal)
    assert sp.simplify(plain_product(w)[:3, :3] - gimbal) == sp.zeros(3)


def test_cli_convert_writes_a_yaml_table_with_the_same_tool_pose(tmp_path, capsys):
    out = tmp_path / "puma560_mod.yaml"
    assert main(["convert", "puma560", "--to", "modified", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert f"wrote {out}" in err and "tool pose agrees at 20 random configurations" in err
    written = read_table(out)
    assert written.convention is Convention.MODIFIED
    assert max_fk_difference(dhsym.load_table("puma560"), written) < 1e-12
    assert written.rows == to_modified(dhsym.load_table("puma560")).rows


def test_cli_convert_prints_yaml_and_reports_errors(capsys):
    assert main(["convert", "planar2r", "--to", "modified"]) == 0
    out = capsys.readouterr().out
    assert "convention: modified" in out and "tool: [{Tx: a2}]" in out
    assert main(["convert", "no_such_robot", "--to", "standard"]) == 2
    assert "dhsym: error: no built-in robot or table file" in capsys.readouterr().err
