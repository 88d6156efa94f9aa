r"""The equations of motion as plain data, in the order the dynamics lecture derives them.

:func:`derive_dynamics` arranges what :mod:`dhsym.dynamics` computes for the templates,
following Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, chapter 7
(Lagrange–Euler) and Craig, *Introduction to Robotics*, chapter 6 (recursive
Newton–Euler): the table of each link's mass, centre of mass and inertia, the kinetic
energy ``K_i`` and potential energy ``P_i`` of each link, the inertia matrix entries
``M_ij`` (Spong's ``d_ij``), the nonzero Christoffel symbols
``c_ijk = ½(∂M_kj/∂q_i + ∂M_ki/∂q_j − ∂M_ij/∂q_k)`` and the matrix ``C(q, q̇)`` they make,
the gravity vector ``g_k = ∂P/∂q_k``
and the joint torques ``τ_k``; then the Newton–Euler table, velocities and accelerations
outward from the base, forces and torques inward from the tip. Every formula is printed
by the robot's :class:`~dhsym.notation.printers.Notation` (compact C/S) and split into
lines when too wide.

Examples
--------
>>> d = derive_dynamics("planar2r")
>>> [e.name.text for e in d.inertia], d.inertia[2].text_lines[0]
(['M11', 'M12', 'M22'], 'Izz2 + m2*(a2**2 + rx2**2 + ry2**2 + 2*a2*rx2)')
>>> [s.value.label.text for s in d.outward if s.link == 1][:2]
['omega_1', 'omegadot_1']
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import sympy as sp

from dhsym.dynamics.compact_form import GroupedConstant, compact_dynamics
from dhsym.dynamics.equations import EquationsOfMotion, NEStep
from dhsym.dynamics.lagrange_euler import RING_JOINTS
from dhsym.dynamics.model import DynamicModel
from dhsym.dynamics.recursive_newton_euler import rne_expressions
from dhsym.model.inertia import LinkInertia
from dhsym.model.table import DHTable
from dhsym.notation.escape import TeX
from dhsym.notation.layout import (
    LATEX_WIDTH,
    Equation,
    Math,
    as_math,
    component_names,
    equation,
    indexed_names,
    legend_lines,
    matrix_block,
)
from dhsym.notation.printers import Notation, TrigStyle
from dhsym.robot import Robot

from .data import DynamicsDerivation, EnergyData, LinkData, NEStepData
from .derivation import heading
from .velocity_kinematics import styled

__all__ = ["derive_dynamics"]

#: a Newton–Euler vector's name → (LaTeX, text) of its symbol, ``{i}`` the link
_VECTORS = {
    "omega": (r"\omega_{{{i}}}", "omega_{i}"),
    "omegadot": (r"\dot{{\omega}}_{{{i}}}", "omegadot_{i}"),
    "a": (r"a_{{{i}}}", "a_{i}"),
    "ac": (r"a_{{c{i}}}", "a_c{i}"),
    "F": (r"F_{{{i}}}", "F_{i}"),
    "N": (r"N_{{{i}}}", "N_{i}"),
    "f": (r"f_{{{i}}}", "f_{i}"),
    "n": (r"n_{{{i}}}", "n_{i}"),
    "tau": (r"\tau_{{{i}}}", "tau_{i}"),
}


#: the Newton–Euler steps a derivation in the compact form prints (the rest nest over pages)
_SHOWN_SIX_JOINTS = ("omega", "omegadot")


def _name(tex: str, text: str) -> Math:
    return Math(TeX(tex), text)


def _eq(name: Math, expr: sp.Expr, nota: Notation, width: float) -> Equation:
    return equation(name, expr, as_math(expr, nota), nota, width)


def _step(s: NEStep, nota: Notation, width: float) -> NEStepData:
    tex, text = _VECTORS[s.name]
    label = _name(tex.format(i=s.link), text.format(i=s.link))
    value = s.value if s.value.cols == 1 else s.value.T
    block = matrix_block(label, value, nota, width=width, names=component_names(label))
    return NEStepData(s.sweep, s.name, s.link, s.equation, block)


def _link(i: int, L: LinkInertia, nota: Notation, width: float) -> LinkData:
    r = sp.Matrix(L.r)
    return LinkData(
        i,
        _eq(_name(f"m_{{{i}}}", f"m_{i}"), L.m, nota, width),
        matrix_block(_name(f"r_{{c{i}}}", f"r_c{i}"), r, nota, width=width),
        matrix_block(_name(f"I_{{{i}}}", f"I_{i}"), L.I, nota, width=width),
    )


def _tau_by_parts(dm: DynamicModel) -> sp.ImmutableMatrix:
    """``τ_k = Σ_j M_kj q̈_j + Σ_j C_kj q̇_j + g_k`` with the entries as names (M_{jk}, j ≤ k,
    as printed): the six-joint τ written out would repeat M, C and g over pages."""
    n = dm.n

    def entry(name: str, k: int, j: int) -> sp.Symbol:
        return sp.Symbol(f"{name}{k + 1}{j + 1}", real=True)

    return sp.ImmutableMatrix(
        [
            sp.Add(
                *(entry("M", min(k, j), max(k, j)) * dm.accelerations[j] for j in range(n)),
                *(entry("C", k, j) * dm.rates[j] for j in range(n)),
                sp.Symbol(f"g{k + 1}", real=True),
            )
            for k in range(n)
        ]
    )


def _grouped(
    robot: Robot, say: Callable[[str], None]
) -> tuple[EquationsOfMotion, tuple[GroupedConstant, ...], tuple[tuple[sp.Symbol, sp.Expr], ...]]:
    """Lagrange–Euler in the compact form with grouped constants (six-joint arms): lengths
    and inertias both symbolic when the table's lengths are symbols, else both numbers."""
    cd = compact_dynamics(robot, symbolic=bool(robot.table.constants), progress=say)
    eom = EquationsOfMotion(
        "lagrange", cd.model, cd.M, cd.C, cd.g, _tau_by_parts(cd.model), cd.christoffel,
        cd.kinetic, cd.potential,
    )  # fmt: skip
    return eom, cd.constants, cd.values


