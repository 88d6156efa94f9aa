"""Decimal angles that are meant to be exact: ``1.5708`` read as ``pi/2``, visibly.

Toolbox printouts and Python print twists as decimals (``1.5708``,
``1.5707963267948966``). A table angle in radians (twist α, the constant part
of θ, a fixed θ, a base/tool rotation) written as a decimal is read as the
nearest multiple of π/12 (0, ±π/12, …, ±π, … ±2π) when it is that multiple
rounded to the digits written, with at least 3 significant digits (``1.57``,
``1.5708`` and ``1.5707963267948966`` are π/2; ``1.6`` and ``1.5`` are not).
A tolerance can replace the digits rule, and snapping can be switched off
(:class:`AngleSnap`: ``snap_angles: false`` or ``snap_angles: 1e-6`` in a
table file, ``snap_angles=`` in :meth:`~dhsym.model.table.DHTable.from_rows`).
Every snapped entry is reported once per table in one sentence.

Examples
--------
>>> exact, diff = snap_angle(sp.Rational(15708, 10000))
>>> exact, f"{diff:.2g}"
(pi/2, '3.7e-06')
>>> snap_angle(sp.Rational(16, 10)), snap_angle(sp.Rational(15708, 10000), AngleSnap(False))
(None, None)
>>> AngleSnap.parse(1e-6)
AngleSnap(enabled=True, tolerance=1e-06)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from dhsym.errors import TableError

from .entries import exact_decimal
from .parsing import parse_expression

__all__ = ["AngleSnap", "Snapped", "snap_angle", "snap_entry", "snap_note"]

_STEP = sp.pi / 12
_MIN_SIGNIFICANT = 3
_FLOAT_SLACK = 2.0**-50  # a few units in the last place of a double: np.deg2rad(30) is pi/6


@dataclass(frozen=True)
class AngleSnap:
    """How decimal angles are read: snapped to multiples of π/12, or kept as written.

    ``tolerance=None`` is the digits rule: the decimal must be the multiple
    rounded to the digits written (``|difference| ≤ ½·10⁻ᵈ`` for d decimals, or a
    few units in the last place of a double) and have at least 3 significant
    digits. A number is an absolute tolerance in radians instead.
    """

    enabled: bool = True
    tolerance: float | None = None

    @classmethod
    def parse(cls, value: object, *, field: str = "snap_angles") -> AngleSnap:
        """``True``/``None`` (digits rule), ``False``, or a tolerance in radians.

        >>> AngleSnap.parse(False), AngleSnap.parse(True)
        (AngleSnap(enabled=False, tolerance=None), AngleSnap(enabled=True, tolerance=None))
        >>> AngleSnap.parse("1e-6")
        AngleSnap(enabled=True, tolerance=1e-06)
        >>> AngleSnap.parse("often")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        dhsym.errors.TableError: field snap_angles: expected true, false or a tolerance ...
        """
        if isinstance(value, AngleSnap):
            return value
        if value is None or value is True:
            return cls()
        if value is False:
            return cls(False)
        if isinstance(value, str):  # YAML reads 1e-6 (no dot) as text
            try:
                number = parse_expression(value, field=field)
            except TableError:
                number = None
            value = float(number) if number is not None and number.is_Rational else value
        if isinstance(value, (int, float)) and math.isfinite(value) and 0 <= value < 0.1:
            return cls(True, float(value))
        raise TableError(
            f"expected true, false or a tolerance in radians (e.g. 1e-6), got {value!r}",
            field=field,
        )


@dataclass(frozen=True)
class Snapped:
    """One decimal angle read as an exact multiple of π/12."""

    where: str  # "alpha", "theta", "base Rx", ...
    row: int | None
    written: sp.Rational
    exact: sp.Expr
    difference: float


def _decimals(r: sp.Rational) -> int | None:
    """Digits after the point of a finite decimal (``3927/2500`` → 4), None for 1/3."""
    text = exact_decimal(r)
    return None if text is None else len(text.split(".")[1])


def snap_angle(value: sp.Expr, rule: AngleSnap = AngleSnap()) -> tuple[sp.Expr, float] | None:
    """The multiple of π/12 that the decimal ``value`` stands for, and ``|difference|``; or None.

    Only finite decimals that are not integers are candidates (``1/3``, ``2``,
    ``pi/7`` and symbols are left alone).

    >>> snap_angle(sp.Rational(-31416, 10000))[0], snap_angle(sp.Rational(repr(math.pi / 4)))[0]
    (-pi, pi/4)
    >>> snap_angle(sp.Rational(79, 100)), snap_angle(sp.Rational(79, 100), AngleSnap(True, 0.01))[0]
    (None, pi/4)
    """
    if not rule.enabled or not isinstance(value, sp.Rational) or value.is_Integer:
        return None
    decimals = _decimals(value)
    if decimals is None:
        return None
    x = int(value.p) / int(value.q)
    k = round(x / math.pi * 12)
    exact = k * _STEP
    diff = abs(float(sp.N(value - exact, 30)))
    if rule.tolerance is not None:
        ok = diff <= rule.tolerance
    else:
        digits = len(str(abs(int(value.p) * 10**decimals // int(value.q))))
        allowed = max(0.5 * 10.0**-decimals, _FLOAT_SLACK * max(1.0, abs(x)))
        ok = digits >= _MIN_SIGNIFICANT and diff <= allowed
    return (exact, diff) if ok else None


def snap_entry(
    entry: sp.Expr, rule: AngleSnap, where: str, row: int | None
) -> tuple[sp.Expr, Snapped | None]:
    """Snap the constant additive term of an angle entry (``q1 + 0.7854`` → ``q1 + pi/4``).

    >>> q1 = sp.Symbol("q1", real=True)
    >>> snap_entry(q1 + sp.Rational("0.7854"), AngleSnap(), "theta", 2)[0]
    q1 + pi/4
    """
    if not rule.enabled:
        return entry, None
    terms = sp.Add.make_args(entry)
    const = [t for t in terms if not t.free_symbols]
    if len(const) != 1:
        return entry, None
    found = snap_angle(const[0], rule)
    if found is None:
        return entry, None
    exact, diff = found
    rest = sp.Add(*(t for t in terms if t.free_symbols))
    return rest + exact, Snapped(where, row, const[0], exact, diff)


def _pi_text(value: sp.Expr) -> str:
    """``π/2``, ``3π/4``, ``π``, ``0`` for a multiple of π/12 (sign dropped)."""
    r = abs(value / sp.pi)
    if r == 0:
        return "0"
    num = "π" if r.p == 1 else f"{r.p}π"
    return num if r.q == 1 else f"{num}/{r.q}"


def snap_note(found: Sequence[Snapped], opt_out: str = "snap_angles: false") -> str:
    """One sentence for a table: what was read as what, and how to keep the decimals.

    >>> s = [Snapped("alpha", r, sp.Rational(sign * 15708, 10000), sign * sp.pi / 2, 3.7e-6)
    ...      for r, sign in ((1, 1), (3, -1), (4, 1), (5, -1))]
    >>> import textwrap
    >>> print(textwrap.fill(snap_note(s), 90))
    Decimal angles read as exact: alpha ±1.5708 in rows 1, 3, 4, 5 as ±π/2 (|difference| ≤
    3.7e-06). Write snap_angles: false to keep the decimals.
    """
    groups: dict[tuple[str, sp.Rational, sp.Expr], list[Snapped]] = {}
    for s in found:
        groups.setdefault((s.where, abs(s.written), abs(s.exact)), []).append(s)
    parts = []
    for (where, written, exact), items in groups.items():
        signs = {s.written > 0 for s in items}
        sign = "±" if len(signs) > 1 else ("" if signs == {True} else "-")
        rows = [s.row for s in items if s.row is not None]
        at = ""
        if rows:
            at = f" in row{'s' if len(rows) > 1 else ''} {', '.join(map(str, rows))}"
        worst = max(s.difference for s in items)
        parts.append(
            f"{where} {sign}{exact_decimal(written)}{at} as {sign}{_pi_text(exact)} "
            f"(|difference| ≤ {worst:.2g})"
        )
    return (
        f"Decimal angles read as exact: {'; '.join(parts)}. Write {opt_out} to keep the decimals."
    )
