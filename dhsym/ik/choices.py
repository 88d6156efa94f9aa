"""Choosing among the solutions: a joint given (seven-joint arms), joint limits, the nearest.

:func:`solve` is what ``Robot.ik`` runs: the closed form of the arm, or, with ``free``,
the closed form of the other joints with one joint's value given (the Panda and the
KUKA LWR have seven joints: one given, the six left form a family of
:mod:`dhsym.ik.families`); where the six left have no closed form, the numeric solver
with the joint held answers from several starts (``method="numeric"``,
:func:`~dhsym.ik.levenberg_marquardt.numeric_solutions`). At a singular wrist the
result's ``note`` names the combination that is determined (:func:`singular_family`;
on the UR arms, the sum of the turns of the four joints with parallel axes).
Then ``limits=True`` shifts each angle by multiples of 2π into its joint's range and
drops the solutions that do not fit, and ``near=q0`` orders them by distance from ``q0``
(angles compared modulo 2π).

Examples
--------
>>> import dhsym
>>> r = dhsym.load("panda")
>>> q = [0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7]
>>> sol = r.ik(r.fk(q), free={7: 0.7})
>>> bool(np.abs(sol.q - q).max(axis=1).min() < 1e-9)
True
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from dhsym.errors import DHError
from dhsym.kinematics.decoupling import StructureError
from dhsym.kinematics.numeric import values_key
from dhsym.model.table import DHRow, JointType

from .accuracy import EXACT as _EXACT
from .accuracy import FLOOR, REFINE, REFINE_STEPS, nearest_rigid, pose_accuracy
from .accuracy import SAME as _SAME
from .accuracy import STUCK as _STUCK
from .closed_form import ClosedForm
from .closed_form_solver import ClosedFormSolver
from .families import inverse
from .general6r import Elimination, EliminationSolver
from .kept_derivations import kept_inverse
from .levenberg_marquardt import DESCRIPTION, numeric_ik, numeric_solutions
from .protocols import IKSolver, NativeCompiler
from .solution import IKSolution

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "GivenJoint",
    "IKCache",
    "build_solver",
    "nearest_first",
    "singular_family",
    "solve",
    "sweep_free_joint",
    "within_limits",
]

_TWO_PI = 2 * np.pi
# the refinement's numbers (REFINE_STEPS, _STUCK, _SAME) are the rule's: dhsym.ik.accuracy


def _limits(robot: KinematicChain) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper joint limits ``(n,)`` (±inf where the table gives none)."""
    values = robot.table.value_map
    lo, hi = [], []
    for row in robot.table.rows:
        if row.variable is None:
            continue
        if row.limits is None:
            lo.append(-np.inf)
            hi.append(np.inf)
        else:
            lo.append(float(row.limits[0].xreplace(values)))
            hi.append(float(row.limits[1].xreplace(values)))
    return np.array(lo), np.array(hi)


def _revolute(robot: KinematicChain) -> np.ndarray:
    return np.array(
        [r.joint is JointType.REVOLUTE for r in robot.table.rows if r.variable is not None]
    )


def within_limits(robot: KinematicChain, sol: IKSolution) -> IKSolution:
    """The solutions inside the joint limits, each angle shifted by 2πk into its range
    (the shift nearest to the middle of the range when several fit).

    >>> import dhsym
    >>> r = dhsym.load("puma560")
    >>> sol = r.ik(r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1]))
    >>> kept = within_limits(r, sol)
    >>> len(sol), len(kept), kept.branches[0]
    (8, 2, 'right arm, elbow down, wrist not flipped')
    """
    lo, hi = _limits(robot)
    rev = _revolute(robot)
    q = sol.q.copy()
    with np.errstate(invalid="ignore"):  # no limits: -inf + inf, the middle read as 0
        mid = np.where(np.isfinite(lo + hi), (lo + hi) / 2, 0.0)
    shifted = q - _TWO_PI * np.round((q - mid) / _TWO_PI)
    q = np.where(rev, shifted, q)
    inside = ((q >= lo - 1e-12) & (q <= hi + 1e-12)).all(axis=1)
    kept = sol.take(np.nonzero(inside)[0], q)
    if len(sol) and not len(kept):
        return replace(kept, reason="no solution lies within the joint limits")
    return kept


def nearest_first(robot: KinematicChain, sol: IKSolution, q0: object) -> IKSolution:
    """The solutions ordered by distance from ``q0`` (angle differences wrapped to [−π, π]).

    >>> import dhsym
    >>> r = dhsym.load("planar2r")
    >>> sol = r.ik(r.fk([0.4, 0.9]), check="position")
    >>> nearest_first(r, sol, [0.5, 0.8]).q[0].round(9).tolist()
    [0.4, 0.9]
    """
    start = np.asarray(q0, dtype=float).reshape(-1)
    if start.shape != (sol.q.shape[1],):
        raise DHError(f"near: expected {sol.q.shape[1]} joint values, got {start.size}")
    d = sol.q - start
    rev = _revolute(robot)
    d = np.where(rev, d - _TWO_PI * np.round(d / _TWO_PI), d)
    return sol.take(np.argsort(np.linalg.norm(d, axis=1), kind="stable"))


