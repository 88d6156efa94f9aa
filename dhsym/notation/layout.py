"""Formula layout: expressions as :class:`Math` (LaTeX and text), matrix blocks, line breaks.

Every formula is printed twice by a :class:`~dhsym.notation.printers.Notation`
(LaTeX and plain text) into a :class:`Math`; a matrix too wide for a line also
gets its entries as :class:`Equation` s split at their ``+``/``-`` signs,
outermost first (:func:`pieces`, :func:`fill`). The derivations, handouts and
feedback pages arrange these values; they never print sympy objects themselves.

Examples
--------
>>> import sympy as sp
>>> from dhsym.notation.printers import Notation
>>> as_math(-sp.Symbol("x"), Notation())
Math(latex='-x', text='-x')
>>> as_decimal(sp.Rational(4, 5), Notation()).text
'0.8'
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from decimal import Decimal
from types import MappingProxyType

import sympy as sp

from dhsym.model.table import Elementary

from .escape import TeX
from .printers import Notation

__all__ = [
    "LATEX_WIDTH",
    "TEXT_WIDTH",
    "Equation",
    "LegendLine",
    "Math",
    "MatrixBlock",
    "Piece",
    "Term",
    "as_decimal",
    "as_math",
    "equation",
    "fill",
    "legend_lines",
    "math_width",
    "matrix_block",
    "pieces",
    "tight",
    "word_math",
]

#: Widths (in rough character units) above which a formula is split.
LATEX_WIDTH = 56.0

TEXT_WIDTH = 100

_OPS = MappingProxyType(
    {(k, a): sp.Function(f"{k}_{a}", commutative=False) for k in "RT" for a in "xyz"}
)

_ENTRY_NAMES = [
    (f"r_{{{r + 1}{c + 1}}}", f"r{r + 1}{c + 1}") for r in range(3) for c in range(3)
] + [(f"p_{{{ax}}}", f"p_{ax}") for ax in "xyz"]


@dataclass(frozen=True)
class Math:
    """One formula printed two ways: LaTeX (math mode) and plain text."""

    latex: TeX
    text: str


@dataclass(frozen=True)
class Term:
    """A signed term of a sum: ``sign`` is ``'+'`` or ``'-'``."""

    sign: str
    math: Math


@dataclass(frozen=True)
class Equation:
    """One matrix entry as an equation ``name = …``, already split into lines."""

    name: Math
    latex_lines: tuple[TeX, ...]
    text_lines: tuple[str, ...]


@dataclass(frozen=True)
class MatrixBlock:
    """A labelled 4×4 matrix: ``label = prefix… = [rows]``, or entry equations when wide."""

    label: Math
    prefix: tuple[Math, ...]
    rows: tuple[tuple[Math, ...], ...]
    entries: tuple[Equation, ...]
    wide: bool
    wide_text: bool


@dataclass(frozen=True)
class LegendLine:
    """An abbreviation and its meaning."""

    abbrev: Math
    meaning: Math


def math_width(tex: str) -> float:
    r"""A rough printed width of math-mode LaTeX, in units of one italic letter (~7.5pt at 11pt).

    Subscripts count 0.7, ``\cos`` three letters, ``\left``/``\right`` nothing,
    binary operators 2.2 (their spacing). Used to decide where to split a formula.

    >>> math_width("C_{12}"), math_width(r"a_{1} \cos{\left(\theta_{1} \right)}")
    (2.4, 8.0)
    """
    s = re.sub(r"\\(?:left|right)(?![A-Za-z])\.?", "", tex)
    s = re.sub(r"\\(?:cos|sin|tan)(?![A-Za-z])", "ccc", s)
    s = re.sub(r"\\[A-Za-z]+", "x", s)
    width, scale, stack, script = 0.0, 1.0, [], False
    for ch in s:
        if ch in "_^":
            script = True
            continue
        if ch == "{":
            stack.append(scale)
            scale = scale * 0.7 if script else scale
        elif ch == "}":
            scale = stack.pop() if stack else 1.0
        elif not ch.isspace():
            w = 2.2 if ch in "+-=" and scale == 1.0 else (0.8 if ch in "()," else 1.0)
            width += w * (0.7 * scale if script else scale)
        script = False
    return width


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


def as_math(expr: object, nota: Notation) -> Math:
    """``expr`` printed by ``nota`` (LaTeX with a tight leading minus, and text)."""
    return Math(TeX(tight(nota.latex(expr))), nota.text(expr))


def as_decimal(value: sp.Expr, nota: Notation) -> Math:
    """A numeric value as the decimal it was written as (0.8, not 4/5) when it is one."""
    if isinstance(value, sp.Rational) and not value.is_Integer:
        q = int(value.q)
        for f in (2, 5):
            while q % f == 0:
                q //= f
        if q == 1:
            text = format(Decimal(int(value.p)) / Decimal(int(value.q)), "f")
            return Math(TeX(text), text)
    return as_math(value, nota)


def word_math(word: Sequence[Elementary], nota: Notation) -> Math:
    """A word of elementary transforms as ``R_z(θ_i) T_z(d_i) …`` (zero factors left out)."""
    factors = [_OPS[(e.kind, e.axis)](e.value) for e in word if e.value != 0]
    return as_math(sp.Mul(*factors) if factors else sp.Integer(1), nota)


def equation(name: Math, expr: sp.Expr, whole: Math, nota: Notation, width: float) -> Equation:
    """``name = expr`` (printed as ``whole``), split into lines when it is too wide."""
    latex_lines = [whole.latex]
    text_lines = [whole.text]
    if math_width(whole.latex) > width or len(whole.text) > TEXT_WIDTH - 12:
        ps = pieces(expr, nota)
        if math_width(whole.latex) > width:
            latex_lines = fill(ps, width, math_width, " ")
        if len(whole.text) > TEXT_WIDTH - 12:
            text_lines = fill(ps, TEXT_WIDTH - 12, len, "")
    return Equation(name, tuple(TeX(x) for x in latex_lines), tuple(text_lines))


def matrix_block(
    label: Math,
    matrix: sp.MatrixBase,
    nota: Notation,
    prefix: Sequence[Math] = (),
    width: float = LATEX_WIDTH,
) -> MatrixBlock:
    """``label = prefix… = matrix``, with entry equations when it is too wide for a line."""
    rows = tuple(tuple(as_math(matrix[r, c], nota) for c in range(4)) for r in range(4))
    cols = [max(math_width(rows[r][c].latex) for r in range(4)) for c in range(4)]
    lead = sum(math_width(m.latex) + 2.2 for m in (label, *prefix))
    wide = lead + sum(cols) + 6 > width + 6
    tcols = [max(len(rows[r][c].text) for r in range(4)) for c in range(4)]
    wide_text = len(label.text) + sum(tcols) + 16 > TEXT_WIDTH
    order = [(r, c) for r in range(3) for c in range(3)] + [(r, 3) for r in range(3)]
    entries = (
        tuple(
            equation(Math(TeX(tn), nn), matrix[r, c], rows[r][c], nota, width)
            for (tn, nn), (r, c) in zip(_ENTRY_NAMES, order, strict=True)
        )
        if wide or wide_text
        else ()
    )
    return MatrixBlock(label, tuple(prefix), rows, entries, wide, wide_text)


def legend_lines(exprs: Sequence[sp.Expr], nota: Notation) -> tuple[LegendLine, ...]:
    """The abbreviations used in ``exprs`` with their meanings."""
    return tuple(
        LegendLine(Math(TeX(e.latex), e.text), Math(TeX(e.meaning_latex), e.meaning_text))
        for e in nota.legend(exprs)
    )
