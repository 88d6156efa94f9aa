"""Are two expressions equal? An exact proof when affordable, numbers at fresh random points.

:class:`Sample` holds random values for a set of symbols; :func:`values` evaluates
an expression or matrix at all of them at once (:mod:`dhsym.kinematics.numeric`).
Entries that agree numerically are confirmed with
:func:`dhsym.kinematics.simplification.prove_equal` when
:func:`~dhsym.checking.reading.limits.expansion_terms` shows the proof is small and the
answer's deadline leaves time for it; entries whose doubles disagree by no more than
the rounding error of the sums they cancel (:func:`cancellation`) are decided by
60-digit numbers or the proof, never by the doubles;
:func:`prove_entry` first rewrites the angles so that half angles (``θ/2``) and whole
angles share one variable, so ``1 - 2 sin²(θ/2)`` is proven equal to ``cos θ``.

**Why a wrong answer cannot pass.**  Every check draws its own :data:`POINTS` = 64 points
from the operating system's entropy (:func:`secrets.randbits` seeds the generator; there is
no fixed seed), uniformly in ``[-2.5, 2.5]`` for each symbol, and compares in double
precision with relative tolerance :data:`EXACT_RTOL` = 1e-9.  If an answer differs from the
key by more than that tolerance on a fraction ``q`` of the sampling box, the chance that
all 64 independent points miss that part is ``(1 - q)**64``: 5.4e-20 for ``q = 1/2``,
1e-64 for ``q = 9/10``.  A difference that is not identically zero (sums and products of
sines, cosines and powers) is below 1e-9 only near its zero set, a set of measure zero,
so ``q`` is 1 up to the width of that band; an answer built to vanish on chosen points
(``key + Π (θ1 − t_k)``) has ``1 - q`` of about 1e-8 and passes with a chance below
1e-500.  The points are not known before the check, so they cannot be chosen.  What
the numbers cannot see is a difference below 1e-9 everywhere (the key plus 1e-30): the
exact proof catches it whenever the proof is affordable (a polynomial in sines and
cosines of at most ``max_terms`` terms), and it is tried first on every entry that agrees
numerically.

Examples
--------
>>> import sympy as sp
>>> t1, t2 = sp.symbols("theta1 theta2", real=True)
>>> s = Sample.random([t1, t2])
>>> close(values(sp.cos(t1 + t2), s), values(sp.cos(t1)*sp.cos(t2) - sp.sin(t1)*sp.sin(t2), s))
True
>>> prove_entry(sp.cos(t1 + t2), sp.cos(t1)*sp.cos(t2) - sp.sin(t1)*sp.sin(t2))
True
>>> prove_entry(1 - 2 * sp.sin((t1 + t2) / 2) ** 2, sp.cos(t1 + t2))
True
"""

from __future__ import annotations

import math
import secrets
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from dhsym.kinematics.simplification import prove_equal

from ..reading.limits import (
    DEFAULT_ANSWER_LIMITS,
    AnswerLimits,
    expansion_terms,
    time_left,
)
from .sampled_frames import EvaluationError, evaluate_many, evaluate_or_nan
from .tolerances import TOLERANCES

__all__ = [
    "EXACT_RTOL",
    "POINTS",
    "Sample",
    "agree_precisely",
    "cancellation",
    "close",
    "prove_entry",
    "values",
]

EXACT_RTOL = TOLERANCES.agree_rtol
POINTS = 64
_POLY_FUNCS = (sp.sin, sp.cos)
_TRIG = (sp.sin, sp.cos, sp.tan)


def _generator(seed: int | None) -> np.random.Generator:
    """A generator seeded from ``seed``, or from 128 bits of OS entropy when it is None."""
    return np.random.default_rng(secrets.randbits(128) if seed is None else seed)


@dataclass(frozen=True, eq=False)
class Sample:
    """Random values for symbols at ``size`` points (row ``k`` of ``table`` for ``symbols[k]``).

    ``origin`` identifies the draw: an extended sample keeps it (its first symbols keep
    their values), so values computed from those symbols may be cached under it.
    """

    symbols: tuple[sp.Symbol, ...]
    table: np.ndarray = field(repr=False)
    origin: int = field(default=0, repr=False)

    @property
    def size(self) -> int:
        """Number of points."""
        return int(self.table.shape[1])

    @property
    def env(self) -> dict[sp.Symbol, np.ndarray]:
        """Symbol → values, for :func:`dhsym.kinematics.numeric.evaluate`."""
        return dict(zip(self.symbols, self.table))

    @classmethod
    def random(
        cls,
        symbols: Iterable[sp.Symbol],
        size: int = POINTS,
        seed: int | None = None,
        fixed: Mapping[sp.Symbol, float] | None = None,
    ) -> Sample:
        """Uniform values in ``TOLERANCES.symbol_range`` ([-2.5, 2.5]); symbols in ``fixed``
        keep one value at every point.

        Without ``seed`` the points are fresh and unpredictable (seeded from OS entropy).
        """
        syms = _ordered(set(symbols))
        table = _generator(seed).uniform(*TOLERANCES.symbol_range, size=(len(syms), size))
        for k, s in enumerate(syms):
            if fixed and s in fixed:
                table[k] = float(fixed[s])
        return cls(syms, table, secrets.randbits(63) if seed is None else seed)

    def extended(self, symbols: Iterable[sp.Symbol], seed: int | None = None) -> Sample:
        """This sample plus (fresh) random values for symbols it does not have yet."""
        new = _ordered(set(symbols) - set(self.symbols))
        if not new:
            return self
        extra = _generator(seed).uniform(*TOLERANCES.symbol_range, size=(len(new), self.size))
        return Sample(self.symbols + tuple(new), np.vstack([self.table, extra]), self.origin)


