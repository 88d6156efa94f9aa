r"""How much rounding of decimals an answer may carry: the instructor's rule, and the test.

A student who writes ``0.7071`` for :math:`\sqrt2/2` or ``cos(θ1 + 1.5708)`` for
:math:`-\sin θ_1` is right *up to rounding*.  :class:`Rounding` says how much is accepted:

``digits`` (the default, ``digits=3``)
    A decimal written with at least that many significant digits may be the exact value
    rounded or truncated to the digits written (``1.5708`` and ``1.5707`` for π/2, not
    ``1.5709``); a shorter decimal must be exact (``0.02`` for 0.0203 is wrong, ``0.5``
    for 1/2 is right).
``abs=<t>`` / ``rel=<t>``
    Any answer with decimals whose value is within ``t`` of the key (``rel``: ``t`` times
    the largest size of the entry) at every sample point.
``off``
    Decimals must be exact.

Only the numbers that stand for the answer's value count (:func:`standing`): a decimal
removed by a zero factor (``0*100.0``) or cancelled by another (``100.1 - 100.0``, which
stands for ``0.1``, one significant digit) gives no rounding room.

The test (:func:`rounding_accepts`) works on the answer as written: each decimal literal
is a placeholder (:func:`dhsym.model.parsing.parse_expression` with ``literal=``) and stands
for *one* value within its allowed interval, the same at every sample point.  The answer
is right up to rounding when such values exist: they are solved for (one unknown per
decimal, all sample points at once) and the answer with them must equal the key at every
point to double precision.  An error that varies with the joint values cannot be absorbed,
however many decimals are written: ``1.00*k*(1 + S2/300)`` is not ``k`` up to rounding.

Examples
--------
>>> Rounding.parse("digits=4"), Rounding.parse({"abs": 0.001}), Rounding.parse(None)
(Rounding('digits=4'), Rounding('abs=0.001'), Rounding('digits=3'))
>>> Rounding.parse("off").describe(0)
'decimals must be exact'
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
import sympy as sp

from dhsym.errors import DHError

from ..comparing.sampled_frames import EvaluationError, evaluate
from ..comparing.tolerances import TOLERANCES
from ..reading.limits import echoed
from ..reading.literals import Literal, decimal_places

__all__ = [
    "DEFAULT_ROUNDING",
    "Rounding",
    "rounding_accepts",
    "standing",
    "value_tolerance",
]

_MODES = ("digits", "abs", "rel", "off")
# Matched on the stripped text; no two neighbouring parts can take the same characters.
_SPEC = re.compile(r"(digits|abs|rel)\s*(?:[=:]\s*)?([0-9.eE+-]+)|([0-9]+)\s*digits?")


@dataclass(frozen=True)
class Rounding:
    """The accepted rounding: ``mode`` is ``digits``, ``abs``, ``rel`` or ``off``."""

    mode: str = "digits"
    digits: int = 3
    tolerance: float = 0.0

    def __post_init__(self) -> None:
        if self.mode not in _MODES:
            raise DHError(f"unknown rounding mode {self.mode!r}: expected one of {_MODES}")
        if self.mode == "digits" and not (type(self.digits) is int and 1 <= self.digits <= 40):
            raise DHError(f"rounding digits must be 1 … 40, got {self.digits!r}")
        if self.mode in ("abs", "rel") and not (0 < self.tolerance < 1e6):
            raise DHError(f"rounding tolerance must be a positive number, got {self.tolerance!r}")

    def __repr__(self) -> str:
        return f"Rounding({str(self)!r})"

    def __str__(self) -> str:
        if self.mode == "digits":
            return f"digits={self.digits}"
        return "off" if self.mode == "off" else f"{self.mode}={self.tolerance:g}"

    @classmethod
    def parse(cls, spec: object) -> Rounding:
        """Read ``digits=4``, ``4 digits``, ``abs=1e-3``, ``rel=0.001``, ``off`` (or
        ``exact``, ``false``), a mapping ``{digits: 4}`` / ``{abs: 0.001}``, a Rounding, or
        None for the default.  Anything else is a :class:`~dhsym.errors.DHError`."""
        if spec is None or isinstance(spec, Rounding):
            return spec or DEFAULT_ROUNDING
        if spec is False or (isinstance(spec, str) and spec.strip().lower() in _OFF):
            return cls("off")
        if isinstance(spec, Mapping) and len(spec) == 1:
            ((mode, value),) = spec.items()
            spec = f"{mode}={value}"
        m = _SPEC.fullmatch(spec.strip()[:100]) if isinstance(spec, str) else None
        if m is None:
            raise DHError(
                f"unknown rounding {echoed(spec)}: expected digits=N, abs=T, rel=T or off"
            )
        try:
            if m[3] is not None or m[1] == "digits":
                return cls("digits", int(m[3] or m[2]))
            return cls(m[1], tolerance=float(m[2]))
        except ValueError:
            raise DHError(
                f"unknown rounding {echoed(spec)}: N is a whole number, T a number"
            ) from None

    def allowed(self, literal: Literal) -> tuple[float, float]:
        """How far the true value may lie from a decimal as written: (below, above).

        Rounded: half a unit either way; truncated: up to one unit above (a literal has no
        sign of its own, so truncation always dropped digits of a larger magnitude).
        """
        digits, unit = decimal_places(literal.text)
        if self.mode != "digits" or digits < self.digits:
            return 0.0, 0.0
        return -unit / 2, unit

    def describe(self, digits: int) -> str:
        """How an entry was accepted, for feedback: ``to 4 significant digits`` …"""
        if self.mode == "digits":
            return f"to {digits} significant digit{'s' * (digits != 1)}"
        if self.mode == "abs":
            return f"within an absolute tolerance of {self.tolerance:g}"
        if self.mode == "rel":
            return f"within a relative tolerance of {self.tolerance:g}"
        return "decimals must be exact"


_OFF = frozenset({"off", "exact", "none", "false", "no"})
DEFAULT_ROUNDING = Rounding()


def _literal_text(value: sp.Rational, unit: float) -> str:
    """A decimal text of ``|value|`` written to ``unit`` (``decimal_places`` reads it back)."""
    places = round(-math.log10(unit))
    if places >= 0:
        return f"{float(abs(value)):.{places}f}"
    return f"{round(float(abs(value)) / unit)}e{-places}"  # an integer count of units


def standing(
    template: sp.Expr, literals: tuple[Literal, ...]
) -> tuple[sp.Expr, tuple[Literal, ...]]:
    """The answer with only the literals that stand for its value (the tolerance policy).

    A literal whose value is zero is an exact zero, and a literal that a zero factor
    removes (``0*100.0``) is gone; constants of one sum that cancel (``100.1 - 100.0``,
    ``100.1 x - 100.0 x``) become one literal, their sum, written to the coarsest of their
    units (here ``0.1``: one significant digit).  Tolerances then come from what is left.

    >>> a, b, c = (Literal(sp.Dummy(n), t, sp.Rational(t)) for n, t in
    ...            (("a", "100.1"), ("b", "100.0"), ("c", "0.7071")))
    >>> x = sp.Symbol("x")
    >>> t, lits = standing(x + a.symbol - b.symbol + 0 * c.symbol, (a, b, c))
    >>> [(lit.text, lit.digits) for lit in lits]
    [('0.1', 1)]
    """
    zeros = {lit.symbol: sp.S.Zero for lit in literals if lit.value == 0}
    template = template.xreplace(zeros) if zeros else template
    by_symbol = {lit.symbol: lit for lit in literals if lit.symbol not in zeros}
    merged: list[Literal] = []

    def merge(terms: tuple[sp.Expr, ...]) -> list[sp.Expr]:
        groups: dict[sp.Expr, list[tuple[sp.Expr, sp.Rational, Literal]]] = {}
        for term in terms:
            rest, lit = term.as_independent(*by_symbol, as_Add=False)
            coeff, factor = rest.as_coeff_Mul()
            if lit in by_symbol and by_symbol[lit].unit > 0:
                groups.setdefault(factor, []).append((term, coeff, by_symbol[lit]))
        out = list(terms)
        for factor, members in groups.items():
            signs = {sp.sign(c * m.value) for _, c, m in members}
            if len(members) < 2 or not {1, -1} <= signs:
                continue  # only constants that cancel are merged
            total = sum((c * m.value for _, c, m in members), sp.S.Zero)
            unit = max(float(abs(c)) * m.unit for _, c, m in members)
            for term, _, _ in members:
                out.remove(term)
            if total != 0:
                lit = Literal(sp.Dummy(f"m{len(merged)}", real=True), "", abs(total))
                lit = Literal(lit.symbol, _literal_text(lit.value, unit), lit.value)
                merged.append(lit)
                out.append(sp.sign(total) * factor * lit.symbol)
        return out

    def rebuild(e: sp.Expr) -> sp.Expr:
        if e.is_Atom:
            return e
        args = tuple(rebuild(a) for a in e.args)
        if e.is_Add:
            return sp.Add(*merge(args))
        return e.func(*args) if args != e.args else e

    template = rebuild(template)
    present = template.free_symbols
    kept = tuple(lit for lit in (*by_symbol.values(), *merged) if lit.symbol in present)
    return template, kept


def value_tolerance(template: sp.Expr, literals: tuple[Literal, ...], digits: int = 3) -> float:
    """One unit in the last digit of the finest decimal that stands for the value (with at
    least ``digits`` significant digits), or 0: how far an inverse-kinematics value written
    with decimals may be from the exact one.

    >>> lit = Literal(sp.Dummy("n"), "380.0e-3", sp.Rational(38, 100))
    >>> value_tolerance(lit.symbol, (lit,))
    0.0001
    """
    _, kept = standing(template, literals)
    units = [lit.unit for lit in kept if lit.unit > 0 and lit.digits >= digits]
    return max(units, default=0.0)


def _at(
    template: sp.Expr,
    env: Mapping[sp.Basic, np.ndarray],
    size: int,
    subs: Mapping[sp.Symbol, float],
) -> np.ndarray:
    values = {**env, **{s: np.asarray(float(v)) for s, v in subs.items()}}
    try:
        return evaluate(template, values, size)
    except (EvaluationError, OverflowError, TypeError, ValueError):
        return np.full(size, np.nan)


def _solve(
    residual: Callable[[np.ndarray], np.ndarray],
    lower: np.ndarray,
    upper: np.ndarray,
    tol: np.ndarray,
) -> np.ndarray | None:
    """A point ``t`` of the box ``lower ≤ t ≤ upper`` where ``|residual(t)| ≤ tol`` at every
    sample point, or None: Levenberg–Marquardt, each step kept inside the box.

    One unknown per decimal (its move, in units of its last digit), the same at every
    point: an error that varies with the point cannot be absorbed.

    >>> x = np.linspace(-1, 1, 5)
    >>> t = _solve(lambda t: (1 + 0.01 * t[0]) * x - 1.003 * x, np.array([-0.5]),
    ...            np.array([1.0]), np.full(5, 1e-12))
    >>> round(float(t[0]), 9)
    0.3
    >>> _solve(lambda t: (1 + 0.01 * t[0]) * x - 1.003 * x**2, np.array([-0.5]),
    ...        np.array([1.0]), np.full(5, 1e-12)) is None
    True
    """
    t = np.zeros(lower.shape)
    r = residual(t)
    damping = 1e-9
    for _ in range(_STEPS):
        if not np.isfinite(r).all():
            return None
        if (np.abs(r) <= tol).all():
            return t
        columns = []
        for i in range(t.size):  # forward differences, stepping into the box
            h = _STEP if t[i] + _STEP <= upper[i] else -_STEP
            moved = t.copy()
            moved[i] += h
            columns.append((residual(moved) - r) / h)
        jac = np.stack(columns, axis=1)
        if not np.isfinite(jac).all():
            return None
        grad = jac.T @ r
        free = ~(((t <= lower) & (grad > 0)) | ((t >= upper) & (grad < 0)))
        if not free.any():
            return None
        jf = jac[:, free]
        normal = jf.T @ jf
        scale = np.diag(normal).copy() + 1e-300
        while damping < 1e12:
            step = np.zeros(t.size)
            step[free] = np.linalg.solve(normal + damping * np.diag(scale), -grad[free])
            trial = np.clip(t + step, lower, upper)
            r_trial = residual(trial)
            if np.isfinite(r_trial).all() and r_trial @ r_trial < r @ r:
                t, r, damping = trial, r_trial, max(damping / 10, 1e-12)
                break
            damping *= 10
        else:
            return None
    return t if np.isfinite(r).all() and (np.abs(r) <= tol).all() else None


#: Levenberg–Marquardt steps, and the finite-difference step (in units of a last digit).
_STEPS, _STEP = 60, 1e-6


def rounding_accepts(
    rounding: Rounding,
    template: sp.Expr,
    literals: tuple[Literal, ...],
    env: Mapping[sp.Basic, np.ndarray],
    size: int,
    key: np.ndarray,
) -> str | None:
    """How the answer is right up to rounding (``to 4 significant digits`` …), or None.

    ``template`` is the answer with its literals as placeholders, ``env`` the sample
    (symbol → values at ``size`` points) and ``key`` the key's values there.  Under a
    ``digits`` rule each decimal stands for one value within its interval, the same at
    every point: the answer is right when such values exist (:func:`_solve` finds them),
    so that ``1.00*k*(1 + S2/300)`` is not ``k`` up to rounding.
    """
    template, literals = standing(template, literals)
    decimals = [lit for lit in literals if decimal_places(lit.text)[1] > 0]
    if rounding.mode == "off" or not decimals:
        return None
    written = {lit.symbol: lit.value for lit in literals}
    answer = _at(template, env, size, written)
    with np.errstate(all="ignore"):
        diff = key - answer
        if not (np.isfinite(answer).all() and np.isfinite(key).all()):
            return None
        room = 1 + TOLERANCES.agree_rtol
        if rounding.mode == "abs":
            ok = np.abs(diff) <= rounding.tolerance * room
            return rounding.describe(0) if ok.all() else None
        if rounding.mode == "rel":
            ok = np.abs(diff) <= rounding.tolerance * float(np.abs(key).max()) * room
            return rounding.describe(0) if ok.all() else None
        moving = [lit for lit in decimals if rounding.allowed(lit) != (0.0, 0.0)]
        if not moving:
            return None
        units = np.array([lit.unit for lit in moving])
        lower = np.array([rounding.allowed(lit)[0] for lit in moving]) / units
        upper = np.array([rounding.allowed(lit)[1] for lit in moving]) / units

        def residual(t: np.ndarray) -> np.ndarray:
            subs = {
                lit.symbol: float(lit.value) + float(u * x) for lit, u, x in zip(moving, units, t)
            }
            out: np.ndarray = _at(template, env, size, {**written, **subs}) - key
            return out

        tol = TOLERANCES.agree_rtol * (1 + np.abs(key))
        t = _solve(residual, lower, upper, tol)
    if t is None:
        return None
    used = [lit.digits for lit, x in zip(moving, t) if x != 0] or [lit.digits for lit in moving]
    return rounding.describe(min(used))
