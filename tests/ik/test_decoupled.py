"""Closed-form inverse kinematics: derivation, every branch, singular poses, errors."""

from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np
import pytest
import sympy as sp
from hypothesis import example, given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.ik import IKSolution, StructureError, inverse, numeric_ik
from dhsym.ik.decoupled import derive_decoupled
from dhsym.model.parsing import symbol
from dhsym.model.table import DHRow, DHTable, Elementary


@functools.cache
def _robot(name: str) -> dhsym.Robot:
    if name == "planar3r":
        return dhsym.Robot(dhsym.load(name).table.with_values({"a1": 1.0, "a2": 0.8, "a3": 0.5}))
    if name == "user_kuka_like":  # a user table: shoulder offset forward (a1), spherical wrist
        rows = [
            DHRow.revolute("q1", d=0.4, a=0.15, alpha=-sp.pi / 2),
            DHRow.revolute("q2", a=0.6),
            DHRow.revolute("q3", a=0.12, alpha=sp.pi / 2),
            DHRow.revolute("q4", d=0.62, alpha=-sp.pi / 2),
            DHRow.revolute("q5", alpha=sp.pi / 2),
            DHRow.revolute("q6", d=0.1),
        ]
        return dhsym.Robot(DHTable.from_rows(rows, name="user arm"))
    if name == "oblique_wrist":  # wrist twists of 60° and -45°: the general wrist formulas
        rows = [
            DHRow.revolute("q1", d=0.4, alpha=sp.pi / 2),
            DHRow.revolute("q2", a=0.5),
            DHRow.revolute("q3", alpha=sp.pi / 2),
            DHRow.revolute("q4", d=0.45, alpha=sp.pi / 3),
            DHRow.revolute("q5", alpha=-sp.pi / 4),
            DHRow.revolute("q6", d=0.1),
        ]
        return dhsym.Robot(DHTable.from_rows(rows, name="oblique wrist"))
    if name == "wrist_alone":
        rows = [
            DHRow.revolute("q1", alpha=-sp.pi / 2),
            DHRow.revolute("q2", alpha=sp.pi / 2),
            DHRow.revolute("q3", d=0.1),
        ]
        return dhsym.Robot(DHTable.from_rows(rows, name="spherical wrist"))
    if name == "puma560_base_tool":
        table = dhsym.load("puma560").table
        base = (Elementary("T", "z", sp.Rational(1, 2)), Elementary("R", "z", sp.Rational(3, 10)))
        tool = (Elementary("T", "z", sp.Rational(1, 10)), Elementary("R", "x", sp.pi / 2))
        return dhsym.Robot(replace(table, base=base, tool=tool))
    return dhsym.load(name)


def _random_q(robot: dhsym.Robot, count: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (count, len(robot.variables)))
    for k, row in enumerate(r for r in robot.table.rows if r.variable is not None):
        if row.joint.value == "P":
            lo, hi = (float(v) for v in row.limits) if row.limits else (0.1, 0.8)
            q[:, k] = rng.uniform(max(lo, 0.05), hi, count)
    return q


