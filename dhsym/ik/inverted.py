r"""Arms whose first three axes meet or are parallel: the chain read backwards.

The inverse of the arm's pose, ``T⁻¹ = A_n⁻¹ ⋯ A_1⁻¹``, is the pose of the base seen
from the tool, and each inverse link is a DH link of the other convention:

* standard ``A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`` gives
  ``A_i⁻¹ = Rx(−α_i) Tx(−a_i) Rz(−θ_i) Tz(−d_i)``, a modified row;
* modified ``Rx(α_{i−1}) Tx(a_{i−1}) Rz(θ_i) Tz(d_i)`` gives
  ``Rz(−θ_i) Tz(−d_i) Tx(−a_{i−1}) Rx(−α_{i−1})``, a standard row.

So the reversed table, with joint variables ``φ_k = −θ_{n+1−k}``, is an arm of its
own whose *last* three axes meet (a spherical wrist) or are parallel: solve it for
``T⁻¹`` with its family, and read the joints back, ``θ_i = −φ_{n+1−i}``.

Examples
--------
>>> import dhsym
>>> t = reversed_table(dhsym.load("planar2r").table)
>>> t.convention.value, t.rows[0]
('modified', DHRow(R: theta=phi1, d=0, a=-a2, alpha=0))
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.decoupling import Decoupling, StructureError
from dhsym.model.kinds import Convention
from dhsym.model.parsing import symbol
from dhsym.model.table import DHRow, DHTable, JointType
from dhsym.notation.layout import sentence

from .closed_form import ClosedForm
from .decoupled import derive_decoupled
from .parallel import derive_parallel
from .steps import Branch, Step, pose_symbols
from .structure import INVERTED, PARALLEL, SPHERICAL_WRIST, classify

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["derive_inverted", "reversed_table"]

Matrix: TypeAlias = sp.ImmutableMatrix


def reversed_table(table: DHTable) -> DHTable:
    """The DH table of the chain read from the tool to the base (other convention),
    with joint variables ``phi_k = −θ_{n+1−k}`` (``psi_k`` when the table's own are
    ``phi``; base and tool left out)."""
    rows = []
    taken = {v.name for v in table.variables}
    letter = "phi" if not any(name.startswith("phi") for name in taken) else "psi"
    for k, row in enumerate(reversed(table.rows), start=1):
        if row.variable is None:
            rows.append(DHRow(JointType.FIXED, -row.theta, -row.d, -row.a, -row.alpha))
            continue
        phi = symbol(f"{letter}{k}")
        back = {row.variable: -phi}
        limits = None if row.limits is None else (-row.limits[1], -row.limits[0])
        rows.append(
            DHRow(
                row.joint,
                sp.expand((-row.theta).xreplace(back)),
                sp.expand((-row.d).xreplace(back)),
                -row.a,
                -row.alpha,
                variable=phi,
                limits=limits,
            )
        )
    other = Convention.MODIFIED if table.convention is Convention.STANDARD else Convention.STANDARD
    return replace(
        table,
        rows=tuple(rows),
        convention=other,
        name=f"{table.name} read backwards",
        base=(),
        tool=(),
    )


def derive_inverted(robot: KinematicChain) -> ClosedForm:
    """The closed form of ``robot`` through its reversed chain.

    >>> import dhsym
    >>> r = dhsym.load("puma560")
    >>> flipped = dhsym.Robot(reversed_table(r.table))
    >>> ik = derive_inverted(flipped)
    >>> ik.family, ik.count
    ('inverted chain', 8)
    """
    from dhsym.kinematics.chain import KinematicChain

    table = robot.table
    n = table.n
    back = KinematicChain(reversed_table(table))
    family = classify(back).family
    derive = {SPHERICAL_WRIST: derive_decoupled, PARALLEL: derive_parallel}.get(family)
    if derive is None:
        raise StructureError(f"read backwards the chain is a {family}: no closer to a closed form")
    try:
        rev = derive(back)
    except StructureError as err:
        raise StructureError(f"read backwards: {err.message}") from None
    pose = pose_symbols()
    R, p = pose[:3, :3], pose[:3, 3]
    inv = Matrix(R.T).row_join(Matrix(-R.T * p).applyfunc(sp.expand))
    primed = {
        pose[i, j]: sp.Symbol(f"{pose[i, j].name}_b", real=True) for i in range(3) for j in range(4)
    }
    steps: list[Step] = []
    words = sentence(
        "Read backwards, from the tool to the base, the chain is a table of the other "
        "convention whose joint k is joint {n1} − k of the table, negated; its pose is the "
        "inverse of the pose, with rotation {Rt} and position {pt} (entries marked b):",
        n1=n + 1,
        Rt=sp.Symbol("R^T"),
        pt=-sp.Symbol("R^T") * sp.Symbol("p"),
    )
    for j in range(4):
        for i in range(3):
            steps.append(Step("inverted chain", words, primed[pose[i, j]], inv[i, j]))
    variables = {v: k for k, v in enumerate(back.variables, start=1)}
    for st in rev.steps:
        steps.append(
            replace(
                st, rhs=st.rhs.xreplace(primed), singular=None, equation=_swap(st.equation, primed)
            )
        )
    branches = []
    for br in rev.branches:
        # read backwards, the reversed chain's wrist is the arm's shoulder; its arm and
        # elbow are no arm or elbow of this table: named by their roots
        role = {"wrist": "shoulder", "arm": "sign", "elbow": "sign"}.get(br.role, br.role)
        branches.append(Branch(br.symbol, role, n + 1 - br.joint, br.sentence))
    joints = [r for r in table.rows if r.variable is not None]
    for i, row in enumerate(joints, start=1):
        phi = back.variables[len(joints) - i]
        steps.append(
            Step(
                "joint values",
                sentence(
                    "Joint {i} of the table is joint {k} of the reversed chain, negated:",
                    i=i,
                    k=variables[phi],
                ),
                row.variable,
                -phi,
            )
        )
    rdec = rev.decoupling
    rows_back = {k: n + 1 - k for k in range(1, n + 1)}
    dec = Decoupling(
        tuple(sorted(rows_back[r] for r in rdec.arm)),
        tuple(sorted(rows_back[r] for r in rdec.wrist)),
        n - rdec.centre,
        rdec.centre_in_last,
    )
    structure = (
        f"{classify(robot)}: read backwards (tool to base) the chain is a {rev.family} — "
        f"{rev.structure} (joints of the reversed chain)"
    )
    return ClosedForm(robot, structure, dec, pose, tuple(steps), tuple(branches), family=INVERTED)


def _swap(eq: sp.Eq | None, primed: dict[sp.Symbol, sp.Symbol]) -> sp.Eq | None:
    return None if eq is None else sp.Eq(eq.lhs.xreplace(primed), eq.rhs.xreplace(primed))
