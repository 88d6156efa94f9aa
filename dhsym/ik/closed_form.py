"""The derived closed form of one robot: its structure, its steps and branches.

Every family of :mod:`dhsym.ik` but the general 6R returns a :class:`ClosedForm`: the
sentence that names the structure it found, the steps (each ``symbol = exact
expression``), the branches (signs ``σ = ±1``) and the decoupling. The solver of
:mod:`dhsym.ik.closed_form_solver` compiles it into numbers.

Examples
--------
>>> import dhsym
>>> ik = dhsym.load("planar2r").inverse()
>>> ik.family, ik.count
('positioning arm', 2)
>>> ik.text(ik.steps[0])
'D_2 = (p_x**2 + p_y**2 - a1**2 - a2**2)/(2*a1*a2)'
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.decoupling import Decoupling

from .steps import Branch, Step, step_latex, step_text

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["ClosedForm"]

Matrix: TypeAlias = sp.ImmutableMatrix


@dataclass(frozen=True)
class ClosedForm:
    """The derived closed-form inverse kinematics of one robot, as lecture steps.

    ``steps`` are in order; each defines one symbol (an intermediate quantity or a joint
    variable) from the pose symbols ``pose``, earlier symbols and the branch signs
    ``branches``. Every combination of signs is one solution (``2 ** len(branches)``).
    ``family`` names the family that solved it (``"spherical wrist"``, ``"three parallel
    axes"``, …) and ``structure`` says, in a sentence, what was recognised in the table.
    ``decoupling`` says which joints place a point (``arm``) and which turn about it
    (``wrist``), and which frame's origin that point is (``centre``).
    """

    robot: KinematicChain = field(compare=False, repr=False)
    structure: str
    decoupling: Decoupling
    pose: Matrix
    steps: tuple[Step, ...]
    branches: tuple[Branch, ...]
    family: str = "spherical wrist"

    @property
    def count(self) -> int:
        """Number of branch combinations (solutions of a generic pose)."""
        return int(2 ** len(self.branches))

    def text(self, step: Step) -> str:
        """``lhs = rhs`` in plain text, compact notation."""
        return step_text(self.robot, step)

    def latex(self, step: Step) -> str:
        """``lhs = rhs`` in LaTeX, compact notation."""
        return step_latex(self.robot, step)
