"""Every tolerance and sample range of the checker, in one frozen value.

The checker decides numerically in several places (entries at random points, tables
by their frames, inverse kinematics by the poses it reaches, decimals by the rounding
they allow). Each of those reads its numbers from :data:`TOLERANCES`, so a course or
a test can see, and a change can touch, all of them at once.

Examples
--------
>>> TOLERANCES.agree_rtol, TOLERANCES.revolute_range
(1e-09, (-3.141592653589793, 3.141592653589793))
>>> from dataclasses import replace
>>> replace(TOLERANCES, ik_atol=1e-6).ik_atol
1e-06
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["TOLERANCES", "Tolerances"]


@dataclass(frozen=True)
class Tolerances:
    """The checker's numeric tolerances (named) and the ranges it samples from.

    Attributes
    ----------
    agree_rtol
        Two values agree at a sample point when they differ by less than this, relative
        to ``1 + |key|``: double precision with room for round-off (entries, the
        rounding slack).
    ik_atol
        Joint values of a symbolic inverse-kinematics answer agree with the key's
        (radians, or lengths relative to ``1 + |q|``).
    reach_atol
        An inverse-kinematics answer reaches the asked pose (entries of ``^0T_n``).
    cell_atol
        Two table cells are the same number (relative to ``1 + |key|``; angles modulo 2π).
    frame_rtol
        Two tables place the same joint axes (relative to the size of the arm).
    vertical_eps, short_length, pick_axis_eps
        Where the table check's geometry degenerates: a line along ``z``
        (``|u_z² − 1|``), a length that is zero, a direction too close to ``x`` to
        build a frame from it.
    symbol_range, revolute_range, prismatic_range, length_range
        Sample ranges: the symbols of an answer, revolute and prismatic joint values,
        the lengths of a table (positive, so that square roots of the key stay real).
    """

    agree_rtol: float = 1e-9
    ik_atol: float = 1e-8
    reach_atol: float = 1e-7
    cell_atol: float = 1e-6
    frame_rtol: float = 1e-3
    vertical_eps: float = 1e-9
    short_length: float = 1e-7
    pick_axis_eps: float = 1e-6
    symbol_range: tuple[float, float] = (-2.5, 2.5)
    revolute_range: tuple[float, float] = (-math.pi, math.pi)
    prismatic_range: tuple[float, float] = (0.2, 1.5)
    length_range: tuple[float, float] = (0.3, 1.5)


#: The tolerances every checker uses.
TOLERANCES = Tolerances()
