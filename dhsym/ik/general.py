"""The general 6R as a family of :func:`dhsym.ik.families.inverse`: its derivation in
words and the elimination's first equation, and its solver behind ``Robot.ik``.

An arm with six revolute joints where no three consecutive axes are parallel or meet in
a point (the Kinova Jaco and Mico) has no closed form by decoupling. Its pose equations
reduce to one polynomial of degree 16 in the half-angle tangent of one joint (Raghavan
and Roth, 1993), solved as a matrix eigenproblem (Manocha and Canny, 1994) by
:mod:`dhsym.ik.general6r`. :func:`derive_general` writes that method as the steps of
an :class:`~dhsym.ik.closed_form.InverseKinematics` (no branch signs: up to 16 solutions,
named ``solution 1`` … in the order of their joint values), and
:class:`EliminationSolver` gives ``Robot.ik`` the :class:`~dhsym.ik.results.IKSolution`
and :class:`~dhsym.ik.results.IKBatch` of every other family, each solution checked by
the robot's own ``fk``.

Examples
--------
>>> import dhsym
>>> r = dhsym.load("jaco")
>>> ik = r.inverse()
>>> ik.family, ik.count, ik.structure
('general 6R', 16, 'no three consecutive axes parallel or meeting: general 6R')
>>> q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
>>> sol = r.ik(r.fk(q))
>>> sol.branches[0], bool(np.abs(sol.q - q).max(axis=1).min() < 1e-9)
('solution 1', True)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.decoupling import Decoupling, StructureError
from dhsym.kinematics.numeric import values_key
from dhsym.model.table import JointType
from dhsym.notation.layout import sentence

from .closed_form import InverseKinematics
from .general6r import General6R, general_6r
from .results import IKBatch, IKSolution
from .steps import Step, pose_symbols
from .structure import GENERAL_6R

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["EliminationSolver", "derive_general"]

#: the most real solutions a general 6R has (the degree of the eliminant)
MOST = 16
_SINGULAR = "singular Jacobian"
_REAL = {"real": True}


@dataclass(frozen=True, eq=False)
class EliminationSolver:
    """The general-6R solver of one robot and one set of values, with the interface of
    :class:`~dhsym.ik.compiler.Solver`: :meth:`solve` returns an :class:`IKSolution`
    for one pose and an :class:`IKBatch` for ``(N, 4, 4)`` (a loop over the poses, each
    solved by the eigenproblem of :class:`~dhsym.ik.general6r.General6R`).

    ``core`` is the compiled elimination, ``fk`` the robot's compiled forward kinematics
    (world to tool) with the same values. A solution is flagged near a singularity
    (``"singular Jacobian"``) when the smallest singular value of its geometric Jacobian,
    by central differences of ``fk``, is below ``singular_tol`` times the largest.
    """

    ik: InverseKinematics = field(repr=False)
    core: General6R
    fk: Callable[[np.ndarray], np.ndarray] = field(repr=False)

    @property
    def robot(self) -> KinematicChain:
        """The robot solved."""
        return self.ik.robot

    @property
    def n(self) -> int:
        """Number of joints (6)."""
        return 6

    @classmethod
    def build(
        cls, ik: InverseKinematics, values: Mapping[object, object] | None
    ) -> EliminationSolver:
        """Compile the elimination for the robot of ``ik`` with ``values`` (a
        :class:`~dhsym.errors.DHError` naming the lengths that have no number).

        >>> import dhsym
        >>> r = dhsym.load("jaco")
        >>> EliminationSolver.build(r.inverse(), None).core.eliminated
        3
        """
        robot = ik.robot
        table = robot.table.with_values(values or {})
        missing = [str(s) for s in table.constants if s not in table.value_map]
        if missing:
            raise DHError(
                f"{robot.name or 'this arm'}: the general 6R is solved in numbers: give values "
                f"for {', '.join(missing)} (values= or 'values:' in the table)"
            )
        fk = robot.fk_function(values=values)
        core = general_6r(table, fk=fk, tol=1e-6)
        return cls(ik, core, fk)

    def solve(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float = 1e-9,
        singular_tol: float = 1e-6,
    ) -> IKSolution | IKBatch:
        """Every real solution of one pose ``(4, 4)`` or of each pose of ``(N, 4, 4)``.

        ``check="pose"`` keeps a solution when its ``fk`` reproduces the 12 entries within
        ``tol``, ``"position"`` the position only; ``None`` keeps what the eigenproblem
        gives after polishing (already checked to ``1e-6``).

        >>> import dhsym
        >>> r = dhsym.load("jaco")
        >>> T = r.fk([[0.3, -0.5, 0.4, 0.2, 0.7, -1.1], [1.0, 0.2, -0.3, 0.5, -0.9, 0.4]])
        >>> batch = r.inverse().solver().solve(T)
        >>> batch.q.shape[1:], bool((batch.count >= 1).all())
        ((16, 6), True)
        """
        arr = np.asarray(T, dtype=float)
        if arr.shape[-1] == 3 and arr.ndim in (1, 2):
            raise DHError("this arm has a wrist: give a full 4×4 pose, not a position")
        if arr.shape[-2:] != (4, 4) or arr.ndim not in (2, 3):
            raise DHError(f"expected poses of shape (4, 4) or (N, 4, 4), got {arr.shape}")
        cells = (slice(0, 3), slice(3, 4)) if check == "position" else (slice(0, 3), slice(0, 4))
        if arr.ndim == 2:
            q, residual, near = self._one(arr, check, cells, tol, singular_tol)
            singular = tuple((_SINGULAR,) if s else () for s in near)
            return IKSolution(q, residual, singular, np.zeros((len(q), 0), dtype=int), self)
        N = len(arr)
        Q = np.full((N, MOST, 6), np.nan)
        valid = np.zeros((N, MOST), dtype=bool)
        res = np.full((N, MOST), np.nan)
        sing = np.zeros((N, MOST, 1), dtype=bool)
        for i, pose in enumerate(arr):  # one eigenproblem per pose
            q, residual, near = self._one(pose, check, cells, tol, singular_tol)
            k = len(q)
            Q[i, :k], valid[i, :k], res[i, :k], sing[i, :k, 0] = q, True, residual, near
        signs = np.zeros((MOST, 0), dtype=int)
        return IKBatch(Q, valid, res, sing, (_SINGULAR,), signs, self)

    def _one(
        self,
        T: np.ndarray,
        check: str | None,
        cells: tuple[slice, slice],
        tol: float,
        singular_tol: float,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if not np.isfinite(T).all():
            return np.empty((0, 6)), np.empty(0), np.empty(0, dtype=bool)
        q = self.core.solve(T)
        if not len(q):
            return q, np.empty(0), np.empty(0, dtype=bool)
        got = self.fk(q)
        residual = np.abs(got[:, cells[0], cells[1]] - T[cells]).max(axis=(1, 2))
        if check is not None:
            keep = residual <= tol
            q, residual = q[keep], residual[keep]
        return q, residual, _near_singular(self.fk, q, singular_tol)


def _near_singular(
    fk: Callable[[np.ndarray], np.ndarray], q: np.ndarray, singular_tol: float
) -> np.ndarray:
    """``(k,)`` True where the geometric Jacobian at ``q`` (central differences of ``fk``,
    world frame, tool point) has ``σ_min < singular_tol · σ_max``."""
    if not len(q):
        return np.zeros(0, dtype=bool)
    h = 1e-6
    k = len(q)
    steps = np.concatenate([q[:, None, :] + h * np.eye(6), q[:, None, :] - h * np.eye(6)], axis=1)
    M = fk(steps.reshape(-1, 6)).reshape(k, 12, 4, 4)
    plus, minus = M[:, :6], M[:, 6:]
    dT = (plus - minus) / (2 * h)  # (k, 6 joints, 4, 4)
    R = fk(q)[:, None, :3, :3]
    W = dT[..., :3, :3] @ np.swapaxes(R, -1, -2)  # [ω]× for each joint
    omega = np.stack([W[..., 2, 1], W[..., 0, 2], W[..., 1, 0]], axis=-1)
    J = np.concatenate([dT[..., :3, 3], omega], axis=-1).transpose(0, 2, 1)  # (k, 6, 6)
    s = np.linalg.svd(J, compute_uv=False)
    return s[:, -1] < singular_tol * s[:, 0]


def _all_numbers(robot: KinematicChain) -> bool:
    known = robot.table.value_map
    return all(s in known for s in robot.table.constants)


def derive_general(robot: KinematicChain) -> InverseKinematics:
    """The general 6R by Raghavan–Roth elimination, as derivation steps and a solver.

    With numbers for every length the elimination is compiled here (about a second; it
    fails for an arm on which it degenerates, a :class:`StructureError`) and its first
    equation shown; with symbolic lengths ``Robot.ik`` needs ``values=``.

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
    x = sp.Symbol(f"x_{k}", **_REAL)
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
        e = sp.Symbol("E_1", **_REAL)
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
    dec = Decoupling(tuple(rows[:3]), tuple(rows[3:]), robot.n, sp.ImmutableMatrix([0, 0, 0]))
    ik = InverseKinematics(
        robot,
        "no three consecutive axes parallel or meeting: general 6R",
        dec,
        pose_symbols(),
        tuple(steps),
        (),
        GENERAL_6R,
        most=MOST,
        build_solver=EliminationSolver.build,
    )
    if core is not None:  # compiled already: kept for robot.ik without values
        ik.solvers[values_key(None)] = EliminationSolver(ik, core, core.fk)
    return ik
