"""The general 6R as a derivation: the Raghavan–Roth elimination explained as steps.

An arm with six revolute joints where no three consecutive axes are parallel or meet in
a point (the Kinova Jaco and Mico) has no closed form by decoupling. Its pose equations
reduce to one polynomial of degree 16 in the half-angle tangent of one joint (Raghavan
and Roth, 1993), solved as a matrix eigenproblem (Manocha and Canny, 1994).
:func:`derive_general` writes that method as the steps of an :class:`Elimination`: no
branch signs, up to 16 solutions, named ``solution 1`` … in the order of their joint
values by :class:`~dhsym.ik.general6r.elimination_solver.EliminationSolver`.

Examples
--------
>>> import dhsym
>>> ik = dhsym.load("jaco").inverse()
>>> type(ik).__name__, ik.family, ik.count, ik.structure
('Elimination', 'general 6R', 16, 'no three consecutive axes parallel or meeting: general 6R')
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.decoupling import StructureError
from dhsym.model.table import JointType
from dhsym.notation.layout import sentence

from ..steps import REAL, Branch, Step, pose_symbols, step_latex, step_text
from ..structure import GENERAL_6R
from .eigenproblem import General6R, general_6r

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["MOST", "Elimination", "derive_general"]

Matrix: TypeAlias = sp.ImmutableMatrix

#: the most real solutions a general 6R has (the degree of the eliminant)
MOST = 16


@dataclass(frozen=True)
class Elimination:
    """The general 6R's inverse kinematics: the elimination explained as steps.

    ``steps`` explain the method (the split of the loop, the fourteen equations, the
    eigenproblem); they define no branch signs (``branches`` is empty) and are not
    compiled: the solver is the eigenproblem, ``core`` when every length has a number
    (compiled while deriving), else built with the values given. ``count`` is the most
    real solutions a pose can have (16).
    """

    robot: KinematicChain = field(compare=False, repr=False)
    structure: str
    pose: Matrix
    steps: tuple[Step, ...]
    family: str = GENERAL_6R
    #: the compiled elimination with the table's own values (None: lengths without numbers)
    core: General6R | None = field(default=None, compare=False, repr=False)

    @property
    def branches(self) -> tuple[Branch, ...]:
        """No branch signs: the solutions are the real eigenvalues, numbered."""
        return ()

    @property
    def count(self) -> int:
        """The most real solutions of one pose (the degree of the eliminant, 16)."""
        return MOST

    def text(self, step: Step) -> str:
        """``lhs = rhs`` in plain text, compact notation."""
        return step_text(self.robot, step)

    def latex(self, step: Step) -> str:
        """``lhs = rhs`` in LaTeX, compact notation."""
        return step_latex(self.robot, step)


def _all_numbers(robot: KinematicChain) -> bool:
    known = robot.table.value_map
    return all(s in known for s in robot.table.constants)


def derive_general(robot: KinematicChain) -> Elimination:
    """The general 6R by Raghavan–Roth elimination, as the steps that explain it.

    With numbers for every length the elimination is compiled here (about a second; it
    fails for an arm on which it degenerates, a :class:`StructureError`), kept in
    :attr:`Elimination.core` and its first equation shown; with symbolic lengths
    ``Robot.ik`` needs ``values=``.

    >>> import dhsym
    >>> ik = derive_general(dhsym.load("jaco"))
    >>> [s.part for s in ik.steps]
    ['elimination', 'elimination', 'eigenproblem']
    >>> derive_general(dhsym.load("stanford"))
    Traceback (most recent call last):
    ...
    dhsym.kinematics.decoupling.StructureError: general 6R: joint 3 is prismatic ...
    """
    table = robot.table
    rows = table.joint_rows
    if len(rows) != 6:
        raise StructureError(f"general 6R: this family has 6 joints, not {len(rows)}")
    if table.n != 6:  # a constant row between joints (a joint of a longer arm given)
        raise StructureError(
            f"general 6R: the elimination takes six rows, one per joint; this table has "
            f"{table.n} (a fixed row between joints)"
        )
    for k, r in enumerate(rows, start=1):
        if table.rows[r - 1].joint is not JointType.REVOLUTE:
            raise StructureError(
                f"general 6R: joint {k} is prismatic (the elimination takes revolute joints)"
            )
    q = list(robot.variables)
    core = None
    if _all_numbers(robot):
        fk = robot.fk_function()
        try:
            core = general_6r(table, fk=fk, tol=1e-6)
        except DHError as err:
            raise StructureError(f"general 6R: {err.message}") from err
    k = core.eliminated if core is not None else 3
    x = sp.Symbol(f"x_{k}", **REAL)
    # the chain angles of the elimination are the table's θ entries (±q + offset)
    angle = [table.rows[r - 1].theta for r in rows]
    theta = q[k - 1]
    steps = []
    order = "as given" if k == 3 else "read backwards (from the tool to the base)"
    loop = sentence(
        "Split the loop, with the chain " + order + ", as A3 A4 A5 = A2⁻¹ A1⁻¹ T A6⁻¹: the "
        "third and fourth columns of the right side, a direction l and a point p, do not "
        "depend on the last joint. Pieper's six equations (p and l) and Raghavan and Roth's "
        "eight (p·p, p·l, p×l, (p·p) l − 2 (p·l) p) are fourteen equations "
        "P(θ3) m45 = Q m12, P 14×9 and Q 14×8: linear in the nine products m45 of the "
        "sines and cosines of the fourth and fifth joints (coefficients linear in cos θ3, "
        "sin θ3) and in the eight products m12 of the first two joints."
    )
    if core is not None:
        m = core.matrices()
        e = sp.Symbol("E_1", **REAL)
        first = sp.expand((m.P[0, :] * m.m45)[0] - (m.Q[0, :] * m.m12)[0])
        first = first.xreplace(dict(zip(sp.symbols("theta1:7", real=True), angle))).evalf(6)
        steps.append(
            Step(
                "elimination",
                sentence(
                    loop.template + " The first of them (the x coordinate of p), with the "
                    "numbers of this arm; here p_x, p_y, p_z and l_x, l_y, l_z are the point "
                    "and the direction of T A6⁻¹ in the base frame:"
                ),
                e,
                first,
            )
        )
    dependent = core is not None and core.arrangement.project is not None
    reduce = (
        "Six combinations of the fourteen equations annihilate Q: they remove the "
        "first two joints. With the half-angle tangents (cos θ = (1 − x²)/(1 + x²), "
        "sin θ = 2x/(1 + x²)) the six equations, and the same times x4, are a "
        "12×12 matrix polynomial Σ({x}) = A {x}² + B {x} + C acting on the monomials "
        "x4^i x5^j (i ≤ 3, j ≤ 2); its determinant is a polynomial of degree 16 in the "
        "half-angle tangent of the eliminated joint"
    )
    if dependent:
        reduce += (
            ". On this arm the six equations are dependent: taken times 1, x4, x5 and x4 x5 "
            "on x4^i x5^j (i, j ≤ 3), 24 equations are combined into 16, a 16×16 Σ({x})"
        )
    reduce += ":"
    if core is None:
        reduce = loop.template + " " + reduce
    steps.append(Step("elimination", sentence(reduce, x=x), x, sp.tan(angle[k - 1] / 2)))
    (joint,) = sp.solve(sp.Eq(angle[k - 1], 2 * sp.atan(x)), theta)
    steps.append(
        Step(
            "eigenproblem",
            sentence(
                "det Σ({x}) = 0 is the generalised eigenproblem of the companion pencil, "
                "twice the size of Σ (Manocha and Canny). Every real eigenvalue gives "
                "the joint below; its eigenvector holds the monomials x4^i x5^j, whose "
                "ratios give the fourth and fifth joints; the first two follow from "
                "Q m12 = P m45 by least squares, the last from A6 = (A1 ⋯ A5)⁻¹ T. Each "
                "candidate is polished by a few Newton steps on the whole pose and kept "
                "when fk reproduces T: up to 16 real solutions.",
                x=x,
            ),
            theta,
            joint,
        )
    )
    return Elimination(
        robot,
        "no three consecutive axes parallel or meeting: general 6R",
        pose_symbols(),
        tuple(steps),
        core=core,
    )
