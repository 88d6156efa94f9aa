r"""The equations of motion in the lecture's compact form, with grouped inertial constants.

Armstrong, Khatib and Burdick, *The Explicit Dynamic Model and Inertial Parameters of the
PUMA 560 Arm* (1986), print M(q), C(q, q̇) and g(q) of a six-joint arm as short sums of
trigonometric monomials (``C2²``, ``S23 C23``, ``C4 S5``) whose coefficients are a few
dozen named constants of the inertial parameters (``I1 = Izz1 + m2·(…)``). This module
derives them that way, fast, and without any general ``simplify``:

1. every entry of ``M = Σ_i m_i J_{v_i}^T J_{v_i} + J_{ω_i}^T I_i J_{ω_i}`` (the link
   Jacobians of :func:`~dhsym.dynamics.lagrange_euler.link_jacobians`, already in the
   compact sum-angle form C23, S23) is a polynomial in the sines and cosines of the joint
   angles (a :class:`TrigRing`), whose coefficients are polynomials in the lengths and
   inertial parameters: sums of the same trigonometric monomial are collected exactly;
2. ``sin² x`` is replaced by ``1 − cos² x`` (a normal form: ``C4² + S4²`` and its relatives
   vanish structurally); for the print, a pair ``k·m·C² − k·m`` is written ``−k·m·S²`` and
   pairs of terms fold into sum angles (``C23 S3 − S23 C3 = −S2``);
3. the Christoffel symbols and g are derivatives of these polynomials (the chain rule on the
   generators: ``d cos x / dq = −sin x ∂x/∂q``), reduced again;
4. each coefficient that is a sum of inertial terms becomes a named constant, the same
   name wherever the same sum (up to a rational factor) appears.

``symbolic=True`` writes numeric inertial parameters of the table as symbols (``m2``,
``Ixx2``, ``rx2``, and the motor's ``Jm2``, ``G2``) with the table's values kept, so that
lengths and inertias are both symbolic; ``symbolic=False`` substitutes the table's values
and ``values`` for both, so every coefficient is a number. Never half and half.

Examples
--------
>>> import dhsym
>>> cd = compact_dynamics(dhsym.load("spong2r"))
>>> for k in cd.constants:
...     print(k.symbol, "=", k.value)
Ig1 = I1 + I2 + l1**2*m2 + lc1**2*m1 + lc2**2*m2
Ig2 = I2 + lc2**2*m2
gamma1 = g*l1*m2 + g*lc1*m1
>>> cd.M[0, 0]
Ig1 + 2*l1*lc2*m2*cos(theta2)
>>> cd.g.T
Matrix([[g*lc2*m2*cos(theta1 + theta2) + gamma1*cos(theta1), g*lc2*m2*cos(theta1 + theta2)]])
>>> cd.proven()
True
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.simplification import fold_sum_angles, prove_equal, tidy_signs
from dhsym.kinematics.trig_ring import lecture_form
from dhsym.model.inertia import LinkInertia

from .lagrange_euler import link_jacobians, ring_energies, ring_equations
from .model import DynamicModel, dynamic_model

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["CompactDynamics", "GroupedConstant", "compact_dynamics", "symbolic_links"]

Matrix: TypeAlias = sp.ImmutableMatrix


@dataclass(frozen=True)
class GroupedConstant:
    """A named constant of the inertial parameters: ``symbol = value``."""

    symbol: sp.Symbol
    value: sp.Expr


class _Namer:
    """Gives a sum of parameter terms its constant's name (one name per sum up to a factor)."""

    def __init__(self, prefix: str, taken: set[str]) -> None:
        self.prefix = prefix
        self.taken = taken
        self.names: dict[sp.Expr, sp.Symbol] = {}
        self.constants: list[GroupedConstant] = []

    def __call__(self, coeff: sp.Expr) -> sp.Expr:
        if not coeff.is_Add or coeff.is_number:
            return coeff
        content, prim = coeff.as_content_primitive()
        if prim.could_extract_minus_sign():
            content, prim = -content, sp.expand(-prim)
        name = self.names.get(prim)
        if name is None:
            k = len(self.constants) + 1
            while f"{self.prefix}{k}" in self.taken:
                k += 1
            name = sp.Symbol(f"{self.prefix}{k}", real=True)
            self.taken.add(name.name)
            self.names[prim] = name
            self.constants.append(GroupedConstant(name, prim))
        return content * name


