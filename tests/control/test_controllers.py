"""Control laws: gains and the derived error equation; closed loops on Spong's 2R and the
PUMA 560 (computed torque with the exact model tracks to 1e-9; with 10 % inertia error
the error stays within the bound the error equation gives)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.control import (
    PD,
    PID,
    ComputedTorque,
    PDGravity,
    error_equation,
    gains,
    scaled_model,
    simulate,
)
from dhsym.errors import DHError
from dhsym.trajectory import quintic

PENDULUM = """
gravity: [0, -9.81, 0]
joints:
  - {type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}
"""


@pytest.fixture(scope="module")
def pendulum() -> dhsym.Robot:
    from dhsym.model.tablefile import read_table_text

    return dhsym.Robot(read_table_text(PENDULUM))


def test_gains_and_error_equation() -> None:
    assert gains(10) == (100, 20)
    assert gains(sp.Rational(1, 2), 2) == (sp.Rational(1, 4), 2)
    with pytest.raises(DHError, match="omega must be positive"):
        gains(0)
    d = error_equation()
    t = sp.Symbol("t", real=True)
    e = sp.Function("e")(t)
    Kp, Kd = sp.symbols("K_p K_d", real=True)
    assert sp.simplify(d.equation.lhs - (e.diff(t, 2) + Kd * e.diff(t) + Kp * e)) == 0
    w, z = sp.symbols("omega zeta", positive=True)
    assert d.gains.solution == (w**2, 2 * z * w) and d.gains.check()


def test_pd_leaves_a_gravity_offset_pd_gravity_does_not(pendulum: dhsym.Robot) -> None:
    model = pendulum.dynamics_functions()
    kp, kd = (float(g) for g in gains(5))
    pd = simulate(pendulum, PD(kp, kd, [0.5]), 6.0, q0=[0.0])
    pdg = simulate(pendulum, PDGravity(kp, kd, [0.5], model=model), 6.0, q0=[0.0])
    # PD's steady state: K_p e = g(q) at the final q = q_d − e, an offset
    e, q = pd.error[-1, 0], pd.q[-1]
    assert e > 0.1 and abs(kp * e - model.gravload(q)[0]) < 1e-3 * kp * e
    assert abs(pdg.error[-1, 0]) < 1e-3


def test_pid_removes_a_constant_disturbance(pendulum: dhsym.Robot) -> None:
    model = pendulum.dynamics_functions()
    kp, kd = (float(g) for g in gains(5))
    pdg = simulate(
        pendulum, PDGravity(kp, kd, [0.5], model=model), 8.0, q0=[0.5], disturbance=[2.0], dt=2e-3
    )
    pid = simulate(
        pendulum,
        PID(kp, kd, [0.5], Ki=40.0, model=model),
        8.0,
        q0=[0.5],
        disturbance=[2.0],
        dt=2e-3,
    )
    assert abs(pdg.error[-1, 0] + 2.0 / kp) < 1e-3  # the disturbance's offset -d/K_p
    assert abs(pid.error[-1, 0]) < 1e-3
    assert np.allclose(pid.disturbance, 2.0)


def test_computed_torque_on_the_2r_tracks(pendulum: dhsym.Robot) -> None:
    ref = quintic([0.0], [1.0], 1)
    kp, kd = (float(g) for g in gains(10))
    run = simulate(pendulum, ComputedTorque(kp, kd, ref, model=pendulum.dynamics_functions()), 1.2)
    assert run.max_error < 1e-9
    np.testing.assert_allclose(run.q_ref[-1], [1.0])


def _error_bound(robot: dhsym.Robot, run, kp: float, kd: float) -> np.ndarray:  # type: ignore[no-untyped-def]
    """sup|e| ≤ sup|η|/K_p for ë + K_d ė + K_p e = η with a critically damped loop from
    rest (the impulse response t e^{−ωt} ≥ 0 has integral 1/ω²)."""
    plant = robot.dynamics_functions()
    qdd = plant.accel(run.q, run.qd, run.tau)
    e, ed = run.error, run.qd_ref - run.qd
    eta = (run.qdd_ref - qdd) + kd * ed + kp * e
    return np.abs(eta).max(axis=0) / kp


@pytest.mark.slow
def test_puma_computed_torque_exact_and_with_inertia_error() -> None:
    r = dhsym.load("puma560")
    qa = np.array([0.0, -0.5, 0.3, 0.1, 0.4, -0.2])
    qb = np.array([0.6, -0.2, -0.1, 0.5, 0.9, 0.3])
    ref = quintic(qa, qb, 1)
    kp, kd = (float(g) for g in gains(10))
    exact = simulate(r, ComputedTorque(kp, kd, ref, model=r.dynamics_functions()), 1.0)
    assert exact.max_error < 1e-9
    heavy = simulate(r, ComputedTorque(kp, kd, ref, model=scaled_model(r, 1.1)), 1.0)
    bound = _error_bound(r, heavy, kp, kd)
    worst = np.abs(heavy.error).max(axis=0)
    assert heavy.max_error > 1e-6  # the model error shows
    assert np.all(worst <= 1.01 * bound + 1e-12), (worst, bound)
