"""The general 6R's solver behind ``Robot.ik``: the eigenproblem of one robot and one set of
values, returning the :class:`~dhsym.ik.solution.IKSolution` of every other solver.

Examples
--------
>>> import dhsym
>>> r = dhsym.load("jaco")
>>> q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
>>> sol = r.ik(r.fk(q))
>>> sol.method, sol.branches[0], bool(np.abs(sol.q - q).max(axis=1).min() < 1e-9)
('general 6R', 'solution 1', True)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dhsym.errors import DHError
from dhsym.kinematics.jacobian import numeric_jacobian

from ..protocols import read_poses
from ..solution import IKSolution
from .eigenproblem import General6R, general_6r
from .method import MOST, Elimination

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["EliminationSolver"]

_SINGULAR = "singular Jacobian"
#: what an :class:`IKSolution` of the general 6R says it is
METHOD = "general 6R"


@dataclass(frozen=True, eq=False)
class EliminationSolver:
    """The general-6R solver of one robot and one set of values (an
    :class:`~dhsym.ik.protocols.IKSolver`): :meth:`solve` loops over the poses, each
    solved by the eigenproblem of :class:`~dhsym.ik.general6r.eigenproblem.General6R`.

    ``core`` is the compiled elimination, ``fk`` the robot's compiled forward kinematics
    (world to tool) with the same ``values``. A solution is flagged near a singularity
    (``"singular Jacobian"``) when the smallest singular value of the robot's geometric
    Jacobian there is below ``singular_tol`` times the largest.
    """

    ik: Elimination = field(repr=False)
    core: General6R
    fk: Callable[[np.ndarray], np.ndarray] = field(repr=False)
    values: Mapping[object, object] | None = field(default=None, repr=False)

    @property
    def robot(self) -> KinematicChain:
        """The robot solved."""
        return self.ik.robot

    @classmethod
    def build(cls, ik: Elimination, values: Mapping[object, object] | None) -> EliminationSolver:
        """The solver of ``ik`` with ``values``: the elimination compiled while deriving when
        no values are given, else compiled now (a :class:`~dhsym.errors.DHError` naming the
        lengths that have no number).

        >>> import dhsym
        >>> r = dhsym.load("jaco")
        >>> EliminationSolver.build(r.inverse(), None).core.eliminated
        3
        """
        if values is None and ik.core is not None:
            return cls(ik, ik.core, ik.core.fk)
        robot = ik.robot
        table = robot.table.with_values(values or {})
        missing = [str(s) for s in table.constants if s not in table.value_map]
        if missing:
            raise DHError(
                f"{robot.name or 'this arm'}: the general 6R is solved in numbers: give values "
                f"for {', '.join(missing)} (values= or 'values:' in the table)"
            )
        fk = robot.fk_function(values=values)
        return cls(ik, general_6r(table, fk=fk, tol=1e-6), fk, values)

    def branch_names(self, q: np.ndarray, signs: np.ndarray) -> tuple[str, ...]:
        """No signs: the solutions are numbered in the order of their joint values.

        >>> import dhsym
        >>> EliminationSolver.build(dhsym.load("jaco").inverse(), None).branch_names(
        ...     np.zeros((2, 6)), np.zeros((2, 0)))
        ('solution 1', 'solution 2')
        """
        return tuple(f"solution {k}" for k in range(1, len(q) + 1))

    def solve(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float = 1e-9,
        singular_tol: float = 1e-6,
    ) -> IKSolution:
        """Every real solution of one pose ``(4, 4)`` or of each pose of ``(N, 4, 4)``.

        ``check="pose"`` keeps a solution when its ``fk`` reproduces the 12 entries within
        ``tol``, ``"position"`` the position only; ``None`` keeps what the eigenproblem
        gives after polishing (already checked to ``1e-6``).

        >>> import dhsym
        >>> r = dhsym.load("jaco")
        >>> T = r.fk([[0.3, -0.5, 0.4, 0.2, 0.7, -1.1], [1.0, 0.2, -0.3, 0.5, -0.9, 0.4]])
        >>> batch = r.ik(T)
        >>> batch.q.shape[1:], bool((batch.count >= 1).all())
        ((16, 6), True)
        """
        arr, check = read_poses(T, check, wrist=True)
        cells = (slice(0, 3), slice(3, 4)) if check == "position" else (slice(0, 3), slice(0, 4))
        if arr.ndim == 2:
            q, residual, near, reason = self._one(arr, check, cells, tol, singular_tol)
            return IKSolution(
                q,
                np.ones(len(q), dtype=bool),
                residual,
                near[:, None],
                (_SINGULAR,),
                np.zeros((len(q), 0), dtype=int),
                METHOD,
                reason,
                namer=self.branch_names,
            )
        N = len(arr)
        Q = np.full((N, MOST, 6), np.nan)
        valid = np.zeros((N, MOST), dtype=bool)
        res = np.full((N, MOST), np.nan)
        sing = np.zeros((N, MOST, 1), dtype=bool)
        for i, pose in enumerate(arr):  # one eigenproblem per pose
            q, residual, near, _ = self._one(pose, check, cells, tol, singular_tol)
            k = len(q)
            Q[i, :k], valid[i, :k], res[i, :k], sing[i, :k, 0] = q, True, residual, near
        signs = np.zeros((MOST, 0), dtype=int)
        return IKSolution(Q, valid, res, sing, (_SINGULAR,), signs, METHOD, namer=self.branch_names)

    def _one(
        self,
        T: np.ndarray,
        check: str | None,
        cells: tuple[slice, slice],
        tol: float,
        singular_tol: float,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, str | None]:
        """The solutions of one pose, their residuals, singular flags, and why there are none."""
        none = np.empty((0, 6)), np.empty(0), np.empty(0, dtype=bool)
        if not np.isfinite(T).all():
            return (*none, "the pose is not finite")
        q = self.core.solve(T, within=tol if check == "pose" else 0.0)
        if not len(q):
            return (*none, "the eigenproblem has no real eigenvalue that gives a solution")
        got = self.fk(q)
        residual = np.abs(got[:, cells[0], cells[1]] - T[cells]).max(axis=(1, 2))
        if check is not None:
            keep = residual <= tol
            q, residual = q[keep], residual[keep]
        reason = None if len(q) else f"no solution reproduces the {check} within {tol:g}"
        return q, residual, self._near_singular(q, singular_tol), reason

    def _near_singular(self, q: np.ndarray, singular_tol: float) -> np.ndarray:
        """``(k,)`` True where the robot's geometric Jacobian at ``q`` (base frame, from the
        chain's numeric frames: a few points, not worth compiling) has
        ``σ_min < singular_tol · σ_max``."""
        if not len(q):
            return np.zeros(0, dtype=bool)
        J = numeric_jacobian(self.robot, q, self.values)
        s = np.linalg.svd(J, compute_uv=False)
        near: np.ndarray = s[:, -1] < singular_tol * s[:, 0]
        return near
