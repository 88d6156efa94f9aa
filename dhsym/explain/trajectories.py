r"""The trajectory lecture as a document: the cubic, the quintic and the linear segment
with parabolic blends of one joint, each derived from its boundary conditions
(:mod:`dhsym.trajectory`), as plain data for the templates ``trajectory.*.j2``
(``dhsym derive NAME --what trajectory``, the handout's ``trajectory`` section); and the
control lecture's closed loop (:func:`dhsym.control.error_equation`) for ``control.*.j2``
(``--what control``).

Examples
--------
>>> d = derive_trajectory("planar2r")
>>> [s.title for s in d.sections]
['Cubic polynomial', 'Quintic polynomial', 'Linear segment with parabolic blends']
>>> d.sections[1].solution[3].text
'a3 = 10*(-q_0 + q_f)/t_f**3'
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.table import DHTable
from dhsym.notation.escape import TeX
from dhsym.notation.layout import LATEX_WIDTH, LegendLine, Math
from dhsym.robot import Robot
from dhsym.trajectory import Derivation as ProfileDerivation
from dhsym.trajectory import Profile, cubic, lspb, quintic
from dhsym.trajectory.profiles import TIME

from .data import Document
from .derivation import as_robot

__all__ = [
    "ControlDerivation",
    "ProfileSection",
    "TrajectoryDerivation",
    "derive_control",
    "derive_trajectory",
]


@dataclass(frozen=True)
class ProfileSection:
    """One profile derived: the ``conditions`` (each a boundary condition as an
    equation), the linear ``system`` when there is one, the ``solution`` (one per
    unknown), the ``assumptions`` it needs and the ``position`` ``q(t)`` it gives."""

    key: str
    title: str
    source: str
    conditions: tuple[Math, ...]
    system: Math | None
    solution: tuple[Math, ...]
    assumptions: tuple[Math, ...]
    position: Math


@dataclass(frozen=True)
class TrajectoryDerivation(Document):
    """The profiles of one joint of ``name`` (every joint ``q_i`` moves so, from
    ``q_{i,0}`` to ``q_{i,f}``), each derived (:class:`ProfileSection`)."""

    kind = "trajectory"

    name: str
    convention: str
    joints: tuple[Math, ...]
    sections: tuple[ProfileSection, ...]
    legend: tuple[LegendLine, ...] = ()
    width: float = LATEX_WIDTH


def _math(expr: sp.Basic) -> Math:
    return Math(TeX(sp.latex(expr)), sp.sstr(expr))


def _equation(lhs: sp.Basic, rhs: sp.Basic) -> Math:
    return Math(TeX(f"{sp.latex(lhs)} = {sp.latex(rhs)}"), f"{sp.sstr(lhs)} = {sp.sstr(rhs)}")


def _section(key: str, title: str, source: str, d: ProfileDerivation, q: sp.Expr) -> ProfileSection:
    system = None
    if d.matrix is not None and d.rhs is not None:
        x = sp.Matrix(d.unknowns)
        system = Math(
            TeX(f"{sp.latex(d.matrix)} {sp.latex(x)} = {sp.latex(d.rhs)}"),
            f"A x = b with A = {sp.sstr(d.matrix.tolist())}, x = {sp.sstr(list(d.unknowns))}, "
            f"b = {sp.sstr(list(d.rhs))}",
        )
    return ProfileSection(
        key=key,
        title=title,
        source=source,
        conditions=tuple(_equation(e.lhs, e.rhs) for e in d.equations),
        system=system,
        solution=tuple(_equation(u, s) for u, s in d.pairs),
        assumptions=tuple(_math(c) for c in d.conditions),
        position=_equation(sp.Function("q")(sp.Symbol("t")), q),
    )


def _position(p: Profile) -> sp.Expr:
    """``q(t)``: the polynomial, or for the blends the lecture's three pieces in the
    derivation's unknowns ``t_b`` and ``a`` (``q_0 + a t²/2``, the line, ``q_f − a (t_f −
    t)²/2``), proven equal to the profile's segments."""
    segs = p.joints[0]
    t = TIME
    if len(segs) == 1:
        return sp.Add(*(c * t**k for k, c in enumerate(segs[0].coefficients)))
    d = p.derivation()
    (tb, tb_value), (acc, acc_value) = d.pairs
    first, line, last = segs
    q0, tf = first.coefficients[0], last.end
    qf = sp.simplify(last.position(tf))
    t = TIME
    pieces = (
        q0 + acc * t**2 / 2,
        q0 + acc * tb**2 / 2 + line.coefficients[1] * (t - tb),
        qf - acc * (tf - t) ** 2 / 2,
    )
    values = {tb: tb_value, acc: acc_value}
    for piece, seg in zip(pieces, segs):
        if sp.simplify(piece.xreplace(values) - seg.position(t)) != 0:  # pragma: no cover
            raise DHError(f"the blend's piece {piece} is not the profile's segment")
    return sp.Piecewise(
        (pieces[0], t <= tb), (pieces[1], t <= tf - tb), (pieces[2], True), evaluate=False
    )