def build_solver(
    ik: ClosedForm | Elimination,
    values: Mapping[object, object] | None,
    native: NativeCompiler | None = None,
) -> IKSolver:
    """The solver of a derivation with ``values`` (by its type): the steps of a closed form
    compiled (:class:`~dhsym.ik.closed_form_solver.ClosedFormSolver`, its program for one
    pose in native code when ``native`` builds it), or the general 6R's eigenproblem
    (:class:`~dhsym.ik.general6r.EliminationSolver`).

    >>> import dhsym
    >>> type(build_solver(dhsym.load("planar2r").inverse(), None)).__name__
    'ClosedFormSolver'
    """
    if isinstance(ik, Elimination):
        return EliminationSolver.build(ik, values)
    numbers = ik.robot.table.with_values(values or {}).value_map
    return ClosedFormSolver(ik, numbers, native)


@dataclass(eq=False)
class IKCache:
    """The inverse kinematics of one chain, derived on first use and kept: the derivation
    (:meth:`inverse`), its solvers by the values they were built with (:meth:`solver`) and,
    for ``free={joint: value}``, the chains with that joint given (:meth:`given`).
    :class:`dhsym.robot.Robot` keeps one; :func:`solve` makes a fresh one when given none.
    ``native`` compiles the closed form's program for one pose into native code (the
    facade passes the export room's C when a compiler is there; ``None``: the solvers'
    own programs only); the chains with a joint given share it.

    >>> from dhsym.kinematics.chain import KinematicChain
    >>> from dhsym.model.library import load_table
    >>> cache = IKCache(KinematicChain(load_table("planar2r")))
    >>> cache.inverse() is cache.inverse(), cache.inverse().count
    (True, 2)
    >>> cache.solver() is cache.solver()
    True
    """

    chain: KinematicChain
    native: NativeCompiler | None = None
    _inverse: ClosedForm | Elimination | None = field(default=None, init=False, repr=False)
    #: the solvers by the values they were built with (:func:`values_key`)
    _solvers: dict[object, IKSolver] = field(default_factory=dict, init=False, repr=False)
    _given: dict[int, GivenJoint] = field(default_factory=dict, init=False, repr=False)
    #: why the chain has no closed form, once that is known
    _failure: str | None = field(default=None, init=False, repr=False)

    def inverse(self) -> ClosedForm | Elimination:
        """The derivation, step by step (:func:`dhsym.ik.families.inverse`), cached here and
        in the disk cache (:func:`dhsym.ik.kept_derivations.kept_inverse`: a later process
        reads it); so is the :class:`~dhsym.kinematics.decoupling.StructureError` of a
        chain without one (raised again, not derived again)."""
        if self._failure is not None:
            raise StructureError(self._failure)
        if self._inverse is None:
            try:
                self._inverse = kept_inverse(self.chain, inverse)
            except StructureError as err:
                self._failure = err.message
                raise
        return self._inverse

    def solver(self, values: Mapping[object, object] | None = None) -> IKSolver:
        """The solver of :meth:`inverse` with ``values`` (:func:`build_solver`), built once
        per set of values and kept."""
        key = values_key(values)  # the values as given: converted only once
        found = self._solvers.get(key)
        if found is None:
            found = self._solvers[key] = build_solver(self.inverse(), values, self.native)
        return found

    def solve(
        self,
        robot: KinematicChain,
        T: object,
        *,
        check: str | None = "pose",
        tol: float | None = None,
        singular_tol: float = 1e-6,
        values: Mapping[object, object] | None = None,
        free: Mapping[int, float] | None = None,
        limits: bool = False,
        near: object = None,
    ) -> IKSolution:
        """:func:`solve` with this cache, for ``robot`` (this cache's chain or one with an
        equal table): ``Robot.ik``'s way in, with nothing imported on each call."""
        return solve(
            robot,
            T,
            check=check,
            tol=tol,
            singular_tol=singular_tol,
            values=values,
            free=free,
            limits=limits,
            near=near,
            cache=self,
        )

    def given(self, joint: int) -> GivenJoint:
        """The chain with joint ``joint`` (1-based) given, and its own cache."""
        found = self._given.get(joint)
        if found is None:
            sub, row = _sub_chain(self.chain, joint)
            found = self._given[joint] = GivenJoint(IKCache(sub, self.native), row)
        return found


@dataclass(frozen=True, eq=False)
class GivenJoint:
    """The arm with one joint given: the chain left (with its :class:`IKCache`) and the
    row of the given joint (1: the chain after it; n: the chain before it; else its row
    made constant)."""

    cache: IKCache
    row: int