def _ordered(symbols: set[sp.Symbol]) -> tuple[sp.Symbol, ...]:
    """``symbols`` in sympy's canonical order (``default_sort_key``), which orders plain
    symbols by name: sorted by name when all are plain symbols (a tenth of the cost).

    >>> x, y, n = sp.Symbol("x"), sp.Symbol("y", real=True), sp.Dummy("n")
    >>> _ordered({y, x}), _ordered({n, y}) == tuple(sorted({n, y}, key=sp.default_sort_key))
    ((x, y), True)
    """
    if all(type(s) is sp.Symbol for s in symbols):
        return tuple(sorted(symbols, key=lambda s: s.name))
    return tuple(sorted(symbols, key=sp.default_sort_key))


def values(
    expr: sp.Basic, sample: Sample, memo: dict[object, np.ndarray] | None = None
) -> np.ndarray:
    """Values at every point: shape ``(size,)`` for an expression, ``(size, r, c)`` for a matrix.

    Unknown node types give ``nan`` (never equal to anything). ``memo`` (subtree → values
    at this sample) may be shared by calls on the same sample: many edits of one entry
    share most of their subtrees, which are then computed once.
    """
    env = sample.env
    if memo is None:
        memo = {}  # subexpressions shared by the entries, computed once
    if isinstance(expr, sp.MatrixBase):
        r, c = expr.shape
        try:  # every entry in one walk (the usual case) ...
            flat = evaluate_many(expr.flat(), env, sample.size, memo)
            return np.ascontiguousarray(flat.T.reshape(sample.size, r, c))
        except (EvaluationError, OverflowError, TypeError, ValueError):
            pass  # ... else entry by entry: only the entries without a value are nan
        out = np.empty((sample.size, r, c))
        for i in range(r):
            for j in range(c):
                out[:, i, j] = evaluate_or_nan(expr[i, j], env, sample.size, memo)
        return out
    return evaluate_or_nan(expr, env, sample.size, memo)


def close(a: np.ndarray, b: np.ndarray, rtol: float = EXACT_RTOL, axis: object = None) -> object:
    """True where ``a`` and ``b`` agree at every point (finite, within ``rtol`` relative).

    With ``axis=0`` the answer is per entry (points along axis 0).
    """
    with np.errstate(all="ignore"):
        ok = np.isfinite(a) & np.isfinite(b) & (np.abs(a - b) <= rtol * (1.0 + np.abs(b)))
    return ok.all(axis=axis) if axis is not None else bool(ok.all())


def _polynomial_trig(expr: sp.Basic) -> bool:
    """True when ``expr`` is a polynomial in symbols and sin/cos (what ``prove_equal`` decides)."""
    for node in sp.preorder_traversal(expr):
        if node.is_Pow and not (node.exp.is_Integer and node.exp > 0):
            return False
        if isinstance(node, sp.Function) and not isinstance(node, _POLY_FUNCS):
            return False
    return True


