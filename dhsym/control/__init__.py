"""Control on the arm's own dynamics: PD, PD + gravity compensation, computed torque and
PID as small frozen objects giving τ(t, q, q̇), the closed-loop error equation and its
gains, and the closed loop simulated with model error and disturbances.

May import model, notation, kinematics, ik, dynamics and trajectory (``docs/architecture.md``).
"""

from __future__ import annotations

from .controllers import (
    PD,
    PID,
    ComputedTorque,
    ErrorEquation,
    PDGravity,
    Reference,
    error_equation,
    gains,
)
from .simulation import ClosedLoop, scaled_model, simulate

__all__ = [
    "PD",
    "PID",
    "ClosedLoop",
    "ComputedTorque",
    "ErrorEquation",
    "PDGravity",
    "Reference",
    "error_equation",
    "gains",
    "scaled_model",
    "simulate",
]