def _sub_chain(robot: KinematicChain, joint: int) -> tuple[KinematicChain, int]:
    """The arm without joint ``joint`` (1-based): the chain after it (first joint), before it
    (last joint), or with its row made constant (its variable becomes a symbol to give)."""
    from dhsym.kinematics.chain import KinematicChain

    table = robot.table
    rows = table.joint_rows
    if not 1 <= joint <= len(rows):
        raise DHError(
            f"free: joint {joint} is not a joint of {robot.name or 'this arm'} (1 … {len(rows)})"
        )
    row = rows[joint - 1]
    if row == 1:
        kept = table.rows[1:]
    elif row == table.n:
        kept = table.rows[:-1]
    else:
        r = table.rows[row - 1]
        fixed = DHRow(JointType.FIXED, r.theta, r.d, r.a, r.alpha)
        kept = table.rows[: row - 1] + (fixed,) + table.rows[row:]
    used = set().union(*(e.free_symbols for r in kept for e in r.params().values()))
    sub = replace(
        table,
        rows=kept,
        name=f"{table.name} (joint {joint} given)",
        base=(),
        tool=(),
        values=tuple((s, v) for s, v in table.values if s in used),
    )
    return KinematicChain(sub), row


def _solve_free(
    cache: IKCache,
    T: np.ndarray,
    joint: int,
    value: float,
    *,
    tol: float,
    singular_tol: float,
    values: Mapping[object, object] | None,
    stretch: bool = False,
) -> IKSolution:
    """Every solution of the pose ``T`` with joint ``joint`` at ``value`` (``stretch``: a
    closed form reads every negative radicand as 0, as for a pose that is not exact)."""
    robot = cache.chain
    given = cache.given(joint)
    row = given.row
    n = len(robot.variables)
    var = robot.variables[joint - 1]
    q = np.zeros(n)
    q[joint - 1] = value
    inner = T
    if robot.table.base:
        inner = np.linalg.inv(robot.fk_function(-1, 0, values)(q)) @ inner
    if robot.table.tool:
        inner = inner @ np.linalg.inv(robot.fk_function(robot.n, robot.n + 1, values)(q))
    extra = dict(values or {})
    if row == 1:
        inner = np.linalg.inv(robot.fk_function(0, 1, values)(q)) @ inner
    elif row == robot.n:
        inner = inner @ np.linalg.inv(robot.fk_function(robot.n - 1, robot.n, values)(q))
    else:
        extra[var] = value
    try:
        solver = given.cache.solver(extra or None)
    except StructureError:
        # no closed form with this joint given: the numeric solver, on the whole arm with
        # the joint held (it says it is numeric, and how far it got)
        return _numeric_free(robot, T, joint, value, tol=tol, values=values)
    if stretch and isinstance(solver, ClosedFormSolver):
        part = solver.solve(inner, check="pose", tol=tol, singular_tol=singular_tol, stretch=True)
    else:
        part = solver.solve(inner, check="pose", tol=tol, singular_tol=singular_tol)
    full = np.insert(part.q, joint - 1, value, axis=1)
    names = part.branches
    got = robot.fk_function(values=values)(full) if len(full) else np.zeros((0, 4, 4))
    residual = np.abs(got - T).reshape(len(full), -1).max(axis=1) if len(full) else np.zeros(0)
    ok = residual <= tol
    return IKSolution(
        full[ok],
        part.valid[ok],
        residual[ok],
        part.near[ok],
        part.factor_kinds,
        part.signs[ok],
        part.method,
        None if ok.any() else (part.reason or f"no branch reproduces the pose within {tol:g}"),
        names=tuple(s for s, k in zip(names, ok) if k),
    )


def _numeric_free(
    robot: KinematicChain,
    T: np.ndarray,
    joint: int,
    value: float,
    *,
    tol: float,
    values: Mapping[object, object] | None,
) -> IKSolution:
    """The solutions the numeric solver finds from several starts with joint ``joint`` held
    at ``value`` (:func:`~dhsym.ik.levenberg_marquardt.numeric_solutions`), each residual
    the largest entry error of its ``fk``, those within ``tol`` kept."""
    sol = numeric_solutions(robot, T, values=values, fixed={joint: value})
    if not len(sol):
        return sol
    got = robot.fk_function(values=values)(sol.q)
    residual = np.abs(got[:, :3] - np.asarray(T)[None, :3]).reshape(len(sol), -1).max(axis=1)
    keep = np.nonzero(residual <= tol)[0]
    kept = replace(sol.take(keep), residual=residual[keep])
    if not len(kept):
        smallest = float(residual.min())
        return replace(
            kept, reason=f"{DESCRIPTION}: no solution within {tol:.1g} (smallest {smallest:.3g})"
        )
    return kept


