"""The plain data of a derivation: frozen dataclasses read by the templates.

:func:`dhsym.explain.derivation.derive` fills these; :mod:`dhsym.explain.rendering`
arranges them. Every formula is a :class:`~dhsym.notation.layout.Math`, printed twice
(LaTeX and plain text). The public names are re-exported by :mod:`dhsym.explain.derivation`.

Examples
--------
>>> from dhsym.notation.escape import TeX
>>> from dhsym.notation.layout import Math, Term
>>> c12 = Math(TeX("C_{12}"), "C12")
>>> Identity((Term("+", Math(TeX("C_1 C_2"), "C1*C2")),), c12).result.text
'C12'
"""

from __future__ import annotations

from dataclasses import dataclass, field

from dhsym.model.table import Convention
from dhsym.notation.layout import (
    LATEX_WIDTH,
    LegendLine,
    Math,
    MatrixBlock,
    Term,
    math_width,
)

__all__ = [
    "Derivation",
    "Factor",
    "GeneralLink",
    "Identity",
    "NumericCheck",
    "Step",
    "TableCell",
    "TableData",
]


@dataclass(frozen=True)
class Identity:
    """A sum-angle identity used in a product: ``terms`` sum to ``result``."""

    terms: tuple[Term, ...]
    result: Math
    wide: bool = False  # too long for running text: display it
    split: bool = False  # too long for one display line: result on the next line


@dataclass(frozen=True)
class Factor:
    """One elementary transform of the general link matrix (Mohan, Lecture 9,
    Transformations 1–4)."""

    kind: str
    axis: str
    value: Math
    block: MatrixBlock


@dataclass(frozen=True)
class GeneralLink:
    """The convention's link matrix with general parameters, factor by factor."""

    parameters: tuple[Math, ...]
    word: Math
    factors: tuple[Factor, ...]
    result: MatrixBlock
    legend: tuple[LegendLine, ...]


@dataclass(frozen=True)
class Step:
    """``^iT_k = ^iT_{k-1} ^{k-1}T_k`` and the identities that combine angles in it."""

    block: MatrixBlock
    identities: tuple[Identity, ...]
    final: bool


@dataclass(frozen=True)
class TableCell:
    """A table cell; ``variable`` marks the joint variable's entry."""

    math: Math
    variable: bool = False


@dataclass(frozen=True)
class TableData:
    """The DH table with the convention's headers (same cells as ``table_latex``)."""

    heads: tuple[Math, ...]
    rows: tuple[tuple[TableCell, ...], ...]
    degrees: bool
    values: tuple[tuple[Math, Math], ...]
    variables: tuple[Math, ...]


@dataclass(frozen=True)
class NumericCheck:
    """The result evaluated at one configuration, with the table's values."""

    q: tuple[tuple[Math, Math], ...]
    rows: tuple[tuple[Math, ...], ...]


@dataclass(frozen=True)
class Derivation:
    """A whole derivation as plain data; render it with :mod:`dhsym.explain.rendering`.

    Strings are trusted LaTeX (:class:`~dhsym.notation.escape.TeX`) or plain text;
    ``name``, ``source`` and ``notes`` are user text, escaped by the templates.
    """

    name: str
    key: str
    source: str
    notes: str
    convention: str
    n: int
    compact: bool
    numeric: bool
    table: TableData
    general: GeneralLink | None
    links: tuple[MatrixBlock, ...]
    products: tuple[Step, ...]
    result: MatrixBlock
    inverse: bool
    legend: tuple[LegendLine, ...]
    check: NumericCheck | None = field(default=None)
    width: float = LATEX_WIDTH
    warnings: tuple[str, ...] = ()  # how the reader read the input (decimal angles snapped)

    @property
    def legend_columns(self) -> int:
        """How many ``abbreviation = meaning`` pairs fit side by side on a page (1 to 3)."""
        w = max(
            (math_width(e.abbrev.latex) + math_width(e.meaning.latex) + 3 for e in self.legend),
            default=0.0,
        )
        return 3 if 3 * w + 4 <= self.width else (2 if 2 * w + 2 <= self.width else 1)

    @property
    def modified(self) -> bool:
        """True for the modified (Craig) convention."""
        return self.convention == Convention.MODIFIED.value

    def to_text(self) -> str:
        """The derivation as terminal text."""
        from .rendering import render

        return render(self, "text")

    def to_markdown(self) -> str:
        """The derivation as Markdown with ``$…$``/``$$…$$`` math."""
        from .rendering import render

        return render(self, "markdown")

    def to_latex(self) -> str:
        """The derivation as a LaTeX fragment (needs ``amsmath``)."""
        from .rendering import render

        return render(self, "latex")

    def _repr_markdown_(self) -> str:
        return self.to_markdown()

    def _repr_latex_(self) -> str:
        return self.to_latex()

    def _latex(self, printer: object) -> str:
        """``sympy.latex(derivation)``: the LaTeX fragment."""
        return self.to_latex()

    def __str__(self) -> str:
        return self.to_text()
