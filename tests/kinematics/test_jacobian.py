"""The geometric and analytic Jacobians: exact proofs, finite differences, frames, batches."""

from __future__ import annotations

import functools

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.errors import DHError
from dhsym.kinematics.jacobian import (
    AnalyticJacobian,
    Jacobian,
    analytic_jacobian,
    analytic_jacobian_function,
    euler_angles,
    geometric_jacobian,
    jacobian_function,
    numeric_jacobian,
    rate_matrix,
)
from dhsym.kinematics.simplification import prove_equal


@functools.cache
def _robot(name: str) -> dhsym.Robot:
    robot = dhsym.load(name)
    if name == "planar3r":  # planar chains carry no lengths
        robot = dhsym.Robot(robot.table.with_values({"a1": 1.0, "a2": 0.8, "a3": 0.5}))
    return robot


ALL = [*dhsym.builtin_names(), "planar3r"]


def _random_q(robot: dhsym.Robot, count: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (count, len(robot.variables)))
    for k, row in enumerate(r for r in robot.table.rows if r.variable is not None):
        if row.joint.value == "P":
            q[:, k] = rng.uniform(0.1, 0.8, count)
    return q


def _vee(W: np.ndarray) -> np.ndarray:
    return np.array([W[2, 1], W[0, 2], W[1, 0]])


def _finite_difference(robot: dhsym.Robot, q: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """Central differences of fk: d(position)/dq and vee(dR/dq Rᵀ)."""
    fk = robot.fk_function()
    T = fk(q)
    J = np.zeros((6, len(q)))
    for i in range(len(q)):
        dq = np.zeros(len(q))
        dq[i] = h
        plus, minus = fk(q + dq), fk(q - dq)
        J[:3, i] = (plus[:3, 3] - minus[:3, 3]) / (2 * h)
        J[3:, i] = _vee((plus[:3, :3] - minus[:3, :3]) / (2 * h) @ T[:3, :3].T)
    return J


@pytest.mark.parametrize("name", ALL)
def test_numeric_jacobian_equals_finite_differences_of_fk(name: str) -> None:
    robot = _robot(name)
    qs = _random_q(robot, 25, seed=1)
    # the compiled base Jacobian (jacobian_function) as the robot keeps it: compiled once
    # per table in a process, shared with the other tests that ask a robot for jacob0
    J = robot.jacob0(qs)
    worst = max(np.abs(_finite_difference(robot, q) - Jk).max() for q, Jk in zip(qs, J))
    assert worst < 1e-7


def test_the_values_of_a_table_are_those_of_its_copy_with_the_values_given() -> None:
    """Without values the table's own map is used, no copy made: the same map (keys, their
    order, the values) as the copy ``with_values`` makes, for every robot; with values, the
    copy's."""
    from dhsym.kinematics.jacobian import _values

    for name in ALL:
        robot = _robot(name)
        for none in (None, {}):
            got = _values(robot, none)
            assert list(got.items()) == list(robot.table.with_values({}).value_map.items())
    r = dhsym.load("planar3r")  # no lengths given
    a1 = sp.Symbol("a1", real=True)
    assert _values(r, {"a1": 2})[a1] == 2 and a1 not in _values(r, None)


@pytest.mark.parametrize(
    "name",
    [
        "planar2r",
        "planar3r",
        "scara",
        "example1_rrp",
        "cylindrical",
        "cartesian",
        "stanford",
        "puma560_modified",
    ],
)
def test_symbolic_jacobian_is_proven_equal_to_the_derivative_of_the_plain_product(
    name: str,
) -> None:
    robot = _robot(name)
    J = geometric_jacobian(robot)
    assert J.verify()
    plain = robot.plain_transform(0, robot.n)[:3, 3]
    assert prove_equal(J.linear, plain.jacobian(list(robot.variables)))


def test_tool_frame_jacobian_is_proven_too() -> None:
    assert geometric_jacobian(_robot("stanford"), frame="tool").verify()


def test_verify_fails_on_a_wrong_entry() -> None:
    J = geometric_jacobian(_robot("planar2r"))
    wrong = J.matrix.as_mutable()
    wrong[0, 1] = -wrong[0, 1]  # the sign a student might lose
    bad = Jacobian(sp.ImmutableMatrix(wrong), J.columns, J.frame, J.point, J.robot)
    assert not bad.verify()


def test_planar_2r_is_the_lecture_jacobian() -> None:
    r = _robot("planar2r")
    J = geometric_jacobian(r)
    assert r.notation.text(J.linear[:2, :]) == (
        "Matrix([\n[-a1*S1 - a2*S12, -a2*S12],\n[ a1*C1 + a2*C12,  a2*C12]])"
    )
    assert list(J.angular.row(2)) == [1, 1]


def test_modified_convention_turns_joint_i_about_z_i() -> None:
    r = _robot("puma560_modified")
    J = geometric_jacobian(r)
    assert [c.axis_frame for c in J.columns] == [1, 2, 3, 4, 5, 6]
    # the last axis passes through the end-effector origin: no linear velocity from it
    assert list(J.linear.col(5)) == [0, 0, 0]
    standard = geometric_jacobian(_robot("puma560"))
    assert [c.axis_frame for c in standard.columns] == [0, 1, 2, 3, 4, 5]


def test_prismatic_column_is_the_axis() -> None:
    J = geometric_jacobian(_robot("stanford"))
    col = J.columns[2]
    assert col.joint.value == "P"
    assert list(col.angular) == [0, 0, 0]
    assert col.linear == col.axis


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-3.0, 3.0), min_size=6, max_size=6))
def test_tool_frame_jacobian_is_the_base_one_rotated(q: list[float]) -> None:
    robot = _robot("puma560")
    J0 = robot.jacob0(q)
    Jt = robot.jacobe(q)
    R = robot.fk(q)[:3, :3]
    assert np.allclose(Jt[:3], R.T @ J0[:3], atol=1e-12)
    assert np.allclose(Jt[3:], R.T @ J0[3:], atol=1e-12)