def solve(
    robot: KinematicChain,
    T: object,
    *,
    check: str | None = "pose",
    tol: float | None = None,
    singular_tol: float = 1e-6,
    values: Mapping[object, object] | None = None,
    free: Mapping[int, float] | None = None,
    limits: bool = False,
    near: object = None,
    cache: IKCache | None = None,
) -> IKSolution:
    """Every solution of ``T``, with a joint given, within limits, nearest first.

    Parameters
    ----------
    T
        One pose ``(4, 4)`` or a batch ``(N, 4, 4)`` (positions for arms without a wrist).
    check, singular_tol
        As :meth:`dhsym.ik.protocols.IKSolver.solve`.
    tol
        The largest entry error of ``fk`` against the pose as given for a solution to be
        kept. By default it follows the pose's own accuracy
        (:func:`dhsym.ik.accuracy.pose_accuracy`): 1e-9 for an exact pose, about twice
        its rotation's distance from the rotations for a rounded or measured one. With
        ``check="pose"``, a pose whose rotation is not a rotation (by more than
        :data:`dhsym.ik.accuracy.EXACT`) is solved at its nearest rigid pose and each
        solution's ``residual`` measured against the pose as given.
    values
        Numbers for the table's symbols (the solver is built once per set of values).
    free
        ``{joint: value}``: one joint (1-based) given; the others solved in closed form,
        or by the general 6R, or numerically where neither fits (``method`` says which).
        One pose only.
    limits
        Keep only solutions within the joint limits of the table (one pose).
    near
        Order the solutions by distance from these joint values (one pose).
    cache
        The :class:`IKCache` of ``robot`` to derive in and keep (``Robot.ik`` passes its
        own); by default a fresh one, so the closed form is derived on this call.
    """
    if cache is None:
        cache = IKCache(robot)
    arr = np.asarray(T, dtype=float)
    one = check == "pose" and arr.shape == (4, 4) and not free
    if one and (tol is None or tol > 0):
        # one pose as it comes (exact, rounded, measured, typed): the rule below in one call
        # of the native program, when there is one and nothing needs the paths below (a
        # branch to refine, no solution of a pose that is not exact and its reason, a
        # singular wrist)
        solver = cache.solver(values)
        if isinstance(solver, ClosedFormSolver):
            pose = arr if arr.flags.c_contiguous else np.ascontiguousarray(arr)
            found = solver.solve_given(pose, tol=tol, singular_tol=singular_tol, within=REFINE)
            if found is not None:
                if limits or near is not None or np.count_nonzero(found.near):
                    return _chosen(robot, found, limits, near, free, values)
                return found  # nothing to choose (as below)
    if one and _surely_exact(arr):
        # one pose whose rotation is a rotation (told without an SVD): solved as given,
        # as below, with the tolerance of an exact pose (a closed form's solver takes the
        # pose as read here, not reading it again)
        solver = cache.solver(values)
        inner_tol = FLOOR if tol is None else tol
        if isinstance(solver, ClosedFormSolver):
            sol = solver.solve_pose(arr, tol=inner_tol, singular_tol=singular_tol)
        else:
            sol = solver.solve(arr, check=check, tol=inner_tol, singular_tol=singular_tol)
        if limits or near is not None or np.count_nonzero(sol.near):
            return _chosen(robot, sol, limits, near, free, values)
        return sol  # nothing to choose: no limits, no order, no singular family to name
    single = arr.ndim in (1, 2) and not (arr.ndim == 2 and arr.shape[-1] == 3)
    if (free or limits or near is not None) and not single:
        raise DHError("free, limits and near apply to one pose: solve the poses one by one")
    given, brought = arr, False
    rigid = nearest_rigid(arr) if _poses(arr, check) else None
    tols = _tolerances(arr, check, tol, rigid)
    if tols is not None and rigid is not None:
        with np.errstate(invalid="ignore"):  # a pose of NaNs is refused later, by its step
            off = np.abs(rigid[..., :3, :3] - arr[..., :3, :3]).max(axis=(-2, -1)) > _EXACT
        if off.any():  # only the poses that are off: an exact pose is solved as given
            arr, brought = np.where(off[..., None, None], rigid, arr), True
    inner_tol = FLOOR if tol is None else tol
    if tols is not None and tols.size:
        inner_tol = max(inner_tol, float(np.max(tols)))
    if brought:
        # the branches within REFINE tolerances of a pose that is not exact are refined
        # against it (_against_given): the arm stretched at a boundary, or a branch whose
        # radicand rounding pushed below 0, lands near the pose, not on it
        inner_tol *= REFINE
    if free:
        if len(free) != 1:
            raise DHError(f"free: give exactly one joint, got {len(free)}")
        ((joint, value),) = free.items()
        sol = _solve_free(
            cache,
            arr,
            int(joint),
            float(value),
            tol=inner_tol,
            singular_tol=singular_tol,
            values=values,
            stretch=brought,
        )
    else:
        solver = cache.solver(values)
        if brought and isinstance(solver, ClosedFormSolver):
            # a pose that is not exact may lie a little outside the workspace: the arm
            # stretched (every negative radicand read as 0), kept if it reproduces the pose
            sol = solver.solve(
                arr, check=check, tol=inner_tol, singular_tol=singular_tol, stretch=True
            )
        else:
            sol = solver.solve(arr, check=check, tol=inner_tol, singular_tol=singular_tol)
    if brought and tols is not None:
        held = None if not free else {int(k): float(v) for k, v in free.items()}
        sol = _against_given(robot, sol, given, tols, values, rigid=arr, held=held)
    return _chosen(robot, sol, limits, near, free, values)