def _angle_error(robot: dhsym.Robot, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    revolute = np.array([r.joint.value == "R" for r in robot.table.rows if r.variable is not None])
    d = a - b
    d[..., revolute] = np.remainder(d[..., revolute] + np.pi, 2 * np.pi) - np.pi
    return np.nan_to_num(np.abs(d), nan=np.inf).max(axis=-1)  # missing solutions: inf


SPEC = ["puma560", "puma560_modified", "stanford", "example4_6dof", "planar2r", "planar3r", "scara"]
MORE = [
    "puma260",
    "cylindrical",
    "cartesian",
    "example1_rrp",
    "user_kuka_like",
    "oblique_wrist",
    "wrist_alone",
    "puma560_base_tool",
]


@pytest.mark.parametrize("name", SPEC + MORE)
def test_ik_of_fk_contains_q_and_every_solution_reproduces_the_pose(name: str) -> None:
    robot = _robot(name)
    q = _random_q(robot, 1000, seed=7)
    T = robot.fk(q)
    batch = robot.ik(T)
    assert isinstance(batch, IKSolution) and batch.batch
    assert _angle_error(robot, batch.q, q[:, None, :]).min(axis=1).max() < 1e-7
    # recompute the error of every returned solution independently of the solver
    got = robot.fk(batch.q[batch.valid])
    want = np.repeat(T[:, None], batch.q.shape[1], axis=1)[batch.valid]
    assert np.abs(got - want).max() < 1e-9


@pytest.mark.parametrize(
    "name", ["puma560", "puma560_modified", "stanford", "example4_6dof", "puma260"]
)
def test_six_joint_arms_have_eight_solutions_none_silently_wrong(name: str) -> None:
    robot = _robot(name)
    q = _random_q(robot, 300, seed=11)
    T = robot.fk(q)
    raw = robot.ik(T, check=None)
    assert raw.valid.all()  # every branch is finite for these generic poses ...
    got = robot.fk(raw.q.reshape(-1, 6)).reshape(300, 8, 4, 4)
    assert np.abs(got - T[:, None]).max() < 1e-9  # ... and each one reaches the pose
    assert (robot.ik(T).count == 8).all()


def test_the_two_elbows_of_a_planar_2r_reach_the_same_point() -> None:
    robot = _robot("planar2r")
    p = robot.fk([0.4, 0.9])[:3, 3]
    sol = robot.ik(p)
    assert len(sol) == 2
    assert sorted(sol.branches) == ["elbow down", "elbow up"]
    assert np.allclose(robot.fk(sol.q)[:, :3, 3], p)
    # the whole pose (orientation included) has one solution
    assert len(robot.ik(robot.fk([0.4, 0.9]))) == 1
    assert robot.ik(robot.fk([0.4, 0.9])).branches == ("elbow down",)


def test_single_pose_result() -> None:
    robot = _robot("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    sol = robot.ik(robot.fk(q))
    assert isinstance(sol, IKSolution)
    assert np.asarray(sol).shape == (8, 6)
    assert len(set(sol.branches)) == 8
    assert all(b.count(",") == 2 for b in sol.branches)
    k = int(np.argmin(_angle_error(robot, sol.q, q)))
    assert sol.branches[k] == "right arm, elbow down, wrist not flipped"
    assert not sol.near_singular.any()
    one = robot.ik(robot.fk(q[None]))
    assert np.allclose(one.solution(0).q, sol.q)


def test_elbow_names_follow_the_geometry() -> None:
    robot = _robot("puma560")
    # at q = 0 the upper arm is horizontal and the forearm points up: the elbow is below
    # the line from the shoulder to the wrist centre; with theta3 = pi it is above it
    for q, name in [([0, 0, 0, 0, 0.5, 0], "elbow down"), ([0, 0, np.pi, 0, 0.5, 0], "elbow up")]:
        sol = robot.ik(robot.fk(q))
        k = int(np.argmin(_angle_error(robot, sol.q, np.array(q))))
        assert name in sol.branches[k]


def test_wrist_singularity_is_reported_and_still_exact() -> None:
    robot = _robot("puma560")
    for theta5 in (0.0, 1e-9, 1e-7, np.pi):
        q = np.array([0.3, -0.5, 0.4, 0.2, theta5, -1.1])
        T = robot.fk(q)
        sol = robot.ik(T)
        assert np.abs(robot.fk(sol.q) - T).max() < 1e-9
        k = int(np.argmin(_angle_error(robot, sol.q, q)))
        assert "wrist" in sol.singular[k]
    # at sin(theta5) = 0 only theta4 + theta6 is defined: theta4 is set to 0
    sol = robot.ik(robot.fk([0.3, -0.5, 0.4, 0.2, 0.0, -1.1]))
    # the solution with the same arm and θ5 = 0 (another branch may share θ6 = -0.9)
    k = int(np.argmin(np.abs(sol.q[:, :3] - [0.3, -0.5, 0.4]).max(axis=1) + np.abs(sol.q[:, 4])))
    assert np.allclose(sol.q[k, 3:], [0.0, 0.0, -0.9])


def test_elbow_boundary_is_reported() -> None:
    robot = _robot("puma560")
    t3 = float(np.arctan2(-0.4318, 0.0203))  # a3 S3 + d4 C3 = 0: arm stretched out
    q = np.array([0.3, -0.5, t3, 0.2, 0.7, -1.1])
    T = robot.fk(q)
    sol = robot.ik(T)
    assert len(sol) == 4  # the elbow branches coincide
    assert all("elbow" in s for s in sol.singular)
    assert np.abs(robot.fk(sol.q) - T).max() < 1e-9


def test_unreachable_pose_has_no_solution() -> None:
    robot = _robot("puma560")
    T = np.eye(4)
    T[:3, 3] = [3.0, 0.0, 0.0]
    sol = robot.ik(T)
    assert len(sol) == 0 and sol.q.shape == (0, 6)


def test_derivation_steps_are_exact_lecture_formulas() -> None:
    ik = inverse(_robot("puma560"))
    texts = [ik.text(s) for s in ik.steps]
    assert texts[:3] == ["c_x = p_x", "c_y = p_y", "c_z = p_z"]
    assert "r = sigma_1*sqrt(c_x**2 + c_y**2 - d3**2)" in texts
    assert "theta1 = atan2(c_y, c_x) - atan2(-d3, r)" in texts
    assert "theta2 = atan2(c_z, r) - atan2(a3*S3 + d4*C3, a2 + a3*C3 - d4*S3)" in texts
    assert [s.part for s in ik.steps][:1] == ["wrist centre"]
    assert {s.part for s in ik.steps} == {"wrist centre", "position", "orientation"}
    assert [b.role for b in ik.branches] == ["arm", "elbow", "wrist"]
    assert all(isinstance(s.rhs, sp.Expr) for s in ik.steps)
    assert all(s.text for s in ik.steps)
    # every atan2 and every root is explicit
    assert sum(s.rhs.has(sp.atan2) for s in ik.steps) >= 6
    latex = ik.latex(ik.steps[-1])
    assert latex.startswith(r"\theta_{6} = ")


def test_stanford_wrist_centre_moves_back_along_the_approach_vector() -> None:
    ik = inverse(_robot("stanford"))
    assert [ik.text(s) for s in ik.steps[:3]] == [
        "c_x = p_x - a_x*d6",
        "c_y = p_y - a_y*d6",
        "c_z = p_z - a_z*d6",
    ]
    assert [b.role for b in ik.branches] == ["arm", "reach", "wrist"]


def test_structure_is_detected_from_the_table_not_the_name() -> None:
    planar = inverse(_robot("planar3r"))
    assert planar.structure.startswith("last joint revolute")
    assert inverse(_robot("scara")).structure.startswith("last joint revolute")
    assert inverse(_robot("cartesian")).branches == ()
    assert inverse(_robot("wrist_alone")).structure.startswith("a spherical wrist alone")
    assert inverse(_robot("user_kuka_like")).structure.startswith("spherical wrist")


def test_missing_structure_is_named() -> None:
    with pytest.raises(StructureError, match="redundant"):
        inverse(_robot("planar4r"))
    table = dhsym.load("puma560").table
    rows = list(table.rows)
    rows[4] = replace(rows[4], a=symbol("a5"))  # wrist axes 5 and 6 no longer meet
    bent = dhsym.Robot(DHTable.from_rows(rows, values={**dict(table.values), "a5": 0.05}))
    with pytest.raises(StructureError, match="do not meet in one point"):
        derive_decoupled(bent)
    assert inverse(bent).family == "general 6R"  # solved by the elimination instead
    with pytest.raises(StructureError, match="more than 6|redundant"):
        inverse(dhsym.load("planar7r"))


def test_dhsym_inverse_is_callable_after_importing_the_module() -> None:
    import dhsym.ik.families  # noqa: F401  (a module of the same idea must not shadow dhsym.inverse)

    assert dhsym.inverse(_robot("planar2r")).count == 2


def test_numeric_solver_is_labelled_and_converges_nearby() -> None:
    robot = _robot("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    sol = numeric_ik(robot, robot.fk(q), q + 0.1)
    assert sol.converged and sol.method == "numeric"
    assert np.abs(robot.fk(sol.q) - robot.fk(q)).max() < 1e-9


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-3.1, 3.1), min_size=6, max_size=6))
@example([0.0, 0.5, -0.75, 1.0, 1.192092896e-07, 0.0])  # found by hypothesis: θ4, θ6 mixed programs
def test_property_every_solution_reproduces_the_pose(q: list[float]) -> None:
    robot = _robot("puma560_modified")
    T = robot.fk(q)
    sol = robot.ik(T, check=None)
    assert np.abs(robot.fk(sol.q) - T).max() < 1e-9
    if _angle_error(robot, sol.q, np.array(q)).min() < 1e-6:
        return
    # at sin(theta5) = 0 only theta4 + theta6 is defined: an equivalent solution, flagged
    d = np.remainder(sol.q - np.array(q) + np.pi, 2 * np.pi) - np.pi
    same_arm = np.abs(d[:, [0, 1, 2, 4]]).max(axis=1) < 1e-6
    assert any("wrist" in sol.singular[k] for k in np.nonzero(same_arm)[0])


