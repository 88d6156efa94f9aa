r"""The Jacobian and its singularities as plain data, in the order the lectures teach them.

:func:`derive_jacobian` builds each column of the geometric Jacobian the way the
lecture does (Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, §4.6):
the joint's axis ``z_{i-1}``, the lever ``o_n − o_{i-1}`` from a point of that axis
to the end effector, their cross product for a revolute joint (the axis itself for a
prismatic one) over the angular part, and then the whole matrix in the compact
notation. In the modified (Craig) convention joint *i* turns about ``z_i``, so the
axis frame is *i*. :func:`derive_singularities` factors its determinant (at the wrist
centre for an arm with a spherical wrist: ``det J = det J11 · det J22``) and names
every factor with the configurations where it vanishes. All numbers and formulas come
from :mod:`dhsym.kinematics.jacobian` and :mod:`dhsym.kinematics.singularities`; every
formula is printed by the robot's :class:`~dhsym.notation.printers.Notation`.

Examples
--------
>>> d = derive_jacobian("planar2r")
>>> [c.axis_label.text for c in d.columns], d.columns[0].column.rows[0][0].text
(['z_0', 'z_1'], '-a1*S1 - a2*S12')
>>> s = derive_singularities("puma560")
>>> s.method, s.determinant.text_lines[0]
('blocks', 'a2*S5*(a2*C2 + a3*C23 - d4*S23)*(a3*S3 + d4*C3)')
>>> [(f.kind, [z.text for z in f.zeros]) for f in s.factors if f.kind == "wrist"]
[('wrist', ['theta5 = 0', 'theta5 = pi'])]
"""

from __future__ import annotations

from pathlib import Path

import sympy as sp

from dhsym.kinematics.jacobian import geometric_jacobian
from dhsym.kinematics.singularities import reference_point, singularities
from dhsym.model.table import DHTable, JointType
from dhsym.notation.escape import TeX
from dhsym.notation.layout import (
    LATEX_WIDTH,
    Math,
    as_math,
    component_names,
    equation,
    indexed_names,
    legend_lines,
    math_width,
    matrix_block,
)
from dhsym.notation.printers import Notation, TrigStyle
from dhsym.robot import Robot

from .data import Block, FactorData, JacobianColumnData, JacobianDerivation, SingularityDerivation
from .derivation import as_robot, heading

__all__ = ["derive_jacobian", "derive_singularities", "styled"]


def styled(
    name_or_robot: str | Path | DHTable | Robot,
    compact: bool | None = None,
    notation: TrigStyle | str | None = None,
) -> Robot:
    """The robot in the asked notation; the same object (and its caches) when nothing changes."""
    robot = as_robot(name_or_robot)
    compact = robot.notation.compact if compact is None else compact
    style = robot.notation.style if notation is None else TrigStyle.parse(notation)
    if compact == robot.notation.compact and style is robot.notation.style:
        return robot
    return Robot(robot.table, compact=compact, style=style)


def _indexed(base: str, index: object) -> Math:
    """``z_{0}``, ``o_{6}``, ``o_{tool}``: a vector's name, printed by the printers."""
    return as_math(sp.Symbol(f"{base}_{index}"), Notation())


