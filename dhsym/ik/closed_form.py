"""The derived closed form of one robot: its structure, its steps and branches, its solver.

Every family of :mod:`dhsym.ik` returns an :class:`InverseKinematics`: the sentence
that names the structure it found, the steps (each ``symbol = exact expression``), the
branches (signs ``σ = ±1``) and, compiled on first use, the solver of
:mod:`dhsym.ik.compiler`.

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

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.decoupling import Decoupling
from dhsym.kinematics.numeric import values_key

from .steps import Branch, Step

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

    from .compiler import Solver
    from .general import EliminationSolver
    from .results import IKBatch, IKSolution

__all__ = ["InverseKinematics"]

Matrix: TypeAlias = sp.ImmutableMatrix


@dataclass(frozen=True)
class InverseKinematics:
    """The derived closed-form inverse kinematics of one robot: steps and a solver.

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
    #: compiled solvers by the values they were built with (filled on first use): the
    #: steps compiled (:class:`~dhsym.ik.compiler.Solver`), or the general 6R's
    #: elimination (:class:`~dhsym.ik.general.EliminationSolver`)
    solvers: dict[object, Solver | EliminationSolver] = field(
        default_factory=dict, compare=False, repr=False, hash=False
    )
    #: the most solutions when they are not branch combinations (16 for the general 6R)
    most: int | None = None
    #: how a family without compiled steps builds its solver (the general 6R: its
    #: elimination, :meth:`~dhsym.ik.general.EliminationSolver.build`); None: the steps
    #: compiled by :class:`~dhsym.ik.compiler.Solver`
    build_solver: (
        Callable[[InverseKinematics, Mapping[object, object] | None], EliminationSolver] | None
    ) = field(default=None, compare=False, repr=False)

    @property
    def count(self) -> int:
        """Number of branch combinations (solutions of a generic pose), or the most
        solutions a pose can have (the general 6R: 16)."""
        return self.most if self.most is not None else 2 ** len(self.branches)

    def text(self, step: Step) -> str:
        """``lhs = rhs`` in plain text, compact notation."""
        nota = self.robot.notation
        return f"{nota.text(step.lhs)} = {nota.text(step.rhs)}"

    def latex(self, step: Step) -> str:
        """``lhs = rhs`` in LaTeX, compact notation."""
        nota = self.robot.notation
        return f"{nota.latex(step.lhs)} = {nota.latex(step.rhs)}"

    def solver(self, values: Mapping[object, object] | None = None) -> Solver | EliminationSolver:
        """The compiled solver (built once per set of values, then kept in ``solvers``):
        the steps compiled, or for the general 6R (no steps to compile: they describe the
        method) its elimination with these values."""
        from .compiler import Solver

        key = values_key(values)  # the values as given: converted only once
        if key not in self.solvers:
            if self.build_solver is not None:
                self.solvers[key] = self.build_solver(self, values)
            else:
                numbers = self.robot.table.with_values(values or {}).value_map
                self.solvers[key] = Solver(self, numbers)
        return self.solvers[key]

    def solve(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float = 1e-9,
        singular_tol: float = 1e-6,
        values: Mapping[object, object] | None = None,
    ) -> IKSolution | IKBatch:
        """All solutions for one pose ``(4, 4)`` or a batch ``(N, 4, 4)`` (see
        :class:`~dhsym.ik.compiler.Solver`)."""
        return self.solver(values).solve(T, check=check, tol=tol, singular_tol=singular_tol)
