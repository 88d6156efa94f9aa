"""What every inverse-kinematics solver returns: one type, for one pose or a batch of poses.

The closed forms (:mod:`dhsym.ik.closed_form_solver`), the general 6R (:mod:`dhsym.ik.general6r`),
the numeric solver (:mod:`dhsym.ik.levenberg_marquardt`) and the compiled C
(``Robot.compiled().ik``) all return an :class:`IKSolution`: the joint values ``q``, which
of them are ``valid``, the ``residual`` of each, the singularities each is near, the
``method`` that found them, and a ``reason`` when there are none. A batch is the same type
with a leading axis of poses. Fields are named, never read back by position;
``np.asarray(solution)`` is ``q``.

Examples
--------
>>> import dhsym
>>> r = dhsym.load("planar2r")
>>> sol = r.ik(r.fk([0.4, 0.9]), check="position")
>>> type(sol).__name__, len(sol), sol.branches, sol.method
('IKSolution', 2, ('elbow down', 'elbow up'), 'closed form')
>>> batch = r.ik(r.fk([[0.4, 0.9], [0.1, -0.3]]), check="position")
>>> type(batch).__name__, batch.q.shape, batch.count.tolist(), batch.solution(1).branches
('IKSolution', (2, 2, 2), [2, 2], ('elbow down', 'elbow up'))
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dhsym.errors import DHError

if TYPE_CHECKING:
    from numpy.typing import DTypeLike

__all__ = ["BranchNamer", "IKSolution", "METHODS"]

#: The methods an :class:`IKSolution` may name: the closed form of a family, the general
#: 6R's elimination, the numeric solver, the exported C loaded with ctypes.
METHODS = ("closed form", "general 6R", "numeric", "compiled")

#: How a solver names its solutions: ``(q (k, n), signs (k, B)) -> one name per row``.
BranchNamer = Callable[[np.ndarray, np.ndarray], tuple[str, ...]]


@dataclass(frozen=True, eq=False, init=False)
class IKSolution:
    """The solutions of one pose, or of a batch of poses along a leading axis.

    One pose: ``q`` is ``(k, n)``, one row per solution; ``valid`` ``(k,)`` (the closed
    forms keep only valid rows; the numeric solver's one row is valid when it converged).
    A batch of N poses: ``q`` is ``(N, K, n)`` padded with NaN where ``valid`` ``(N, K)``
    is False, :meth:`solution` gives pose ``i`` alone.

    ``residual`` is each solution's error (the largest entry error of its ``fk`` for the
    closed forms, the general 6R and the compiled C; the norm of the position error and the
    rotation vector for the numeric solver); ``near`` ``(..., F)`` marks the singular
    factors ``factor_kinds`` each solution is near; ``signs`` the branch signs of each row
    (one pose: ``(k, B)``; a batch: ``(K, B)``, the same for every pose); ``method`` one of
    :data:`METHODS`; ``reason`` says why there is no solution, when that is known (None
    when there are solutions); ``iterations`` the steps of the numeric solver.
    """

    q: np.ndarray
    valid: np.ndarray
    residual: np.ndarray
    near: np.ndarray = field(repr=False)
    factor_kinds: tuple[str, ...] = field(repr=False)
    signs: np.ndarray = field(repr=False)
    method: str
    reason: str | None = None
    iterations: int | None = None
    #: the names of the rows of one pose, when known already (else ``namer`` finds them)
    names: tuple[str, ...] | None = field(default=None, repr=False)
    #: the solver's way of naming rows by their values and signs (computed on first use)
    namer: BranchNamer | None = field(default=None, repr=False)
    #: what else the solver knows of one pose's solutions: at a singular pose, the
    #: combination of joints that is all that is determined ("θ4 + θ6 = 0.7 is all that
    #: is determined; one solution given with θ4 = 0"), None otherwise
    note: str | None = None

    def __init__(
        self,
        q: np.ndarray,
        valid: np.ndarray,
        residual: np.ndarray,
        near: np.ndarray,
        factor_kinds: tuple[str, ...],
        signs: np.ndarray,
        method: str,
        reason: str | None = None,
        iterations: int | None = None,
        names: tuple[str, ...] | None = None,
        namer: BranchNamer | None = None,
        note: str | None = None,
    ) -> None:
        # the fields in order, written once into the instance's dict: what the generated
        # __init__ of a frozen dataclass does through object.__setattr__ per field, about
        # a microsecond of each single-pose answer (the instance stays frozen after)
        d = self.__dict__
        d["q"] = q
        d["valid"] = valid
        d["residual"] = residual
        d["near"] = near
        d["factor_kinds"] = factor_kinds
        d["signs"] = signs
        d["method"] = method
        d["reason"] = reason
        d["iterations"] = iterations
        d["names"] = names
        d["namer"] = namer
        d["note"] = note

    @property
    def batch(self) -> bool:
        """True for a batch of poses (``q`` is ``(N, K, n)``)."""
        return self.q.ndim == 3

    @functools.cached_property
    def branches(self) -> tuple[str, ...]:
        """The name of each solution of one pose (``"right arm, elbow up, wrist not
        flipped"``, ``"solution 3"``), computed on first use; a batch names its poses'
        solutions through :meth:`solution`."""
        if self.batch:
            raise DHError("a batch of poses: name the solutions of pose i by solution(i).branches")
        if self.names is not None:
            return self.names
        if self.namer is None:
            return tuple(f"solution {k}" for k in range(1, len(self.q) + 1))
        return self.namer(self.q, self.signs)

    @property
    def count(self) -> np.ndarray:
        """The number of valid solutions: ``()`` for one pose, ``(N,)`` for a batch."""
        counts: np.ndarray = self.valid.sum(axis=-1)
        return counts

    @property
    def converged(self) -> bool:
        """Whether any solution was found (the numeric solver: whether it converged)."""
        return bool(self.valid.any())

    @property
    def near_singular(self) -> np.ndarray:
        """True where a solution is near a singular configuration: ``(k,)`` or ``(N, K)``."""
        return np.asarray(self.near.any(axis=-1))

    @property
    def singular(self) -> tuple[tuple[str, ...], ...]:
        """The singularities each solution of one pose is near (empty when none)."""
        if self.batch:
            raise DHError("a batch of poses: solution(i).singular for pose i")
        return tuple(tuple(k for k, hit in zip(self.factor_kinds, row) if hit) for row in self.near)

    def solution(self, i: int) -> IKSolution:
        """The solutions of pose ``i`` of a batch (only the valid ones, with their names)."""
        if not self.batch:
            raise DHError("solution(i) takes pose i of a batch; this is one pose")
        keep = self.valid[i]
        return IKSolution(
            self.q[i][keep],
            self.valid[i][keep],
            self.residual[i][keep],
            self.near[i][keep],
            self.factor_kinds,
            self.signs[keep],
            self.method,
            namer=self.namer,
        )

    def take(self, keep: np.ndarray, q: np.ndarray | None = None) -> IKSolution:
        """The solutions ``keep`` of one pose (indices, in that order), with joint values
        ``q`` when given.

        >>> import dhsym
        >>> r = dhsym.load("planar2r")
        >>> sol = r.ik(r.fk([0.4, 0.9]), check="position")
        >>> sol.take(np.array([1, 0])).branches
        ('elbow up', 'elbow down')
        """
        keep = np.asarray(keep, dtype=int)
        rows = keep.tolist()
        if self.names is None and "branches" not in self.__dict__:
            # named when asked, as this solution's rows would be (naming looks at the arm)
            def namer(_q: np.ndarray, _signs: np.ndarray) -> tuple[str, ...]:
                return tuple(self.branches[k] for k in rows)

            known, later = None, namer
        else:
            known, later = tuple(self.branches[k] for k in rows), None
        return IKSolution(
            (self.q if q is None else q)[keep],
            self.valid[keep],
            self.residual[keep],
            self.near[keep],
            self.factor_kinds,
            self.signs[keep],
            self.method,
            self.reason,
            self.iterations,
            known,
            later,
            note=self.note,
        )

    def __len__(self) -> int:
        return int(self.q.shape[0])

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter(self.q)

    def __getitem__(self, k: int) -> np.ndarray:
        row: np.ndarray = self.q[k]
        return row

    def __array__(self, dtype: DTypeLike | None = None, copy: object = None) -> np.ndarray:
        return self.q if dtype is None else self.q.astype(dtype)
