"""What the closed-form solver returns: the solutions of one pose and of a batch, with the
names of their branches.

Fields are named (``q``, ``residual``, ``singular``, ``signs``), never read back by
position. ``np.asarray(solution)`` is ``q``.

Examples
--------
>>> import dhsym
>>> r = dhsym.load("planar2r")
>>> sol = r.ik(r.fk([0.4, 0.9]), check="position")
>>> type(sol).__name__, len(sol), sol.branches
('IKSolution', 2, ('elbow down', 'elbow up'))
"""

from __future__ import annotations

import functools
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, cast

import numpy as np

from dhsym.kinematics.jacobian import axis_frame

if TYPE_CHECKING:
    from numpy.typing import DTypeLike

    from .compiler import Solver
    from .general import EliminationSolver
    from .steps import Branch

__all__ = ["BRANCH_NAMES", "IKBatch", "IKSolution", "branch_word", "solver_branch_names"]

#: The one list of branch names, by the role of the branch: (first, second). For
#: ``"arm"`` and ``"wrist"`` the first is the sign +1; for ``"elbow"`` the first is the
#: elbow above the shoulder-to-wrist line (found from the geometry, not from the sign).
BRANCH_NAMES: Mapping[str, tuple[str, str]] = MappingProxyType(
    {
        "arm": ("right arm", "left arm"),
        "elbow": ("elbow up", "elbow down"),
        "wrist": ("wrist not flipped", "wrist flipped"),
    }
)


def branch_word(role: str, first: bool, variable: object = "") -> str:
    """The name of one branch: derivations, IK results, feedback and notebooks all use it.

    ``first`` is the sign +1 for the arm and the wrist, the elbow up for the elbow; a branch
    of another role (the sign of a square root) is named by that sign and its variable.

    >>> branch_word("elbow", True), branch_word("arm", False), branch_word("reach", True, "d3")
    ('elbow up', 'left arm', '+ root for d3')
    """
    if role in BRANCH_NAMES:
        return BRANCH_NAMES[role][0 if first else 1]
    return f"{'+' if first else '-'} root for {variable}".rstrip()


@dataclass(frozen=True, eq=False)
class IKSolution:
    """All solutions of one pose: ``q`` is ``(k, n)``, one row per solution (k ≤ 8).

    ``branches`` names each solution (``"right arm, elbow up, wrist not flipped"``);
    ``residual`` is the largest entry error of its ``fk``; ``singular`` names the
    singularities it is near (empty when none). ``np.asarray(solution)`` is ``q``.
    """

    q: np.ndarray
    residual: np.ndarray
    singular: tuple[tuple[str, ...], ...]
    signs: np.ndarray = field(repr=False)
    solver: Solver | EliminationSolver = field(repr=False)
    #: the branch names when known already (a solution with a joint given, reordered)
    names: tuple[str, ...] | None = field(default=None, repr=False)

    @functools.cached_property
    def branches(self) -> tuple[str, ...]:
        """The name of each solution's branch (computed on first use)."""
        if self.names is not None:
            return self.names
        return solver_branch_names(self.solver, self.q, self.signs)

    def take(self, keep: np.ndarray, q: np.ndarray | None = None) -> IKSolution:
        """The solutions ``keep`` (indices, in that order), with joint values ``q`` when given.

        >>> import dhsym
        >>> r = dhsym.load("planar2r")
        >>> sol = r.ik(r.fk([0.4, 0.9]), check="position")
        >>> sol.take(np.array([1, 0])).branches
        ('elbow up', 'elbow down')
        """
        keep = np.asarray(keep, dtype=int)
        names = self.branches
        return IKSolution(
            (self.q if q is None else q)[keep],
            self.residual[keep],
            tuple(self.singular[k] for k in keep),
            self.signs[keep],
            self.solver,
            tuple(names[k] for k in keep),
        )

    @property
    def near_singular(self) -> np.ndarray:
        """``(k,)`` True where a solution is near a singular configuration."""
        return np.array([bool(s) for s in self.singular], dtype=bool)

    def __len__(self) -> int:
        return int(self.q.shape[0])

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter(self.q)

    def __getitem__(self, k: int) -> np.ndarray:
        row: np.ndarray = self.q[k]
        return row

    def __array__(self, dtype: DTypeLike | None = None, copy: object = None) -> np.ndarray:
        return self.q if dtype is None else self.q.astype(dtype)