def test_batches_and_shapes() -> None:
    robot = _robot("puma560")
    qs = _random_q(robot, 7, seed=3)
    batch = robot.jacob0(qs)
    assert batch.shape == (7, 6, 6)
    assert robot.jacob0(qs[2]).shape == (6, 6)
    assert np.array_equal(batch[2], robot.jacob0(qs[2]))
    assert robot.jacobe(qs).shape == (7, 6, 6)


def test_exact_and_numbers_have_their_own_names() -> None:
    robot = _robot("puma560")
    assert isinstance(robot.jacobian(), Jacobian)
    assert robot.jacobian(frame="tool").frame == 6
    A = robot.analytic_jacobian("rpy", frame="tool")
    assert isinstance(A, AnalyticJacobian) and A.euler == "rpy" and A.geometric.frame == 6
    with pytest.raises(DHError, match="analytic_jacobian"):
        robot.jacobian(euler="zyz")  # type: ignore[call-overload]  # the exact one has no euler


def test_jacobian_of_q_is_an_alias_of_the_numbers() -> None:
    robot = _robot("puma560")
    qs = _random_q(robot, 4, seed=9)
    assert np.array_equal(robot.jacobian(qs), robot.jacob0(qs))
    assert np.array_equal(robot.jacobian(qs, frame="tool"), robot.jacobe(qs))
    assert np.array_equal(robot.jacobian(qs, euler="rpy"), robot.jacob0(qs, euler="rpy"))
    assert np.array_equal(robot.jacobian(qs, frame=3), jacobian_function(robot, 3)(qs))
    values = {"a2": 0.5}
    assert np.array_equal(robot.jacobian(qs, values=values), robot.jacob0(qs, values=values))
    assert not np.allclose(robot.jacob0(qs, values=values), robot.jacob0(qs))


