"""Valid alternative tables of the PUMA 560 and the Stanford arm; where wrong tables diverge."""

from __future__ import annotations

from dataclasses import replace

import pytest
import sympy as sp

from dhsym import load_table
from dhsym.checking.comparing.table_match import (
    Chain,
    KeyFrames,
    RowVerdicts,
    compare_tables,
    same_cells,
)
from dhsym.model.table import DHTable

pi = sp.pi
PUMA, STANFORD = load_table("puma560"), load_table("stanford")


def table(key: DHTable, rows) -> DHTable:
    return DHTable(tuple(rows), key.convention, values=key.values)


def reverse_z(key: DHTable, k: int) -> list:
    """Reverse z_k (the axis of joint k+1, standard): α_k += π; row k+1 variable, d and α flip."""
    rows = list(key.rows)
    rows[k - 1] = replace(rows[k - 1], alpha=rows[k - 1].alpha + pi - 2 * pi)
    nxt = rows[k]
    own = nxt.variable_field
    rows[k] = replace(
        nxt,
        d=-nxt.d if own != "d" else -nxt.d,
        alpha=nxt.alpha + pi,
        **({"theta": -nxt.theta} if own == "theta" else {"theta": -nxt.theta}),
    )
    return rows


def shift_d(key: DHTable, k: int, t: sp.Expr) -> list:
    """Move origin k along z_k when z_k ∥ z_{k+1}: d_k += t, d_{k+1} -= t."""
    rows = list(key.rows)
    rows[k - 1] = replace(rows[k - 1], d=rows[k - 1].d + t)
    rows[k] = replace(rows[k], d=rows[k].d - t)
    return rows


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_puma_with_a_reversed_z_axis_is_a_valid_alternative(k):
    m = compare_tables(PUMA, table(PUMA, reverse_z(PUMA, k)))
    assert m.same_robot and not m.same_table
    assert m.reversed_joints == (k + 1,)
    assert any(f"z{k} reversed" in d for d in m.differences)


def test_puma_other_common_normal_x0_and_frame0_freedoms():
    m = compare_tables(PUMA, table(PUMA, shift_d(PUMA, 2, sp.Rational(1, 10))))
    assert (
        m.same_robot
        and "origin of frame 2 moved by 0.1 along z2 (another common normal)" in m.differences
    )
    rows = list(PUMA.rows)
    rows[0] = replace(rows[0], theta=rows[0].theta - pi / 2)
    m = compare_tables(PUMA, table(PUMA, rows))
    assert m.same_robot and m.differences == ("x0 rotated by 90° about z0",)
    rows = list(PUMA.rows)
    rows[0] = replace(rows[0], d=sp.Rational(67, 100))
    m = compare_tables(PUMA, table(PUMA, rows))
    assert m.same_robot and "frame 0 moved by -0.67 along z0" in m.differences
    rows = [replace(PUMA.rows[0], theta=-PUMA.rows[0].variable, alpha=-pi / 2), *PUMA.rows[1:]]
    m = compare_tables(PUMA, table(PUMA, rows))
    assert m.same_robot and m.reversed_joints == (1,)


def test_puma_combined_freedoms():
    rows = shift_d(PUMA, 2, sp.Rational(1, 20))  # then z1 reversed, then x0 turned
    rows = reverse_z(table(PUMA, rows), 1)
    rows[0] = replace(rows[0], theta=rows[0].theta + pi)
    m = compare_tables(PUMA, table(PUMA, rows))
    assert m.same_robot and len(m.differences) == 3


@pytest.mark.parametrize("k", [1, 2, 4, 5])
def test_stanford_reversed_axes_are_valid_alternatives(k):
    m = compare_tables(STANFORD, table(STANFORD, reverse_z(STANFORD, k)))
    assert m.same_robot and m.reversed_joints == (k + 1,)


def test_stanford_prismatic_axis_reversed_and_d_shift():
    rows = list(STANFORD.rows)
    rows[1] = replace(rows[1], alpha=rows[1].alpha - pi)
    rows[2] = replace(rows[2], d=-rows[2].variable, alpha=rows[2].alpha + pi)
    m = compare_tables(STANFORD, table(STANFORD, rows))
    assert m.same_robot and m.reversed_joints == (3,)
    m = compare_tables(STANFORD, table(STANFORD, shift_d(STANFORD, 3, sp.Rational(1, 5))))
    assert m.same_robot and any("frame 3" in d for d in m.differences)