def _chosen(
    robot: KinematicChain,
    sol: IKSolution,
    limits: bool,
    near: object,
    free: Mapping[int, float] | None,
    values: Mapping[object, object] | None,
) -> IKSolution:
    """The solutions of one pose within the joint limits (``limits``), nearest to ``near``
    first, with the singular family named (a batch as it is)."""
    if not sol.batch:
        if not free and len(sol) and np.count_nonzero(sol.near):
            sol = replace(sol, note=singular_family(robot, sol, values))
        if limits:
            sol = within_limits(robot, sol)
        if near is not None:
            sol = nearest_first(robot, sol, near)
    return sol


def _surely_exact(T: np.ndarray) -> bool:
    """Whether the rotation of one pose ``(4, 4)`` is surely within
    :data:`~dhsym.ik.accuracy.EXACT` of the rotations, told without an SVD: ``RᵀR`` within
    1e-13 of ``I`` (then the distance from the nearest rotation is below 2e-13) and
    ``det R > 0``. False says nothing (NaN, a rounded pose): :func:`pose_accuracy` decides.

    >>> _surely_exact(np.eye(4)), _surely_exact(np.round(np.diag([0.6, 0.6, 1, 1]), 3))
    (True, False)
    """
    rows: list[list[float]] = T[:3].tolist()
    (a, b, c, _), (d, e, f, _), (g, h, i, _) = rows
    # each comparison is False for a NaN: a pose of NaNs is not surely exact
    return (
        a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g) > 0.0
        and abs(a * a + d * d + g * g - 1.0) <= 1e-13
        and abs(b * b + e * e + h * h - 1.0) <= 1e-13
        and abs(c * c + f * f + i * i - 1.0) <= 1e-13
        and abs(a * b + d * e + g * h) <= 1e-13
        and abs(a * c + d * f + g * i) <= 1e-13
        and abs(b * c + e * f + h * i) <= 1e-13
    )


def singular_family(
    robot: KinematicChain, sol: IKSolution, values: Mapping[object, object] | None = None
) -> str | None:
    """At a singular pose, the combination of two joints that is all that is determined,
    in words, or None: two revolute joints that turn about one line (the wrist at θ5 = 0)
    move together without moving the tool, so only their sum (or difference) is fixed and
    the solver gives one member of the family.

    Found from the first solution near a singularity: a null vector of its Jacobian with
    two equal entries (±) names the pair, and ``fk`` confirms the motion at a finite step
    (0.3 rad) keeps the pose (an instantaneous null motion, the stretched elbow, is not a
    family and gives None). A null vector over three or more joints with parallel axes
    (the UR arms at θ5 = 0: joints 2, 3, 4 and 6) names the sum of their turns
    (:func:`_parallel_family`).

    >>> import dhsym
    >>> r = dhsym.load("puma560")
    >>> import textwrap
    >>> print(textwrap.fill(r.ik(r.fk([0.3, -0.5, 0.4, 0.2, 0.0, -1.1])).note, 80))
    θ5 = 0: the wrist is singular (joints 4 and 6 turn about one line); θ4 + θ6 =
    -0.9 is all that is determined (the solutions there are given with θ4 = 0)
    """
    rows = [r for r in robot.table.rows if r.variable is not None]
    n = len(rows)
    if sol.batch or not len(sol) or n > 6:
        return None
    fk = robot.fk_function(values=values)
    revolute = _revolute(robot)
    for q, near in zip(sol.q, sol.near_singular):
        if not near:
            continue
        J = np.asarray(robot.jacobian(q, values=values))
        _, sv, vt = np.linalg.svd(J)
        if sv[-1] > 1e-6 * sv[0]:
            continue
        v = vt[-1]
        big = np.nonzero(np.abs(v) > 0.3)[0]
        if len(big) != 2 or not revolute[big].all() or abs(abs(v[big[0]]) - abs(v[big[1]])) > 1e-6:
            parallel = _parallel_family(robot, sol, q, v, J, values)
            if parallel is not None:
                return parallel
            continue
        i, j = (int(k) for k in big)
        step = np.zeros(n)
        step[[i, j]] = 0.3 * np.sign(v[[i, j]])
        if np.abs(fk(q + step) - fk(q)).max() > 1e-9:
            continue  # not a finite motion: no family
        same = np.sign(v[i]) != np.sign(v[j])  # opposite turns keep the sum
        name_i, name_j = _plain(robot.variables[i]), _plain(robot.variables[j])
        combo = _angle(q[i] + q[j] if same else q[j] - q[i])
        text = f"{name_i} + {name_j}" if same else f"{name_j} − {name_i}"
        place = _singular_place(robot, q, [i, j])
        every, given = _stated_choice(robot, sol, q, i)
        return (
            f"{place} is singular (joints {i + 1} and {j + 1} turn about one line); "
            f"{text} = {combo} is all that is determined ("
            + (f"the solutions there are given with {given}" if every else f"given {given}")
            + ")"
        )
    return None


