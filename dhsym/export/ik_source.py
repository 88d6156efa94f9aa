"""The one place the exporters read the closed-form IK derivation (an adapter).

The exporters need, of a derived inverse kinematics: the pose symbols and how they
follow from a world-to-tool pose (base and tool undone), the steps in order (each
``lhs = rhs`` exact, with its sentence and the value at a singular wrist), the branch
signs in the order ``robot.ik`` enumerates them, each branch's name, and the
numbers the solver uses (the ``fk`` tolerance, the rounding of a radicand, the
wrist thresholds). :class:`IKSource` is that interface; :func:`ik_source` fills it
from :mod:`dhsym.ik` (the derivation, its compiler and results). When they move, only this
module changes.

Examples
--------
>>> import dhsym
>>> src = ik_source(dhsym.load("puma560"))
>>> [s.name for s in src.signs], len(src.steps), src.branch_names[0]
(['sigma_1', 'sigma_3', 'sigma_5'], 22, 'right arm, elbow down, wrist not flipped')
>>> src.steps[3].comment[0]
'Step 4 (position): Joint 1 turns the arm about z_0; ...'
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.ik import compiler as numbers
from dhsym.ik.derivation import InverseKinematics
from dhsym.ik.results import IKBatch
from dhsym.ik.results import _branch_names as solver_branch_names
from dhsym.model.table import JointType

if TYPE_CHECKING:
    from dhsym.kinematics.robot import Robot

__all__ = ["IKSource", "IKStep", "ik_source", "pose_input"]

_REAL = {"real": True}


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
class IKSource:
    """What the exporters need of a closed-form IK (see the module docstring)."""

    structure: str
    pose_symbols: tuple[sp.Symbol, ...]
    pose_inputs: tuple[tuple[sp.Symbol, sp.Expr], ...]
    steps: tuple[IKStep, ...]
    signs: tuple[sp.Symbol, ...]
    branch_names: tuple[str, ...]
    sqrt_rounding: float
    tolerance: float

    @property
    def count(self) -> int:
        """Number of branches (``MAX_IK_SOLUTIONS``)."""
        return 2 ** len(self.signs)

    def singular_guard(self, step: IKStep) -> tuple[sp.Symbol, float]:
        """The symbol whose magnitude decides the singular value of ``step``, and below what."""
        assert step.guard is not None
        return step.guard, step.threshold

    def has_sqrt(self, e: sp.Expr) -> bool:
        """Whether a prepared expression takes a square root."""
        return bool(e.has(numbers.SafeSqrt))

    def prepare(self, e: sp.Expr) -> sp.Expr:
        """``sqrt`` as the solver reads it: a radicand within rounding of 0 counts as 0."""
        return numbers._with_safe_sqrt(e)


def ik_source(robot: Robot, ik: InverseKinematics | None = None) -> IKSource:
    """Read the derivation of ``robot.inverse()`` into an :class:`IKSource`."""
    ik = ik if ik is not None else robot.inverse()
    assert ik is not None
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
    wrist = [s.lhs for s in ik.steps if s.branch is not None and s.branch.role == "wrist"]
    singular_steps = [s for s in ik.steps if s.singular is not None]
    # the solver's rule: the first singular step (θ4) takes its singular value at
    # |sin θ5| < _WRIST_ZERO, the second (θ6) at |sin θ5| < _WRIST_NEAR
    limits = (numbers._WRIST_ZERO, numbers._WRIST_NEAR)
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
        numbers._ROUNDING,
        1e-9,
    )


def _branch_names(robot: Robot, ik: InverseKinematics) -> tuple[str, ...]:
    """The name ``robot.ik`` gives each branch, in its order (signs ``+`` first, the first
    sign slowest). Elbow names depend on the geometry, so they are read off the solver at
    sample poses; a branch whose name changes between samples is named by its signs."""
    B = len(ik.branches)
    combos = list(itertools.product([1, -1], repeat=B))
    rng = np.random.default_rng(0)
    rows = [r for r in robot.table.rows if r.variable is not None]
    q = rng.uniform(-2.5, 2.5, (32, len(rows)))
    for k, r in enumerate(rows):
        if r.joint is not JointType.REVOLUTE:
            q[:, k] = rng.uniform(0.2, 0.8, 32)
    seen: list[set[str]] = [set() for _ in combos]
    try:
        batch = robot.ik(robot.fk(q))
        assert isinstance(batch, IKBatch)  # N poses give a batch
        solver = batch.solver
        for i in range(len(q)):
            if batch.valid[i].all():
                names = solver_branch_names(solver, batch.q[i], batch.branch_signs)
                for k, name in enumerate(names):
                    seen[k].add(name)
    except Exception:  # noqa: BLE001  (names are comments; the signs always name a branch)
        seen = [set() for _ in combos]
    out = []
    for k, signs in enumerate(combos):
        if len(seen[k]) == 1:
            out.append(next(iter(seen[k])))
        else:
            out.append(
                ", ".join(
                    f"{b.role} {b.symbol.name} = {'+1' if s > 0 else '-1'}"
                    for b, s in zip(ik.branches, signs)
                )
            )
    return tuple(out)
