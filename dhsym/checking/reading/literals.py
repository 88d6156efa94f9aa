"""The numeric literals of an answer as written: ``0.7071`` keeps its four digits.

The reader replaces each decimal of an answer by a placeholder (:class:`Literal`) so that
the judging room can tell how much rounding the student's digits allow
(:mod:`dhsym.checking.judging.rounding`).

Examples
--------
>>> decimal_places("0.0203"), decimal_places("1.5708"), decimal_places("7.071e-1")
((3, 0.0001), (5, 0.0001), (4, 0.0001))
>>> import sympy as sp
>>> Literal(sp.Dummy("n0"), "1.50", sp.Rational(3, 2)).digits
3
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import sympy as sp

__all__ = ["Literal", "decimal_places"]

_LITERAL = re.compile(r"^(?P<whole>[0-9]*)(?:\.(?P<frac>[0-9]*))?(?:[eE](?P<exp>[+-]?[0-9]+))?$")


def decimal_places(text: str) -> tuple[int, float]:
    """(significant digits written, one unit in the last digit) of a decimal literal.

    Leading zeros do not count, trailing ones do (``1.50`` has 3).  An integer literal
    (no point, no exponent) is exact: ``(0, 0.0)``.
    """
    m = _LITERAL.match(text.strip())
    if m is None or (m["frac"] is None and m["exp"] is None):
        return 0, 0.0
    frac, exp = m["frac"] or "", int(m["exp"] or 0)
    digits = len((m["whole"] + frac).lstrip("0"))
    return digits, 10.0 ** (exp - len(frac))


@dataclass(frozen=True)
class Literal:
    """A numeric literal of an answer: its placeholder symbol, text and exact value."""

    symbol: sp.Symbol
    text: str
    value: sp.Rational

    @property
    def digits(self) -> int:
        """Significant digits written (0 for an integer)."""
        return decimal_places(self.text)[0]

    @property
    def unit(self) -> float:
        """One unit in the last digit written (0 for an integer)."""
        return decimal_places(self.text)[1]