def _parallel_family(
    robot: KinematicChain,
    sol: IKSolution,
    q: np.ndarray,
    v: np.ndarray,
    J: np.ndarray,
    values: Mapping[object, object] | None,
) -> str | None:
    """The family of :func:`singular_family` when three or more revolute joints turn about
    parallel axes (the UR arms at θ5 = 0: joints 2, 3, 4 and 6), or None.

    ``v`` is the null vector of the Jacobian ``J`` at ``q``; its joints (the entries not 0)
    must turn about parallel axes (the angular columns of ``J``), so their turns about that
    direction add up: ``Σ ±θ_k`` (the sign of each axis against the first) is what the
    rotation fixes. ``fk`` confirms a finite family: the last of these joints turned by
    ±0.3 rad and held, the Levenberg–Marquardt solver finds the others again from ``q``; the
    pose and the sum must be kept and another joint must have moved.

    >>> import dhsym
    >>> import textwrap
    >>> r = dhsym.load("ur5")
    >>> note = r.ik(r.fk([0.3, -1.1, 1.4, -0.6, 0.0, 0.4])).note
    >>> print(textwrap.fill(note.split(" (the")[0], 80))
    θ5 = 0: the wrist is singular (joints 2, 3, 4 and 6 turn about parallel axes); θ2
    + θ3 + θ4 + θ6 = 0.1 is all that is determined of their turns: θ6 may be chosen
    (within reach), θ2, θ3 and θ4 follow
    """
    revolute = _revolute(robot)
    support = np.nonzero(np.abs(v) > 1e-6)[0]
    if len(support) < 3 or not revolute[support].all():
        return None
    axes = J[3:, support]
    u = axes[:, 0] / np.linalg.norm(axes[:, 0])
    if np.abs(np.cross(u, axes.T)).max() > 1e-6:
        return None  # not all parallel: no sum of turns
    signs = np.sign(axes.T @ u)
    last = int(support[-1])
    fk = robot.fk_function(values=values)
    T = fk(q)
    total = float(signs @ q[support])
    for step in (0.3, -0.3):
        start = q.copy()
        start[last] += step
        moved = numeric_ik(robot, T, start, values=values, fixed={last + 1: float(start[last])})
        if not moved.converged:
            continue
        m = moved.q[0]
        kept = np.abs(fk(m) - T).max() <= 1e-9
        same = _angle(float(signs @ m[support]) - total) == "0"
        others = np.abs(np.angle(np.exp(1j * (m - start))))[support[:-1]].max() > 1e-6
        if kept and same and others:
            break
    else:
        return None  # no finite motion: no family
    names = [_plain(robot.variables[k]) for k in support]
    text = names[0] + "".join(
        f" + {name}" if sign > 0 else f" − {name}" for name, sign in zip(names[1:], signs[1:])
    )
    listed = ", ".join(str(k + 1) for k in support[:-1]) + f" and {last + 1}"
    place = _singular_place(robot, q, [int(k) for k in support])
    follow = ", ".join(names[:-2]) + f" and {names[-2]}" if len(names) > 2 else names[0]
    every, given = _stated_choice(robot, sol, q, last)
    return (
        f"{place} is singular (joints {listed} turn about parallel axes); "
        f"{text} = {_angle(total)} is all that is determined of their turns: {names[-1]} may "
        f"be chosen (within reach), {follow} follow ("
        + (
            f"the solutions there are given with {given}"
            if every
            else f"the first given with {given}"
        )
        + ")"
    )


def _singular_place(robot: KinematicChain, q: np.ndarray, joints: list[int]) -> str:
    """What is singular, in words: ``"θ5 = 0: the wrist"`` when one revolute joint between
    the first and the last of ``joints`` (0-based, in order) is not among them, and the
    family reaches the last joint of the arm; ``"joints i to j"`` otherwise."""
    revolute = _revolute(robot)
    first, last = joints[0], joints[-1]
    between = [
        f"{_plain(robot.variables[k])} = {_angle(q[k])}"
        for k in range(first + 1, last)
        if revolute[k] and k not in joints
    ]
    what = "the wrist" if last == len(q) - 1 else f"joints {first + 1} to {last + 1}"
    return (f"{between[0]}: " if len(between) == 1 else "") + what


