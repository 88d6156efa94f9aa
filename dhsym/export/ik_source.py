"""The one place the exporters read the closed-form IK derivation (an adapter).

The exporters need, of a derived inverse kinematics: the pose symbols and how they
follow from a world-to-tool pose (base and tool undone), the steps in order (each
``lhs = rhs`` exact, with its sentence and the value at a singular wrist), the branch
signs in the order ``robot.ik`` enumerates them, each branch's name, and the
numbers the solver uses (the ``fk`` tolerance, the rounding of a radicand, the
wrist thresholds). :class:`IKSource` is that interface; :func:`ik_source` fills it
from the ik room: the derivation (:mod:`dhsym.ik.families`, one module per family:
spherical wrist and planar arms, three parallel axes, the chain read backwards), the
numbers of its program rewriting (:mod:`dhsym.ik.rewriting`) and the branch names of
its solver (:mod:`dhsym.ik.closed_form_solver`). When the derivation moves, only this
module changes.

Every family whose steps are closed forms is exported; the general 6R, solved by an
eigenvalue problem per pose (:mod:`dhsym.ik.general6r`), is not: :func:`ik_source`
refuses it with a :class:`~dhsym.errors.DHError` that says so.

Examples
--------
>>> import dhsym
>>> src = ik_source(dhsym.load("puma560"))
>>> [s.name for s in src.signs], len(src.steps), src.branch_names[0]
(['sigma_1', 'sigma_3', 'sigma_5'], 22, 'right arm, elbow down, wrist not flipped')
>>> src.steps[3].comment[0]
'Step 4 (position): Joint 1 turns the arm about z_0; ...'
>>> ur5 = ik_source(dhsym.load("ur5"))
>>> [s.name for s in ur5.signs], ur5.count, ur5.branch_names[0]
(['sigma_1', 'sigma_5', 'sigma_3'], 8, 'right arm, wrist not flipped, elbow sigma_3 = +1')
>>> ik_source(dhsym.load("jaco"))  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
dhsym.errors.DHError: Kinova Jaco: general 6R: the eigenvalue solver is not exported ...
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.ik import levenberg_marquardt as _lm
from dhsym.ik.accuracy import EXACT, FLOOR, MOST_DECIMALS, REFINE, REFINE_STEPS, SAME, STUCK
from dhsym.ik.choices import IKCache
from dhsym.ik.closed_form import ClosedForm
from dhsym.ik.closed_form import ClosedForm as InverseKinematics  # what is exported
from dhsym.ik.closed_form_solver import ClosedFormSolver
from dhsym.ik.rewriting import ROUNDING, WRIST_NEAR, WRIST_ZERO, SafeSqrt, with_safe_sqrt
from dhsym.ik.structure import GENERAL_6R, classify
from dhsym.kinematics.decoupling import StructureError
from dhsym.model.table import JointType

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["IKSource", "IKStep", "Refinement", "ik_source", "pose_input"]


def pose_input() -> sp.IndexedBase:
    """The input pose ``T`` (4×4, row-major in C): ``T[i, j]``."""
    return sp.IndexedBase("T", shape=(4, 4))


@dataclass(frozen=True)
class IKStep:
    """One step: ``lhs = rhs``; ``comment`` names the step and says what it does;
    ``singular`` is the value used at a singular wrist (``None``: the same)."""

    lhs: sp.Symbol
    rhs: sp.Expr
    comment: tuple[str, ...]
    singular: sp.Expr | None
    guard: sp.Symbol | None
    threshold: float


@dataclass(frozen=True)
class Refinement:
    """The numbers of ``robot.ik``'s refinement of a branch near a pose that is not exact
    (:mod:`dhsym.ik.accuracy`, and the steps of
    :func:`~dhsym.ik.levenberg_marquardt.numeric_ik`), which the exported IK repeats.

    A branch whose residual against the pose as given is above the tolerance but within
    ``within`` tolerances gets at most ``steps`` Levenberg–Marquardt steps towards the
    nearest rigid pose (the error: the position and the rotation vector, base frame; the
    step: ``(JᵀJ + λ diag(diag(JᵀJ) + diagonal_floor)) Δq = Jᵀe``, λ from ``damping``,
    divided or multiplied by ``damping_step`` within ``damping_range``; stop when the
    error's length is below ``converged``). When that does not reach the tolerance and the
    Jacobian's smallest singular value is below ``stuck`` times its largest (a stretched
    arm), it starts again from ``q ± √res v`` (``v`` the Jacobian's null direction). Rows
    closer than ``same`` (by cosine and sine) are one once a row moved.

    >>> r = Refinement()
    >>> r.within, r.steps, r.stuck, r.same
    (30.0, 12, 0.001, 1e-06)
    """

    within: float = float(REFINE)
    steps: int = REFINE_STEPS
    stuck: float = STUCK
    same: float = SAME
    damping: float = _lm.DAMPING
    damping_step: float = _lm.DAMPING_STEP
    damping_range: tuple[float, float] = _lm.DAMPING_RANGE
    diagonal_floor: float = _lm.DIAGONAL_FLOOR
    converged: float = _lm.CONVERGED


@dataclass(frozen=True)
class IKSource:
    """What the exporters need of a closed-form IK (see the module docstring)."""

    structure: str
    pose_symbols: tuple[sp.Symbol, ...]
    pose_inputs: tuple[tuple[sp.Symbol, sp.Expr], ...]
    steps: tuple[IKStep, ...]
    signs: tuple[sp.Symbol, ...]
    branch_names: tuple[str, ...]
    sqrt_rounding: float
    #: the tolerance of an exact pose (the least of any), and the rule's other numbers
    #: (:mod:`dhsym.ik.accuracy`): a rotation off the rotations by at most ``exact`` is
    #: exact; the most decimals looked for in a pose's entries
    tolerance: float
    exact: float = EXACT
    most_decimals: int = MOST_DECIMALS
    #: how a branch near a pose that is not exact is refined (as ``robot.ik`` does)
    refinement: Refinement = Refinement()

    @property
    def count(self) -> int:
        """Number of branches (``MAX_IK_SOLUTIONS``)."""
        return int(2 ** len(self.signs))

    def singular_guard(self, step: IKStep) -> tuple[sp.Symbol, float]:
        """The symbol whose magnitude decides the singular value of ``step``, and below what."""
        assert step.guard is not None
        return step.guard, step.threshold

    def has_sqrt(self, e: sp.Expr) -> bool:
        """Whether a prepared expression takes a square root."""
        return bool(e.has(SafeSqrt))

    def prepare(self, e: sp.Expr) -> sp.Expr:
        """``sqrt`` as the solver reads it: a radicand within rounding of 0 counts as 0."""
        return with_safe_sqrt(e)


def derivation(robot: KinematicChain, cache: IKCache | None = None) -> InverseKinematics:
    """The closed form of ``robot`` (derived in ``cache``, by default a fresh
    :class:`~dhsym.ik.choices.IKCache`), or one :class:`~dhsym.errors.DHError` saying why
    it cannot be exported (the general 6R: its eigenvalue solver is not exported; no
    closed form).

    >>> import dhsym
    >>> derivation(dhsym.load("ur3")).family
    'three parallel axes'
    >>> derivation(dhsym.load("planar4r"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: Planar 4R (redundant): no closed-form IK to export: ...
    """
    name = robot.name or "this robot"
    general = DHError(
        f"{name}: general 6R: the eigenvalue solver is not exported (its IK is a "
        "generalised eigenproblem per pose, dhsym.ik.general6r, not straight-line "
        "code); export fk and jacobian only"
    )
    try:
        ik = (cache if cache is not None else IKCache(robot)).inverse()
    except StructureError as err:
        if classify(robot).family == GENERAL_6R:
            raise general from None
        raise DHError(f"{name}: no closed-form IK to export: {err.message}") from None
    if not isinstance(ik, ClosedForm):  # the general 6R: an Elimination
        raise general
    return ik


def _straight_line_steps(robot: KinematicChain, ik: InverseKinematics) -> None:
    """Refuse a derivation whose steps are not straight-line code (naming why): every
    step must be an expression of the pose, earlier steps and the branch signs."""
    known = set(ik.pose.free_symbols) | {b.symbol for b in ik.branches}
    for k, s in enumerate(ik.steps, start=1):
        for e in (s.rhs, s.singular):
            if e is None:
                continue
            unknown = e.free_symbols - known - set(robot.table.constants)
            bad = [f for f in e.atoms(sp.Function) if not _printable(f)]
            if unknown or bad:
                what = ", ".join(sorted(map(str, unknown | set(bad))))
                raise DHError(
                    f"{robot.name or 'this robot'}: the {ik.family} IK is not exported: step "
                    f"{k} ({s.part}) uses {what}, which is not straight-line code"
                )
        known.add(s.lhs)


def _printable(f: sp.Expr) -> bool:
    """Functions every exporter prints (the rest would be a solver, not a formula)."""
    return isinstance(f, (sp.sin, sp.cos, sp.tan, sp.atan2, sp.atan, sp.asin, sp.acos, sp.Abs))


def ik_source(
    robot: KinematicChain, ik: InverseKinematics | None = None, *, cache: IKCache | None = None
) -> IKSource:
    """Read the closed form of ``robot`` (``ik``, else derived in ``cache``: see
    :func:`derivation`) into an :class:`IKSource`.

    Raises
    ------
    DHError
        For an arm without a closed form, and for the general 6R (its eigenvalue solver
        is not exported).
    """
    ik = ik if ik is not None else derivation(robot, cache)
    _straight_line_steps(robot, ik)
    pose = ik.pose
    T = pose_input()
    Tin = sp.Matrix(4, 4, lambda i, j: T[i, j])
    first = -1 if robot.table.base else 0
    last = robot.n + 1 if robot.table.tool else robot.n
    inner = Tin
    if first == -1:
        inner = robot.transform(0, -1).matrix * inner
    if last == robot.n + 1:
        inner = inner * robot.transform(robot.n + 1, robot.n).matrix
    cells = [(i, j) for j in range(4) for i in range(3)]
    pose_symbols = tuple(pose[i, j] for i, j in cells)
    inputs = tuple((pose[i, j], sp.expand(inner[i, j])) for i, j in cells)
    # as the compiler: only a derivation that says what to do at a singular wrist watches it
    wrist = [s.lhs for s in ik.steps if s.branch is not None and s.branch.role == "wrist"]
    singular_steps = [s for s in ik.steps if s.singular is not None]
    # the solver's rule: the first singular step (θ4) takes its singular value at
    # |sin θ5| < _WRIST_ZERO, the second (θ6) at |sin θ5| < _WRIST_NEAR
    limits = (WRIST_ZERO, WRIST_NEAR)
    thresholds = {id(s): t for s, t in zip(singular_steps, limits)}
    steps = []
    for k, s in enumerate(ik.steps, start=1):
        words = f"Step {k} ({s.part}): {s.text}"
        steps.append(
            IKStep(
                s.lhs,
                s.rhs,
                (words, f"{ik.text(s)}"),
                s.singular,
                wrist[0] if (s.singular is not None and wrist) else None,
                thresholds.get(id(s), 0.0),
            )
        )
    return IKSource(
        ik.structure,
        pose_symbols,
        inputs,
        tuple(steps),
        tuple(b.symbol for b in ik.branches),
        _branch_names(robot, ik),
        ROUNDING,
        FLOOR,
    )


def _branch_names(robot: KinematicChain, ik: InverseKinematics) -> tuple[str, ...]:
    """The name ``robot.ik`` gives each branch, in its order (signs ``+`` first, the first
    sign slowest), one part per branch sign. Elbow names depend on the geometry, so they
    are read off the solver at sample poses; a part that changes between samples (the
    elbow of a UR, up or down depending on the other signs) is named by its sign."""
    B = len(ik.branches)
    combos = list(itertools.product([1, -1], repeat=B))
    rng = np.random.default_rng(0)
    rows = [r for r in robot.table.rows if r.variable is not None]
    q = rng.uniform(-2.5, 2.5, (32, len(rows)))
    for k, r in enumerate(rows):
        if r.joint is not JointType.REVOLUTE:
            q[:, k] = rng.uniform(0.2, 0.8, 32)
    seen: list[list[set[str]]] = [[set() for _ in range(B)] for _ in combos]
    try:
        solver = ClosedFormSolver(ik, robot.table.value_map)
        batch = solver.solve(robot.fk(q), check="pose", tol=1e-9, singular_tol=1e-6)
        for i in range(len(q)):
            if batch.valid[i].all():
                names = batch.solution(i).branches
                for k, name in enumerate(names):
                    parts = name.split(", ")
                    if len(parts) == B:
                        for j, part in enumerate(parts):
                            seen[k][j].add(part)
    except Exception:  # noqa: BLE001  (names are comments; the signs always name a branch)
        seen = [[set() for _ in range(B)] for _ in combos]
    out = []
    for k, signs in enumerate(combos):
        parts = []
        for j, (b, s) in enumerate(zip(ik.branches, signs)):
            if len(seen[k][j]) == 1:
                parts.append(next(iter(seen[k][j])))
            else:
                parts.append(f"{b.role} {b.symbol.name} = {'+1' if s > 0 else '-1'}")
        out.append(", ".join(parts))
    return tuple(out)
