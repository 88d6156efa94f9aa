"""Entries of a DH table: exact sympy expressions from numbers and text, angles in radians.

>>> to_radians(as_expr("q3 + 90"), "deg")
q3 + pi/2
"""

from __future__ import annotations

import math
from typing import TypeAlias

import sympy as sp

from dhsym.errors import TableError

from .kinds import AngleUnit
from .parsing import DEFAULT_LIMITS, numeral_problem, parse_expression

__all__ = ["as_expr", "check_radians", "check_real", "exact_decimal", "to_radians"]

Expr: TypeAlias = sp.Expr


def as_expr(value: object, *, field: str | None = None, row: int | None = None) -> Expr:
    """Turn a Python number, string or sympy object into an exact sympy expression.

    Strings go through the whitelist parser (never ``sympify``); floats become
    exact decimals; booleans, NaN and infinities are refused.

    >>> as_expr(0.4318)
    2159/5000
    >>> as_expr("a1 + d3")
    a1 + d3
    """
    if isinstance(value, bool) or value is None:
        raise TableError(f"expected a number or expression, got {value!r}", row=row, field=field)
    if isinstance(value, sp.Basic):
        if _plainly_finite_real(value):  # the checks below pass; they cost more than the entry
            return value
        expr = value
    elif isinstance(value, int):
        if abs(value) >= 10**DEFAULT_LIMITS.max_digits:  # before any str(value)
            raise TableError(
                f"number with more than {DEFAULT_LIMITS.max_digits} digits: "
                f"expected at most max_digits={DEFAULT_LIMITS.max_digits}",
                row=row,
                field=field,
            )
        expr = sp.Integer(value)
    elif isinstance(value, float):
        if value != value or value in (float("inf"), float("-inf")):
            raise TableError(f"non-finite number {value!r}", row=row, field=field)
        if problem := numeral_problem(repr(abs(value))):
            raise TableError(f"{problem[0]}: {problem[1]}", row=row, field=field)
        expr = sp.Rational(repr(value))
    elif isinstance(value, str):
        expr = parse_expression(value, row=row, field=field)
    else:
        raise TableError(
            f"expected a number or expression, got {type(value).__name__}", row=row, field=field
        )
    if expr.has(sp.oo, -sp.oo, sp.zoo, sp.nan):
        raise TableError("non-finite number", row=row, field=field)
    check_real(expr, row=row, field=field, text=isinstance(value, str))
    return expr


def _plainly_finite_real(expr: sp.Basic) -> bool:
    """True for the commonest entries, which :func:`as_expr` accepts unchanged: a symbol, a
    rational far inside a double's range, a named real constant (``pi``, ``E``) or such a
    rational times one (``pi/2``).

    >>> [_plainly_finite_real(e) for e in (sp.Symbol("q1"), sp.Integer(0), -sp.pi / 2)]
    [True, True, True]
    >>> [_plainly_finite_real(e) for e in (sp.pi**2 / 360, sp.pi**5, sp.sqrt(2) * sp.pi)]
    [True, False, False]
    >>> [_plainly_finite_real(e) for e in (sp.Integer(10) ** 309, sp.I, 2 * sp.I, sp.oo)]
    [False, False, False, False]
    """
    if expr.is_Symbol:
        return True
    if expr.is_Mul and len(expr.args) == 2 and _named_constant(expr.args[1]):
        expr = expr.args[0]
    elif _named_constant(expr):
        return True
    return bool(expr.is_Rational) and abs(expr.p) < _SMALL and abs(expr.q) < _SMALL


def _named_constant(expr: sp.Basic) -> bool:
    """``pi``, ``E`` and such, or one to a small integer power (``pi**2``: a table read
    in the wrong unit has ``pi**2/360``): a finite real number between 1e-4 and 1e4."""
    if expr.is_Pow and expr.exp.is_Integer and 1 <= abs(expr.exp) <= _SMALL_POWER:
        expr = expr.base
    return bool(expr.is_NumberSymbol)


_SMALL = 10**300
_SMALL_POWER = 4


#: The largest magnitude a double holds: beyond it a value is ``inf`` in any exported code.
_FLOAT_MAX = sp.Float(1.7976931348623157e308)


def check_real(
    expr: Expr, *, row: int | None = None, field: str | None = None, text: bool = True
) -> None:
    """Refuse a complex value (``sqrt(-1)``, ``acos(2)``) and a number beyond a double's range.

    Every entry of a table is a real quantity (a length, an angle, a mass): an
    imaginary part would reach exported C or Rust (which do not compile it) or be
    dropped by NumPy. ``text=False`` (a sympy object from Python) skips the
    assumptions query on symbolic expressions, which can be slow on large ones.

    >>> check_real(sp.sqrt(-4), row=2, field="I")
    Traceback (most recent call last):
    ...
    dhsym.errors.TableError: row 2, field I: 2*I is complex: every entry is a real number ...
    >>> check_real(sp.Integer(10) ** 309, field="m")
    Traceback (most recent call last):
    ...
    dhsym.errors.TableError: field m: 1.0E+309 is beyond the range of floating-point ...
    """
    complex_ = expr.has(sp.I) or ((text or expr.is_number) and expr.is_extended_real is False)
    if complex_:
        raise TableError(
            f"{expr} is complex: every entry is a real number (a length, an angle, a mass)",
            row=row,
            field=field,
        )
    if expr.is_number:
        value = expr.evalf(20)
        if value.is_Float and abs(value) > _FLOAT_MAX:
            raise TableError(
                f"{sp.Float(value, 2)} is beyond the range of floating-point numbers "
                f"(about 1.8e308): exported code and written tables would read it as inf",
                row=row,
                field=field,
            )


