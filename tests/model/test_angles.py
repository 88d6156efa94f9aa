"""Decimal angles meant to be exact: 1.5708 is read as pi/2, visibly, and can be kept."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import TableError
from dhsym.model.angles import AngleSnap, snap_angle
from dhsym.model.table import DHRow, DHTable, Elementary
from dhsym.model.tablefile import dump_table, read_table_text

pi = sp.pi
PUMA = (Path(dhsym.__file__).parent / "model" / "robots" / "puma560.yaml").read_text()


def dec(text: str) -> sp.Rational:
    """The exact value of a decimal literal, as the table reader makes it."""
    return dhsym.model.entries.as_expr(text)


def puma_with(twist: str) -> str:
    return PUMA.replace("alpha: pi/2", f"alpha: {twist}").replace(
        "alpha: -pi/2", f"alpha: -{twist}"
    )


@pytest.mark.parametrize(
    ("written", "exact"),
    [
        ("1.5708", pi / 2),
        ("1.57", pi / 2),
        ("1.5707963267948966", pi / 2),
        ("-1.5707963267949", -pi / 2),
        ("3.1416", pi),
        ("3.14", pi),
        ("0.7854", pi / 4),
        ("0.785", pi / 4),
        ("0.2618", pi / 12),
        ("2.0944", 2 * pi / 3),
        ("-2.618", -5 * pi / 6),
        ("6.2832", 2 * pi),
        (repr(float(np.deg2rad(30.0))), pi / 6),  # a float with rounding in its last place
        (repr(3 * math.pi / 4), 3 * pi / 4),
    ],
)
def test_decimals_that_round_a_multiple_of_pi_over_12_are_read_as_it(written, exact):
    found = snap_angle(dec(written))
    assert found is not None and found[0] == exact
    assert found[1] < 10 ** -(len(written.split(".")[1]) - 1)


@pytest.mark.parametrize(
    "written", ["1.6", "1.5", "0.79", "1.2", "0.5", "1.5718", "3.15", "0.0001", "1/3", "1", "2"]
)
def test_other_numbers_stay_as_written(written):
    assert snap_angle(dec(written)) is None


def test_a_tolerance_replaces_the_digits_rule_and_false_switches_it_off():
    assert snap_angle(dec("1.5708"), AngleSnap(True, 1e-6)) is None
    assert snap_angle(dec("1.5707963"), AngleSnap(True, 1e-6))[0] == pi / 2
    assert snap_angle(dec("1.6"), AngleSnap(True, 0.05))[0] == pi / 2
    assert snap_angle(dec("1.5708"), AngleSnap(False)) is None
    assert AngleSnap.parse(0.001) == AngleSnap(True, 0.001)
    for bad in ("yes", -1, 2.0, float("nan")):
        with pytest.raises(TableError, match="snap_angles"):
            AngleSnap.parse(bad)


@pytest.mark.parametrize("twist", ["1.5708", "1.5707963267948966"])
def test_a_toolbox_printout_derives_to_the_builtin_arm_matrix(twist):
    typed = read_table_text(puma_with(twist))
    builtin = dhsym.builtin_table("puma560")
    assert typed == builtin
    T_typed = dhsym.Robot(typed).arm_matrix()
    T_builtin = dhsym.Robot(builtin).arm_matrix()
    assert T_typed.matrix == T_builtin.matrix
    assert T_typed.count_ops() == T_builtin.count_ops() == 261
    assert "cos(3927" not in str(T_typed.matrix) and "7853981633974483" not in str(T_typed.matrix)


def test_the_table_says_once_what_it_read_as_what():
    t = read_table_text(puma_with("1.5708"))
    assert t.warnings == (
        "Decimal angles read as exact: alpha ±1.5708 in rows 1, 3, 4, 5 as ±π/2 "
        "(|difference| ≤ 3.7e-06). Write snap_angles: false to keep the decimals.",
    )
    assert dhsym.builtin_table("puma560").warnings == ()


def test_offsets_fixed_angles_and_base_tool_rotations_are_snapped_but_not_limits():
    text = """
