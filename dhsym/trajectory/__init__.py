"""Trajectories: time profiles derived from their boundary conditions (cubic, quintic,
linear segments with parabolic blends, the minimum-time profile, via points and cubic
splines) and paths of an arm in joint space and in a straight Cartesian line.

May import model, notation, kinematics and ik (``docs/architecture.md``).
"""

from __future__ import annotations

from .blends import lspb, minimum_time, trapezoidal
from .paths import CartesianPath, JointPath, ctraj, jtraj
from .profiles import Derivation, Profile, Segment, cubic, quintic
from .via import mstraj, spline, via_blends, via_cubic

__all__ = [
    "CartesianPath",
    "JointPath",
    "ctraj",
    "jtraj",
    "Derivation",
    "Profile",
    "Segment",
    "cubic",
    "lspb",
    "minimum_time",
    "mstraj",
    "quintic",
    "spline",
    "trapezoidal",
    "via_blends",
    "via_cubic",
]