def test_inputs_are_checked() -> None:
    with pytest.raises(dhsym.DHError, match="no numeric value for a1, a2, a3"):
        dhsym.load("planar3r").ik(np.eye(4))
    with pytest.raises(dhsym.DHError, match="give a full 4×4 pose"):
        _robot("puma560").ik([0.3, 0.1, 0.2])
    with pytest.raises(dhsym.DHError, match="expected poses of shape"):
        _robot("puma560").ik(np.eye(5))


def test_empty_batch() -> None:
    batch = _robot("puma560").ik(np.zeros((0, 4, 4)))
    assert batch.q.shape == (0, 8, 6) and batch.count.shape == (0,)


# --- the two compiled programs: one pose by floats, a batch by numpy ------------------------


def _same_solutions(robot: dhsym.Robot, one: IKSolution, other: IKSolution) -> None:
    assert len(one) == len(other)
    assert (one.signs == other.signs).all()
    if len(one):
        assert _angle_error(robot, one.q, other.q).max() < 1e-12  # angles mod 2π
    assert np.allclose(one.residual, other.residual, rtol=0, atol=1e-12)
    assert one.singular == other.singular


@pytest.mark.parametrize("name", SPEC + MORE)
def test_one_pose_by_floats_equals_the_batch(name: str) -> None:
    robot = _robot(name)
    solver = robot.ik_cache().solver()
    q = _random_q(robot, 40, seed=5)
    T = robot.fk(q)
    batch = robot.ik(T)
    for i in range(len(T)):
        one = solver._solve_one(T[i], "pose", tuple(range(12)), 1e-9, 1e-6)
        assert one is not None  # generic poses: the float program finishes them
        _same_solutions(robot, one, batch.solution(i))
        # ... and it is what robot.ik gives for one pose
        _same_solutions(robot, robot.ik(T[i]), one)