def _stated_choice(
    robot: KinematicChain, sol: IKSolution, q: np.ndarray, k: int
) -> tuple[bool, str]:
    """Whether every solution near the singularity has joint ``k`` (0-based) at its value
    in ``q``, and that choice in words (``"θ4 = 0"``)."""
    singular = [row for row, hit in zip(sol.q, sol.near_singular) if hit]
    every = all(_angle(row[k] - q[k]) == "0" for row in singular)
    return every, f"{_plain(robot.variables[k])} = {_angle(q[k])}"


def _angle(x: float) -> str:
    """An angle in (−π, π] to four digits, rounding noise below 1e-9 read as 0."""
    y = float(np.angle(np.exp(1j * x)))
    return f"{0.0 if abs(y) < 1e-9 else y:.4g}"


def _plain(variable: object) -> str:
    """A joint variable as a student reads it (``θ4``)."""
    from .steps import branch_word

    return branch_word("sign", True, variable).split(" ")[4]


def _poses(arr: np.ndarray, check: str | None) -> bool:
    """Whether ``arr`` holds poses to bring to rigid ones (``check="pose"``, one pose
    ``(4, 4)`` or a batch ``(N, 4, 4)``), not positions."""
    return check == "pose" and arr.shape[-2:] == (4, 4) and arr.ndim in (2, 3)


def _tolerances(
    arr: np.ndarray, check: str | None, tol: float | None, rigid: np.ndarray | None = None
) -> np.ndarray | None:
    """The tolerance of each pose of ``arr`` (``()`` or ``(N,)``): ``tol`` when given, else
    the pose's own (:func:`~dhsym.ik.accuracy.pose_accuracy`, of ``rigid``, the nearest
    rigid poses, when known); None when :func:`_poses` says there is nothing to bring to a
    rigid pose."""
    if not _poses(arr, check):
        return None
    if tol is not None:
        return np.full(arr.shape[:-2], float(tol))
    if arr.ndim == 2:
        return np.array(pose_accuracy(arr, rigid).tol)
    # a batch: the poses surely exact (told at once, as _surely_exact tells one) have the
    # tolerance of an exact pose; only the others are measured one by one
    R = arr[:, :3, :3]
    with np.errstate(invalid="ignore", over="ignore"):
        gram = np.abs(np.matmul(R.transpose(0, 2, 1), R) - np.eye(3)).max(axis=(1, 2))
        exact = (gram <= 1e-13) & (np.linalg.det(np.where(np.isfinite(R), R, 0.0)) > 0.0)
    tols = np.full(len(arr), FLOOR)
    for k in np.nonzero(~exact)[0]:
        tols[k] = pose_accuracy(arr[k], None if rigid is None else rigid[k]).tol
    return tols


def _against_given(
    robot: KinematicChain,
    sol: IKSolution,
    given: np.ndarray,
    tols: np.ndarray,
    values: Mapping[object, object] | None,
    *,
    rigid: np.ndarray,
    held: Mapping[int, float] | None = None,
) -> IKSolution:
    """``sol`` (solutions of the nearest ``rigid`` poses) with each residual measured
    against the poses as ``given`` (largest entry error of ``fk``), the solutions within
    ``tols`` kept.

    A solution within :data:`~dhsym.ik.accuracy.REFINE` tolerances but not within one is
    refined first (:func:`_refined`): where rounding put the pose a little outside the
    workspace or a radicand a little below 0, the closed form (stretched) lands near the
    pose, not on it. Refined rows that meet an earlier row are dropped (two branches that
    merge at a singularity)."""
    fk = robot.fk_function(values=values)
    revolute = _revolute(robot)
    if not sol.batch:
        tol = float(tols)
        if not len(sol):
            return replace(sol, reason=_reason(sol.reason, given, tol))
        q = sol.q.copy()
        res = _entry_error(fk(q), given[None])
        moved = _refined(robot, q, res, rigid, given, tol, values, held)
        keep = np.nonzero(res <= tol)[0]
        if moved.any():
            keep = keep[_first_of_each(q[keep], revolute)]
        kept = replace(sol.take(keep, q), residual=res[keep])
        if not len(kept):
            said = sol.reason or (
                f"no branch of the {sol.method} reproduces the pose within {tol:.1g} "
                f"(the closest to {float(res.min()):.2g})"
            )
            return replace(kept, reason=_reason(said, given, tol))
        return kept
    valid = sol.valid.copy()
    residual = np.array(sol.residual, dtype=float)
    q = sol.q.copy()
    i, k = np.nonzero(valid)
    if i.size:
        flat = q[i, k]
        res = _entry_error(fk(flat), given[i])
        for pose in np.unique(i[(res > tols[i]) & (res <= REFINE * tols[i])]):
            rows = np.nonzero(i == pose)[0]
            part, part_res = flat[rows], res[rows]
            if _refined(
                robot, part, part_res, rigid[pose], given[pose], float(tols[pose]), values, held
            ).any():
                ok = np.nonzero(part_res <= tols[pose])[0]
                merged = np.setdiff1d(ok, ok[_first_of_each(part[ok], revolute)])
                part_res[merged] = np.inf  # a refined row that meets an earlier one
            flat[rows], res[rows] = part, part_res
        q[i, k] = flat
        residual[i, k] = res
        valid[i, k] = res <= tols[i]
    q[~valid] = np.nan
    return replace(sol, q=q, valid=valid, residual=residual)


