"""The two extension points of the ik room: a derivation and a solver.

A family derives an :class:`InverseKinematics` (what ``Robot.inverse()`` returns): the
closed form of :mod:`dhsym.ik.closed_form` (steps, branch signs, a decoupling) or the
general 6R's elimination of :mod:`dhsym.ik.general6r` (its explanation, up to 16
solutions). Callers that need more than the protocol tell the two apart by type
(``isinstance(ik, ClosedForm)``), never by probing fields.

An :class:`IKSolver` turns one derivation into numbers for one set of values: the
compiled steps (:class:`~dhsym.ik.closed_form_solver.ClosedFormSolver`) or the eigenproblem
(:class:`~dhsym.ik.general6r.EliminationSolver`); both return the one
:class:`~dhsym.ik.solution.IKSolution` and name its rows.

Examples
--------
>>> import dhsym
>>> from dhsym.ik.closed_form import ClosedForm
>>> r = dhsym.load("puma560")
>>> isinstance(r.inverse(), InverseKinematics), isinstance(r.inverse(), ClosedForm)
(True, True)
>>> isinstance(r.ik_cache().solver(), IKSolver)
True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol, runtime_checkable

import numpy as np

from dhsym.errors import DHError

# at run time, so that the documentation resolves the annotations (three rooms have a Step)
from .steps import Branch, Step

if TYPE_CHECKING:
    import sympy as sp

    from dhsym.kinematics.chain import KinematicChain

    from .solution import IKSolution

__all__ = [
    "IKSolver",
    "InverseKinematics",
    "NativeCompiler",
    "NativeGiven",
    "NativeProgram",
    "NativeRule",
    "NativeRun",
    "read_poses",
]

#: the program run on one pose: ``run(inner, pose, stretch)`` of the pose from frame 0 to
#: frame n and the pose as given (contiguous row-major ``(4, 4)`` float arrays) gives the
#: program's outputs as a new ``(outputs,)`` float array the caller owns; ``stretch``
#: reads every negative radicand as 0 (the ``"stretched"`` program of
#: :mod:`dhsym.ik.closed_form_solver`)
NativeRun = Callable[[np.ndarray, np.ndarray, bool], np.ndarray]
#: the program run on one pose as it comes (:mod:`dhsym.ik.accuracy`):
#: ``given(pose, tol, base_inv, tool_inv)`` of the pose as given (contiguous row-major
#: ``(4, 4)``), the tolerance asked for (0: the pose's own) and the inverses of the base
#: and tool transforms (``None``: none) gives ``[tol, stretch, verdict, kept, low,
#: *outputs, *against_given]``: the pose's tolerance (not above 0: the rotation is no
#: rotation, nothing else said), whether it is not exact, the :class:`NativeRule`'s
#: verdict and the branches it keeps (a bit mask), the smallest closeness to a
#: singularity, the program's outputs (an exact pose as given, else its nearest rigid pose
#: stretched) and, for a pose that is not exact, the outputs again with the residuals
#: against the pose as given
NativeGiven = Callable[[np.ndarray, float, np.ndarray | None, np.ndarray | None], np.ndarray]


@dataclass(frozen=True)
class NativeRule:
    """Where the program for one pose keeps what robot.ik decides by, and the numbers it
    decides with, for the rule around it (:data:`NativeGiven`): the residuals of the
    ``branches`` against the whole pose from ``whole``, the ``wrist_count`` wrist sines
    from ``wrist``, the ``factor_count`` closenesses to a singularity from ``factors``
    (offsets into the outputs); a wrist sine below ``wrist_near`` is a singular wrist, a
    closeness below ``suspect`` may make two branches one, and a branch of a pose that is
    not exact is a candidate within ``within`` tolerances of its nearest rigid pose.

    The verdict: 0 when the kept branches are the answer (each within the tolerance of
    the pose as given, none to refine, no singular wrist, no closeness below
    ``suspect``); 1 when robot.ik's own path must answer (a singular wrist, a branch of a
    pose that is not exact to refine, or none kept); 2 when the outputs must be read one
    by one (a closeness below ``suspect``; an exact pose with no branch kept)."""

    branches: int
    whole: int
    wrist: int
    wrist_count: int
    factors: int
    factor_count: int
    wrist_near: float
    suspect: float
    within: float


@dataclass(frozen=True, eq=False)
class NativeProgram:
    """A closed form's program for one pose in native code (safe to call from several
    threads at once): :data:`NativeRun` ``run``, and :data:`NativeGiven` ``given`` (the
    rule for a pose as it comes around it; ``None`` when the compiler has none).
    ``keep`` holds what the functions need alive (the loaded library)."""

    run: NativeRun
    given: NativeGiven | None = None
    keep: object = field(default=None, repr=False)


@runtime_checkable
class InverseKinematics(Protocol):
    """A derived inverse kinematics: the arm, what was recognised, and the steps to show.

    ``structure`` is the sentence naming what was found in the table, ``family`` the
    family that solved it, ``pose`` the symbolic pose ``[n s a p; 0 0 0 1]``, ``steps`` the
    derivation in order, ``branches`` its branch signs (none for the general 6R), ``count``
    the most solutions a generic pose has.
    """

    @property
    def robot(self) -> KinematicChain: ...

    @property
    def structure(self) -> str: ...

    @property
    def family(self) -> str: ...

    @property
    def pose(self) -> sp.ImmutableMatrix: ...

    @property
    def steps(self) -> tuple[Step, ...]: ...

    @property
    def branches(self) -> tuple[Branch, ...]: ...

    @property
    def count(self) -> int: ...

    def text(self, step: Step) -> str: ...

    def latex(self, step: Step) -> str: ...


@runtime_checkable
class IKSolver(Protocol):
    """A derivation in numbers: solves poses and names the solutions it finds."""

    @property
    def robot(self) -> KinematicChain: ...

    def solve(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float = 1e-9,
        singular_tol: float = 1e-6,
    ) -> IKSolution:
        """Every solution of one pose ``(4, 4)`` or of each pose of ``(N, 4, 4)``."""
        ...

    def branch_names(self, q: np.ndarray, signs: np.ndarray) -> tuple[str, ...]:
        """The name of each solution ``q`` ``(k, n)`` with branch signs ``(k, B)``."""
        ...


class NativeCompiler(Protocol):
    """A compiler of the closed-form solver's program for one pose into native code: the
    facade passes the export room's C (:func:`dhsym.export.shared_library.native_program`)
    when a C compiler is there; the ik room never imports it.

    Called with the program's arguments (the 12 entries of the pose from frame 0 to
    frame n, then the 12 of the pose as given, each column by column), its lines in
    order, its outputs and the :class:`NativeRule` of the rule around it; returns a
    :data:`NativeProgram` with the same outputs, or ``None`` when it cannot build one
    (the solver keeps its own program for floats).
    """

    def __call__(
        self,
        args: Sequence[sp.Symbol],
        program: Sequence[tuple[sp.Symbol, sp.Expr]],
        outputs: Sequence[sp.Expr],
        rule: NativeRule,
    ) -> NativeProgram | None: ...


def read_poses(T: object, check: str | None, *, wrist: bool) -> tuple[np.ndarray, str | None]:
    """The poses every :class:`IKSolver` takes, checked once: ``(4, 4)`` or ``(N, 4, 4)``;
    for an arm without a wrist also positions ``(3,)`` or ``(N, 3)``, read as poses with the
    identity rotation and checked by position. Returns the poses and the check to apply.

    >>> read_poses([0.1, 0.2, 0.3], "pose", wrist=False)[0][:3, 3].tolist(), "position"
    ([0.1, 0.2, 0.3], 'position')
    >>> read_poses(np.eye(3), "pose", wrist=True)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: this arm has a wrist: give a full 4×4 pose, not a position
    >>> read_poses(np.zeros((2, 4)), "pose", wrist=True)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: expected poses of shape (4, 4) or (N, 4, 4), got (2, 4)
    """
    arr = np.asarray(T, dtype=float)
    if arr.shape[-1] == 3 and arr.ndim in (1, 2):
        if wrist:
            raise DHError("this arm has a wrist: give a full 4×4 pose, not a position")
        pose = np.zeros(arr.shape[:-1] + (4, 4))
        pose[..., :3, :3] = np.eye(3)
        pose[..., :3, 3] = arr
        pose[..., 3, 3] = 1.0
        arr, check = pose, ("position" if check is not None else None)
    if arr.shape[-2:] != (4, 4) or arr.ndim not in (2, 3):
        raise DHError(f"expected poses of shape (4, 4) or (N, 4, 4), got {arr.shape}")
    return arr, check