@pytest.mark.parametrize("check", ["pose", "position", None])
def test_one_pose_by_floats_equals_the_batch_unchecked_and_unreachable(check: str | None) -> None:
    robot = _robot("puma560")
    T = robot.fk(_random_q(robot, 20, seed=9))
    far = T.copy()
    far[:, :3, 3] *= 3.0  # out of reach: no real branch
    for poses in (T, far):
        batch = robot.ik(poses, check=check)
        for i in range(len(poses)):
            _same_solutions(robot, robot.ik(poses[i], check=check), batch.solution(i))
    assert robot.ik(far[0]).q.shape == (0, 6)
    if check == "position":  # the residual is the position's error only
        one = robot.ik(T[0], check=check)
        error = np.abs(robot.fk(one.q)[:, :3, 3] - T[0, :3, 3]).max(axis=1)
        assert np.abs(one.residual - error).max() < 1e-13


def test_positions_by_floats_equal_the_batch() -> None:
    robot = _robot("planar2r")
    p = robot.fk(_random_q(robot, 20, seed=3))[:, :3, 3]
    batch = robot.ik(p)
    assert (batch.count == 2).all()
    for i in range(len(p)):
        _same_solutions(robot, robot.ik(p[i]), batch.solution(i))


def test_reported_residual_is_the_fk_error_of_the_returned_angles() -> None:
    for name in ("puma560", "stanford", "puma560_base_tool", "scara"):
        robot = _robot(name)
        T = robot.fk(_random_q(robot, 200, seed=13))
        batch = robot.ik(T, check=None)
        got = robot.fk(batch.q[batch.valid])
        want = np.repeat(T[:, None], batch.q.shape[1], axis=1)[batch.valid]
        independent = np.abs(got - want)[:, :3].reshape(len(got), -1).max(axis=1)
        assert np.abs(batch.residual[batch.valid] - independent).max() < 1e-13
        one = robot.ik(T[0], check=None)
        assert np.abs(one.residual - np.abs(robot.fk(one.q) - T[0]).max(axis=(1, 2))).max() < 1e-13