def test_frames_are_checked() -> None:
    with pytest.raises(DHError, match="frame must be"):
        geometric_jacobian(_robot("planar2r"), frame=9)


def test_rate_matrix_maps_euler_rates_to_angular_velocity() -> None:
    rng = np.random.default_rng(0)
    for euler in ("zyz", "rpy"):
        B = sp.lambdify(sp.symbols("phi theta psi", real=True), rate_matrix(euler), "numpy")
        axes = {"zyz": "zyz", "rpy": "zyx"}[euler]
        for _ in range(5):
            ang, rate = rng.uniform(-1, 1, 3), rng.uniform(-1, 1, 3)
            h = 1e-6
            R = _euler_matrix(axes, ang)
            dR = (_euler_matrix(axes, ang + h * rate) - _euler_matrix(axes, ang - h * rate)) / (
                2 * h
            )
            assert np.allclose(_vee(dR @ R.T), np.asarray(B(*ang), float) @ rate, atol=1e-8)


def _euler_matrix(axes: str, ang: np.ndarray) -> np.ndarray:
    from dhsym.kinematics.transforms import Rx, Ry, Rz

    rot = {"x": Rx, "y": Ry, "z": Rz}
    M = sp.eye(4)
    for a, v in zip(axes, ang):
        M = M * rot[a](float(v))
    return np.array(M[:3, :3], dtype=float)


@pytest.mark.parametrize("euler", ["zyz", "rpy"])
def test_analytic_jacobian_is_the_derivative_of_the_euler_angles(euler: str) -> None:
    robot = _robot("puma560")
    fk = robot.fk_function()
    JA = analytic_jacobian_function(robot, euler)
    for q in _random_q(robot, 10, seed=5):
        num = np.zeros((3, 6))
        for i in range(6):
            dq = np.zeros(6)
            dq[i] = 1e-6
            a, b = euler_angles(fk(q + dq), euler), euler_angles(fk(q - dq), euler)
            num[:, i] = (np.remainder(a - b + np.pi, 2 * np.pi) - np.pi) / 2e-6
        assert np.allclose(JA(q)[3:], num, atol=1e-6)
        assert np.allclose(JA(q)[:3], robot.jacob0(q)[:3])


def test_analytic_jacobian_symbolic_form() -> None:
    A = analytic_jacobian(_robot("planar2r"), "rpy")
    assert A.angles == sp.symbols("phi theta psi", real=True)
    assert A.matrix.shape == (6, 2)
    # for a planar arm the yaw rate is the sum of the joint rates
    assert sp.simplify(A.matrix[3, 0] - 1) == 0
    assert A.matrix[5, 0] == 0


def test_robot_jacobian_with_euler_is_the_analytic_one() -> None:
    robot = _robot("puma560")
    q = _random_q(robot, 3, seed=8)
    assert np.allclose(robot.jacob0(q, euler="zyz"), analytic_jacobian_function(robot, "zyz")(q))
    assert robot.analytic_jacobian("rpy").euler == "rpy"
    with pytest.raises(DHError, match="base frame"):
        robot.jacobian(q, frame="tool", euler="zyz")


def test_base_and_tool_transforms_are_part_of_the_jacobian() -> None:
    from dataclasses import replace

    from dhsym.model.table import Elementary

    table = dhsym.load("puma560").table
    base = (Elementary("T", "z", sp.Rational(1, 2)), Elementary("R", "x", sp.pi / 3))
    tool = (Elementary("T", "z", sp.Rational(1, 10)), Elementary("R", "y", sp.pi / 2))
    robot = dhsym.Robot(replace(table, base=base, tool=tool))
    qs = _random_q(robot, 10, seed=4)
    J = robot.jacob0(qs)
    assert max(np.abs(_finite_difference(robot, q) - Jk).max() for q, Jk in zip(qs, J)) < 1e-7
    assert geometric_jacobian(robot).frame == "W"
    assert geometric_jacobian(robot).point == "tool"