def test_tool_frame_is_fixed_unless_the_question_frees_it():
    rows = list(PUMA.rows)
    rows[5] = replace(rows[5], d=sp.Rational(56, 1000))
    m = compare_tables(PUMA, table(PUMA, rows))
    assert not m.same_robot and m.tool_differs and m.diverges_at == 7
    m = compare_tables(PUMA, table(PUMA, rows), tool_free=True)
    assert m.same_robot and m.tool_differs


@pytest.mark.parametrize(
    ("row", "change", "joint"),
    [(2, {"a": sp.Rational(1, 2)}, 3), (1, {"alpha": 0}, 2), (4, {"d": 0}, 5)],
)
def test_first_joint_where_the_geometry_diverges(row, change, joint):
    rows = list(PUMA.rows)
    rows[row - 1] = replace(rows[row - 1], **change)
    m = compare_tables(PUMA, DHTable(tuple(rows), PUMA.convention))
    assert not m.same_robot and m.diverges_at == joint
    assert f"check row {row}" in m.reason


def test_joint_count_and_kinds():
    short = DHTable(PUMA.rows[:5], PUMA.convention)
    assert compare_tables(PUMA, short).reason == "the table has 5 joints; the robot has 6"
    rows = list(STANFORD.rows)
    rows[2] = replace(rows[2], joint="R", theta=sp.Symbol("q3", real=True), d=0, variable=None)
    m = compare_tables(STANFORD, DHTable(tuple(rows), STANFORD.convention))
    assert m.diverges_at == 3 and "prismatic" in m.reason


def test_same_cells_ignores_variable_names_and_full_turns():
    rows = [
        replace(r, theta=sp.Symbol(f"q{k}", real=True), variable=None)
        for k, r in enumerate(PUMA.rows, 1)
    ]
    assert same_cells(PUMA, DHTable(tuple(rows), PUMA.convention), PUMA.value_map)
    assert not same_cells(PUMA, Chain(PUMA.rows[:5], PUMA.convention))


def test_same_cells_evaluates_what_might_have_no_value():
    """A cell that is the same in both tables is taken as equal only when it has a value:
    one that uses another row's joint variable, or one without a real value, still fails
    (as when each cell was evaluated)."""
    t = load_table("planar2r")
    r1, r2 = t.rows
    other = Chain((replace(r1, d=r2.variable), r2), t.convention)
    assert not same_cells(other, other)
    a1 = next(s for s in t.constants if s.name == "a1")
    no_value = Chain((replace(r1, d=sp.sqrt(-(a1**2) - 1)), r2), t.convention)
    assert not same_cells(no_value, no_value)
    assert same_cells(t, t) and same_cells(Chain.of(t), t)


def test_same_cells_still_finds_the_one_changed_cell():
    t = load_table("planar2r")
    r1, r2 = t.rows
    for row in (
        replace(r2, a=-r2.a),
        replace(r2, alpha=r2.alpha + sp.pi),
        replace(r2, theta=r2.theta + sp.pi / 2),
    ):
        assert not same_cells(t, Chain((r1, row), t.convention))
    full_turn = replace(r2, theta=r2.theta + 2 * sp.pi)
    assert same_cells(t, Chain((r1, full_turn), t.convention))


def _match_fields(m):
    return (m.same_robot, m.same_table, m.diverges_at, m.differences, m.reason, m.tool_differs)


@pytest.mark.parametrize("values", ["own", "none"])
def test_key_frames_prepared_once_give_the_same_match(values):
    """The key's frames computed once (KeyFrames) are the frames computed per answer:
    every kind of answer gets the same match with them as without them."""
    given = PUMA.value_map if values == "own" else {}
    frames = KeyFrames.of(PUMA)
    assert frames.get(given, 11) is not None and frames.get(given, 12) is None
    wrong = list(PUMA.rows)
    wrong[2] = replace(wrong[2], a=sp.Rational(1, 2))
    answers = [
        table(PUMA, reverse_z(PUMA, 2)),
        table(PUMA, shift_d(PUMA, 2, sp.Rational(1, 10))),
        DHTable(tuple(wrong), PUMA.convention),
    ]
    for answer in answers:
        plain = compare_tables(PUMA, answer, values=given)
        once = compare_tables(PUMA, answer, values=given, key_frames=frames)
        assert _match_fields(once) == _match_fields(plain)
    other = {**PUMA.value_map, next(iter(PUMA.value_map)): sp.Integer(7)}
    assert frames.get(other, 11) is None  # other numbers: computed per answer as before


