"""A joint given (seven-joint arms), the sweep, joint limits and the nearest solution."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.ik.choices import sweep_free_joint


def _table_limits(r: dhsym.Robot) -> tuple[np.ndarray, np.ndarray]:
    """The lower and upper joint limits of the table (every row has them)."""
    lo = np.array([float(row.limits[0]) for row in r.table.rows])
    hi = np.array([float(row.limits[1]) for row in r.table.rows])
    return lo, hi


@pytest.mark.slow
@pytest.mark.parametrize("name", ["panda", "kuka_lwr4"])
def test_seven_joints_with_one_given_recover_q(name: str) -> None:
    r = dhsym.load(name)
    rng = np.random.default_rng(4)
    lo, hi = _table_limits(r)
    for q in rng.uniform(lo, hi, (20, 7)):
        sol = r.ik(r.fk(q), free={7: q[6]})
        d = np.angle(np.exp(1j * (sol.q - q)))  # modulo 2π
        assert np.abs(d).max(axis=1).min() < 1e-8


@pytest.mark.slow
def test_the_sweep_lists_branches_within_limits() -> None:
    r = dhsym.load("panda")
    q = [0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7]
    found = sweep_free_joint(r, r.fk(q), 7, num=8)
    assert found
    lo = np.array([float(row.limits[0]) for row in r.table.rows])
    hi = np.array([float(row.limits[1]) for row in r.table.rows])
    for value, sol in found:
        assert np.all(sol.q >= lo - 1e-9) and np.all(sol.q <= hi + 1e-9)
        assert np.allclose(sol.q[:, 6], value)


def test_limits_shift_by_two_pi_and_drop_the_rest() -> None:
    r = dhsym.load("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    every = r.ik(r.fk(q))
    kept = r.ik(r.fk(q), limits=True)
    assert 0 < len(kept) < len(every)
    lo = np.array([float(row.limits[0].xreplace(r.table.value_map)) for row in r.table.rows])
    hi = np.array([float(row.limits[1].xreplace(r.table.value_map)) for row in r.table.rows])
    assert np.all((kept.q >= lo) & (kept.q <= hi))


def test_near_orders_by_distance() -> None:
    r = dhsym.load("ur5")
    q = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.4])
    sol = r.ik(r.fk(q), near=q + 0.01)
    assert np.abs(sol.q[0] - q).max() < 1e-9
    d = np.linalg.norm(np.angle(np.exp(1j * (sol.q - q - 0.01))), axis=1)
    assert np.all(np.diff(d) >= -1e-12)


def test_a_joint_in_the_middle_can_be_given() -> None:
    # a PUMA 560 with one more joint about z3, between the elbow and the wrist
    from dhsym.model.table import DHRow, DHTable

    puma = dhsym.load("puma560").table
    extra = DHRow.revolute("theta7")
    rows = puma.rows[:3] + (extra,) + puma.rows[3:]
    r = dhsym.Robot(DHTable.from_rows(rows, values=dict(puma.values)))
    q = np.array([0.3, -0.5, 0.4, 0.25, 0.2, 0.7, -1.1])
    sol = r.ik(r.fk(q), free={4: 0.25})
    assert len(sol) == 8
    assert np.abs(sol.q - q).max(axis=1).min() < 1e-9


@pytest.mark.slow
@pytest.mark.parametrize("name", ["panda", "kuka_lwr4"])
def test_any_joint_of_a_seven_joint_arm_can_be_given(name: str) -> None:
    # issue 32, item 4: free={k: v} for every k; where no closed form exists with joint k
    # given (the Panda's joint 4 raised "phi2, phi3 appear together"), the general 6R or
    # the numeric solver answers and the result says which
    r = dhsym.load(name)
    rng = np.random.default_rng(32)
    lo, hi = _table_limits(r)
    methods = {}
    for k in range(1, 8):
        q = rng.uniform(lo, hi)
        T = r.fk(q)
        sol = r.ik(T, free={k: q[k - 1]})
        assert len(sol), (k, sol.reason)
        assert np.all(sol.q[:, k - 1] == q[k - 1])  # the given joint stays at its value
        assert np.abs(r.fk(sol.q) - T).max() <= 1e-9  # each reproduces the pose
        assert sol.residual.max() <= 1e-9
        methods[k] = sol.method
        if sol.method == "numeric":
            assert sol.iterations and all(b.startswith("numeric solution") for b in sol.branches)
    assert methods[7] == "closed form" and "numeric" in methods.values()


def test_the_numeric_answer_with_a_joint_given_says_it_is_numeric() -> None:
    r = dhsym.load("panda")
    q = [0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7]
    sol = r.ik(r.fk(q), free={4: -2.0})
    assert sol.method == "numeric" and sol.converged and sol.iterations > 0
    d = np.angle(np.exp(1j * (sol.q - q)))
    assert np.abs(d).max(axis=1).min() < 1e-8  # the start at zero finds the arm's own q
    assert sol.branches[0] == "numeric solution 1"
    # joint 4 of the LWR4 given leaves a self-motion (two spherical joints): said so
    lwr = dhsym.load("kuka_lwr4")
    sol = lwr.ik(lwr.fk(q), free={4: -2.0})
    assert all(s == ("self-motion",) for s in sol.singular)
    assert all("one of a continuum" in b for b in sol.branches)


def test_an_unreachable_pose_with_a_joint_given_numerically_gets_a_reason() -> None:
    r = dhsym.load("panda")
    T = r.fk([0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7])
    T[:3, 3] *= 5  # far beyond the reach of the arm
    sol = r.ik(T, free={4: -2.0})
    assert len(sol) == 0 and sol.method == "numeric"
    assert "no start of 24 converged" in sol.reason and "smallest error" in sol.reason


@pytest.mark.parametrize("name", ["puma560", "stanford"])
@pytest.mark.parametrize("theta5", [0.0, np.pi])
def test_a_singular_wrist_names_the_combination_that_is_determined(name, theta5) -> None:
    # issue 32, item 2: "θ4 + θ6 = 0.7 is all that is determined", not nothing
    r = dhsym.load(name)
    q = np.array([0.3, -0.5, 0.4, 0.2, theta5, -1.1])
    T = r.fk(q)
    sol = r.ik(T)
    assert sol.note is not None and "the wrist is singular" in sol.note
    text = "θ4 + θ6" if theta5 == 0 else "θ6 − θ4"
    value = float(np.angle(np.exp(1j * (q[3] + q[5] if theta5 == 0 else q[5] - q[3]))))
    assert f"{text} = {value:.4g} is all that is determined" in sol.note
    # the family it names keeps the pose: θ4 moved by t, θ6 by ∓t
    row = sol.q[np.nonzero(sol.near_singular)[0][0]].copy()
    for t in (0.5, -1.2):
        moved = row.copy()
        moved[3] += t
        moved[5] += -t if theta5 == 0 else t
        assert np.abs(r.fk(moved) - T).max() < 1e-9


def test_a_regular_pose_has_no_family_note() -> None:
    r = dhsym.load("puma560")
    assert r.ik(r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])).note is None


def test_batch_tolerances_are_each_poses_own() -> None:
    """A batch's poses get the tolerance each has alone (pose_accuracy): exact poses told
    at once, rounded, NaN, infinite, reflected and slightly perturbed ones measured."""
    from dhsym.ik.accuracy import FLOOR, pose_accuracy
    from dhsym.ik.choices import _tolerances

    r = dhsym.load("puma560")
    T = r.fk(np.random.default_rng(3).uniform(-3.0, 3.0, (80, 6)))
    T[10:20] = np.round(T[10:20], 6)
    T[20:30] = np.round(T[20:30], 3)
    T[30:33] = np.nan
    T[33:36, 0, 0] = np.inf
    T[36:40, :3, 0] *= -1.0  # a reflection: RᵀR = I, det R = -1
    T[40:45, :3, :3] += 1e-11
    got = _tolerances(T, "pose", None)
    want = np.array([pose_accuracy(x).tol for x in T])
    assert np.array_equal(got, want)
    assert (got[:10] == FLOOR).all() and (got[20:30] > FLOOR).all() and (got[36:40] > FLOOR).all()


@pytest.mark.parametrize("name", ["ur5", "ur3"])
@pytest.mark.parametrize("theta5", [0.0, np.pi])
def test_a_ur_singular_wrist_names_the_sum_of_the_parallel_joints(name, theta5) -> None:
    # issue 32, item 2: joints 2, 3, 4 and 6 turn about parallel axes at θ5 = 0 or π; only
    # θ2 + θ3 + θ4 ± θ6 is determined, θ6 may be chosen and the others follow
    from dhsym.ik.levenberg_marquardt import numeric_ik

    r = dhsym.load(name)
    q = np.array([0.3, -1.1, 1.4, -0.6, theta5, 0.4])
    T = r.fk(q)
    sol = r.ik(T)
    assert sol.note is not None
    sign = 1 if theta5 == 0 else -1
    text = "θ2 + θ3 + θ4 + θ6" if theta5 == 0 else "θ2 + θ3 + θ4 − θ6"
    value = float(np.angle(np.exp(1j * (q[1] + q[2] + q[3] + sign * q[5]))))
    assert sol.note.startswith(f"θ5 = {0 if theta5 == 0 else 3.142}: the wrist is singular")
    assert "(joints 2, 3, 4 and 6 turn about parallel axes)" in sol.note
    assert f"{text} = {value:.4g} is all that is determined" in sol.note
    # the stated choice is the first singular solution's θ6
    row = sol.q[np.nonzero(sol.near_singular)[0][0]]
    assert f"given with θ6 = {float(np.angle(np.exp(1j * row[5]))):.4g})" in sol.note
    # the family it names keeps the pose: another θ6, the other joints found again (fk),
    # the sum unchanged
    for t in (0.2, -0.25):
        start = row.copy()
        start[5] += t
        moved = numeric_ik(r, T, start, fixed={6: start[5]}).q[0]
        assert np.abs(r.fk(moved) - T).max() < 1e-9
        d = moved[1] + moved[2] + moved[3] + sign * moved[5] - value
        assert abs(np.angle(np.exp(1j * d))) < 1e-9
        assert abs(moved[1] - row[1]) > 1e-3  # a family, not one point


def test_a_regular_ur5_pose_has_no_family_note() -> None:
    r = dhsym.load("ur5")
    sol = r.ik(r.fk([0.3, -1.1, 1.4, -0.6, 1.2, 0.4]))
    assert sol.note is None and not sol.near_singular.any()
