"""A joint given (seven-joint arms), the sweep, joint limits and the nearest solution."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.ik.choices import sweep_free_joint


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
