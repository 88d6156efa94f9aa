"""DH -> PoE: the screw axes and M of every built-in robot and URDF example, the PoE fk
proven equal to the DH fk, and J_s, J_b equal to the DH Jacobian carried to their frames."""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import DHError
from dhsym.kinematics.jacobian import geometric_jacobian, numeric_jacobian
from dhsym.kinematics.simplification import prove_equal
from dhsym.model.library import builtin_names
from dhsym.robot import from_urdf
from dhsym.screws.algebra import adjoint
from dhsym.screws.product import (
    ProductOfExponentials,
    body_from_geometric,
    prove_same_fk,
    space_from_geometric,
)

URDF = Path(__file__).parents[1] / "data" / "urdf"
TIPS = {
    "ur5_robot.urdf": "tool0",
    "panda.urdf": "panda_hand_tcp",
    "kinova.urdf": "j2s6s200_end_effector",
}
#: proofs that take more than ~10 s on the loaded 2-core machine: the so100's offsets are
#: arctangents, whose sines and cosines are square roots of 40-digit integers (26 s at a
#: load average of 15, the import included; every other proof took 0.5–10 s there)
SLOW = {"so100.urdf"}


@functools.cache
def _robot(name: str) -> dhsym.Robot:
    if name.endswith(".urdf"):  # the UR5's tree branches: its chain ends at tool0
        return from_urdf(str(URDF / name), tip=TIPS.get(name))
    return dhsym.load(name)


#: arms with twisted, offset axes (the Jaco) and URDF imports with measured axes: their
#: PoE fk is also checked in numbers by a Rodrigues' formula written again here
INDEPENDENT = ["jaco", "so100.urdf", "panda.urdf", "kinova.urdf"]


def _names() -> list[object]:
    return [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in builtin_names()]


def _urdfs() -> list[object]:
    return [
        pytest.param(p.name, marks=pytest.mark.slow) if p.name in SLOW else p.name
        for p in sorted(URDF.glob("*.urdf"))
    ]


@pytest.mark.parametrize("name", _names())
def test_poe_fk_equals_dh_fk_exactly_for_every_built_in_robot(name: str) -> None:
    robot = _robot(name)
    assert prove_same_fk(robot.poe(), robot)


@pytest.mark.parametrize("name", _urdfs())
def test_poe_fk_equals_dh_fk_exactly_for_the_urdf_examples(name: str) -> None:
    robot = _robot(name)
    assert prove_same_fk(robot.poe(), robot)


def _numeric_exp(S: np.ndarray, theta: float) -> np.ndarray:
    """exp([S]θ) in numbers, Rodrigues' formula written again here (independent of
    dhsym.screws.algebra)."""
    w, v = S[:3], S[3:]
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    T = np.eye(4)
    if np.linalg.norm(w) < 1e-12:  # prismatic
        T[:3, 3] = v * theta
        return T
    R = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    G = np.eye(3) * theta + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W
    T[:3, :3], T[:3, 3] = R, G @ v
    return T


@pytest.mark.parametrize(
    "name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in INDEPENDENT]
)
def test_poe_fk_agrees_with_an_independent_exponential_in_numbers(name: str) -> None:
    robot = _robot(name)
    poe = robot.poe()
    vals = robot.table.value_map
    S = np.array(poe.screw_matrix("space").xreplace(vals).evalf(), dtype=float)
    M = np.array(poe.home.xreplace(vals).evalf(), dtype=float)
    rng = np.random.default_rng(5)
    for q in rng.uniform(-2, 2, size=(5, S.shape[1])):
        T = np.eye(4)
        for k, theta in enumerate(q):
            T = T @ _numeric_exp(S[:, k], theta)
        np.testing.assert_allclose(T @ M, robot.fk(q), atol=1e-9)


def test_a_wrong_axis_fails_the_proof() -> None:
    robot = _robot("planar2r")
    poe = robot.poe()
    S1, S2 = poe.space
    wrong = ProductOfExponentials(
        poe.name, poe.variables, (S1, S2.scaled(-1)), poe.home, poe.notation
    )
    assert not prove_same_fk(wrong, robot)


@pytest.mark.parametrize(
    "name", ["planar2r", "scara", "stanford", "cylindrical", "example1_rrp", "puma560_modified"]
)
def test_numbers_agree_with_dh_fk(name: str) -> None:
    robot = _robot(name)
    poe = robot.poe()
    rng = np.random.default_rng(3)
    q = rng.uniform(-2, 2, size=(5, robot.n))
    for frame in ("fk_space", "fk_body"):
        f = poe.function(frame)
        np.testing.assert_allclose(f(q), robot.fk(q), atol=1e-12)


def test_screw_axes_of_a_planar_arm() -> None:
    S, M = _robot("planar2r").screw_axes("space")
    a1, a2 = sp.symbols("a1 a2", real=True)
    assert S == sp.Matrix([[0, 0], [0, 0], [1, 1], [0, 0], [0, -a1], [0, 0]])
    assert M[:3, 3].T == sp.Matrix([[a1 + a2, 0, 0]])
    B, _ = _robot("planar2r").screw_axes("body")
    assert B == sp.Matrix([[0, 0], [0, 0], [1, 1], [0, 0], [a1 + a2, a2], [0, 0]])
    with pytest.raises(DHError, match="space or 'body'|'space' or 'body'"):
        _robot("planar2r").screw_axes("world")


def test_body_axes_are_the_space_axes_seen_from_m() -> None:
    poe = _robot("stanford").poe()
    Ad = adjoint(poe.home)
    for S, B in zip(poe.space, poe.body):
        assert sp.simplify(Ad * B.vector - S.vector) == sp.zeros(6, 1)


