r"""A control law on the arm's own dynamics: the closed loop simulated with the robot's
compiled dynamics (:meth:`~dhsym.dynamics.compiled_dynamics.DynamicsFunctions.simulate`,
fixed-step RK4), with an optional disturbance torque, and controllers that believe in a
model with scaled inertias (:func:`scaled_model`).

A PID's integral is summed per step of ``dt`` from the error at the step's start (a
digital controller's sample-and-hold), the arm integrated by RK4 within each step.

Examples
--------
>>> from dhsym.kinematics.chain import KinematicChain
>>> from dhsym.model.tablefile import read_table_text
>>> from dhsym.control.controllers import PDGravity
>>> pendulum = KinematicChain(read_table_text('''
... gravity: [0, -9.81, 0]
... joints: [{type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}]
... '''))
>>> from dhsym.dynamics.compiled_dynamics import dynamics_functions
>>> f = dynamics_functions(pendulum)
>>> run = simulate(pendulum, PDGravity(25, 10, [0.5], model=f), 3.0, q0=[0.0])
>>> bool(abs(run.error[-1, 0]) < 1e-3)
True
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from functools import partial
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError

from .controllers import PID, Reference

if TYPE_CHECKING:
    from dhsym.dynamics.compiled_dynamics import DynamicsFunctions
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["ClosedLoop", "plant_of", "scaled_model", "simulate"]


@dataclass(frozen=True)
class ClosedLoop:
    """A simulated closed loop: times ``t`` ``(T,)``; the arm's ``q``, ``qd``, the
    reference ``q_ref``, ``qd_ref``, ``qdd_ref``, the controller's torque ``tau`` and the
    disturbance ``disturbance``, all ``(T, n)``; ``error = q_ref − q``."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    q_ref: np.ndarray
    qd_ref: np.ndarray
    qdd_ref: np.ndarray
    tau: np.ndarray
    disturbance: np.ndarray

    @property
    def error(self) -> np.ndarray:
        """The tracking error ``q_ref − q`` ``(T, n)``."""
        e: np.ndarray = self.q_ref - self.q
        return e

    @property
    def max_error(self) -> float:
        """The largest tracking error of any joint at any time."""
        return float(np.abs(self.error).max())


def plant_of(
    robot: KinematicChain, values: Mapping[object, object] | None = None
) -> DynamicsFunctions:
    """The compiled dynamics of ``robot`` (a ``Robot``'s own, cached; else compiled)."""
    own = getattr(robot, "dynamics_functions", None)
    if callable(own):
        functions: DynamicsFunctions = own(values)
        return functions
    from dhsym.dynamics.compiled_dynamics import dynamics_functions

    return dynamics_functions(robot, values)


def scaled_model(
    robot: KinematicChain, factor: object, values: Mapping[object, object] | None = None
) -> DynamicsFunctions:
    """The compiled dynamics of ``robot`` with every link's mass, inertia tensor and motor
    inertia multiplied by ``factor`` (``1.1``: a model 10 % heavier than the arm), the
    centres of mass kept: the model a controller with model error believes in.

    >>> from dhsym.kinematics.chain import KinematicChain
    >>> from dhsym.model.tablefile import read_table_text
    >>> arm = KinematicChain(read_table_text('''
    ... gravity: [0, -9.81, 0]
    ... joints:
    ...   - {type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}
    ... '''))
    >>> scaled_model(arm, 1.1).inertia([0.0])
    array([[0.66]])
    """
    from dhsym.dynamics.compiled_dynamics import DynamicsFunctions, numeric_model
    from dhsym.model.entries import as_expr

    k = as_expr(factor, field="factor")
    if k.is_number and not bool(k > 0):
        raise DHError(f"scaled_model: factor must be positive, got {k}")
    dm = numeric_model(robot, values)
    links = tuple(
        replace(L, m=L.m * k, I=sp.ImmutableMatrix(L.I * k), Jm=L.Jm * k) for L in dm.links
    )
    return DynamicsFunctions(replace(dm, links=links))


def _disturbance(d: object, n: int) -> Callable[[float], np.ndarray]:
    if d is None:
        return lambda t: np.zeros(n)
    if callable(d):
        return lambda t: np.broadcast_to(np.asarray(d(t), dtype=float), (n,))
    const = np.broadcast_to(np.asarray(d, dtype=float), (n,))
    return lambda t: const


def _held_drive(
    pid: PID,
    dist: Callable[[float], np.ndarray],
    start: float,
    held: np.ndarray,
    t: float,
    q: np.ndarray,
    v: np.ndarray,
) -> np.ndarray:
    """The PID's torque within one step begun at ``start``, its integral ``held``."""
    out: np.ndarray = pid(start + t, q, v, held) + dist(start + t)
    return out


def _run_pid(
    plant: DynamicsFunctions,
    pid: PID,
    dist: Callable[[float], np.ndarray],
    Q0: np.ndarray,
    V0: np.ndarray,
    steps: int,
    h: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Step by step: RK4 over one step with the integral held, then the integral summed."""
    sums = [np.zeros_like(Q0)]
    qs, vs = [Q0], [V0]
    for k in range(steps):
        start, held = k * h, sums[-1]
        drive = partial(_held_drive, pid, dist, start, held)
        step = plant.simulate(qs[-1], vs[-1], h, dt=h, tau=drive)
        sums.append(held + h * pid.error(start, qs[-1]))
        qs.append(step.q[-1])
        vs.append(step.qd[-1])
    t = np.linspace(0.0, steps * h, steps + 1)
    q, qd = np.stack(qs), np.stack(vs)
    tau = np.stack([pid(ti, qi, vi, si) for ti, qi, vi, si in zip(t, q, qd, sums)])
    return t, q, qd, tau


def simulate(
    robot: KinematicChain,
    controller: Callable[..., np.ndarray],
    duration: float,
    *,
    q0: object = None,
    qd0: object = None,
    dt: float = 1e-3,
    disturbance: object = None,
    values: Mapping[object, object] | None = None,
) -> ClosedLoop:
    """The arm ``robot`` (its true dynamics, with ``values``) driven by ``controller`` for
    ``duration`` s, plus a ``disturbance`` torque (constant ``(n,)`` or ``d(t)``); the
    start is the reference's at 0 unless ``q0``, ``qd0`` are given."""
    plant = plant_of(robot, values)
    n = plant.n
    ref = Reference.of(getattr(controller, "reference", None))
    r0, v0, _ = ref.at(0.0)
    if r0.size != n:
        raise DHError(f"simulate: the reference has {r0.size} joints, the arm {n}")
    Q0 = r0 if q0 is None else np.asarray(q0, dtype=float)
    V0 = v0 if qd0 is None else np.asarray(qd0, dtype=float)
    dist = _disturbance(disturbance, n)
    steps = max(1, int(round(duration / dt)))
    h = duration / steps
    if isinstance(controller, PID):
        t, q, qd, tau = _run_pid(plant, controller, dist, Q0, V0, steps, h)
    else:
        law = controller

        def drive(t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
            out: np.ndarray = law(t, q, v) + dist(t)
            return out

        run = plant.simulate(Q0, V0, duration, dt=dt, tau=drive)
        t, q, qd = run.t, run.q, run.qd
        tau = np.stack([law(ti, qi, vi) for ti, qi, vi in zip(t, q, qd)])
    refs = [ref.at(float(ti)) for ti in t]
    return ClosedLoop(
        t,
        q,
        qd,
        np.stack([r[0] for r in refs]),
        np.stack([r[1] for r in refs]),
        np.stack([r[2] for r in refs]),
        tau,
        np.stack([dist(float(ti)) for ti in t]),
    )
