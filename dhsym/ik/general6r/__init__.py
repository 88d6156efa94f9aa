"""The general 6R: every real inverse-kinematics solution (up to 16) by Raghavan–Roth elimination.

For an arm whose axes neither meet nor run parallel in any closed-form pattern (the
Kinova Jaco and Mico, a random 6R), the inverse kinematics reduces to one polynomial of
degree 16 in the half-angle tangent of one joint (Raghavan and Roth, "Inverse kinematics
of the general 6R manipulator and related linkages", ASME J. Mech. Des. 115, 1993), solved
as a matrix eigenproblem (Manocha and Canny, "Efficient inverse kinematics for general
6R manipulators", IEEE Trans. Robot. Autom. 10(5), 1994). One module per idea:

* :mod:`.elimination`: the arm in standard form and the fourteen equations
  ``P(θ3) m45 = Q m12``, exact (:func:`elimination_matrices`);
* :mod:`.eigenproblem`: the same in numbers, one eigenproblem per pose, compiled and
  self-tested once per arm (:func:`general_6r`, :class:`General6R`);
* :mod:`.method`: the method explained as steps, the :class:`Elimination` that
  ``Robot.inverse()`` returns for such an arm (:func:`derive_general`);
* :mod:`.elimination_solver`: the :class:`EliminationSolver` behind ``Robot.ik``.

An arm for which the elimination degenerates (``Q`` loses rank or ``Σ`` is singular for
every x3: the PUMA, UR arms, any arm with a spherical wrist or three parallel axes) is
first retried with the chain reversed; if that fails too, :func:`general_6r` raises
:class:`~dhsym.errors.DHError` naming the closed-form families instead. Prismatic joints
are refused.

Examples
--------
>>> from dhsym.model.library import builtin_table
>>> general_6r(builtin_table("puma560"))
General6R('PUMA 560', eliminated joint 4, 16×16 pencil)
"""

from .eigenproblem import General6R, general_6r
from .elimination import (
    EQUATIONS,
    EliminationMatrices,
    StandardLink,
    elimination_matrices,
    standard_chain,
)
from .elimination_solver import EliminationSolver
from .method import MOST, Elimination, derive_general

__all__ = [
    "EQUATIONS",
    "MOST",
    "Elimination",
    "EliminationMatrices",
    "EliminationSolver",
    "General6R",
    "StandardLink",
    "derive_general",
    "elimination_matrices",
    "general_6r",
    "standard_chain",
]