def _with_base_and_tool(name: str) -> dhsym.Robot:
    from dataclasses import replace

    from dhsym.model.table import Elementary

    table = dhsym.load(name).table
    base = (Elementary("T", "z", sp.Rational(1, 2)), Elementary("R", "x", sp.pi / 3))
    tool = (Elementary("T", "z", sp.Rational(1, 10)), Elementary("R", "y", sp.pi / 2))
    return dhsym.Robot(replace(table, base=base, tool=tool))


@pytest.mark.parametrize("name", ["planar3r", "stanford", "puma560_modified", "base_and_tool"])
def test_jacobian_from_numeric_frames_is_jacob0(name: str) -> None:
    robot = _with_base_and_tool("stanford") if name == "base_and_tool" else _robot(name)
    qs = _random_q(robot, 5, seed=8)
    J = numeric_jacobian(robot, qs)
    assert J.shape == (5, 6, robot.n)
    assert np.abs(J - robot.jacob0(qs)).max() < 1e-12
    assert np.abs(numeric_jacobian(robot, qs[0]) - J[0]).max() == 0.0


def test_jacobian_from_numeric_frames_takes_values() -> None:
    robot = dhsym.load("planar3r")
    values = {"a1": 1.0, "a2": 0.8, "a3": 0.5}
    q = [0.3, -0.7, 1.1]
    assert np.abs(numeric_jacobian(robot, q, values) - robot.jacob0(q, values=values)).max() < 1e-12


def test_the_geometric_and_the_screw_jacobians_print_through_one_mixin() -> None:
    """``Jacobian`` and the screws room's ``ScrewJacobian`` share the printing hooks of
    :class:`LectureMatrix`: plain text, LaTeX, sympy's printers and Jupyter's display."""
    from dhsym.kinematics.jacobian import LectureMatrix
    from dhsym.screws.product import ScrewJacobian

    robot = dhsym.load("planar2r")
    J = geometric_jacobian(robot)
    Js = robot.poe().jacobian_space()
    assert isinstance(J, LectureMatrix) and isinstance(Js, ScrewJacobian)
    assert isinstance(Js, LectureMatrix)
    assert J._repr_latex_() == r"$${}^{0}J = " + J.latex() + "$$"
    assert Js._repr_latex_() == "$$J_{s} = " + Js.latex() + "$$"
    assert sp.sstr(J) == J.text() and sp.latex(Js) == Js.latex()
    assert Js.text().splitlines()[5] == "[0, -a1*C1],"


def test_joint_rows_name_each_joint_and_its_rate() -> None:
    from dhsym.kinematics.jacobian import joint_rows
    from dhsym.model.table import DHRow, DHTable

    rows = joint_rows(dhsym.load("stanford"))
    assert [(r, str(v), j.value) for r, v, j, _ in rows][:3] == [
        (1, "theta1", "R"),
        (2, "theta2", "R"),
        (3, "d3", "P"),
    ]
    table = DHTable.from_rows([DHRow.revolute("-theta1", a="a1"), DHRow.revolute("theta2")])
    assert [rate for *_, rate in joint_rows(dhsym.Robot(table))] == [-1, 1]


@pytest.mark.parametrize("name", ["stanford", "puma560_modified", "ur5", "example4_6dof"])
def test_jacobe_is_the_exact_tool_frame_jacobian_in_numbers(name: str) -> None:
    """``jacobe`` (diag(Rᵀ, Rᵀ) jacob0 in numbers) equals the exact Jacobian in the tool
    frame, compiled."""
    from dhsym.kinematics.jacobian import jacobian_function

    robot = dhsym.load(name)
    q = np.random.default_rng(11).uniform(-2, 2, (5, robot.n))
    exact = jacobian_function(robot, "tool")  # derived and compiled once, for both checks
    np.testing.assert_allclose(robot.jacobe(q), exact(q), atol=1e-12)
    np.testing.assert_allclose(robot.jacobe(q[0]), exact(q[0]), atol=1e-12)