def _variants(key):
    """The key's rows under every slip of the pair search and every pair of them: what a
    table's diagnosis compares an answer with, many variants sharing most rows."""
    from dhsym.checking.mistakes.registry import TABLE_PAIR_MISTAKES

    base = tuple(key.rows)
    out = []
    for a in TABLE_PAIR_MISTAKES:
        for rows_a, _, _ in a.table_edits(base, key):
            out.append(rows_a)
            for b in TABLE_PAIR_MISTAKES:
                out.extend(rows_b for rows_b, _, _ in b.table_edits(rows_a, key))
    return out


@pytest.mark.parametrize("name", ["puma560", "stanford", "puma560_modified"])
def test_row_verdicts_give_the_verdicts_of_same_cells(name):
    """Rows judged once for one answer (RowVerdicts) give, variant after variant, the
    verdict same_cells gives each variant alone, for answers right, wrong in one cell,
    written in numbers, and under a slip (some variants equal them)."""
    key = load_table(name)
    variants = _variants(key)
    rows = list(key.rows)
    rows[1] = replace(rows[1], a=rows[2].a if rows[2].a != 0 else sp.Rational(1, 3))
    answers = [key, DHTable(tuple(rows), key.convention), key.with_values(key.value_map)]
    answers += [Chain(variants[k], key.convention) for k in (0, len(variants) // 2, -1)]
    agreed = 0
    for answer in answers:
        values = key.value_map
        memo = RowVerdicts(answer, values)
        for rows_v in variants:
            chain = Chain(rows_v, key.convention)
            plain = same_cells(chain, answer, values)
            assert same_cells(chain, answer, values, verdicts=memo) == plain
            agreed += plain
        assert 0 < len(memo) <= 4 * key.n * len(variants)
    assert agreed >= 3  # each variant answer meets itself


def test_row_verdicts_keep_no_row_that_depends_on_other_rows():
    """A cell holding another row's joint variable is judged with both tables' constants:
    that row's verdict is not kept (another variant may change which symbols those are),
    and a memo made for another answer or another values map is not used."""
    t = load_table("planar2r")
    r1, r2 = t.rows
    other = Chain((replace(r1, d=r2.variable), r2), t.convention)
    memo = RowVerdicts(other, {})
    assert same_cells(other, other, {}, verdicts=memo) == same_cells(other, other, {})
    assert len(memo) == 0
    values = t.value_map
    memo = RowVerdicts(t, values)
    assert same_cells(t, t, values, verdicts=memo) and len(memo) == 2
    wrong = Chain((r1, replace(r2, a=-r2.a)), t.convention)
    assert not same_cells(wrong, t, values, verdicts=memo) and len(memo) == 3
    assert not memo.serves(Chain.of(t), values, 3) and not memo.serves(t, dict(values), 3)
    assert not memo.serves(t, values, 4)


def test_signed_frames_are_the_frames_of_each_sign_pattern():
    """The answer's frames per sign pattern, each row computed once per signs of the
    variables in its cells, are those frames() computes for that pattern, also when a
    row names another row's variable (a student's wrong table)."""
    import itertools

    import numpy as np

    from dhsym.checking.comparing.sampled_frames import frames
    from dhsym.checking.comparing.table_match import (
        Chain,
        _configurations,
        _constant_env,
        _joints,
        _signed_frames,
    )

    q1, q2 = PUMA.variables[:2]
    rows = list(PUMA.rows)
    rows[2] = replace(rows[2], theta=rows[2].theta + q2, d=rows[2].d + q1)  # rows 1, 2 named
    chain = Chain(tuple(rows), PUMA.convention)
    joints = _joints(chain)
    Q = _configurations(joints, 11)
    consts = _constant_env(chain, chain, PUMA.value_map, 11)
    signed = _signed_frames(chain, joints, consts, Q, len(Q))
    for signs in itertools.product((1.0, -1.0), repeat=3):
        pattern = [*signs, 1.0, 1.0, -1.0]
        env = {**consts, **{jt[2]: s * Q[:, j] for j, (jt, s) in enumerate(zip(joints, pattern))}}
        assert np.array_equal(signed(pattern), frames(chain, env, len(Q)))