def derive_dynamics(
    name_or_robot: str | Path | DHTable | Robot,
    *,
    compact: bool | None = None,
    notation: TrigStyle | str | None = None,
    width: float = LATEX_WIDTH,
    progress: Callable[[str], None] | None = None,
) -> DynamicsDerivation:
    """The equations of motion of a robot: Lagrange–Euler step by step, then Newton–Euler.

    Parameters
    ----------
    name_or_robot
        A built-in name, a table file, a DHTable or a Robot. A table without inertial
        parameters gets the textbook symbols (``m1``, ``rx1``, ``Izz1``, …).
    compact, notation, width
        As for :func:`~dhsym.explain.derivation.derive`.
    progress
        Told each stage of the derivation (the command line prints it on standard error).

    From :data:`~dhsym.dynamics.lagrange_euler.RING_JOINTS` joints on, M, C and g are
    printed in the compact form with grouped inertial constants
    (:func:`~dhsym.dynamics.compact_form.compact_dynamics`), listed in ``constants``.

    >>> d = derive_dynamics("planar2r")
    >>> [e.name.text for e in d.christoffel]
    ['c112', 'c121', 'c221']
    >>> [e.text_lines[0] for e in d.gravity_vector], [g.text for g in d.gravity]
    (['0', '0'], ['0', '0', '-9.81'])
    """
    robot = styled(name_or_robot, compact, notation)
    nota = robot.notation
    say = progress or (lambda _msg: None)
    constants: tuple[GroupedConstant, ...] = ()
    numbers: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()
    if len(robot.table.variables) >= RING_JOINTS:
        lag, constants, numbers = _grouped(robot, say)
    else:
        lag = robot.dynamics()
    say("Newton-Euler recursion")
    if constants or numbers:  # six joints: the angular rates of the recursion; the forces
        recorded: list[NEStep] = []  # nested over pages are what the compiled rne computes
        rne_expressions(lag.model, record=recorded)
        ne_steps = tuple(s for s in recorded if s.name in _SHOWN_SIX_JOINTS)
    else:
        ne_steps = robot.dynamics(method="newton-euler").steps
    say("layout")
    n = lag.M.rows
    shown: list[sp.Expr] = []
    energies = []
    for i, (k, p) in enumerate(zip(lag.kinetic, lag.potential, strict=True), start=1):
        energies.append(
            EnergyData(
                i,
                _eq(_name(f"K_{{{i}}}", f"K{i}"), k, nota, width),
                _eq(_name(f"P_{{{i}}}", f"P{i}"), p, nota, width),
            )
        )
        shown += [k, p]
    inertia = tuple(
        _eq(_name(f"M_{{{i + 1}{j + 1}}}", f"M{i + 1}{j + 1}"), lag.M[i, j], nota, width)
        for i in range(n)
        for j in range(i, n)
    )
    christoffel = tuple(
        _eq(
            _name(f"c_{{{i + 1}{j + 1}{k + 1}}}", f"c{i + 1}{j + 1}{k + 1}"),
            lag.christoffel[i][j][k],
            nota,
            width,
        )
        for i in range(n)
        for j in range(i, n)
        for k in range(n)
        if lag.christoffel[i][j][k] != 0
    )
    coriolis = matrix_block(
        _name(r"C(q, \dot{q})", "C(q, qdot)"), lag.C, nota, width=width, names=indexed_names("C")
    )
    gvec = tuple(_eq(_name(f"g_{{{k + 1}}}", f"g{k + 1}"), lag.g[k], nota, width) for k in range(n))
    tau = tuple(
        _eq(_name(rf"\tau_{{{k + 1}}}", f"tau{k + 1}"), lag.tau[k], nota, width) for k in range(n)
    )
    shown += [*lag.M, *lag.C, *lag.g]
    steps = tuple(_step(s, nota, width) for s in ne_steps)
    return DynamicsDerivation(
        **heading(robot, n),
        gravity=tuple(as_math(x, nota) for x in lag.model.gravity),
        energies=tuple(energies),
        inertia=inertia,
        christoffel=christoffel,
        gravity_vector=gvec,
        tau=tau,
        outward=tuple(s for s in steps if s.sweep == "outward"),
        inward=tuple(s for s in steps if s.sweep == "inward"),
        legend=legend_lines(shown, nota),
        width=width,
        links=tuple(_link(i, L, nota, width) for i, L in enumerate(lag.model.links, start=1)),
        coriolis=coriolis,
        constants=tuple(
            _eq(_name(sp.latex(k.symbol), str(k.symbol)), k.value, nota, width) for k in constants
        ),
        parameter_values=tuple(_eq(_name(sp.latex(s), str(s)), v, nota, width) for s, v in numbers),
    )
