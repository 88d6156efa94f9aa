"""Factored Jacobian determinants and named singular configurations."""

from __future__ import annotations

import functools

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.kinematics.jacobian import jacobian_function
from dhsym.kinematics.singularities import factored_det, singularities


@functools.cache
def _robot(name: str) -> dhsym.Robot:
    robot = dhsym.load(name)
    if name == "planar3r":
        robot = dhsym.Robot(robot.table.with_values({"a1": 1.0, "a2": 0.8, "a3": 0.5}))
    return robot


SQUARE = [
    "puma560",
    "puma560_modified",
    "stanford",
    "example4_6dof",
    "puma260",
    "planar2r",
    "planar3r",
    "scara",
    "cylindrical",
    "cartesian",
    "example1_rrp",
]


@pytest.mark.parametrize("name", SQUARE)
def test_factored_determinant_is_proven_and_matches_numbers(name: str) -> None:
    robot = _robot(name)
    s = singularities(robot)
    assert s.verify()
    rng = np.random.default_rng(2)
    q = rng.uniform(-np.pi, np.pi, (20, len(robot.variables)))
    q[:, [r.joint.value == "P" for r in robot.table.rows]] = rng.uniform(0.1, 0.8, (20, 1))
    J = jacobian_function(robot)(q)[:, list(s.rows)]
    assert np.allclose(np.linalg.det(J), s.function()(q), atol=1e-10)


@pytest.mark.parametrize("name", ["puma560", "puma560_modified"])
def test_puma_determinant_has_the_arm_and_wrist_factors(name: str) -> None:
    s = singularities(_robot(name))
    assert s.measure == "det J"
    assert [b.name for b in s.blocks] == ["J11", "J22"]
    kinds = {f.kind: f.text() for f in s.factors}
    assert kinds == {
        "constant": "a2",
        "elbow": "a3*S3 + d4*C3",
        "shoulder": "a2*C2 + a3*C23 - d4*S23",
        "wrist": "S5",
    }
    wrist = next(f for f in s.factors if f.kind == "wrist")
    assert wrist.solutions == (
        (sp.Symbol("theta5", real=True), 0),
        (sp.Symbol("theta5", real=True), sp.pi),
    )


def test_named_configurations_make_the_jacobian_singular() -> None:
    robot = _robot("puma560")
    s = singularities(robot)
    J = jacobian_function(robot)
    base = np.array([0.3, -0.4, 0.5, 0.2, 0.7, -0.1])
    values = robot.table.value_map
    for factor in s.factors:
        for var, value in factor.solutions:
            q = base.copy()
            q[robot.variables.index(var)] = float(value.subs(values))
            assert abs(np.linalg.det(J(q))) < 1e-12, (factor.kind, value)
    assert abs(np.linalg.det(J(base))) > 1e-4


def test_shoulder_singularity_puts_the_wrist_centre_on_the_offset_line() -> None:
    robot = _robot("puma560")
    s = singularities(robot)
    shoulder = next(f for f in s.factors if f.kind == "shoulder")
    t2, t3 = sp.symbols("theta2 theta3", real=True)
    f = sp.lambdify((t2, t3), shoulder.expr.subs(robot.table.value_map))
    theta3 = 0.5
    # find theta2 with f = 0 by bisection on a sign change
    lo, hi = -np.pi, np.pi
    grid = np.linspace(lo, hi, 721)
    vals = np.array([f(g, theta3) for g in grid])
    k = int(np.nonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0][0])
    a, b = grid[k], grid[k + 1]
    for _ in range(80):
        m = (a + b) / 2
        a, b = (a, m) if np.sign(f(a, theta3)) != np.sign(f(m, theta3)) else (m, b)
    q = np.array([0.7, a, theta3, 0.3, 0.9, 0.2])
    centre = robot.fk_function(0, 4)(q)[:3, 3]
    assert np.isclose(np.hypot(centre[0], centre[1]), 0.15005, atol=1e-9)
    assert abs(np.linalg.det(jacobian_function(robot)(q))) < 1e-10


def test_stanford_and_planar_and_positioning_arms() -> None:
    assert singularities(_robot("stanford")).text() == "det J = d3**2*S2*S5"
    two = singularities(_robot("planar2r"))
    assert two.text() == "det J_v = a1*a2*S2"
    assert [f.kind for f in two.factors] == ["constant", "constant", "elbow"]
    assert singularities(_robot("cartesian")).factors == ()
    cyl = singularities(_robot("cylindrical"))
    assert [(f.kind, f.text()) for f in cyl.factors] == [("shoulder", "d3")]


def test_redundant_arm_gets_the_manipulability_by_cauchy_binet() -> None:
    robot = _robot("planar4r")
    s = singularities(robot)
    assert s.measure == "det(J J^T)"
    assert s.verify()
    q = np.random.default_rng(0).uniform(-np.pi, np.pi, (10, 4))
    J = jacobian_function(robot)(q)[:, list(s.rows)]
    assert np.allclose(np.linalg.det(J @ np.swapaxes(J, 1, 2)), s.function()(q))


def test_factored_det_expands_along_the_sparsest_line() -> None:
    a, b, c = sp.symbols("a b c")
    M = sp.Matrix([[a, 0, 0], [b, c, 0], [1, 2, a * b]])
    assert factored_det(M) == a**2 * b * c


def test_many_redundant_joints_are_refused_quickly() -> None:
    from dhsym.kinematics.decoupling import StructureError

    with pytest.raises(StructureError, match="10 squared minors"):
        singularities(dhsym.load("planar5r"))


