"""Control on the arm's own dynamics: PD, PD + gravity compensation, computed torque and
PID as small frozen objects giving τ(t, q, q̇), the closed-loop error equation and its
gains, the closed loop simulated with model error and disturbances, and its tracking
error and torques drawn (matplotlib, imported when drawing).

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
from .tracking_plots import plot_torques, plot_tracking_error

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
    "plot_torques",
    "plot_tracking_error",
    "scaled_model",
    "simulate",
]