def derive_jacobian(
    name_or_robot: str | Path | DHTable | Robot,
    *,
    frame: int | str = "base",
    point: int | str = "tool",
    compact: bool | None = None,
    notation: TrigStyle | str | None = None,
    width: float = LATEX_WIDTH,
) -> JacobianDerivation:
    """The geometric Jacobian of a robot, column by column, as the lecture builds it.

    Parameters
    ----------
    name_or_robot
        A built-in name, a table file, a DHTable or a Robot.
    frame, point
        Where the vectors are written and whose origin moves (see
        :func:`~dhsym.kinematics.jacobian.geometric_jacobian`).
    compact, notation, width
        As for :func:`~dhsym.explain.derivation.derive`.

    >>> d = derive_jacobian("stanford")
    >>> d.columns[2].revolute, d.columns[2].lever is None, d.result.wide
    (False, True, True)
    """
    robot = styled(name_or_robot, compact, notation)
    nota = robot.notation
    J = geometric_jacobian(robot, frame, point)
    point_label = _indexed("o", J.point)
    columns = []
    shown: list[sp.Expr] = list(J.matrix)
    for i, c in enumerate(J.columns, start=1):
        axis_label = _indexed("z", c.axis_frame)
        origin_label = _indexed("o", c.axis_frame)
        revolute = c.joint is JointType.REVOLUTE
        names = component_names(axis_label)
        axis = matrix_block(axis_label, c.axis, nota, width=width, names=names)
        lever = None
        if revolute:
            lever_label = Math(
                TeX(f"{point_label.latex} - {origin_label.latex}"),
                f"{point_label.text} - {origin_label.text}",
            )
            lever = matrix_block(
                lever_label, c.lever, nota, width=width, names=component_names(lever_label)
            )
            shown += list(c.lever)
        formula = 2 * math_width(axis_label.latex) + 10
        formula += math_width(point_label.latex) + math_width(origin_label.latex)
        column = matrix_block(
            Math(TeX(f"J_{{{i}}}"), f"J{i}"),
            sp.Matrix.vstack(c.linear, c.angular),
            nota,
            width=width - formula,
            names=indexed_names("J", start=(1, i)),
        )
        together = sum(
            math_width(b.label.latex) + max(math_width(r[0].latex) for r in b.rows) + 4
            for b in (axis, lever)
            if b is not None
        )
        columns.append(
            JacobianColumnData(
                i,
                revolute,
                as_math(c.variable, nota),
                axis_label,
                origin_label,
                point_label,
                axis,
                lever,
                column,
                as_math(c.rate, nota) if c.rate != 1 else None,
                lever is None or (not lever.wide and together <= width),
            )
        )
    frame_label = "" if J.frame in (0, "W") else str(J.frame)
    label = (
        Math(TeX(f"{{}}^{{{frame_label}}}J"), f"J({frame_label})")
        if frame_label
        else Math(TeX("J"), "J")
    )
    result = matrix_block(
        label, J.matrix, nota, width=width, names=indexed_names("J", columns=True)
    )
    return JacobianDerivation(
        **heading(robot, len(J.columns)),
        frame=_frame_math(J.frame),
        point=point_label,
        columns=tuple(columns),
        result=result,
        legend=legend_lines(shown, nota),
        width=width,
    )


def _frame_math(frame: int | str) -> Math:
    return Math(TeX(str(frame)), str(frame))


#: measure → (LaTeX, text) of the measure and of the matrix it is the determinant of
_MEASURE = {
    "det J": (r"\det J", "det J", "J", "J"),
    "det J_v": (r"\det J_{v}", "det J_v", "J_{v}", "J_v"),
    "det J_w": (r"\det J_{\omega}", "det J_w", r"J_{\omega}", "J_w"),
    "det(J J^T)": (r"\det(J J^{T})", "det(J J^T)", "J", "J"),
}


def _method(measure: str, blocks: int) -> str:
    if blocks == 2:
        return "blocks"
    return {
        "det J_w": "wrist",
        "det J_v": "position",
        "det J": "rows",
        "det(J J^T)": "manipulability",
    }[measure]


def derive_singularities(
    name_or_robot: str | Path | DHTable | Robot,
    *,
    compact: bool | None = None,
    notation: TrigStyle | str | None = None,
    width: float = LATEX_WIDTH,
) -> SingularityDerivation:
    """The factored Jacobian determinant of a robot, each factor named, with its zeros.

    >>> d = derive_singularities("planar2r")
    >>> d.measure.text, d.determinant.text_lines, [f.kind for f in d.factors]
    ('det J_v', ('a1*a2*S2',), ['constant', 'constant', 'elbow'])
    """
    robot = styled(name_or_robot, compact, notation)
    nota = robot.notation
    s = singularities(robot)
    method = "whole" if s.whole else _method(s.measure, len(s.blocks))
    measure = Math(TeX(_MEASURE[s.measure][0]), _MEASURE[s.measure][1])
    blocks = []
    shown: list[sp.Expr] = [s.determinant]
    for b in s.blocks:
        if method == "blocks":
            tex, text = (f"J_{{{b.name[1:]}}}", b.name)
        else:
            tex, text = _MEASURE[s.measure][2:]
        label = Math(TeX(tex), text)
        mat = matrix_block(label, b.matrix, nota, width=width, names=indexed_names("b"))
        det_label = Math(TeX(rf"\det {tex}"), f"det {text}")
        det = equation(det_label, b.determinant, as_math(b.determinant, nota), nota, width)
        blocks.append(Block(label, _frame_math(b.frame), None if mat.wide else mat, det))
        shown += list(b.matrix) if not mat.wide else []
        shown.append(b.determinant)
    factors = tuple(
        FactorData(
            f.kind,
            f.name,
            f.description,
            as_math(f.expr, nota),
            f.power,
            tuple(as_math(sp.Eq(v, z), nota) for v, z in f.solutions),
        )
        for f in s.factors
    )
    return SingularityDerivation(
        **heading(robot, len(robot.variables)),
        method=method,
        point=(
            reference_point(robot)[1]
            if method == "whole"
            else "wrist centre"
            if method in ("blocks", "wrist")
            else "end effector"
        ),
        measure=measure,
        blocks=tuple(blocks),
        determinant=equation(measure, s.determinant, as_math(s.determinant, nota), nota, width),
        factors=factors,
        legend=legend_lines(shown, nota),
        width=width,
    )