def test_poses_that_are_not_numbers_have_no_solution() -> None:
    robot = _robot("puma560")
    for bad in (np.full((4, 4), np.nan), np.full((4, 4), np.inf)):
        assert len(robot.ik(bad)) == 0
        assert robot.ik(bad[None]).count.tolist() == [0]


def test_raw_branches_are_the_unchecked_solutions() -> None:
    robot = _robot("puma560")
    T = robot.fk(_random_q(robot, 50, seed=17))
    raw = robot.ik_cache().solver().raw(T)
    unchecked = robot.ik(T, check=None)
    assert raw.shape == unchecked.q.shape == (50, 8, 6)
    assert unchecked.valid.all()  # generic poses: all eight are real
    # two programs (one without the check), so equal up to rounding
    assert _angle_error(robot, raw, unchecked.q).max() < 1e-12


def test_signs_come_out_of_sines_cosines_and_wraps_exactly() -> None:
    from dhsym.ik.rewriting import pull_signs as _pull_signs
    from dhsym.ik.rewriting import trig_signs as _trig_signs

    s, t = sp.symbols("sigma_1 sigma_2", real=True)
    x, y = sp.symbols("x y", real=True)
    for e, inside in [
        (sp.cos(s * x), set()),
        (sp.sin(s * x) * sp.cos(t * y), set()),
        (sp.sin(x + sp.pi * (1 - s) / 2), set()),
        (sp.cos(x - sp.pi * (1 - s) / 2 + t * y), {t}),  # x + σ2·y is neither odd nor shifted
        (sp.sin(s * t * x), set()),
        (sp.cos(x + s * y), {s}),
    ]:
        rewritten = _trig_signs(e, {s, t})
        for a, b in [(1, 1), (1, -1), (-1, 1), (-1, -1)]:
            at = {s: a, t: b, x: 0.37, y: -1.21}
            assert abs(float(e.subs(at)) - float(rewritten.subs(at))) < 1e-15
        left = set().union(*(f.args[0].free_symbols for f in rewritten.atoms(sp.sin, sp.cos)))
        assert left & {s, t} == inside
    # a step x = π(1 − σ)/2 + atan2(Y, X) keeps the shift out of the stored value
    steps = [(x, sp.pi * (1 - s) / 2 + sp.atan2(y, 2))]
    program, (out,) = _pull_signs(steps, [sp.cos(x)], [s])
    assert program[0][1] == sp.atan2(y, 2)
    assert out.has(s) and not any(f.args[0].has(s) for f in out.atoms(sp.cos))


@pytest.mark.parametrize("name", ["puma560", "puma560_modified", "stanford", "example4_6dof"])
def test_near_a_singular_wrist_theta4_and_theta6_stay_consistent(name: str) -> None:
    robot = _robot(name)
    rng = np.random.default_rng(3)
    q = rng.uniform(-3, 3, (400, 6))
    q[:, 4] = rng.choice([0.0, 1e-9, 1.192092896e-07, 1e-6, 9e-6], 400) * rng.choice([-1, 1], 400)
    T = robot.fk(q)
    for check in (None, "pose"):
        batch = robot.ik(T, check=check)
        for k in range(len(q)):
            sol = batch.solution(k) if hasattr(batch, "solution") else batch[k]
            assert len(sol.q) >= 1
            assert np.abs(robot.fk(sol.q) - T[k]).max() < 1e-9
