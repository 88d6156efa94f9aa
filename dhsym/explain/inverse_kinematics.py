r"""Closed-form inverse kinematics as plain data, step by step, as the lectures derive it.

:func:`derive_inverse` arranges the steps of
:func:`dhsym.ik.families.inverse` for the templates: the pose
``[n s a p; 0 0 0 1]``, then the wrist centre, the position sub-problem
(``θ1 = atan2(p_y, p_x)`` and its second branch, the law of cosines for the elbow) and
the orientation sub-problem (the two wrist solutions), each step a sentence with its
math, the equation it solves and what it defines; every sign ``σ_j = ±1`` of an
``atan2`` or ``±√`` branch is named. With ``check`` it adds every solution of one pose,
named by its branches. Formulas come from the robot's
:class:`~dhsym.notation.printers.Notation`, split into lines when too wide.

Examples
--------
>>> d = derive_inverse("planar2r")
>>> [p.title for p in d.parts], d.count
(['Position: joints 1, 2'], 2)
>>> [r.name.text + " = " + r.text_lines[0] for s in d.parts[0].steps for r in s.results][-1]
'theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)'
>>> d.branches[0].role, "".join(r.words or r.math.text for r in d.branches[0].sentence)
('elbow', 'sigma_2 = 1 and sigma_2 = -1: the two elbow configurations (elbow up and elbow down)')
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.ik.closed_form import ClosedForm
from dhsym.ik.steps import BRANCH_NAMES, Branch, Step, root_words
from dhsym.model.table import DHTable, JointType
from dhsym.notation.escape import TeX
from dhsym.notation.layout import (
    LATEX_WIDTH,
    Equation,
    Math,
    Run,
    as_math,
    equation,
    legend_lines,
    matrix_block,
    sentence_runs,
)
from dhsym.notation.printers import Notation, TrigStyle
from dhsym.robot import Robot

from .data import BranchData, IKCheck, IKDerivation, IKPart, IKStepData
from .derivation import heading
from .velocity_kinematics import styled

__all__ = ["default_configuration", "derive_inverse"]

_TITLES = {
    "wrist centre": "The wrist centre",
    "position": "Position",
    "orientation": "Orientation",
    "inverted chain": "The chain read backwards",
    "shoulder": "The shoulder",
    "wrist": "The wrist",
    "planar arm": "The planar arm",
    "joint values": "Back to the joints of the table",
    "elimination": "The Raghavan–Roth elimination",
    "eigenproblem": "The eigenproblem",
}


def default_configuration(robot: Robot) -> list[float]:
    """A configuration away from every singularity of the built-in arms, for examples:
    ``(−1)^k (0.3 + 0.15 k)`` rad for revolute joint k, ``0.2 + 0.05 k`` for a prismatic one.

    >>> import dhsym
    >>> default_configuration(dhsym.load("planar2r"))
    [-0.45, 0.6]
    """
    out = []
    rows = [r for r in robot.table.rows if r.variable is not None]
    for k, row in enumerate(rows, start=1):
        if row.joint is JointType.REVOLUTE:
            out.append(round((-1) ** k * (0.3 + 0.15 * k), 10))
        else:
            out.append(round(0.2 + 0.05 * k, 10))
    return out


def _joints(numbers: Sequence[int]) -> str:
    js = list(numbers)
    return f"{js[0]}–{js[-1]}" if len(js) > 2 else ", ".join(map(str, js))


def _equation(lhs: sp.Expr, rhs: sp.Expr, nota: Notation, width: float) -> Equation:
    return equation(as_math(lhs, nota), rhs, as_math(rhs, nota), nota, width)


def _branch(b: Branch, nota: Notation) -> BranchData:
    return BranchData(as_math(b.symbol, nota), b.role, b.joint, sentence_runs(b.sentence, nota))


def _steps(steps: Sequence[Step], nota: Notation, width: float) -> tuple[IKStepData, ...]:
    """The steps of one part; consecutive plain steps with one sentence share it."""
    out: list[IKStepData] = []
    last = None
    for st in steps:
        result = _equation(st.lhs, st.rhs, nota, width)
        singular = (_equation(st.lhs, st.singular, nota, width),) if st.singular is not None else ()
        plain = st.equation is None and st.branch is None and not singular
        if plain and last is not None and last == st.sentence and out[-1].branch is None:
            prev = out[-1]
            out[-1] = IKStepData(
                prev.sentence, prev.equation, (*prev.results, result), None, prev.singular
            )
            continue
        # the equation is shown unless the result says it
        shown = st.equation if st.equation is not None and st.equation.rhs != st.rhs else None
        out.append(
            IKStepData(
                sentence_runs(st.sentence, nota),
                _equation(shown.lhs, shown.rhs, nota, width) if shown is not None else None,
                (result,),
                _branch(st.branch, nota) if st.branch is not None else None,
                singular,
            )
        )
        last = st.sentence if plain else None
    return tuple(out)


def _check(robot: Robot, q: Sequence[float], nota: Notation) -> IKCheck:
    missing = [str(s) for s in robot.table.constants if s not in robot.table.value_map]
    if missing:
        raise DHError(
            f"the numeric check needs values for {', '.join(missing)} "
            "(add them under 'values:' in the table)"
        )
    if len(q) != len(robot.variables):
        raise DHError(f"the numeric check needs {len(robot.variables)} joint values, got {len(q)}")
    ik = robot.inverse()
    T = robot.fk([float(x) for x in q])
    # a positioning arm reaches points, not poses (the general 6R has a wrist)
    position_only = isinstance(ik, ClosedForm) and not ik.decoupling.wrist
    sol = robot.ik(T[:3, 3] if position_only else T)
    revolute = [r.joint is JointType.REVOLUTE for r in robot.table.rows if r.variable is not None]

    def num(x: float, rev: bool) -> Math:
        s = f"{np.degrees(x):.2f}" if rev else f"{x:.4f}"
        s = s[1:] if s.lstrip("-").strip("0.") == "" else s
        return Math(TeX(s), s)

    def name(words: str, signs: Sequence[int]) -> tuple[Run, ...]:
        if not isinstance(ik, ClosedForm):  # no signs (the general 6R): "solution k"
            return (Run(words),)
        runs: list[Run] = []
        for k, (part, b, sign) in enumerate(zip(words.split(", "), ik.branches, signs)):
            runs += [Run(", ")] if k else []
            if b.role not in BRANCH_NAMES:  # the words of the IK results, the variable typeset
                var = robot.variables[b.joint - 1]
                before, after = root_words(sign > 0)
                runs += [Run(before + " "), Run(math=as_math(var, nota)), Run(" " + after)]
            else:
                runs.append(Run(part))
        return tuple(runs)

    plain = Notation()
    return IKCheck(
        tuple(
            (as_math(v, plain), num(float(x), rev))
            for v, x, rev in zip(robot.variables, q, revolute, strict=True)
        ),
        tuple(as_math(v, plain) for v in robot.variables),
        tuple(
            (
                name(words, signs),
                tuple(num(float(x), rev) for x, rev in zip(row, revolute, strict=True)),
            )
            for words, signs, row in zip(sol.branches, sol.signs, sol.q, strict=True)
        ),
        any(revolute),
        position_only,
    )


def derive_inverse(
    name_or_robot: str | Path | DHTable | Robot,
    *,
    compact: bool | None = None,
    notation: TrigStyle | str | None = None,
    check: bool | Sequence[float] | None = None,
    width: float = LATEX_WIDTH,
) -> IKDerivation:
    """The closed-form inverse kinematics of a robot, step by step.

    Parameters
    ----------
    name_or_robot
        A built-in name, a table file, a DHTable or a Robot.
    compact, notation, width
        As for :func:`~dhsym.explain.derivation.derive`.
    check
        Solve the pose of these joint values and list every solution (``True``: at
        :func:`default_configuration`); needs numbers for every length.

    Raises
    ------
    StructureError
        When the arm has no closed form by decoupling (the message says what is missing).

    >>> d = derive_inverse("puma560", check=True)
    >>> [p.title for p in d.parts]
    ['The wrist centre', 'Position: joints 1–3', 'Orientation: joints 4–6']
    >>> name, values = d.check.solutions[0]
    >>> len(d.check.solutions), "".join(r.words for r in name), [x.text for x in values][:3]
    (8, 'right arm, elbow down, wrist not flipped', ['-25.78', '34.38', '-42.97'])
    """
    robot = styled(name_or_robot, compact, notation)
    nota = robot.notation
    ik = robot.inverse()
    number = {r: i for i, r in enumerate(robot.table.joint_rows, start=1)}
    joints: dict[str, list[int]] = {}
    if isinstance(ik, ClosedForm):  # the general 6R has no decoupling
        joints["position"] = [number[r] for r in ik.decoupling.arm]
        joints["orientation"] = [number[r] for r in ik.decoupling.wrist]
    parts = []
    variables = {v: k for k, v in enumerate(robot.variables, start=1)}
    for part in dict.fromkeys(s.part for s in ik.steps):  # the parts in order of appearance
        steps = [s for s in ik.steps if s.part == part]
        title = _TITLES.get(part, part.capitalize())
        if part not in joints and part != "joint values":  # the joints this part solves
            joints[part] = sorted(variables[s.lhs] for s in steps if s.lhs in variables)
        if part in joints and joints[part]:
            word = "joint" if len(joints[part]) == 1 else "joints"
            title += f": {word} {_joints(joints[part])}"
        parts.append(IKPart(part, title, _steps(steps, nota, width)))
    shown: list[sp.Expr] = [s.rhs for s in ik.steps]
    shown += [s.equation.lhs for s in ik.steps if s.equation is not None]
    shown += [s.singular for s in ik.steps if s.singular is not None]
    flip = [b for b in ik.branches if b.role == "wrist"]
    wrist_angle = robot.variables[flip[0].joint - 1] if flip else None
    q = None if check is None or check is False else check
    if q is True:
        q = default_configuration(robot)
    return IKDerivation(
        **heading(robot, len(robot.variables)),
        structure=ik.structure,
        pose=matrix_block(Math(TeX("T"), "T"), ik.pose, Notation(), width=width),
        parts=tuple(parts),
        branches=tuple(_branch(b, nota) for b in ik.branches),
        count=ik.count,
        singular_when=as_math(sp.Eq(sp.sin(wrist_angle), 0), nota) if flip else None,
        legend=legend_lines(shown, nota),
        check=_check(robot, list(q), nota) if q is not None else None,
        width=width,
    )