def test_steps_say_v_is_minus_omega_cross_q() -> None:
    poe = _robot("scara").poe()
    texts = [s.text(poe.notation) for s in poe.steps]
    assert len(texts) == 4
    assert texts[0].startswith("Joint 1 (R, theta1) turns about z of frame 0")
    assert "v1 = -omega1 x q1" in texts[0]
    assert any("slides along z" in t for t in texts)
    for s in poe.steps:
        if s.kind.value == "R":
            assert s.v == -s.omega.cross(s.point).applyfunc(sp.expand) or sp.simplify(
                s.v + s.omega.cross(s.point)
            ) == sp.zeros(3, 1)


def test_formula_prints_in_lecture_notation() -> None:
    poe = _robot("planar2r").poe()
    assert poe.formula_latex("space") == (
        r"T(\theta) = e^{[\mathcal{S}_{1}]\theta_{1}} e^{[\mathcal{S}_{2}]\theta_{2}} M"
    )
    assert poe.formula_text("body") == "T(theta) = M e^([B1]*theta1) e^([B2]*theta2)"


# --- Jacobians ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["planar2r", "stanford", "scara", "cylindrical", "example1_rrp"])
def test_space_and_body_jacobians_equal_the_dh_jacobian_in_their_frames_exactly(
    name: str,
) -> None:
    robot = _robot(name)
    poe = robot.poe()
    J0 = geometric_jacobian(robot, "base").matrix
    Je = geometric_jacobian(robot, "tool").matrix
    T = robot.plain_transform(0, robot.n)
    assert robot.table.base == () and robot.table.tool == ()
    assert prove_equal(poe.jacobian_space().matrix, space_from_geometric(J0, T))
    assert prove_equal(poe.jacobian_body().matrix, body_from_geometric(Je))


def test_space_jacobian_is_the_adjoint_of_the_body_jacobian() -> None:
    robot = _robot("stanford")
    poe = robot.poe()
    T = poe.fk_space().matrix
    assert prove_equal(poe.jacobian_space().matrix, adjoint(T) * poe.jacobian_body().matrix)


@pytest.mark.parametrize("name", _names() + _urdfs())
def test_jacobian_numbers_equal_jacob0_and_jacobe_carried(name: str) -> None:
    """For every built-in robot and URDF example: ``robot.jacobian_space(q)`` and
    ``jacobian_body(q)`` (the adjoint products of the screw axes, in numbers) equal the DH
    geometric Jacobian carried to their frames."""
    robot = _robot(name)
    rng = np.random.default_rng(7)
    for q in rng.uniform(-2, 2, size=(3, robot.n)):
        # the DH Jacobian from the frames in numbers (nothing derived: the Panda's exact
        # Jacobian takes a minute to write out), carried to the tool by R
        J0, T = numeric_jacobian(robot, q), robot.fk(q)
        Rt = T[:3, :3].T
        Je = np.vstack([Rt @ J0[:3], Rt @ J0[3:]])
        p = T[:3, 3]
        px = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
        Js = np.vstack([J0[3:], J0[:3] + px @ J0[3:]])
        Jb = np.vstack([Je[3:], Je[:3]])
        np.testing.assert_allclose(robot.jacobian_space(q), Js, atol=1e-12)
        np.testing.assert_allclose(robot.jacobian_body(q), Jb, atol=1e-12)


#: the exact J_s and J_b compiled, against the numbers of the adjoint products (two methods);
#: the LWR4's and the Jaco's exact Jacobians take minutes to write out and are left out
@pytest.mark.parametrize("name", ["ur5", "puma560", "puma560_modified", "stanford"])
def test_exact_jacobians_compiled_equal_their_numbers(name: str) -> None:
    robot = _robot(name)
    poe = robot.poe()
    q = np.random.default_rng(3).uniform(-2, 2, size=(4, robot.n))
    np.testing.assert_allclose(
        poe.function("jacobian_space")(q), robot.jacobian_space(q), atol=1e-12
    )
    np.testing.assert_allclose(poe.function("jacobian_body")(q), robot.jacobian_body(q), atol=1e-12)


def test_jacobians_batch_and_exact_forms() -> None:
    robot = _robot("planar2r")
    q = np.array([[0.1, 0.2], [0.3, -0.4], [1.0, 2.0]])
    assert robot.jacobian_space(q).shape == (3, 6, 2)
    assert robot.jacobian_body(q, values={"a1": 2}).shape == (3, 6, 2)
    Js = robot.jacobian_space()
    assert Js.frame == "space" and "S1" in Js.text() and "C" not in Js.text().split("S1")[0]
    with pytest.raises(DHError, match="values need q"):
        robot.jacobian_body(values={"a1": 2})


def test_singularities_from_the_determinant() -> None:
    robot = _robot("puma560")
    det = robot.poe().jacobian_determinant("body")
    # the lecture's factors: the wrist (S5), the elbow and the shoulder
    theta5 = sp.Symbol("theta5", real=True)
    assert det.subs(theta5, 0) == 0
    q = np.array([0.2, -0.4, 0.5, 0.3, 0.9, -0.6])
    value = float(det.subs(dict(zip(robot.variables, q))).subs(robot.table.value_map))
    Jb = robot.jacobian_body(q)
    assert value == pytest.approx(np.linalg.det(Jb), rel=1e-9)
    # det J_s = det J_b (det Ad_T = 1) = -det J (rows [v; w] swapped)
    assert np.linalg.det(robot.jacobian_space(q)) == pytest.approx(value, rel=1e-9)
    assert np.linalg.det(robot.jacob0(q)) == pytest.approx(-value, rel=1e-9)
    with pytest.raises(DHError, match="square"):
        _robot("planar2r").poe().jacobian_determinant()