@dataclass(frozen=True)
class CompactDynamics:
    """``τ = M q̈ + C q̇ + g`` in the compact form, with the named constants it uses.

    Attributes
    ----------
    M, C, g, tau
        The equations with the grouped constants as symbols.
    christoffel
        Spong's ``c_ijk`` as ``[i][j][k]`` (0-based), in the same form.
    constants
        The grouped constants of M and C (``I1``, …) then of g (``gamma1``, …).
    kinetic, potential
        Each link's kinetic and potential energy (nothing named).
    values
        The numbers of the inertial symbols introduced by ``symbolic=True`` (empty
        otherwise): ``expanded().M.subs(values)`` is the table's M.
    """

    model: DynamicModel = field(repr=False, compare=False)
    M: Matrix
    C: Matrix
    g: Matrix
    tau: Matrix
    christoffel: tuple[tuple[tuple[sp.Expr, ...], ...], ...]
    constants: tuple[GroupedConstant, ...]
    values: tuple[tuple[sp.Symbol, sp.Expr], ...]
    kinetic: tuple[sp.Expr, ...] = ()
    potential: tuple[sp.Expr, ...] = ()

    @property
    def substitution(self) -> dict[sp.Symbol, sp.Expr]:
        """Each constant's symbol → its value."""
        return {k.symbol: k.value for k in self.constants}

    def expanded(self, what: str = "M") -> Matrix:
        """``M``, ``C``, ``g`` or ``tau`` with the constants substituted back, expanded."""
        part: Matrix = getattr(self, what)
        return Matrix(part.xreplace(self.substitution).applyfunc(sp.expand))

    def terms(self, i: int, j: int = 0, what: str = "M") -> int:
        """The number of terms of entry ``(i, j)`` (1-based) once the constants are named."""
        part: Matrix = getattr(self, what)
        return len(sp.Add.make_args(part[i - 1, j - 1]))

    def proven(self) -> bool:
        """Proof that M, C and g, constants substituted back, equal the plain Lagrange–Euler
        sums (``Σ m Jvᵀ Jv + Jωᵀ I Jω``, its Christoffel symbols, ``∂P/∂q``), computed
        again here without any rewriting (:func:`~dhsym.kinematics.simplification.prove_equal`).
        """
        from .lagrange_euler import christoffel_symbols, coriolis_matrix, potential_energies

        dm = self.model
        n = dm.n
        M = sp.zeros(n, n)
        for i, L in enumerate(dm.links, start=1):
            if L.m == 0 and L.I.is_zero_matrix:
                continue
            Jv, Jw = link_jacobians(dm, i)
            M += L.m * Jv.T * Jv + Jw.T * L.I * Jw
        M += sp.diag(*dm.armature())
        if not prove_equal(self.expanded("M"), M):
            return False
        plain = tuple(
            tuple(tuple(sp.expand(c) for c in cj) for cj in ci)
            for ci in (christoffel_symbols(M.applyfunc(sp.expand), dm.variables))
        )
        C = coriolis_matrix(plain, dm.rates)
        if not prove_equal(self.expanded("C"), C):
            return False
        P = sum(potential_energies(dm), sp.Integer(0))
        g = Matrix([sp.diff(P, q) for q in dm.variables])
        return prove_equal(self.expanded("g"), g)


#: Entries with at most this many terms get the sum-angle fold (``C23 S3 − S23 C3 = −S2``);
#: the pair search is quadratic in the terms.
_FOLD_TERMS = 40


def _folded(expr: sp.Expr) -> sp.Expr:
    """``expr`` with pairs of terms folded into sum angles (exact; never ``simplify``)."""
    if len(sp.Add.make_args(expr)) > _FOLD_TERMS:
        return expr
    return tidy_signs(fold_sum_angles(expr))