@dataclass(frozen=True, eq=False)
class IKBatch:
    """Solutions of N poses as padded arrays: ``q`` is ``(N, K, n)`` with NaN where invalid.

    ``valid`` ``(N, K)`` marks real, checked, distinct solutions; ``residual`` ``(N, K)``
    the entry error of each branch's ``fk``; ``singular`` ``(N, K, F)`` the
    singularities (``factor_kinds``) each solution is near; ``branch_signs`` ``(K, B)``
    the signs of the branches, in the order of the derivation's ``branches``.
    """

    q: np.ndarray
    valid: np.ndarray
    residual: np.ndarray
    singular: np.ndarray
    factor_kinds: tuple[str, ...]
    branch_signs: np.ndarray
    solver: Solver | EliminationSolver = field(repr=False)

    @property
    def count(self) -> np.ndarray:
        """``(N,)`` number of solutions of each pose."""
        counts: np.ndarray = self.valid.sum(axis=1)
        return counts

    @property
    def near_singular(self) -> np.ndarray:
        """``(N, K)`` True where a solution is near a singular configuration."""
        return np.asarray(self.singular.any(axis=-1))

    def __len__(self) -> int:
        return int(self.q.shape[0])

    def solution(self, i: int) -> IKSolution:
        """The solutions of pose ``i`` (only the valid ones, with their branch names)."""
        keep = self.valid[i]
        sing = tuple(
            tuple(k for k, hit in zip(self.factor_kinds, row) if hit)
            for row in self.singular[i][keep]
        )
        return IKSolution(
            self.q[i][keep], self.residual[i][keep], sing, self.branch_signs[keep], self.solver
        )


def solver_branch_names(
    solver: Solver | EliminationSolver, q: np.ndarray, signs: np.ndarray
) -> tuple[str, ...]:
    """Each solution's branch in words (``"left arm, elbow up, wrist flipped"``), as
    :class:`IKSolution` names them; ``"solution k"`` for a general 6R, which has no signs.
    The export room names its generated branches with the same words.
    """
    ik = solver.ik
    if not ik.branches:  # no signs (the general 6R): numbered in the order of their values
        return tuple(f"solution {k}" for k in range(1, len(q) + 1))
    parts: list[list[str]] = [[] for _ in range(len(q))]
    for b, col in zip(ik.branches, signs.T):
        var = solver.robot.variables[b.joint - 1]
        if b.role == "elbow":
            # branch signs come from compiled steps: the solver is a compiler.Solver
            up = _elbow_up(cast("Solver", solver), q, b) if len(q) else np.zeros(0, dtype=bool)
            words = [branch_word("elbow", bool(u)) for u in up]
        else:
            words = [branch_word(b.role, bool(sgn > 0), var) for sgn in col]
        for k, w in enumerate(words):
            parts[k].append(w)
    return tuple(", ".join(p) for p in parts)


def _elbow_up(solver: Solver, q: np.ndarray, branch: Branch) -> np.ndarray:
    """True where the elbow lies above the line from the shoulder to the wrist centre.

    "Above" is the side of +z0 for an arm that moves in a vertical plane, and the left of
    the shoulder-to-wrist line seen from above (+z0) for a planar arm. ``q`` is ``(k, n)``.
    """
    robot = solver.robot
    rows = robot.table.joint_rows
    elbow_row = rows[branch.joint - 1]
    shoulder_row = rows[branch.joint - 2]
    s = solver.frame(axis_frame(robot, shoulder_row))(q)[:, :3, 3]
    E = solver.frame(axis_frame(robot, elbow_row))(q)
    e, h = E[:, :3, 3] - s, E[:, :3, 2]
    w = solver.frame(solver.ik.decoupling.centre)(q)[:, :3, 3] - s
    up = h[:, 2]
    planar = np.abs(up) > 0.5
    h_up = h * np.where(up < 0, -1.0, 1.0)[:, None]
    left = np.einsum("ij,ij->i", e, np.cross(h_up, w)) > 0
    w_perp = w - np.einsum("ij,ij->i", w, h)[:, None] * h
    e_perp = e - np.einsum("ij,ij->i", e, h)[:, None] * h
    n = np.cross(h, w_perp)
    n = n * np.where(n[:, 2] < 0, -1.0, 1.0)[:, None]
    above = np.einsum("ij,ij->i", e_perp, n) > 0
    elbow_up: np.ndarray = np.where(planar, left, above)
    return elbow_up