def _whole_angles(answer: sp.Expr, key: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """Both expressions in variables scaled so that every trigonometric argument is a
    whole multiple of them (``θ → 2θ`` when ``θ/2`` appears), so that ``prove_equal``
    sees ``sin θ`` and ``sin(θ/2)`` as related, not as independent unknowns."""
    scale: dict[sp.Symbol, int] = {}
    for f in answer.atoms(*_TRIG) | key.atoms(*_TRIG):
        for term in sp.Add.make_args(f.args[0]):
            coeff, rest = term.as_coeff_Mul()
            if rest.is_Symbol and coeff.is_Rational and coeff.q > 1:
                scale[rest] = math.lcm(scale.get(rest, 1), int(coeff.q))
    if not scale:
        return answer, key
    sub = {s: m * s for s, m in scale.items()}
    return answer.xreplace(sub), key.xreplace(sub)


def prove_entry(
    answer: sp.Expr,
    key: sp.Expr,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    *,
    agreed: bool = False,
) -> bool | None:
    """Exact check ``answer == key``: True, False, or None when it cannot be decided.

    None means the proof was skipped (too large, not a trigonometric polynomial, larger
    than ``limits.proof_terms`` when the numbers already ``agreed``, or less time left
    than ``limits.proof_seconds``); the numeric comparison then stands alone.  False is exact for
    polynomials in sines and cosines of whole multiples of the variables; other constants
    inside the functions may make it a false False, which :func:`agree_precisely` catches.
    """
    if answer == key:  # the same expression: the difference below is 0, without building it
        return True
    diff = answer - key
    if diff == 0:
        return True
    if not (_polynomial_trig(answer) and _polynomial_trig(key)):
        return None
    answer, key = _whole_angles(answer, key)
    terms = expansion_terms(answer - key)
    if terms > limits.max_terms:
        return None
    if agreed and terms > limits.proof_terms:
        return None  # the numbers agree: a large proof would only confirm them
    if time_left() < limits.proof_seconds:
        return None  # no time for a proof: the numbers stand (the deadline is kept)
    try:
        return bool(prove_equal(sp.Matrix([answer]), sp.Matrix([key])))
    except (RecursionError, MemoryError):
        return None


def _magnitude(
    expr: sp.Expr, sample: Sample, memo: dict[object, np.ndarray] | None = None
) -> np.ndarray:
    """The size of the numbers a double-precision evaluation of ``expr`` adds up: every sum
    taken as the sum of its terms' sizes (its rounding error is about ``eps`` times it);
    ``memo``: the values of subtrees at this sample already computed (:func:`values`)."""
    if expr.is_Add:
        return sum((_magnitude(a, sample, memo) for a in expr.args), np.zeros(sample.size))
    if expr.is_Mul:
        out = np.ones(sample.size)
        for a in expr.args:
            out = out * _magnitude(a, sample, memo)
        return out
    if expr.is_Pow and expr.exp.is_Integer and expr.exp > 0:
        return _magnitude(expr.base, sample, memo) ** int(expr.exp)
    size: np.ndarray = np.abs(values(expr, sample, memo))  # an expression's: (size,) already
    return size


def cancellation(
    answer: sp.Expr,
    sample: Sample,
    difference: np.ndarray,
    memo: dict[object, np.ndarray] | None = None,
) -> bool:
    """True when ``difference`` (answer minus key at the sample) may be rounding error:
    below ``2**-40`` times the size of the numbers the answer's sums cancel (``memo``: the
    values of the answer's subtrees at this sample, when its walk computed them).

    Such an entry is decided by a higher precision or an exact proof, never by the
    doubles: ``(C1² + S1² − 1)·10¹³ + C12`` is ``C12``.

    >>> x = sp.Symbol("x", real=True)
    >>> s = Sample.random([x])
    >>> a = (sp.cos(x) ** 2 + sp.sin(x) ** 2 - 1) * 10**13 + sp.cos(x)
    >>> cancellation(a, s, values(a, s) - values(sp.cos(x), s))
    True
    >>> cancellation(sp.cos(x) + 1e-3, s, np.full(s.size, 1e-3))
    False
    """
    try:
        with np.errstate(all="ignore"):
            size = _magnitude(answer, sample, memo)
    except (EvaluationError, TypeError, ValueError, OverflowError):
        return False
    with np.errstate(all="ignore"):
        return bool(np.all(np.abs(difference) <= 2.0**-40 * (1 + size)))


def agree_precisely(
    answer: sp.Expr, key: sp.Expr, points: int = 3, digits: int = 60, seed: int | None = None
) -> bool:
    """True when ``answer - key`` is below ``10**-(digits - 15)`` (relative) at ``points``
    fresh random points, computed with ``digits`` significant digits.

    For an exact proof that said "not equal" while double precision said "equal": a
    difference far below double precision (``key + 1e-30``) is real and stays; one that
    vanishes to 45 digits at random points is the proof's blind spot (a numeric
    constant such as ``cos(1/2)`` next to ``cos(1)``), and the answer is equal.

    >>> x = sp.Symbol("x", real=True)
    >>> agree_precisely(2 * sp.cos(sp.Rational(1, 2)) ** 2 - 1 + x, sp.cos(1) + x)
    True
    >>> agree_precisely(sp.cos(x) + sp.Rational(1, 10**30), sp.cos(x))
    False
    """
    syms = sorted(answer.free_symbols | key.free_symbols, key=sp.default_sort_key)
    rng = _generator(seed)
    for _ in range(points):
        subs = {s: sp.Float(rng.uniform(*TOLERANCES.symbol_range), digits) for s in syms}
        try:
            a, k = answer.evalf(digits, subs=subs), key.evalf(digits, subs=subs)
            if not (a.is_number and k.is_number):
                return False
            if abs(complex(a - k)) > 10.0 ** -(digits - 15) * (1 + abs(complex(k))):
                return False
        except (ArithmeticError, TypeError, ValueError):
            return False
    return True
