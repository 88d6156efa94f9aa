"""The families of closed forms: classification, UR (three parallel axes), the chain read
backwards, seven joints with one given, limits and the nearest solution."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.ik import StructureError, classify, numeric_ik
from dhsym.ik.choices import sweep_free_joint
from dhsym.ik.inverted import reversed_table

DATA = Path(__file__).parents[1] / "data" / "rtb"


def _random_q(robot: dhsym.Robot, n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(-np.pi, np.pi, (n, len(robot.variables)))


def _recovered(robot: dhsym.Robot, q: np.ndarray, **kw: object) -> np.ndarray:
    """For each row of q: True when a solution of ik(fk(q)) equals it modulo 2π."""
    batch = robot.ik(robot.fk(q), **kw)
    d = batch.q - q[:, None, :]
    d = np.abs(np.angle(np.exp(1j * d)))  # angle differences modulo 2π
    return np.nan_to_num(d, nan=np.inf).max(axis=-1).min(axis=-1) < 1e-7


def test_the_classification_is_printed_from_the_axes_in_either_convention() -> None:
    ur5 = dhsym.load("ur5")
    assert str(classify(ur5)) == "axes 2, 3, 4 parallel"
    assert classify(ur5).family == "three parallel axes"
    modified = dhsym.Robot(dhsym.to_modified(ur5.table))
    assert str(classify(modified)) == "axes 2, 3, 4 parallel"
    assert str(classify(dhsym.load("puma560"))) == "axes 4, 5, 6 meet in a point"
    assert classify(dhsym.load("panda")).sentences == ("axes 1, 2, 3 meet in a point",)


def test_ur5_has_eight_named_solutions() -> None:
    r = dhsym.load("ur5")
    q = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.4])
    sol = r.ik(r.fk(q))
    assert len(sol) == 8 and len(set(sol.branches)) == 8
    assert np.abs(r.fk_function()(sol.q) - r.fk(q)).max() < 1e-9
    assert np.abs(sol.q - q).max(axis=1).min() < 1e-9


@pytest.mark.slow
@pytest.mark.parametrize("name", ["ur3", "ur5", "ur10"])
def test_ur_recovers_a_thousand_random_configurations(name: str) -> None:
    r = dhsym.load(name)
    q = _random_q(r, 1000)
    ok = _recovered(r, q)
    # the few misses are configurations within rounding of sin θ5 = 0 (none in 1,000 draws)
    assert ok.mean() == 1.0


@pytest.mark.slow
def test_ur5_in_modified_dh_is_solved_directly() -> None:
    r = dhsym.Robot(dhsym.to_modified(dhsym.load("ur5").table))
    assert r.inverse().family == "three parallel axes"
    q = _random_q(r, 1000, seed=1)
    assert _recovered(r, q).all()


@pytest.mark.slow
def test_a_chain_whose_first_three_axes_meet_is_solved_backwards() -> None:
    puma = dhsym.load("puma560")
    back = dhsym.Robot(reversed_table(puma.table))
    assert classify(back).family == "inverted chain"
    ik = back.inverse()
    assert ik.family == "inverted chain" and ik.count == 8
    q = _random_q(back, 1000, seed=2)
    assert _recovered(back, q).mean() > 0.999
    # and the reversed chain's pose is the inverse of the arm's
    qa = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert np.allclose(back.fk(-qa[::-1]), np.linalg.inv(puma.fk(qa)))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["irb140", "kr5", "puma560", "ur3", "ur5", "ur10"])
def test_roboticstoolbox_six_joint_models_are_solved(name: str) -> None:
    r = dhsym.load(DATA / f"{name}.yaml")
    q = _random_q(r, 200, seed=3)
    assert _recovered(r, q).mean() > 0.99


@pytest.mark.slow
@pytest.mark.parametrize("name", ["panda", "kuka_lwr4"])
def test_seven_joints_with_one_given_recover_q(name: str) -> None:
    r = dhsym.load(name)
    rng = np.random.default_rng(4)
    lo = np.array([float(row.limits[0]) for row in r.table.rows])
    hi = np.array([float(row.limits[1]) for row in r.table.rows])
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


def test_closed_form_and_levenberg_marquardt_agree_on_ur5() -> None:
    r = dhsym.load("ur5")
    q = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.4])
    found = numeric_ik(r, r.fk(q), q + 0.05)
    assert found.converged
    sol = r.ik(r.fk(q))
    d = np.angle(np.exp(1j * (sol.q - found.q)))
    assert np.abs(d).max(axis=1).min() < 1e-8


def test_a_general_6r_is_refused_in_one_clear_sentence() -> None:
    table = dhsym.load("puma560").table
    rows = list(table.rows)
    from dataclasses import replace

    rows[4] = replace(rows[4], a=0.05)
    rows[1] = replace(rows[1], alpha=0.3)
    r = dhsym.Robot(replace(table, rows=tuple(rows)))
    assert classify(r).family == "general 6R"
    with pytest.raises(StructureError, match="general 6R: not yet solvable in closed form"):
        r.inverse()


def test_qlim_is_read_as_limits() -> None:
    row = "{type: R, theta: q1, d: 0, a: 1, alpha: 0, qlim: [-1, 2]}"
    text = f"convention: standard\njoints:\n  - {row}\n"
    t = dhsym.read_table_text(text)
    assert tuple(float(v) for v in t.rows[0].limits) == (-1.0, 2.0)
    with pytest.raises(dhsym.TableError, match="not both"):
        dhsym.read_table_text(text.replace("qlim", "limits: [0, 1], qlim"))