joints:
  - {type: R, theta: q1 + 0.7854, d: 0, a: 1, alpha: 0, limits: [-0.7854, 0.7854]}
  - {type: P, theta: -1.5708, d: q2, a: 0, alpha: 3.1416}
  - {type: F, theta: 0.5236, d: 1, a: 0, alpha: 0}
base: [{Rx: 1.5708}, {Tz: 0.5}]
tool: [{Rz: -3.1416}]
"""
    t = read_table_text(text)
    q1 = sp.Symbol("q1", real=True)
    assert [r.theta for r in t.rows] == [q1 + pi / 4, -pi / 2, pi / 6]
    assert t.rows[1].alpha == pi
    assert t.rows[0].limits == (dec("-0.7854"), dec("0.7854"))  # limits are not snapped
    assert t.base[0] == Elementary("R", "x", pi / 2) and t.base[1].value == sp.Rational(1, 2)
    assert t.tool == (Elementary("R", "z", -pi),)
    (note,) = t.warnings
    for part in (
        "theta 0.7854 in row 1 as π/4",
        "theta -1.5708 in row 2 as -π/2",
        "alpha 3.1416 in row 2 as π",
        "theta 0.5236 in row 3 as π/6",
        "base Rx 1.5708 as π/2",
        "tool Rz -3.1416 as -π",
    ):
        assert part in note


def test_the_opt_out_and_the_tolerance_in_the_file():
    kept = read_table_text("snap_angles: false\n" + puma_with("1.5708"))
    assert kept.rows[0].alpha == dec("1.5708") and kept.warnings == ()
    strict = read_table_text("snap_angles: 1e-9\n" + puma_with("1.5708"))
    assert strict.rows[0].alpha == dec("1.5708")
    loose = read_table_text("snap_angles: 1e-2\n" + puma_with("1.57"))
    assert loose.rows[0].alpha == pi / 2
    with pytest.raises(TableError, match="arm.yaml: field snap_angles"):
        read_table_text("snap_angles: maybe\n" + PUMA, file="arm.yaml")


def test_the_opt_out_in_the_api_and_degree_tables():
    row = DHRow.revolute("q1", alpha=1.5708)
    assert DHTable.from_rows([row]).rows[0].alpha == pi / 2
    assert DHTable.from_rows([row], snap_angles=False).rows[0].alpha == dec("1.5708")
    assert DHTable.from_rows([row], snap_angles=1e-7).rows[0].alpha == dec("1.5708")
    deg = DHTable.from_rows([DHRow.revolute("q1", alpha=89.99)], angles="deg")
    assert deg.rows[0].alpha == dec("89.99") * pi / 180 and deg.warnings == ()
    symbolic = DHTable.from_rows([DHRow.revolute("q1", alpha="alpha1")])
    assert symbolic.rows[0].alpha == sp.Symbol("alpha1", real=True)


def test_kept_decimals_survive_a_yaml_round_trip():
    kept = read_table_text("snap_angles: false\n" + puma_with("1.5708"))
    text = dump_table(kept)
    assert "snap_angles: false" in text and "alpha: 1.5708" in text
    assert read_table_text(text) == kept
    snapped = read_table_text(puma_with("1.5708"))
    assert "snap_angles" not in dump_table(snapped) and "alpha: pi/2" in dump_table(snapped)


def test_a_twist_near_no_multiple_stays_a_number_and_its_cosine_is_a_float():
    t = read_table_text(puma_with("1.2"))
    robot = dhsym.Robot(t)
    M = robot.arm_matrix().matrix
    assert t.rows[0].alpha == sp.Rational(6, 5) and t.warnings == ()
    assert not M.has(sp.cos(sp.Rational(6, 5))) and M.atoms(sp.Float)
    assert robot.verify()  # proven against the plain product (floats at their exact values)
    q = np.random.default_rng(3).uniform(-3, 3, 6)
    subs = {**t.value_map, **dict(zip(t.variables, q, strict=True))}
    plain = robot.plain_transform(0, 6).subs(subs).evalf()
    np.testing.assert_allclose(robot.fk_function(0, 6)(q), np.array(plain, dtype=float), atol=1e-12)
