"""Exact constants as floats: the one conversion every numeric path of dhsym starts from.

* :func:`to_float` evaluates an exact constant (huge integers, nested roots, π)
  with arbitrary precision and returns a float, or raises :class:`~dhsym.errors.DHError`;
* :func:`float_constants` replaces every constant subtree of an expression by its
  float, so generated code sees floats only (never a Python integer beyond 2⁶³ under
  ``sqrt``);
* :func:`as_basic` takes a sympy object or a Python/numpy number, never text.

The compilers (:mod:`dhsym.kinematics.numeric`) and the tree walker
(:mod:`dhsym.kinematics.interpreter`) both fold their constants here. No numpy: the
transform kernel imports this module and stays light.

Examples
--------
>>> huge = sp.sqrt(sp.Integer(10) ** 40 + 1) / 10**20
>>> to_float(huge), float_constants(huge * sp.Symbol("q1"))
(1.0, 1.0*q1)
"""

from __future__ import annotations

import math
from fractions import Fraction

import sympy as sp

from dhsym.errors import DHError

__all__ = ["as_basic", "float_constants", "measured", "to_float"]

_DIGITS = 30  # working precision of constant evaluation (decimal digits)
_EXACT_INT = 2**53


def to_float(expr: object) -> float:
    """The value of an exact real constant as a float (evaluated at 30 digits first).

    Safe for integers far beyond 2⁶³, nested roots and π; raises
    :class:`~dhsym.errors.DHError` for symbols, non-real or non-finite values.

    >>> to_float(sp.sqrt(2) / 2), to_float(sp.pi), to_float(sp.Integer(7) ** 400 / 7 ** 399)
    (0.7071067811865476, 3.141592653589793, 7.0)
    >>> to_float(sp.Integer(10) ** 400)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: the number 1000000000000...0000000000000 is too large for a float
    >>> to_float(sp.zoo)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: zoo is not a real number
    """
    if isinstance(expr, float):
        value = expr
    else:
        e = as_basic(expr)
        if e.free_symbols:
            raise DHError(f"no numeric value for {', '.join(sorted(map(str, e.free_symbols)))}")
        if e.is_Rational:
            value = _rational_float(e)
        elif e.is_Float:
            value = float(e)
        elif (turn := _pi_multiple(e)) is not None:  # θ = π/2 in a table: no evalf
            value = float(turn * _PI)
        else:
            v = sp.N(e, _DIGITS)
            re, im = v.as_real_imag()
            real = re.is_Number and im.is_Number and sp.nan not in (re, im)
            if not real or abs(im) > abs(re) * 1e-20 + 1e-40:  # below the 30 digits: round-off
                raise DHError(f"{_short(e)} is not a real number")
            value = float(re) if re.is_finite else math.inf
    if not math.isfinite(value):
        raise DHError(f"the number {_short(expr)} is too large for a float")
    return value


#: π to 60 digits, exact as a fraction: ``float(r * _PI)`` is the rounded value of ``r·π``
_PI = Fraction(314159265358979323846264338327950288419716939937510582097494, 10**59)


def _pi_multiple(e: sp.Basic) -> Fraction | None:
    """``r`` when ``e`` is ``π`` or ``r·π`` with a rational ``r`` (an angle of a table), else None.

    >>> _pi_multiple(-sp.pi / 2), _pi_multiple(sp.pi), _pi_multiple(sp.sqrt(2))
    (Fraction(-1, 2), Fraction(1, 1), None)
    """
    if e is sp.pi:
        return Fraction(1)
    if e.is_Mul and len(e.args) == 2 and e.args[1] is sp.pi and e.args[0].is_Rational:
        r = e.args[0]
        return Fraction(int(r.p), int(r.q))
    return None


def measured(expr: object) -> bool:
    """Whether ``expr`` holds a rational beyond a float's exact integers (numerator or
    denominator above 2⁵³): a measured number read as exact (a skewed URDF axis), whose
    closed forms grow huge radicals; numbers for it start from floats.

    >>> measured(sp.Rational(89159, 1000000)), measured(sp.sqrt(sp.Rational(10**40 + 1, 3)))
    (False, True)
    """
    e = as_basic(expr)
    return any(abs(r.p) > _EXACT_INT or r.q > _EXACT_INT for r in e.atoms(sp.Rational))


def _rational_float(r: sp.Rational) -> float:
    try:
        return int(r.p) / int(r.q)  # exact rounding, even for huge integers
    except OverflowError:
        return math.inf


def _short(expr: object) -> str:
    s = str(expr)
    return s if len(s) <= 60 else f"{s[:30]}...{s[-30:]}"


def float_constants(expr: sp.Basic) -> sp.Basic:
    """``expr`` with every constant subtree replaced by its float (integer exponents kept).

    >>> x = sp.Symbol("x")
    >>> float_constants(sp.sqrt(2) * sp.cos(x + sp.pi / 3) - x**2 / 4)
    -0.25*x**2 + 1.4142135623730951*cos(x + 1.0471975511965979)
    """
    memo: dict[sp.Basic, sp.Basic] = {}
    # whether a subtree holds a symbol, found once per shared subtree: sympy's free_symbols
    # (and as_independent, which asks it of every argument) walk every copy of a subtree,
    # minutes on the expanded torques of a non-orthogonal wrist (the Jaco)
    symbolic: dict[sp.Basic, bool] = {}

    def has_symbols(e: sp.Basic) -> bool:
        hit = symbolic.get(e)
        if hit is None:
            if e.is_Atom or not (e.is_Add or e.is_Mul or e.is_Pow or isinstance(e, sp.Function)):
                hit = bool(e.free_symbols)  # an atom, or a node that may bind its symbols
            else:
                hit = any(has_symbols(a) for a in e.args)
            symbolic[e] = hit
        return hit

    def walk(e: sp.Basic) -> sp.Basic:
        hit = memo.get(e)
        if hit is not None:
            return hit
        if not has_symbols(e):
            small = e.is_Integer and abs(int(e)) <= _EXACT_INT  # ±1, 2: exact in floats too
            out: sp.Basic = e if small or not isinstance(e, sp.Expr) else sp.Float(to_float(e), 17)
        elif e.is_Atom:
            out = e
        elif e.is_Pow and e.exp.is_Integer:
            out = sp.Pow(walk(e.base), e.exp)
        elif e.is_Add or e.is_Mul:  # fold the constant part as one number
            const = e.func(*(a for a in e.args if not has_symbols(a)))
            rest = [walk(a) for a in e.args if has_symbols(a)]
            out = e.func(walk(const), *rest)
        else:
            out = e.func(*(walk(a) for a in e.args))
        memo[e] = out
        return out

    return walk(as_basic(expr))


def as_basic(value: object) -> sp.Basic:
    """A sympy object for a sympy object or a Python/numpy number; text is refused.

    Nothing here parses or evaluates a string (``sympy.sympify`` would): text goes
    through :func:`dhsym.model.parsing.parse_expression` first.

    >>> as_basic(3), as_basic(0.5), as_basic(sp.Symbol("t"))
    (3, 0.500000000000000, t)
    >>> as_basic("__import__('os')")
    Traceback (most recent call last):
    ...
    TypeError: expected a sympy expression or a number, got str
    """
    if hasattr(value, "dtype") and hasattr(value, "item"):  # numpy scalar
        value = value.item()
    if isinstance(value, sp.Basic):
        return value
    if isinstance(value, int) and not isinstance(value, bool):
        return sp.Integer(value)
    if isinstance(value, float):
        return sp.Float(value)
    raise TypeError(f"expected a sympy expression or a number, got {type(value).__name__}")
