"""Newton–Euler equals Lagrange–Euler, proven exactly (sympy), in both DH conventions."""

from __future__ import annotations

import pytest
import sympy as sp

import dhsym
from dhsym.dynamics import lagrange, newton_euler
from dhsym.dynamics.model import dynamic_model
from dhsym.dynamics.recursive_newton_euler import rne_expressions
from dhsym.kinematics.simplification import prove_equal
from dhsym.model.tablefile import read_table_text
from dhsym.robot import Robot

# Craig's RRR arm (modified DH, Introduction to Robotics, Fig. 3.6 style), twisted and offset
MODIFIED_3R = """
convention: modified
joints:
  - {type: R, theta: q1, d: 0, a: 0, alpha: 0}
  - {type: R, theta: q2, d: d2, a: a1, alpha: -pi/2}
  - {type: R, theta: q3, d: 0, a: a2, alpha: 0}
"""
MODIFIED_RPR = """
convention: modified
gravity: [0, -g, 0]
joints:
  - {type: R, theta: q1, d: 0, a: 0, alpha: 0}
  - {type: P, theta: 0, d: d2, a: a1, alpha: pi/2}
  - {type: R, theta: q3, d: d3, a: 0, alpha: -pi/2}
"""


def _proven_equal(robot: Robot) -> bool:
    lag = lagrange(robot)
    raw = rne_expressions(lag.model)  # the recursion as compiled, never simplified
    return prove_equal(lag.tau, raw)


@pytest.mark.parametrize(
    "name", ["planar2r", "spong2r", "example1_rrp", "cylindrical", "cartesian"]
)
def test_lagrange_equals_newton_euler_on_built_in_robots(name):
    assert _proven_equal(dhsym.load(name))


@pytest.mark.parametrize("text", [MODIFIED_3R, MODIFIED_RPR])
def test_lagrange_equals_newton_euler_in_modified_dh(text):
    assert _proven_equal(Robot(read_table_text(text)))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["scara", "planar4r"])
def test_lagrange_equals_newton_euler_on_four_joint_robots(name):
    assert _proven_equal(dhsym.load(name))


def _numeric_inertias(robot: Robot) -> Robot:
    """The robot with fixed rational inertial parameters (so six joints stay quick)."""
    rows = []
    for i, row in enumerate(robot.table.rows, start=1):
        data = {
            "m": sp.Rational(3, i + 1),
            "r": [sp.Rational(1, 10 * i), sp.Rational(-1, 20), sp.Rational(i, 30)],
            "I": [sp.Rational(k, 100 * i) for k in (5, 6, 7)] + [sp.Rational(1, 1000), 0, 0],
        }
        from dataclasses import replace

        from dhsym.model.inertia import LinkInertia

        rows.append(replace(row, inertia=LinkInertia.from_data(data, row=i)))
    from dataclasses import replace as rep

    return Robot(rep(robot.table, rows=tuple(rows)).substituted())


@pytest.mark.slow
@pytest.mark.parametrize("name", ["stanford", "puma560_modified"])
def test_lagrange_equals_newton_euler_on_six_joint_robots(name):
    assert _proven_equal(_numeric_inertias(dhsym.load(name)))


@pytest.mark.slow
def test_lagrange_equals_newton_euler_on_the_puma560_with_its_published_parameters():
    assert _proven_equal(Robot(dhsym.load("puma560").table.substituted()))


def test_newton_euler_result_has_the_recursion_as_steps():
    eom = newton_euler(dhsym.load("planar2r"))
    outward = [s for s in eom.steps if s.sweep == "outward"]
    inward = [s for s in eom.steps if s.sweep == "inward"]
    assert [s.name for s in outward[:6]] == ["omega", "omegadot", "a", "ac", "F", "N"]
    assert [s.name for s in inward[:3]] == ["f", "n", "tau"] and inward[0].link == 2
    omega2 = next(s for s in outward if s.name == "omega" and s.link == 2).value
    t1, t2 = (sp.Symbol(f"thetadot{k}", real=True) for k in (1, 2))
    assert omega2 == sp.Matrix([0, 0, t1 + t2])
    lag = lagrange(dhsym.load("planar2r"))
    assert prove_equal(eom.M, lag.M) and prove_equal(eom.C, lag.C) and prove_equal(eom.g, lag.g)


def test_gravity_in_a_base_frame_turned_by_a_base_transform():
    # a pendulum hung from a base turned a quarter about x: gravity -z of the world
    # is +y... of frame 0, so the torque at q = 0 follows the turned gravity
    text = """
base: [{Rx: 90}]
angles: deg
joints: [{type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}]
"""
    robot = Robot(read_table_text(text))
    dm = dynamic_model(robot)
    assert dm.gravity == (0, sp.Rational(-981, 100), 0)
    eom = lagrange(robot)
    q1 = robot.variables[0]
    assert sp.expand(eom.g[0] - 2 * sp.Rational(981, 100) * sp.Rational(1, 2) * sp.cos(q1)) == 0


def test_robot_dynamics_names_its_methods():
    robot = dhsym.load("planar2r")
    assert robot.dynamics("newton-euler").method == "newton-euler"
    assert robot.dynamics() is robot.dynamics("lagrange")
    with pytest.raises(dhsym.DHError, match="lagrange or newton-euler"):
        robot.dynamics("hamilton")