def derive_trajectory(robot: Robot | str | Path | DHTable) -> TrajectoryDerivation:
    """The cubic, quintic and LSPB profiles of a joint of ``robot``, derived symbolically
    (``q_0``, ``q_f``, ``t_f``; the blend's velocity ``V``)."""
    r = as_robot(robot)
    q0, qf, tf, V = sp.symbols("q_0 q_f t_f V", positive=True)
    profiles = (
        ("cubic", "Cubic polynomial", "Craig, Introduction to Robotics, ch. 7", cubic(q0, qf, tf)),
        (
            "quintic",
            "Quintic polynomial",
            "Spong, Hutchinson and Vidyasagar, Robot Modeling and Control, ch. 5",
            quintic(q0, qf, tf),
        ),
        (
            "lspb",
            "Linear segment with parabolic blends",
            "Lynch and Park, Modern Robotics, ch. 9",
            lspb(q0, qf, tf, v=V),
        ),
    )
    sections = tuple(
        _section(key, title, source, p.derivation(), _position(p))
        for key, title, source, p in profiles
    )
    return TrajectoryDerivation(
        name=r.name or "robot",
        convention=r.convention.value,
        joints=tuple(_math(v) for v in r.variables),
        sections=sections,
    )


@dataclass(frozen=True)
class ControlDerivation(Document):
    """The closed loop of computed torque on ``name``: the ``steps`` from the arm's
    equation to the error equation, and the ``gains`` for a natural frequency and
    damping."""

    kind = "control"

    name: str
    convention: str
    steps: tuple[tuple[str, Math], ...]
    gains: tuple[Math, ...]
    legend: tuple[LegendLine, ...] = ()
    width: float = LATEX_WIDTH


def _dotted(eq: sp.Eq) -> tuple[sp.Expr, sp.Expr]:
    """Both sides of ``eq`` with the derivatives of q(t), q_d(t), e(t) written with dots
    (``\\dot q``, ``\\ddot q_d``) as the lecture writes them."""
    t = sp.Symbol("t", real=True)
    names = {
        "q": ("q", "qdot", "qddot"),
        "q_d": ("q_d", "qdot_d", "qddot_d"),
        "e": ("e", "edot", "eddot"),
    }
    pairs: list[tuple[sp.Basic, sp.Basic]] = []
    for fn, (zero, one, two) in names.items():
        f = sp.Function(fn)(t)
        pairs += [(f.diff(t, 2), sp.Symbol(two)), (f.diff(t), sp.Symbol(one)), (f, sp.Symbol(zero))]
    return eq.lhs.subs(pairs), eq.rhs.subs(pairs)


def derive_control(robot: Robot | str | Path | DHTable) -> ControlDerivation:
    """The computed-torque closed loop of ``robot`` derived (M, h = C q̇ + g its own).

    >>> [label for label, _ in derive_control("planar2r").steps][-1]
    'M is invertible: the error equation'
    """
    from dhsym.control import error_equation

    r = as_robot(robot)
    e = error_equation()
    return ControlDerivation(
        name=r.name or "robot",
        convention=r.convention.value,
        steps=tuple((label, _equation(*_dotted(eq))) for label, eq in e.steps),
        gains=tuple(_equation(u, v) for u, v in e.gains.pairs),
    )
