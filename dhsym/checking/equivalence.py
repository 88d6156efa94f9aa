"""Are two expressions equal? Numbers at many random points first, then an exact proof.

:class:`Sample` holds random values for a set of symbols; :func:`values` evaluates
an expression or matrix at all of them at once (:mod:`dhsym.checking._numeric`).
Entries that agree numerically are confirmed with
:func:`dhsym.kinematics.simplification.prove_equal` under a time limit, after
:func:`~dhsym.checking._limits.expansion_terms` has shown the proof is affordable.

Examples
--------
>>> import sympy as sp
>>> t1, t2 = sp.symbols("theta1 theta2", real=True)
>>> s = Sample.random([t1, t2])
>>> close(values(sp.cos(t1 + t2), s), values(sp.cos(t1)*sp.cos(t2) - sp.sin(t1)*sp.sin(t2), s))
True
>>> prove_entry(sp.cos(t1 + t2), sp.cos(t1)*sp.cos(t2) - sp.sin(t1)*sp.sin(t2))
True
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from dhsym.kinematics.simplification import prove_equal

from ._limits import (
    DEFAULT_ANSWER_LIMITS,
    AnswerLimits,
    CheckTimeout,
    expansion_terms,
    time_limit,
)
from ._numeric import EvaluationError, evaluate

__all__ = [
    "EXACT_RTOL",
    "ROUNDING_RTOL",
    "Sample",
    "close",
    "has_decimals",
    "prove_entry",
    "values",
]

EXACT_RTOL = 1e-9
ROUNDING_RTOL = 2e-3
_POLY_FUNCS = (sp.sin, sp.cos)


@dataclass(frozen=True, eq=False)
class Sample:
    """Random values for symbols at ``size`` points (row ``k`` of ``table`` for ``symbols[k]``)."""

    symbols: tuple[sp.Symbol, ...]
    table: np.ndarray = field(repr=False)

    @property
    def size(self) -> int:
        """Number of points."""
        return int(self.table.shape[1])

    @property
    def env(self) -> dict[sp.Symbol, np.ndarray]:
        """Symbol → values, for :func:`dhsym.checking._numeric.evaluate`."""
        return dict(zip(self.symbols, self.table))

    @classmethod
    def random(
        cls,
        symbols: Iterable[sp.Symbol],
        size: int = 24,
        seed: int = 20240,
        fixed: Mapping[sp.Symbol, float] | None = None,
    ) -> Sample:
        """Uniform values in [-2.5, 2.5]; symbols in ``fixed`` keep one value at every point."""
        syms = tuple(sorted(set(symbols), key=sp.default_sort_key))
        rng = np.random.default_rng(seed)
        table = rng.uniform(-2.5, 2.5, size=(len(syms), size))
        for k, s in enumerate(syms):
            if fixed and s in fixed:
                table[k] = float(fixed[s])
        return cls(syms, table)

    def extended(self, symbols: Iterable[sp.Symbol], seed: int = 7) -> Sample:
        """This sample plus random values for symbols it does not have yet."""
        new = sorted(set(symbols) - set(self.symbols), key=sp.default_sort_key)
        if not new:
            return self
        rng = np.random.default_rng(seed)
        extra = rng.uniform(-2.5, 2.5, size=(len(new), self.size))
        return Sample(self.symbols + tuple(new), np.vstack([self.table, extra]))


def values(expr: sp.Basic, sample: Sample) -> np.ndarray:
    """Values at every point: shape ``(size,)`` for an expression, ``(size, r, c)`` for a matrix.

    Unknown node types give ``nan`` (never equal to anything).
    """
    env = sample.env
    if isinstance(expr, sp.MatrixBase):
        r, c = expr.shape
        out = np.empty((sample.size, r, c))
        for i in range(r):
            for j in range(c):
                out[:, i, j] = values(expr[i, j], sample)
        return out
    try:
        return evaluate(expr, env, sample.size)
    except (EvaluationError, OverflowError, TypeError, ValueError):
        return np.full(sample.size, np.nan)


def close(a: np.ndarray, b: np.ndarray, rtol: float = EXACT_RTOL, axis: object = None) -> object:
    """True where ``a`` and ``b`` agree at every point (finite, within ``rtol`` relative).

    With ``axis=0`` the answer is per entry (points along axis 0).
    """
    with np.errstate(all="ignore"):
        ok = np.isfinite(a) & np.isfinite(b) & (np.abs(a - b) <= rtol * (1.0 + np.abs(b)))
    return ok.all(axis=axis) if axis is not None else bool(ok.all())


def has_decimals(expr: sp.Basic) -> bool:
    """True when ``expr`` holds a decimal number such as ``0.7071`` (a power-of-ten fraction).

    >>> has_decimals(sp.Rational(7071, 10000)), has_decimals(sp.Rational(1, 2))
    (True, False)
    """
    for r in expr.atoms(sp.Rational):
        q = int(r.q)
        if q > 1 and 10 ** len(str(q)) // 10 == q:
            return True
    return False


def _polynomial_trig(expr: sp.Basic) -> bool:
    """True when ``expr`` is a polynomial in symbols and sin/cos (what ``prove_equal`` decides)."""
    for node in sp.preorder_traversal(expr):
        if node.is_Pow and not (node.exp.is_Integer and node.exp > 0):
            return False
        if isinstance(node, sp.Function) and not isinstance(node, _POLY_FUNCS):
            return False
    return True


def prove_entry(
    answer: sp.Expr, key: sp.Expr, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS
) -> bool | None:
    """Exact check ``answer == key``: True, False, or None when it cannot be decided.

    None means the proof was skipped (too large, not a trigonometric polynomial)
    or ran out of time; the numeric comparison then stands alone.
    """
    diff = answer - key
    if diff == 0:
        return True
    if not (_polynomial_trig(answer) and _polynomial_trig(key)):
        return None
    if expansion_terms(diff) > limits.max_terms:
        return None
    try:
        with time_limit(limits.proof_seconds):
            return bool(prove_equal(sp.Matrix([answer]), sp.Matrix([key])))
    except (CheckTimeout, RecursionError, MemoryError):
        return None