def to_radians(expr: Expr, unit: AngleUnit | str) -> Expr:
    """Convert an angle entry to radians, exactly.

    Numeric additive terms are degrees; terms with symbols (joint variables,
    symbolic twists) are already angles and stay as they are.

    >>> to_radians(as_expr("q3 + 90"), "deg")
    q3 + pi/2
    >>> to_radians(sp.Integer(-90), "deg"), to_radians(sp.Integer(180), "deg")
    (-pi/2, pi)
    """
    if AngleUnit.parse(unit) is AngleUnit.RAD:
        return expr
    terms = sp.Add.make_args(sp.expand(expr)) if expr.free_symbols else (expr,)
    out = []
    for term in terms:
        if term.free_symbols:
            out.append(term)
        else:
            if term.has(sp.pi):
                raise TableError(
                    f"angles are in degrees but {term} contains pi: write degrees (e.g. 90) "
                    "or set angles: rad"
                )
            out.append(term * sp.pi / 180)
    return sp.Add(*out)


def check_radians(expr: Expr, *, row: int | None, field: str) -> None:
    """Refuse a constant angle above 2π (a table in degrees read as radians).

    >>> check_radians(sp.Symbol("q1") - sp.pi / 2, row=1, field="theta")
    >>> check_radians(sp.Integer(90), row=2, field="alpha")
    Traceback (most recent call last):
    ...
    dhsym.errors.TableError: row 2, field alpha: angle 90 is larger than 2*pi radians: ...
    """
    for term in sp.Add.make_args(expr):
        if not term.free_symbols and term.is_number and _above_turn(term):
            raise TableError(
                f"angle {term} is larger than 2*pi radians: is this table in degrees? "
                "(set angles: deg)",
                row=row,
                field=field,
            )


#: a constant angle above this many radians is refused (:func:`check_radians`)
_TURN = 2 * float(sp.pi) + 1e-9


def _above_turn(term: Expr) -> bool:
    """``abs(float(term)) > _TURN`` for a constant term. A rational and a rational times
    ``pi`` (the angles of tables) are compared in floats without a symbolic evaluation:
    ``p / q`` is the rounded value ``float`` gives, and ``r * math.pi`` is within a few
    units in the last place of it; a value that close to the bound is evaluated as before.

    >>> [_above_turn(t) for t in (sp.pi / 2, -2 * sp.pi, sp.Integer(-7), sp.Rational(13, 2))]
    [False, False, True, True]
    """
    r = term.args[0] if term.is_Mul and len(term.args) == 2 and term.args[1] is sp.pi else None
    turns = None
    try:
        if term.is_Rational:
            return bool(abs(term.p / term.q) > _TURN)
        if term is sp.pi:
            turns = 1.0
        elif r is not None and r.is_Rational:
            turns = abs(r.p / r.q)
    except OverflowError:  # beyond a float: evaluated as before
        turns = None
    if turns is not None:
        approx = turns * math.pi
        if abs(approx - _TURN) > 1e-12 * _TURN:  # far from the bound: the same verdict
            return approx > _TURN
    return abs(float(term)) > _TURN


def exact_decimal(value: object, max_digits: int | None = None) -> str | None:
    """The finite decimal an exact number was written as (``2159/5000`` → ``0.4318``), or None.

    The one formatter of exact decimals: a rational whose denominator is
    2^a 5^b prints as its finite decimal, an integer as itself; anything else
    (``1/3``, ``sqrt(2)``, symbols, or more than ``max_digits`` decimals) gives None.

    >>> exact_decimal(sp.Rational(2159, 5000)), exact_decimal(sp.Rational(-3, 10))
    ('0.4318', '-0.3')
    >>> exact_decimal(sp.Integer(3)), exact_decimal(sp.Rational(1, 3)), exact_decimal(sp.sqrt(2))
    ('3', None, None)
    >>> exact_decimal(sp.Rational(1, 2**20)), exact_decimal(sp.Rational(1, 2**20), max_digits=6)
    ('0.00000095367431640625', None)
    """
    if not isinstance(value, sp.Rational):
        return None
    p, q = int(value.p), int(value.q)
    if q == 1:
        return str(p)
    twos = fives = 0
    while q % 2 == 0:
        q //= 2
        twos += 1
    while q % 5 == 0:
        q //= 5
        fives += 1
    digits = max(twos, fives)
    if q != 1 or (max_digits is not None and digits > max_digits):
        return None
    scaled = p * 10**digits // int(value.q)
    sign = "-" if scaled < 0 else ""
    s = str(abs(scaled)).rjust(digits + 1, "0")
    return f"{sign}{s[:-digits]}.{s[-digits:]}"
