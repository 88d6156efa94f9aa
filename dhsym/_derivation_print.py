"""Printing for derivations: sympy objects and poses as :class:`Math` and matrix blocks.

Every formula goes through the project's :class:`~dhsym.notation.Notation`
(LaTeX and plain text); a matrix too wide for a line also gets its entries as
equations split by :mod:`dhsym._linebreak`. Used by :mod:`dhsym.derivation`.

Examples
--------
>>> import sympy as sp
>>> from dhsym.notation import Notation
>>> as_math(-sp.Symbol("x"), Notation())
Math(latex='-x', text='-x')
>>> as_decimal(sp.Rational(4, 5), Notation()).text
'0.8'
"""

from __future__ import annotations

from collections.abc import Sequence
from decimal import Decimal
from types import MappingProxyType

import sympy as sp

from ._derivation_data import LATEX_WIDTH, TEXT_WIDTH, Equation, LegendLine, Math, MatrixBlock
from ._linebreak import fill, pieces, tight
from .latex import TeX, math_width
from .notation import Notation
from .pose import Pose
from .table import Elementary

__all__ = [
    "as_decimal",
    "as_math",
    "equation",
    "inverse_math",
    "label_math",
    "legend_lines",
    "matrix_block",
    "product_math",
    "word_math",
]

_OPS = MappingProxyType(
    {(k, a): sp.Function(f"{k}_{a}", commutative=False) for k in "RT" for a in "xyz"}
)

_ENTRY_NAMES = [
    (f"r_{{{r + 1}{c + 1}}}", f"r{r + 1}{c + 1}") for r in range(3) for c in range(3)
] + [(f"p_{{{ax}}}", f"p_{ax}") for ax in "xyz"]


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


def label_math(pose: Pose) -> Math:
    """The pose's label, ``^iT_j``."""
    return Math(TeX(pose.label_latex), pose.label_text)


def product_math(left: Pose, right: Pose) -> Math:
    """``^iT_{k-1} ^{k-1}T_k`` as written in a derivation step."""
    return Math(
        TeX(rf"{left.label_latex}\,{right.label_latex}"), f"{left.label_text}*{right.label_text}"
    )


def inverse_math(pose: Pose) -> Math:
    """``(^jT_i)^{-1}``, where the inverse result comes from."""
    return Math(TeX(rf"\left({pose.label_latex}\right)^{{-1}}"), f"({pose.label_text})^-1")


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
