"""The tree walker: one-off exact expressions evaluated at many points, without code generation.

Where an expression is evaluated once (the checker's one-off expressions: a student's
answer at 64 random points), generating code costs more than walking it:
:func:`evaluate` walks one expression at many points at once, each node one numpy
operation over all points, shared subtrees computed once, every subtree without
symbols one constant through :func:`~dhsym.kinematics.constants.to_float`;
:func:`evaluate_many` walks several (the entries of a matrix) sharing their subtrees.
Expressions used often are compiled instead (:mod:`dhsym.kinematics.numeric`, which
also multiplies a word of elementary transforms from these values,
:func:`~dhsym.kinematics.numeric.word_product`).

Examples
--------
>>> q = sp.Symbol("q")
>>> evaluate(sp.sqrt(2) * sp.sin(q + sp.pi / 4), {q: np.array([0.0, -np.pi / 4])}, 2).round(12)
array([1., 0.])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError

from .constants import to_float

__all__ = ["EvaluationError", "evaluate", "evaluate_many"]


class EvaluationError(DHError, ValueError):
    """An expression that has no numeric value: an unknown function, a symbol without
    values, a constant that is not a real float (``zoo``, ``10**400``)."""


_UNARY = {sp.sin: np.sin, sp.cos: np.cos, sp.tan: np.tan}
_UNARY |= {sp.atan: np.arctan, sp.asin: np.arcsin, sp.acos: np.arccos}
_CONSTANT = object()  # the walker's mark of a subtree without symbols


def evaluate(
    expr: sp.Basic,
    env: Mapping[sp.Basic, np.ndarray | float],
    size: int,
    memo: dict[object, np.ndarray] | None = None,
) -> np.ndarray:
    """Values of ``expr`` at ``size`` points (``(size,)``); ``env`` maps each symbol to its values.

    A tree walker (no code generation, no ``lambdify``): each node is one numpy
    operation over all points, shared subtrees are computed once, and every subtree
    without symbols is one constant evaluated exactly by :func:`to_float` (huge
    integers, nested roots). Non-finite results (division by zero, overflow at a
    point) come out as ``nan``/``inf``; an expression without a value raises
    :class:`EvaluationError`. ``memo`` (subtree → values) may be shared by calls with
    the same ``env`` (the entries of one matrix).

    >>> x = sp.Symbol("x")
    >>> evaluate(sp.cos(x) ** 2 + sp.sin(x) ** 2, {x: np.array([0.3, 1.2])}, 2)
    array([1., 1.])
    >>> evaluate(x * sp.sqrt(sp.Integer(10) ** 40 + 1) / 10**20, {x: np.array([2.0])}, 1)
    array([2.])
    """
    memo = {} if memo is None else memo
    try:
        with np.errstate(all="ignore"):
            out = _walk(expr, env, memo)
            if out is _CONSTANT:
                out = _constant(expr, memo)
    except (OverflowError, ZeroDivisionError) as err:  # e.g. x**(10**400)
        raise EvaluationError(f"cannot evaluate numerically ({type(err).__name__})") from None
    return _points(out, size)


def evaluate_many(
    exprs: Sequence[sp.Basic],
    env: Mapping[sp.Basic, np.ndarray | float],
    size: int,
    memo: dict[object, np.ndarray] | None = None,
) -> np.ndarray:
    """Values of several expressions at ``size`` points: shape ``(len(exprs), size)``.

    One walk over all of them (:func:`evaluate`'s rules), their shared subtrees computed
    once: the entries of a matrix, the factors of a word.  The first expression without
    a value raises :class:`EvaluationError`.

    >>> x = sp.Symbol("x")
    >>> evaluate_many([sp.cos(x), 2 * sp.cos(x), sp.pi / 2], {x: np.array([0.0, np.pi])}, 2)
    array([[ 1.        , -1.        ],
           [ 2.        , -2.        ],
           [ 1.57079633,  1.57079633]])
    """
    memo = {} if memo is None else memo
    out = np.empty((len(exprs), size))
    try:
        with np.errstate(all="ignore"):
            for k, expr in enumerate(exprs):
                val = _walk(expr, env, memo)
                out[k] = _points(_constant(expr, memo) if val is _CONSTANT else val, size)
    except (OverflowError, ZeroDivisionError) as err:  # e.g. x**(10**400)
        raise EvaluationError(f"cannot evaluate numerically ({type(err).__name__})") from None
    return out


def _points(value: object, size: int) -> np.ndarray:
    """A walker's result as a fresh float array of ``size`` points (a constant repeated)."""
    points = np.empty(size)
    points[...] = np.asarray(value, dtype=float)  # np.broadcast_to's rules, without its cost
    return points


def _constant(e: sp.Basic, memo: dict[object, np.ndarray]) -> np.ndarray:
    key = ("constant", e)
    hit = memo.get(key)
    if hit is None:
        try:
            hit = memo[key] = np.asarray(to_float(e))
        except DHError as err:
            raise EvaluationError(err.message) from None
    return hit


def _walk(
    e: sp.Basic, env: Mapping[sp.Basic, np.ndarray | float], memo: dict[object, np.ndarray]
) -> Any:
    """Values of ``e`` at every point, or :data:`_CONSTANT` for a subtree without symbols.

    (``Any``: an ``np.ndarray`` or the ``_CONSTANT`` mark, told apart by ``is``.)
    """
    hit = memo.get(e)
    if hit is not None:
        return hit
    if e.is_Symbol:
        if e not in env:
            raise EvaluationError(f"no value for symbol {e}")
        memo[e] = val = np.asarray(env[e], dtype=float)
        return val
    if not e.args:  # a number, pi, I, zoo, ...
        return _CONSTANT
    parts = [_walk(a, env, memo) for a in e.args]
    if all(p is _CONSTANT for p in parts):
        return _CONSTANT
    if e.is_Pow and parts[1] is _CONSTANT and e.exp.is_Integer:
        base, k = parts[0], int(e.exp)
        val = base**k if k >= 0 else 1.0 / base ** (-k)
    elif e.is_Pow and parts[1] is _CONSTANT and e.exp == sp.S.Half:
        val = np.sqrt(parts[0])
    else:
        args = [_constant(a, memo) if p is _CONSTANT else p for a, p in zip(e.args, parts)]
        val = _apply(e, args)
    memo[e] = val
    return val


def _apply(e: sp.Basic, args: list[np.ndarray]) -> np.ndarray:
    val: np.ndarray
    if e.is_Add:
        val = args[0]
        for a in args[1:]:
            val = val + a
        return val
    if e.is_Mul:
        val = args[0]
        for a in args[1:]:
            val = val * a
        return val
    if e.is_Pow:
        val = np.power(args[0], args[1])
        return val
    if type(e) in _UNARY:
        val = _UNARY[type(e)](args[0])
        return val
    if isinstance(e, sp.atan2):
        val = np.arctan2(args[0], args[1])
        return val
    raise EvaluationError(f"cannot evaluate {type(e).__name__} numerically")