def _refined(
    robot: KinematicChain,
    q: np.ndarray,
    res: np.ndarray,
    rigid: np.ndarray,
    given: np.ndarray,
    tol: float,
    values: Mapping[object, object] | None,
    held: Mapping[int, float] | None,
) -> np.ndarray:
    """Refine in place the rows of ``q`` ``(k, n)`` whose residual ``res`` against the pose
    as ``given`` is above ``tol`` but within :data:`~dhsym.ik.accuracy.REFINE` tolerances:
    Levenberg–Marquardt (:func:`~dhsym.ik.levenberg_marquardt.numeric_ik`, the joints of
    ``held`` held) from the row towards the ``rigid`` pose, the refined row and its
    residual kept when closer to the pose as given. Returns which rows moved.

    A stretched arm sits at a singular configuration, where the pose moves only to second
    order along the Jacobian's null direction ``v`` and Levenberg–Marquardt cannot leave
    it: when the first start does not reach the tolerance and the Jacobian there is nearly
    singular (:data:`_STUCK`), the row is refined again from ``q ± δ v``, ``δ = √res``
    (the step that moves the pose by about ``res``)."""
    fk = robot.fk_function(values=values)
    moving = np.array([k + 1 not in (held or {}) for k in range(q.shape[1])])
    moved = np.zeros(len(q), dtype=bool)
    for r in np.nonzero((res > tol) & (res <= REFINE * tol))[0]:
        starts = [q[r]]
        for attempt in range(2):
            for start in starts:
                step = numeric_ik(
                    robot, rigid, start, max_iter=REFINE_STEPS, values=values, fixed=held
                )
                better = float(_entry_error(fk(step.q), given[None])[0])
                if better < res[r]:
                    q[r], res[r], moved[r] = step.q[0], better, True
            if res[r] <= tol or attempt:
                break
            J = np.asarray(robot.jacobian(q[r], values=values))[:, moving]
            _, sv, vt = np.linalg.svd(J)
            if sv[-1] > _STUCK * sv[0]:
                break  # not singular: nothing holds it, it is no solution
            v = np.zeros(q.shape[1])
            v[moving] = vt[-1] * np.sqrt(res[r])
            starts = [q[r] + v, q[r] - v]
    return moved


def _first_of_each(q: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """The indices of the rows of ``q`` ``(k, n)`` that differ from every earlier row by
    more than :data:`_SAME` (angles compared by cosine and sine)."""
    key = np.concatenate([np.cos(q[:, revolute]), np.sin(q[:, revolute]), q[:, ~revolute]], axis=1)
    first = [
        r
        for r in range(len(q))
        if not (np.abs(key[:r] - key[r]).max(axis=1, initial=0) < _SAME).any()
    ]
    return np.array(first, dtype=int)


def _entry_error(got: np.ndarray, want: np.ndarray) -> np.ndarray:
    """The largest entry error of the top three rows of poses ``got`` against ``want``."""
    err: np.ndarray = np.abs(got[..., :3, :] - want[..., :3, :]).reshape(len(got), -1).max(axis=1)
    return err


def _reason(reason: str | None, given: np.ndarray, tol: float) -> str:
    """Why a pose brought to its nearest rigid pose has no solution."""
    acc = pose_accuracy(given)
    said = reason or "no solution"
    return (
        f"{said} (the pose as given is {acc.off:.1g} from a rigid pose: solved at the "
        f"nearest one, solutions kept within {tol:.1g} of the pose as given)"
    )


def sweep_free_joint(
    robot: KinematicChain,
    T: object,
    joint: int,
    *,
    num: int = 36,
    values: Mapping[object, object] | None = None,
    cache: IKCache | None = None,
) -> list[tuple[float, IKSolution]]:
    """The given joint swept over its range (``num`` values): the solutions within the
    joint limits at each value, as ``(value, solutions)`` for the values that have some
    (the chain with that joint given is derived once, in ``cache``: see :func:`solve`).

    >>> import dhsym
    >>> r = dhsym.load("panda")
    >>> T = r.fk([0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7])
    >>> found = sweep_free_joint(r, T, 7, num=12)
    >>> len(found) > 0 and all(len(s) for _, s in found)
    True
    """
    lo, hi = _limits(robot)
    a, b = lo[joint - 1], hi[joint - 1]
    if not np.isfinite(a + b):
        a, b = -np.pi, np.pi
    if cache is None:
        cache = IKCache(robot)
    out = []
    for v in np.linspace(a, b, num):
        sol = solve(robot, T, values=values, free={joint: float(v)}, limits=True, cache=cache)
        if len(sol):
            out.append((float(v), sol))
    return out