def symbolic_links(dm: DynamicModel) -> tuple[DynamicModel, dict[sp.Symbol, sp.Expr]]:
    """``dm`` with every numeric nonzero inertial parameter a symbol (zeros kept), and the
    symbols' numbers: the structure of the table with the lecture's names
    (``m2``, ``rx2``, ``Ixx2``, ``Ixy2``, ``Jm2``, ``G2``).

    >>> import dhsym
    >>> dm, vals = symbolic_links(dynamic_model(dhsym.load("puma560")))
    >>> dm.links[5].r, vals[dm.links[5].r[2]]
    ((0, 0, rz6), 4/125)
    """
    values: dict[sp.Symbol, sp.Expr] = {}

    def name(value: sp.Expr, label: str, neutral: int = 0) -> sp.Expr:
        if not value.is_number or value == neutral:
            return value
        s = sp.Symbol(label, real=True)
        values[s] = value
        return s

    links = []
    for i, L in enumerate(dm.links, start=1):
        tb = LinkInertia.textbook(i)
        inertia = Matrix([[name(L.I[a, b], tb.I[a, b].name) for b in range(3)] for a in range(3)])
        links.append(
            replace(
                L,
                m=name(L.m, f"m{i}"),
                r=tuple(name(v, t.name) for v, t in zip(L.r, tb.r)),
                I=inertia,
                Jm=name(L.Jm, f"Jm{i}"),
                G=name(L.G, f"G{i}", neutral=1) if L.Jm != 0 else L.G,
            )
        )
    return replace(dm, links=tuple(links)), values


def _taken(dm: DynamicModel) -> set[str]:
    syms = set(dm.parameters) | set(dm.robot.table.constants) | set(dm.variables)
    return {s.name for s in syms}


def compact_dynamics(
    robot: KinematicChain,
    values: Mapping[object, object] | None = None,
    *,
    symbolic: bool = True,
    model: DynamicModel | None = None,
    progress: Callable[[str], None] | None = None,
) -> CompactDynamics:
    """The equations of motion of ``robot`` in the compact form (see the module docstring).

    Parameters
    ----------
    robot
        The chain (its table's inertial parameters, or the textbook symbols).
    values
        Numbers for symbols of the table (lengths, inertial parameters); implies
        ``symbolic=False``.
    symbolic
        Lengths and inertias both symbolic (numeric inertial parameters of the table become
        symbols, their numbers in ``values`` of the result), or both numeric.
    model
        A dynamic model to use instead of the table's.
    progress
        Called with a short message before each stage (for a progress line).
    """
    say = progress or (lambda _msg: None)
    extra: dict[sp.Symbol, sp.Expr] = {}
    if values or not symbolic:
        from .compiled_dynamics import numeric_model

        dm = numeric_model(robot, values)
    else:
        dm, extra = symbolic_links(model or dynamic_model(robot))
    eq = ring_equations(dm, say)
    ring, n = eq.ring, dm.n
    taken = _taken(dm)
    # Armstrong, Khatib and Burdick's I1, I2, …; Ig1, … when the table has an I1 of its own
    inertial = _Namer("Ig" if any(re.fullmatch(r"I\d+", t) for t in taken) else "I", taken)
    gravitational = _Namer("gamma", taken)
    upper = {
        (j, k): _folded(lecture_form(ring, eq.M[j][k], inertial))
        for j, k in itertools.combinations_with_replacement(range(n), 2)
    }
    Mx = Matrix(n, n, lambda j, k: upper[min(j, k), max(j, k)])
    shown = {
        (i, j, k): _folded(lecture_form(ring, eq.christoffel[i][j][k], inertial))
        for i, j, k in itertools.product(range(n), repeat=3)
        if i <= j
    }
    chris = tuple(
        tuple(tuple(shown[min(i, j), max(i, j), k] for k in range(n)) for j in range(n))
        for i in range(n)
    )
    C = Matrix(n, n, lambda k, j: sp.Add(*(chris[i][j][k] * dm.rates[i] for i in range(n))))
    say("grouped constants")
    g = Matrix([_folded(lecture_form(ring, p, gravitational)) for p in eq.g])
    qd, qdd = Matrix(dm.rates), Matrix(dm.accelerations)
    tau = Matrix(Mx * qdd + C * qd + g)
    return CompactDynamics(
        dm,
        Mx,
        C,
        g,
        tau,
        chris,
        (*inertial.constants, *gravitational.constants),
        tuple(sorted(extra.items(), key=lambda kv: kv[0].name)),
        *ring_energies(dm, eq),
    )
