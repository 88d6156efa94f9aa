r"""The linear-in-parameters form τ = Y(q, q̇, q̈) π and the base (identifiable) parameters.

Each link has the 10 standard parameters of Khalil and Dombre (*Modeling, Identification
and Control of Robots*, §9.3): the inertia about the link *origin*
``XX, XY, XZ, YY, YZ, ZZ``, the first moments ``MX, MY, MZ`` (= m r) and the mass ``M``.
They relate to the centre-of-mass parameters by the parallel-axis theorem,
``L = I + m (rᵀr 1 − r rᵀ)``. The Newton–Euler recursion written with them
(:func:`.newton_euler.rne_expressions` with ``first_moments``) is linear in π, so
``Y = ∂τ/∂π`` exactly.

Base parameters: columns of Y that vanish or depend linearly on earlier ones are found
numerically, by a QR decomposition of Y stacked at random states (Gautier's method), at
the table's numeric lengths; each base parameter is printed as the standard
parameter it stands for plus the combination of dependent ones grouped into it, with
coefficients rationalised (lengths in the grouping, e.g. ``XX2 + 16/25*M2``, appear as
numbers, not symbols).

Examples
--------
>>> import dhsym
>>> reg = regressor(dhsym.load("planar2r"))
>>> reg.Y.shape, reg.parameters[:3]
((2, 20), (XX1, XY1, XZ1))
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.numeric import compile_exprs
from dhsym.model.parsing import REAL

from .lagrange_euler import tidy
from .model import DynamicModel, dynamic_model
from .recursive_newton_euler import rne_expressions

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "STANDARD_NAMES",
    "BaseParameters",
    "Regressor",
    "base_parameters",
    "regressor",
    "standard_values",
]

Matrix: TypeAlias = sp.ImmutableMatrix

#: The 10 standard parameters of a link, in Khalil's order.
STANDARD_NAMES = ("XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M")


@dataclass(frozen=True)
class Regressor:
    """``tau = Y * Matrix(parameters)``; ``parameters`` are the 10 symbols of each link."""

    Y: Matrix
    parameters: tuple[sp.Symbol, ...]
    model: DynamicModel = field(repr=False, compare=False)


@dataclass(frozen=True)
class BaseParameters:
    """The identifiable combinations: ``tau = Y[:, independent] * Matrix(combinations)``."""

    combinations: tuple[sp.Expr, ...]
    independent: tuple[int, ...]
    unidentifiable: tuple[sp.Symbol, ...]
    regressor: Regressor = field(repr=False, compare=False)

    @property
    def Y(self) -> Matrix:
        """The base regressor: the independent columns of Y."""
        return Matrix(
            self.regressor.Y.extract(list(range(self.regressor.Y.rows)), list(self.independent))
        )

    def lines(self) -> list[str]:
        """One ``name = combination`` line per base parameter (plain text).

        >>> import dhsym
        >>> base_parameters(dhsym.load("planar2r")).lines()[0]
        'ZZ1R = M1 + M2 + 2*MX1 + ZZ1'
        """
        out = []
        for k, combo in zip(self.independent, self.combinations):
            name = self.regressor.parameters[k]
            out.append(f"{name}R = {combo}" if combo != name else f"{name}")
        return out


def _link_symbols(i: int) -> tuple[sp.Symbol, ...]:
    return tuple(sp.Symbol(f"{n}{i}", **REAL) for n in STANDARD_NAMES)


def regressor(robot: KinematicChain, model: DynamicModel | None = None) -> Regressor:
    """The regressor Y of ``robot`` (the links' own parameters are not used: π is symbolic)."""
    dm = model or dynamic_model(robot)
    moments: list[tuple[sp.Symbol, Matrix, Matrix]] = []
    params: list[sp.Symbol] = []
    for i in range(1, len(dm.links) + 1):
        XX, XY, XZ, YY, YZ, ZZ, MX, MY, MZ, M = s = _link_symbols(i)
        Lo = Matrix([[XX, XY, XZ], [XY, YY, YZ], [XZ, YZ, ZZ]])
        moments.append((M, Matrix([MX, MY, MZ]), Lo))
        params.extend(s)
    tau = rne_expressions(dm, first_moments=moments)
    Y = Matrix(len(tau), len(params), lambda r, c: tidy(sp.diff(tau[r], params[c])))
    return Regressor(Y, tuple(params), dm)


def standard_values(model: DynamicModel) -> dict[sp.Symbol, sp.Expr]:
    """The 10 standard parameters of every link from its ``m, r, I`` (parallel axes).

    >>> import dhsym
    >>> v = standard_values(dynamic_model(dhsym.load("puma560")))
    >>> v[sp.Symbol("M2", real=True)], v[sp.Symbol("MX2", real=True)]
    (87/5, -158253/25000)
    """
    out: dict[sp.Symbol, sp.Expr] = {}
    for i, L in enumerate(model.links, start=1):
        r = Matrix(L.r)
        Lo = L.inertia_about((0, 0, 0))  # the parallel-axis theorem, to the link origin
        values = (
            Lo[0, 0], Lo[0, 1], Lo[0, 2], Lo[1, 1], Lo[1, 2], Lo[2, 2],
            L.m * r[0], L.m * r[1], L.m * r[2], L.m,
        )  # fmt: skip
        out.update({s: sp.expand(v) for s, v in zip(_link_symbols(i), values)})
    return out


def base_parameters(
    robot: KinematicChain, *, states: int = 40, seed: int = 0, tol: float = 1e-9
) -> BaseParameters:
    """The base parameters by QR of Y stacked at ``states`` random states (Gautier).

    Lengths take the table's values (they must all have one); the combinations'
    coefficients are rationalised.
    """
    reg = regressor(robot)
    dm = reg.model
    args = (*dm.variables, *dm.rates, *dm.accelerations)
    Yn = reg.Y.subs(robot.table.value_map)
    gsyms = set().union(*(g.free_symbols for g in dm.gravity))
    Yn = Yn.subs({g: 1 for g in gsyms})
    missing = Yn.free_symbols - set(args)
    if missing:
        names = ", ".join(sorted(map(str, missing)))
        raise DHError(f"base parameters need numbers for the lengths: give values for {names}")
    f = compile_exprs(list(Yn), args)
    rng = np.random.default_rng(seed)
    X = rng.uniform(-np.pi, np.pi, (states, len(args)))
    cols = f(*X.T)
    n, p = reg.Y.shape
    W = np.empty((states, n * p))
    for k, v in enumerate(cols):
        W[:, k] = v
    W = W.reshape(states, n, p).reshape(states * n, p)
    # Gautier: QR without pivoting; a column whose |R_kk| vanishes is a combination of the
    # columns before it (Khalil's order: it is grouped into parameters of earlier links)
    _, R = np.linalg.qr(W)
    diag = np.abs(np.diag(R))
    scale = max(1.0, float(diag.max()))
    independent = [k for k in range(p) if diag[k] > tol * scale]
    # each dependent column as a combination of the independent ones (least squares)
    A = W[:, independent]
    dependent = [k for k in range(p) if k not in independent]
    coeffs, *_ = np.linalg.lstsq(A, W[:, dependent], rcond=None)
    combos = []
    params = reg.parameters
    unidentifiable = []
    for k in dependent:
        if np.allclose(W[:, k], 0, atol=tol):
            unidentifiable.append(params[k])
    for row, k in enumerate(independent):
        combo = params[k]
        for j, d in enumerate(dependent):
            c = coeffs[row, j]
            if abs(c) > tol:
                combo = combo + sp.nsimplify(round(c, 9), rational=True) * params[d]
        combos.append(combo)
    return BaseParameters(tuple(combos), tuple(independent), tuple(unidentifiable), reg)
