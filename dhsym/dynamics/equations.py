"""The result of a dynamics derivation: τ = M(q) q̈ + C(q, q̇) q̇ + g(q), with its parts.

Examples
--------
>>> import dhsym
>>> eom = dhsym.load("planar2r").dynamics()
>>> eom.method, eom.M.shape, len(eom.kinetic)
('lagrange', (2, 2), 2)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.notation.printers import Notation

if TYPE_CHECKING:
    from .model import DynamicModel

__all__ = ["EquationsOfMotion", "NEStep"]

Matrix: TypeAlias = sp.ImmutableMatrix


@dataclass(frozen=True)
class NEStep:
    """One step of the Newton–Euler recursion: a named vector of link ``link`` in its frame.

    ``name`` is one of ``omega``, ``omegadot``, ``a`` (acceleration of the frame origin,
    gravity included), ``ac`` (of the centre of mass), ``F``, ``N`` (outward) and ``f``,
    ``n``, ``tau`` (inward); ``sweep`` is ``"outward"`` or ``"inward"``.
    """

    sweep: str
    name: str
    link: int
    value: Matrix
    equation: str


@dataclass(frozen=True)
class EquationsOfMotion:
    """``τ = M(q) q̈ + C(q, q̇) q̇ + g(q)`` of a robot, exact.

    Attributes
    ----------
    M, C, g, tau
        Inertia matrix (n×n), Coriolis/centrifugal matrix (n×n, from the Christoffel
        symbols), gravity vector (n×1) and joint torques (n×1).
    christoffel
        ``christoffel[i][j][k]`` is Spong's ``c_ijk`` (0-based indices), with
        ``C[k, j] = Σ_i c_ijk q̇_i``.
    kinetic, potential
        Each link's kinetic and potential energy (Lagrange), or empty.
    steps
        The Newton–Euler recursion (:class:`NEStep`), or empty.
    """

    method: str
    model: DynamicModel = field(repr=False, compare=False)
    M: Matrix
    C: Matrix
    g: Matrix
    tau: Matrix
    christoffel: tuple[tuple[tuple[sp.Expr, ...], ...], ...] = ()
    kinetic: tuple[sp.Expr, ...] = ()
    potential: tuple[sp.Expr, ...] = ()
    steps: tuple[NEStep, ...] = ()

    @property
    def variables(self) -> tuple[sp.Symbol, ...]:
        """The joint variables q."""
        return self.model.variables

    @property
    def rates(self) -> tuple[sp.Symbol, ...]:
        """The joint rates q̇."""
        return self.model.rates

    @property
    def accelerations(self) -> tuple[sp.Symbol, ...]:
        """The joint accelerations q̈."""
        return self.model.accelerations

    @property
    def notation(self) -> Notation:
        """The robot's lecture notation (C12, S2, …)."""
        return self.model.robot.notation

    def c(self, i: int, j: int, k: int) -> sp.Expr:
        """Spong's Christoffel symbol ``c_ijk`` with 1-based indices."""
        return self.christoffel[i - 1][j - 1][k - 1]

    def text(self, what: str = "tau") -> str:
        """One part (``M``, ``C``, ``g``, ``tau``) in plain text, compact notation."""
        return self.notation.text(getattr(self, what))

    def latex(self, what: str = "tau") -> str:
        """One part in LaTeX, compact notation."""
        return self.notation.latex(getattr(self, what))

    def _repr_latex_(self) -> str:
        return f"$$\\tau = {self.latex('tau')}$$"
