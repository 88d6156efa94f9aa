"""The plain data of a derivation: frozen dataclasses read by the templates.

:func:`dhsym.derivation.derive` fills these; :mod:`dhsym.rendering` arranges them.
Every formula is a :class:`Math`, printed twice (LaTeX and plain text). The
public names are re-exported by :mod:`dhsym.derivation`.

Examples
--------
>>> m = Math(TeX("C_{1}"), "C1")
>>> Term("-", m).math.text
'C1'
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .latex import TeX, math_width
from .table import Convention

__all__ = [
    "LATEX_WIDTH",
    "TEXT_WIDTH",
    "Derivation",
    "Equation",
    "Factor",
    "GeneralLink",
    "Identity",
    "LegendLine",
    "Math",
    "MatrixBlock",
    "NumericCheck",
    "Step",
    "TableCell",
    "TableData",
    "Term",
]

#: Widths (in rough character units) above which a formula is split.
LATEX_WIDTH = 56.0
TEXT_WIDTH = 100


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
class Identity:
    """A sum-angle identity used in a product: ``terms`` sum to ``result``."""

    terms: tuple[Term, ...]
    result: Math
    wide: bool = False  # too long for running text: display it
    split: bool = False  # too long for one display line: result on the next line


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
class Factor:
    """One elementary transform of the general link matrix (seed 002, Transformations 1–4)."""

    kind: str
    axis: str
    value: Math
    block: MatrixBlock


@dataclass(frozen=True)
class LegendLine:
    """An abbreviation and its meaning."""

    abbrev: Math
    meaning: Math


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
    """A whole derivation as plain data; render it with :mod:`dhsym.rendering`.

    Strings are trusted LaTeX (:class:`~dhsym.latex.TeX`) or plain text;
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

    def __str__(self) -> str:
        return self.to_text()
