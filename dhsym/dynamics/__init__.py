"""Robot dynamics: the equations of motion of a DH chain, derived as the lecture does.

Owns the inertial model of a chain, Lagrange–Euler and recursive Newton–Euler (both DH
conventions), statics, the regressor and base parameters, and their compiled numbers.
May import ``model``, ``notation`` and ``kinematics``.
"""

from __future__ import annotations

from dhsym._lazy import public_dir

from .compact_form import CompactDynamics, GroupedConstant, compact_dynamics
from .equations import EquationsOfMotion, NEStep
from .inertial_parameters import BaseParameters, Regressor, base_parameters, regressor
from .lagrange_euler import lagrange
from .model import DynamicModel, dynamic_model, rate_symbols
from .recursive_newton_euler import newton_euler
from .static_forces import Statics, static_torques, statics

__all__ = [
    "BaseParameters",
    "CompactDynamics",
    "GroupedConstant",
    "compact_dynamics",
    "DynamicModel",
    "Regressor",
    "Statics",
    "base_parameters",
    "regressor",
    "static_torques",
    "statics",
    "EquationsOfMotion",
    "NEStep",
    "dynamic_model",
    "lagrange",
    "newton_euler",
    "rate_symbols",
]


def __dir__() -> list[str]:
    return public_dir(__name__)
