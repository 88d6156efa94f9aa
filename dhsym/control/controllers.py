r"""Joint-space control laws, each a small frozen object giving ``τ(t, q, q̇)``, their
closed-loop error equations, and the gains for a natural frequency and damping.

With the reference ``q_d(t)`` (a :class:`~dhsym.trajectory.profiles.Profile` or a set
point) and ``e = q_d − q`` (Spong–Hutchinson–Vidyasagar, *Robot Modeling and Control*,
ch. 8 and 9; Craig, *Introduction to Robotics*, ch. 10):

* :class:`PD`: ``τ = K_p e + K_d ė``;
* :class:`PDGravity`: ``τ = K_p e + K_d ė + g(q)`` (the model's gravity);
* :class:`ComputedTorque`: ``τ = M(q)(q̈_d + K_d ė + K_p e) + C(q, q̇) q̇ + g(q)`` (the
  model's inverse dynamics), so that with an exact model ``ë + K_d ė + K_p e = 0``
  (:func:`error_equation`);
* :class:`PID`: ``τ = K_p e + K_d ė + K_i ∫e`` (+ ``g(q)`` with a model); its integral is a
  state, kept by :func:`dhsym.control.simulation.simulate` step by step.

Gains are per joint (a number or one per joint); :func:`gains` gives ``K_p = ω²``,
``K_d = 2ζω``.

Examples
--------
>>> kp, kd = gains(10)
>>> kp, kd
(100, 20)
>>> law = PD(kp, kd, reference=[1.0, 0.0])
>>> law(0.0, np.array([0.5, 0.0]), np.zeros(2))
array([50.,  0.])
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.model.entries import as_expr
from dhsym.trajectory.profiles import Derivation, Profile

if TYPE_CHECKING:
    from dhsym.dynamics.compiled_dynamics import DynamicsFunctions

__all__ = [
    "PD",
    "PID",
    "ComputedTorque",
    "PDGravity",
    "Reference",
    "ErrorEquation",
    "error_equation",
    "gains",
]


def gains(omega: object, zeta: object = 1) -> tuple[sp.Expr, sp.Expr]:
    r"""``(K_p, K_d) = (ω², 2ζω)``: the gains that make ``ë + K_d ė + K_p e = 0`` the
    second-order system of natural frequency ``ω`` and damping ratio ``ζ`` (``ζ = 1``:
    critically damped, the fastest response without overshoot). Exact.

    >>> w, z = sp.symbols("omega zeta", positive=True)
    >>> gains(w, z)
    (omega**2, 2*omega*zeta)
    >>> gains(4, 0.5)
    (16, 4)
    """
    w, z = as_expr(omega, field="omega"), as_expr(zeta, field="zeta")
    for name, v in (("omega", w), ("zeta", z)):
        if v.is_number and not bool(v > 0):
            raise DHError(f"gains: {name} must be positive, got {v}")
    return w**2, 2 * z * w


@dataclass(frozen=True)
class ErrorEquation:
    """The closed loop of a control law, derived: ``steps`` (a label and an equation
    each, from the arm's equation to the error equation) and ``gains``, the
    :class:`~dhsym.trajectory.profiles.Derivation` of the gains from the characteristic
    polynomial."""

    steps: tuple[tuple[str, sp.Eq], ...]
    gains: Derivation

    @property
    def equation(self) -> sp.Eq:
        """The error equation ``ë + K_d ė + K_p e = 0``."""
        return self.steps[-1][1]


def error_equation() -> ErrorEquation:
    r"""The closed loop of computed torque, derived: the arm ``M q̈ + h = τ`` (``h = C q̇ +
    g``) under ``τ = M (q̈_d + K_d ė + K_p e) + h`` gives ``M (ë + K_d ė + K_p e) = 0``;
    ``M`` is invertible, so ``ë + K_d ė + K_p e = 0``, whose characteristic polynomial
    ``s² + K_d s + K_p`` matched to ``s² + 2ζω s + ω²`` gives the gains.

    >>> d = error_equation()
    >>> d.equation
    Eq(K_d*Derivative(e(t), t) + K_p*e(t) + Derivative(e(t), (t, 2)), 0)
    >>> d.gains.pairs, d.gains.check()
    (((K_p, omega**2), (K_d, 2*omega*zeta)), True)
    """
    t = sp.Symbol("t", real=True)
    M, h, Kp, Kd = sp.symbols("M h K_p K_d", real=True)
    w, z, s = sp.symbols("omega zeta s", positive=True)
    q, qd = sp.Function("q")(t), sp.Function("q_d")(t)
    e = qd - q
    tau = M * (qd.diff(t, 2) + Kd * e.diff(t) + Kp * e) + h
    arm = sp.Eq(M * q.diff(t, 2) + h, tau, evaluate=False)
    E = sp.Function("e")(t)
    error = sp.Eq(E.diff(t, 2) + Kd * E.diff(t) + Kp * E, 0)
    closed = sp.Eq(M * error.lhs, 0, evaluate=False)
    poly = sp.Poly(s**2 + Kd * s + Kp - (s**2 + 2 * z * w * s + w**2), s)
    match = [sp.Eq(c, 0, evaluate=False) for c in poly.all_coeffs() if c != 0]
    solution = sp.solve([m.lhs for m in match], [Kp, Kd], dict=True)[0]
    # the closed loop is M times the error equation: checked, not assumed
    difference = sp.simplify((arm.rhs - arm.lhs) - M * error.lhs.subs(E, e).doit())
    if difference != 0:  # pragma: no cover - the algebra above
        raise DHError(f"error_equation: the closed loop is not M (ë + K_d ė + K_p e): {difference}")
    gains = Derivation(
        labels=tuple("s² + K_d s + K_p = s² + 2ζω s + ω²" for _ in match),
        equations=tuple(match),
        unknowns=(Kp, Kd),
        solution=(solution[Kp], solution[Kd]),
    )
    return ErrorEquation(
        (
            ("the arm under the computed torque", arm),
            ("h cancels and M factors out", closed),
            ("M is invertible: the error equation", error),
        ),
        gains,
    )


@dataclass(frozen=True, eq=False)
class Reference:
    """What the joints should do: a profile (``q_d(t)``, ``q̇_d``, ``q̈_d``) or a set point
    (at rest)."""

    profile: Profile | None = None
    setpoint: np.ndarray | None = None

    @classmethod
    def of(cls, value: object) -> Reference:
        """A reference from a profile, a set point or a reference.

        >>> Reference.of([0.1, 0.2]).at(3.0)[0]
        array([0.1, 0.2])
        """
        if isinstance(value, Reference):
            return value
        if isinstance(value, Profile):
            return cls(profile=value)
        point = np.asarray(value, dtype=float).reshape(-1)
        if not np.all(np.isfinite(point)):
            raise DHError("reference: a set point of finite numbers")
        return cls(setpoint=point)

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(q_d, q̇_d, q̈_d)`` at time ``t`` (a profile rests at its end after ``t_f``)."""
        if self.profile is not None:
            tf = float(self.profile.duration)
            q, qd, qdd = self.profile.sample([min(max(t, 0.0), tf)])
            if t > tf:
                return q.reshape(-1), np.zeros(q.size), np.zeros(q.size)
            return q.reshape(-1), qd.reshape(-1), qdd.reshape(-1)
        assert self.setpoint is not None
        zero = np.zeros_like(self.setpoint)
        return self.setpoint, zero, zero


def _gain(value: object, name: str) -> np.ndarray:
    g = np.asarray(value, dtype=float)
    if g.ndim > 1 or not np.all(np.isfinite(g)) or np.any(g < 0):
        raise DHError(f"{name}: a gain of nonnegative numbers, one or one per joint")
    return g


@dataclass(frozen=True, eq=False)
class PD:
    """``τ = K_p e + K_d ė`` toward ``reference``."""

    Kp: object
    Kd: object
    reference: object = field(default=None)

    def _errors(self, t: float, q: np.ndarray, qd: np.ndarray) -> tuple[np.ndarray, ...]:
        qr, vr, ar = Reference.of(self.reference).at(t)
        return qr - q, vr - qd, ar

    def __call__(self, t: float, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        e, ed, _ = self._errors(t, q, qd)
        out: np.ndarray = _gain(self.Kp, "Kp") * e + _gain(self.Kd, "Kd") * ed
        return out


@dataclass(frozen=True, eq=False)
class PDGravity(PD):
    """``τ = K_p e + K_d ė + g(q)``, the gravity of ``model`` (the compiled dynamics the
    controller believes in)."""

    model: DynamicsFunctions | None = None

    def __call__(self, t: float, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        if self.model is None:
            raise DHError("PDGravity: give the model (robot.dynamics_functions())")
        out: np.ndarray = super().__call__(t, q, qd) + self.model.gravload(q)
        return out


@dataclass(frozen=True, eq=False)
class ComputedTorque(PD):
    """``τ = M(q)(q̈_d + K_d ė + K_p e) + C q̇ + g``: the inverse dynamics of ``model`` at
    the commanded acceleration (one call of its Newton–Euler recursion)."""

    model: DynamicsFunctions | None = None

    def __call__(self, t: float, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        if self.model is None:
            raise DHError("ComputedTorque: give the model (robot.dynamics_functions())")
        e, ed, ar = self._errors(t, q, qd)
        v = ar + _gain(self.Kd, "Kd") * ed + _gain(self.Kp, "Kp") * e
        return self.model.rne(q, qd, v)


@dataclass(frozen=True, eq=False)
class PID(PD):
    """``τ = K_p e + K_d ė + K_i ∫e`` (+ ``g(q)`` when ``model`` is given). Called as
    ``τ(t, q, q̇, integral)``: the integral of the error is the caller's state
    (:func:`dhsym.control.simulation.simulate` keeps it)."""

    Ki: object = 0.0
    model: DynamicsFunctions | None = None

    def __call__(
        self, t: float, q: np.ndarray, qd: np.ndarray, integral: np.ndarray | None = None
    ) -> np.ndarray:
        tau = super().__call__(t, q, qd)
        if integral is not None:
            tau = tau + _gain(self.Ki, "Ki") * integral
        if self.model is not None:
            tau = tau + self.model.gravload(q)
        return tau

    def error(self, t: float, q: np.ndarray) -> np.ndarray:
        """``e = q_d(t) − q``, what the integral sums."""
        qr, _, _ = Reference.of(self.reference).at(t)
        e: np.ndarray = qr - q
        return e
