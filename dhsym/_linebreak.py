"""Line breaking of long sums: where a wide matrix entry may be split, and how.

:func:`pieces` flattens an expression into printable pieces, marking the ``+``/``-``
signs at which a new line may start together with their nesting depth;
:func:`fill` packs the pieces into lines no wider than a limit, breaking at the
outermost signs first. Used by :mod:`dhsym.derivation` for entries too wide
for one line.

Examples
--------
>>> import sympy as sp
>>> from dhsym.notation import Notation
>>> a, b, c = sp.symbols("a b c")
>>> fill(pieces(a + b - c, Notation()), 3, len, "")
['a', '+ b', '- c']
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .notation import Notation

__all__ = ["Piece", "fill", "pieces", "tight"]


def tight(latex: str) -> str:
    """``- S_{12}`` → ``-S_{12}`` (a leading unary minus hugs its term).

    >>> tight("- S_{12}")
    '-S_{12}'
    """
    return "-" + latex[2:] if latex.startswith("- ") else latex


@dataclass(frozen=True)
class Piece:
    """A printable piece; a line may start at it when ``brk`` (an operator at ``depth``)."""

    latex: str
    text: str
    depth: int
    brk: bool


def pieces(expr: sp.Expr, nota: Notation, depth: int = 0, star: bool = False) -> list[Piece]:
    """Flatten ``expr`` into printable pieces; a line may start at an operator (``brk``)."""
    pre = "*" if star else ""
    if expr.is_Add:
        out: list[Piece] = []
        for k, term in enumerate(expr.as_ordered_terms()):
            neg = term.could_extract_minus_sign()
            body = -term if neg else term
            if k == 0 and neg:
                out.append(Piece("-", pre + "-", depth, False))
            elif k > 0:
                out.append(Piece("- " if neg else "+ ", " - " if neg else " + ", depth, True))
            out.extend(pieces(body, nota, depth, star=pre != "" and k == 0 and not neg))
        return out
    if expr.is_Mul and any(f.is_Add for f in expr.args):
        coeff, rest = expr.as_coeff_Mul()
        out = []
        if coeff.could_extract_minus_sign():
            out.append(Piece("-", pre + "-", depth, False))
            coeff, pre = -coeff, ""
        factors = ([coeff] if coeff != 1 else []) + list(rest.as_ordered_factors())
        for k, f in enumerate(factors):
            lead = pre if k == 0 else "*"
            if f.is_Add:
                out.append(Piece("(", lead + "(", depth + 1, False))
                out.extend(pieces(f, nota, depth + 1))
                out.append(Piece(")", ")", depth + 1, False))
            else:
                out.append(Piece(tight(nota.latex(f)), lead + nota.text(f), depth, False))
        return out
    return [Piece(tight(nota.latex(expr)), pre + nota.text(expr), depth, False)]


def fill(items: list[Piece], width: float, measure: object, join: str) -> list[str]:
    """Pack ``items`` into lines no wider than ``width``, breaking at the shallowest depth."""
    size = measure  # type: ignore[assignment]

    def chunks(level: int) -> list[list[Piece]]:
        out: list[list[Piece]] = [[]]
        for p in items:
            if p.brk and p.depth <= level and out[-1]:
                out.append([])
            out[-1].append(p)
        return out

    def text(ps: list[Piece]) -> str:
        return join.join(p.latex if join == " " else p.text for p in ps).strip()

    deepest = max((p.depth for p in items), default=0)
    level = 0
    parts = chunks(level)
    while level < deepest and max(size(text(c)) for c in parts) > width:  # type: ignore[operator]
        level += 1
        parts = chunks(level)
    lines: list[list[Piece]] = [[]]
    for c in parts:
        if lines[-1] and size(text(lines[-1] + c)) > width:  # type: ignore[operator]
            lines.append([])
        lines[-1].extend(c)
    return [text(line) for line in lines]
