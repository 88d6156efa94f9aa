"""Vectorised numbers from sympy trees: evaluate expressions, words and frames at many points.

A small tree walker (no code generation, no ``lambdify``): each node is one numpy
operation over all sample points at once, shared subtrees are computed once.
Words of elementary transforms come from :mod:`dhsym.kinematics.transforms` (the core's
convention logic); only ``Rx … Tz`` themselves are written here as numbers.

Examples
--------
>>> import numpy as np, sympy as sp
>>> x = sp.Symbol("x")
>>> evaluate(sp.cos(x) ** 2 + sp.sin(x) ** 2, {x: np.array([0.3, 1.2])}, 2)
array([1., 1.])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from dhsym.kinematics.transforms import link_word
from dhsym.model.table import DHTable, Elementary

__all__ = ["EvaluationError", "evaluate", "frames", "word_product"]

_UNARY = {sp.sin: np.sin, sp.cos: np.cos, sp.tan: np.tan}
_UNARY |= {sp.atan: np.arctan, sp.asin: np.arcsin, sp.acos: np.arccos}


class EvaluationError(ValueError):
    """An expression node that the numeric walker does not know."""


def evaluate(
    expr: sp.Basic, env: Mapping[sp.Basic, np.ndarray], size: int, memo: dict | None = None
) -> np.ndarray:
    """Values of ``expr`` at ``size`` points; ``env`` maps each symbol to its values.

    Non-finite results (division by zero, overflow) come out as ``nan``/``inf``;
    callers treat them as "not equal".  ``memo`` (subtree → values) may be shared by
    calls with the same ``env`` (the entries of one matrix).
    """
    memo = {} if memo is None else memo
    with np.errstate(all="ignore"):
        out = _walk(expr, env, size, memo)
    return np.broadcast_to(np.asarray(out, dtype=float), (size,)).copy()


def _walk(e: sp.Basic, env: Mapping, size: int, memo: dict) -> np.ndarray:
    hit = memo.get(e)
    if hit is not None:
        return hit
    if e.is_Symbol:
        if e not in env:
            raise EvaluationError(f"no value for symbol {e}")
        val = np.asarray(env[e], dtype=float)
    elif e.is_Number or e.is_NumberSymbol:
        val = np.asarray(float(e))
    elif e.is_Add:
        val = _walk(e.args[0], env, size, memo)
        for a in e.args[1:]:
            val = val + _walk(a, env, size, memo)
    elif e.is_Mul:
        val = _walk(e.args[0], env, size, memo)
        for a in e.args[1:]:
            val = val * _walk(a, env, size, memo)
    elif e.is_Pow:
        base = _walk(e.args[0], env, size, memo)
        exp = e.args[1]
        if exp.is_Integer:
            k = int(exp)
            val = base**k if k >= 0 else 1.0 / base ** (-k)
        elif exp == sp.S.Half:
            val = np.sqrt(base)
        else:
            val = np.power(base, float(exp))
    elif type(e) in _UNARY:
        val = _UNARY[type(e)](_walk(e.args[0], env, size, memo))
    elif isinstance(e, sp.atan2):
        val = np.arctan2(_walk(e.args[0], env, size, memo), _walk(e.args[1], env, size, memo))
    else:
        raise EvaluationError(f"cannot evaluate {type(e).__name__} numerically")
    memo[e] = val
    return val


def _elementary(e: Elementary, value: np.ndarray) -> np.ndarray:
    """Batch of 4×4 matrices of one elementary transform, shape (size, 4, 4)."""
    size = value.shape[0]
    out = np.zeros((size, 4, 4))
    out[:, 0, 0] = out[:, 1, 1] = out[:, 2, 2] = out[:, 3, 3] = 1.0
    if e.kind == "T":
        out[:, "xyz".index(e.axis), 3] = value
        return out
    c, s = np.cos(value), np.sin(value)
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[e.axis]
    out[:, i, i] = c
    out[:, j, j] = c
    out[:, i, j] = -s
    out[:, j, i] = s
    return out


def word_product(word: Sequence[Elementary], env: Mapping, size: int) -> np.ndarray:
    """Product of a word of elementary transforms at every point: shape (size, 4, 4).

    >>> import sympy as sp
    >>> t = sp.Symbol("t")
    >>> M = word_product([Elementary("R", "z", t), Elementary("T", "x", 2)],
    ...                  {t: np.array([0.0, np.pi / 2])}, 2)
    >>> np.round(M[:, :2, 3], 12) + 0.0
    array([[2., 0.],
           [0., 2.]])
    """
    out = np.broadcast_to(np.eye(4), (size, 4, 4)).copy()
    for e in word:
        if e.value == 0:
            continue
        out = out @ _elementary(e, evaluate(e.value, env, size))
    return out


def frames(table: DHTable, env: Mapping, size: int) -> np.ndarray:
    """The DH frames ``^0T_k`` for k = 0 … n at every point: shape (size, n + 1, 4, 4)."""
    out = np.empty((size, table.n + 1, 4, 4))
    current = np.broadcast_to(np.eye(4), (size, 4, 4)).copy()
    out[:, 0] = current
    for k, row in enumerate(table.rows, start=1):
        current = current @ word_product(link_word(row, table.convention), env, size)
        out[:, k] = current
    return out