_RRR = """name: an articulated arm
convention: standard
angles: deg
joints:
  - {type: R, theta: theta1, d: d1, a: 0, alpha: 90}
  - {type: R, theta: theta2, d: 0, a: a2, alpha: 0}
  - {type: R, theta: theta3, d: 0, a: a3, alpha: 0}
"""


def test_one_vocabulary_names_the_same_singularity_the_same_on_every_arm(tmp_path) -> None:
    from dhsym.kinematics.singularities import SingularityKind

    path = tmp_path / "rrr.yaml"
    path.write_text(_RRR)
    arm = {f.kind: f for f in singularities(dhsym.load(path)).factors}
    puma = {f.kind: f for f in singularities(_robot("puma560")).factors}
    # the arm's reach a2*C2 + a3*C23 is the shoulder singularity for the bare arm as for the
    # PUMA (it was "arm singularity" on one and "shoulder" on the other)
    assert arm["shoulder"].text() == "a2*C2 + a3*C23"
    assert arm["shoulder"].name == puma["shoulder"].name == "shoulder singularity"
    assert arm["elbow"].name == puma["elbow"].name == "elbow singularity"
    names = {k.value: k.phrase for k in SingularityKind}
    for name in SQUARE:
        for f in singularities(_robot(name)).factors:
            assert f.name == names[f.kind]
    assert "arm singularity" not in names.values()


# --- six-joint arms without a spherical wrist (issue 32, item 2) ------------------------------

UR = ["ur3", "ur5", "ur10"]


@pytest.mark.parametrize("name", UR)
def test_an_arm_without_a_spherical_wrist_gets_its_whole_determinant_factored(name: str) -> None:
    robot = _robot(name)
    s = singularities(robot)
    assert s.whole and s.measure == "det J" and s.rows == (0, 1, 2, 3, 4, 5)
    assert s.text() == "det J = a2*a3*S3*S5*(a2*C2 + a3*C23 + d5*S234)"
    (block,) = s.blocks
    assert block.frame == 4 and "wrist point" in s.method
    kinds = {f.kind: f.text() for f in s.factors if f.kind != "constant"}
    assert kinds == {"elbow": "S3", "shoulder": "a2*C2 + a3*C23 + d5*S234", "wrist": "S5"}
    wrist = next(f for f in s.factors if f.kind == "wrist")
    t5 = sp.Symbol("theta5", real=True)
    assert wrist.solutions == ((t5, 0), (t5, sp.pi))
    assert wrist.description.startswith("the axes of joints 4 and 6 are parallel: joints 2, 3, 4")
    shoulder = next(f for f in s.factors if f.kind == "shoulder")
    assert "wrist point" in shoulder.description
    assert s.verify()
    # a second method: the determinant of the numeric Jacobian (frame 0, tool point)
    rng = np.random.default_rng(3)
    q = rng.uniform(-np.pi, np.pi, (20, 6))
    J = jacobian_function(robot)(q)
    assert np.allclose(np.linalg.det(J), s.function()(q), atol=1e-12)


def test_a_wrong_whole_determinant_is_not_proven() -> None:
    from dataclasses import replace

    s = singularities(_robot("ur5"))
    assert not replace(s, determinant=2 * s.determinant).verify()
    (block,) = s.blocks
    t3 = sp.Symbol("theta3", real=True)
    wrong = block.determinant.xreplace({sp.sin(t3): sp.cos(t3)})
    assert not replace(s, determinant=wrong, blocks=(replace(block, determinant=wrong),)).verify()


def test_the_ur5_singular_configurations_make_the_jacobian_singular() -> None:
    robot = _robot("ur5")
    s = singularities(robot)
    J = jacobian_function(robot)
    base = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.4])
    assert abs(np.linalg.det(J(base))) > 1e-4
    for factor in s.factors:
        for var, value in factor.solutions:
            q = base.copy()
            q[robot.variables.index(var)] = float(value)
            assert abs(np.linalg.det(J(q))) < 1e-12, (factor.kind, value)
    # at θ5 = 0 the axes of joints 2, 3, 4 and 6 (the angular columns) are all parallel
    q = base.copy()
    q[4] = 0.0
    axes = J(q)[3:, [1, 2, 3, 5]]
    assert np.abs(np.cross(axes[:, 0], axes.T)).max() < 1e-12
    # shoulder: θ4 chosen so that a2*C2 + a3*C23 + d5*S234 = 0; the wrist point (frame 5)
    # then lies at the shoulder offset d4 from the axis of joint 1
    v = robot.table.value_map
    a2, a3, d4, d5 = (float(v[sp.Symbol(n, real=True)]) for n in ("a2", "a3", "d4", "d5"))
    t2, t3 = 1.3, 0.4
    s234 = -(a2 * np.cos(t2) + a3 * np.cos(t2 + t3)) / d5
    q = base.copy()
    q[1:4] = t2, t3, np.arcsin(s234) - t2 - t3
    point = robot.fk_function(0, 5)(q)[:3, 3]
    assert np.isclose(np.hypot(point[0], point[1]), abs(d4), atol=1e-12)
    assert abs(np.linalg.det(J(q))) < 1e-12


def test_an_arm_whose_determinant_does_not_factor_is_refused_within_the_bound() -> None:
    from dhsym.kinematics.decoupling import StructureError

    with pytest.raises(StructureError, match="not factored here: a minor of the determinant"):
        singularities(dhsym.load("jaco"))


def test_the_whole_determinant_is_kept_and_read_back_equal() -> None:
    from dhsym.kinematics.singularities import singularities_data, stored_singularities

    robot = _robot("ur5")
    s = singularities(robot)
    data = singularities_data(s)
    assert data is not None
    back = stored_singularities(data, robot)
    assert back == s and isinstance(back, type(s)) and back.whole
