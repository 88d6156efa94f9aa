r"""The ``screws`` derivation: a robot's screw axes and home configuration as data for the
templates (``screws.txt.j2``, ``screws.md.j2``, ``screws.tex.j2``).

The steps are those of :func:`dhsym.screws.product.from_chain` (Lynch and Park, *Modern
Robotics*, chapter 4): for each joint the DH frame whose ``z`` is its axis, the axis
``ω_i`` and a point ``q_i`` at home, ``v_i = −ω_i × q_i``; then ``M``, the space axes ``S``,
the body axes ``B = Ad_{M^{-1}} S`` and the two product-of-exponentials formulas.

>>> d = derive_screws("planar2r")
>>> d.kind, d.n, d.product_space.text
('screws', 2, 'e^([S1]*theta1) e^([S2]*theta2) M')
>>> d.steps[1].v.rows[1][0].text
'-a1'
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import sympy as sp

from dhsym.model.table import DHTable, JointType
from dhsym.notation.escape import TeX
from dhsym.notation.layout import (
    LATEX_WIDTH,
    LegendLine,
    Math,
    MatrixBlock,
    as_math,
    component_names,
    indexed_names,
    legend_lines,
    matrix_block,
)
from dhsym.notation.printers import TrigStyle
from dhsym.robot import Robot

from .data import Document
from .derivation import heading
from .velocity_kinematics import styled

__all__ = ["AxisData", "ScrewDerivation", "derive_screws"]


@dataclass(frozen=True)
class AxisData:
    """One joint's screw axis as the lecture finds it: the DH ``frame`` whose ``z`` is the
    axis, ``omega`` and ``point`` at home and ``v`` (``−ω × q``, or the direction)."""

    index: int
    revolute: bool
    variable: Math
    frame: Math
    omega: MatrixBlock
    point: MatrixBlock | None
    v: MatrixBlock


@dataclass(frozen=True)
class ScrewDerivation(Document):
    """A robot in product-of-exponentials form: the axes step by step, ``M``, ``S``, ``B``."""

    kind = "screws"

    name: str
    key: str
    convention: str
    n: int
    space_frame: Math
    tool_frame: Math
    steps: tuple[AxisData, ...]
    home: MatrixBlock
    space: MatrixBlock
    body: MatrixBlock
    product_space: Math
    product_body: Math
    legend: tuple[LegendLine, ...]
    width: float = LATEX_WIDTH


def _vector(label: Math, v: sp.MatrixBase, robot: Robot, width: float) -> MatrixBlock:
    return matrix_block(
        label, sp.Matrix(v), robot.notation, width=width, names=component_names(label)
    )


def derive_screws(
    name_or_robot: str | Path | DHTable | Robot,
    *,
    compact: bool | None = None,
    notation: TrigStyle | str | None = None,
    width: float = LATEX_WIDTH,
) -> ScrewDerivation:
    """The screw axes of a robot read off its DH frames at home, with ``M``, ``S`` and ``B``.

    ``compact``, ``notation`` and ``width`` as for :func:`~dhsym.explain.derivation.derive`.
    """
    robot = styled(name_or_robot, compact, notation)
    poe = robot.poe()
    steps = []
    for s in poe.steps:
        i = s.joint
        revolute = s.kind is JointType.REVOLUTE
        w = _vector(Math(TeX(rf"\omega_{{{i}}}"), f"omega{i}"), s.omega * s.rate, robot, width)
        q = _vector(Math(TeX(f"q_{{{i}}}"), f"q{i}"), s.point, robot, width) if revolute else None
        v = _vector(Math(TeX(f"v_{{{i}}}"), f"v{i}"), s.v, robot, width)
        steps.append(
            AxisData(
                i,
                revolute,
                as_math(s.variable, robot.notation),
                Math(TeX(str(s.frame)), str(s.frame)),
                w,
                q,
                v,
            )
        )
    S = poe.screw_matrix("space")
    B = poe.screw_matrix("body")
    return ScrewDerivation(
        **heading(robot, poe.n),
        space_frame=Math(TeX(str(poe.frames[0])), str(poe.frames[0])),
        tool_frame=Math(TeX(str(poe.frames[1])), str(poe.frames[1])),
        steps=tuple(steps),
        home=matrix_block(Math(TeX("M"), "M"), poe.home, robot.notation, width=width),
        space=matrix_block(
            Math(TeX("S"), "S"), S, robot.notation, width=width, names=indexed_names("S")
        ),
        body=matrix_block(
            Math(TeX("B"), "B"), B, robot.notation, width=width, names=indexed_names("B")
        ),
        product_space=Math(TeX(poe.product_latex("space")), poe.product_text("space")),
        product_body=Math(TeX(poe.product_latex("body")), poe.product_text("body")),
        legend=legend_lines([*poe.home, *S, *B], robot.notation),
        width=width,
    )
