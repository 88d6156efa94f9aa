"""Formula layout: expressions as :class:`Math` (LaTeX and text), matrix blocks, line breaks.

Every formula is printed twice by a :class:`~dhsym.notation.printers.Notation`
(LaTeX and plain text) into a :class:`Math`; a matrix too wide for a line also
gets its entries as :class:`Equation` s split into lines (:func:`pieces`,
:func:`fill`): at the outermost ``+``/``-`` first, then inside the outermost
bracket, each continuation indented under the bracket it continues. The
derivations, handouts and feedback pages arrange these values; they never
print sympy objects themselves.

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
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from types import MappingProxyType
from typing import TYPE_CHECKING

import sympy as sp

from dhsym.model.entries import exact_decimal

from .escape import TeX
from .printers import Notation, Token, delimiter

if TYPE_CHECKING:  # the model imports this room at call time (a table's view): no circle
    from dhsym.model.table import Elementary

__all__ = [
    "LATEX_WIDTH",
    "TEXT_WIDTH",
    "WORD_FUNCTIONS",
    "Equation",
    "LegendLine",
    "Math",
    "MatrixBlock",
    "Piece",
    "Run",
    "Sentence",
    "Term",
    "as_decimal",
    "as_math",
    "component_names",
    "equation",
    "fill",
    "homogeneous_names",
    "indexed_names",
    "legend_lines",
    "math_width",
    "matrix_block",
    "pieces",
    "sentence",
    "sentence_runs",
    "word_expr",
    "word_math",
]

#: Widths (in rough character units) above which a formula is split.
LATEX_WIDTH = 56.0

TEXT_WIDTH = 100

_OPS = MappingProxyType(
    {(k, a): sp.Function(f"{k}_{a}", commutative=False) for k in "RT" for a in "xyz"}
)

#: The non-commuting factors of :func:`word_expr` by name (``R_z``, ``T_x``, …): the classes
#: a stored derivation's sentences may apply (:func:`dhsym.cache.codec.read_exprs`).
WORD_FUNCTIONS = MappingProxyType({f.__name__: f for f in _OPS.values()})

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
    """One matrix entry as an equation ``name = …``, already split into lines.

    A continuation line carries its own indent (``\\quad`` or ``\\phantom{…}`` in
    LaTeX, spaces in text), relative to where the first line's ``=`` (LaTeX)
    or right-hand side (text) starts: a template writes ``\\ &`` before it.
    """

    name: Math
    latex_lines: tuple[TeX, ...]
    text_lines: tuple[str, ...]


@dataclass(frozen=True)
class MatrixBlock:
    """A labelled matrix: ``label = prefix… = [rows]``, or entry equations when wide.

    ``names`` is the matrix of the wide form: entry names (``r_{11}``, ``J_{21}``) where
    ``entries`` give their values, the values themselves elsewhere (``0 0 0 1``).
    """

    label: Math
    prefix: tuple[Math, ...]
    rows: tuple[tuple[Math, ...], ...]
    entries: tuple[Equation, ...]
    wide: bool
    wide_text: bool
    names: tuple[tuple[Math, ...], ...] = ()  # the symbolic matrix of the wide form


@dataclass(frozen=True)
class LegendLine:
    """An abbreviation and its meaning."""

    abbrev: Math
    meaning: Math


def math_width(tex: str) -> float:
    r"""A rough printed width of math-mode LaTeX, in units of one italic letter (~7.5pt at 11pt).

    Subscripts count 0.7, ``\cos`` three letters, ``\left``/``\right`` and
    ``\Bigl``/``\Bigr`` nothing, ``\quad`` two, ``\phantom{x}`` as ``x``,
    binary operators 2.2 (their spacing). Used to decide where to split a formula.

    >>> math_width("C_{12}"), math_width(r"a_{1} \cos{\left(\theta_{1} \right)}")
    (2.4, 8.0)
    >>> math_width(r"\phantom{{}={}C_{1}[}\quad")
    6.9
    """
    s = re.sub(r"\\(?:left|right|[bB]igg?[lr]?)(?![A-Za-z])\.?", "", tex)
    s = re.sub(r"\\phantom(?![A-Za-z])", "", s)
    s = re.sub(r"\\quad(?![A-Za-z])", "xx", s)
    s = s.replace(r"\{", "(").replace(r"\}", ")")
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


@dataclass(frozen=True)
class Piece:
    """A piece of a formula in LaTeX and text; a line may start at an ``op`` (``brk``).

    ``kind``, ``depth``, ``level`` and ``tall`` are those of the printers'
    :class:`~dhsym.notation.printers.Token` s; ``latex`` is the piece as printed on one line.
    """

    kind: str
    latex: str
    text: str
    depth: int
    level: int = 0
    tall: bool = False

    @property
    def brk(self) -> bool:
        """True when a line may start here (a ``+`` or ``-`` between terms)."""
        return self.kind == "op"


def pieces(expr: sp.Expr, nota: Notation) -> list[Piece]:
    """``expr`` as the printers lay it out: the same tokens in LaTeX and in text.

    >>> t1, a1 = sp.symbols("theta1 a1", real=True)
    >>> [(p.kind, p.text) for p in pieces(a1 * (1 + sp.cos(t1)), Notation.from_variables([t1]))]
    [('atom', 'a1'), ('atom', '*'), ('open', '('), ('atom', 'C1'), ('op', ' + '), \
('atom', '1'), ('close', ')')]
    """
    latex, text = nota.tokens(expr, latex=True), nota.tokens(expr, latex=False)
    return [
        Piece(
            a.kind,
            delimiter(a, True) if a.kind in ("open", "close") else a.text,
            b.text,
            a.depth,
            a.level,
            a.tall,
        )
        for a, b in zip(latex, text, strict=True)
    ]


#: What stands before the first line of an entry after the alignment point: ``&= …``.
_ANCHOR = "{}={}"
#: The indent of a continuation under the sum (text, LaTeX), also the fallback when a
#: continuation under its bracket would not fit.
_SHALLOW = {False: "  ", True: r"\quad "}


def _fitting(breaks: list[int], size: Callable[[int], float], budget: float) -> list[int]:
    r"""The breaks whose line is within ``budget``. A longer line holds a shorter one as its
    prefix (only a bracket's form, ``(`` or ``\Bigl(``, may differ), so the scan stops once
    a line is over twice the budget: a long sum costs its lines, not its length per line.

    >>> _fitting([1, 2, 3, 4], lambda j: 10.0 * j, 25.0)
    [1, 2]
    """
    out = []
    for j in breaks:
        w = size(j)
        if w <= budget:
            out.append(j)
        elif w > 2 * budget + 20:
            break
    return out


def _line_size(
    measure: Callable[[str], float],
    indent: str,
    content: Callable[[int, int], str],
    start: int,
    end: int,
) -> float:
    return measure(indent + content(start, end))


def fill(items: Sequence[Piece], width: float, latex: bool) -> list[str]:
    r"""Lines of ``items`` no wider than ``width`` (LaTeX in ``math_width``, text in characters).

    Each line ends at the last ``+``/``-`` that fits among those of the fewest
    brackets: the outermost sum first, then inside the outermost bracket. A
    continuation starts with its sign; it is indented by ``\quad`` (two spaces)
    under a sum, and under the opening bracket when it continues one
    (``\phantom`` of what stands before it in LaTeX, spaces in text). A bracket
    that spans lines prints as ``\Bigl(``…``\Bigr)`` when tall (``\left`` cannot span).
    """
    measure = math_width if latex else len
    n = len(items)
    partner: dict[int, int] = {}
    stack: list[int] = []
    for k, p in enumerate(items):
        if p.kind == "open":
            stack.append(k)
        elif p.kind == "close" and stack:
            o = stack.pop()
            partner[o], partner[k] = k, o

    def content(lo: int, hi: int) -> str:
        out = []
        for k in range(lo, hi):
            p = items[k]
            if p.kind in ("open", "close"):
                broken = not lo <= partner.get(k, k) < hi
                out.append(delimiter(_token(p), latex, broken))
            elif k == lo and p.kind == "op":  # a continuation starts with its sign,
                sign = p.latex.strip() if latex else p.text.strip()
                out.append(("{}" if latex else "") + sign + " ")  # binary in LaTeX
            else:
                out.append(p.latex if latex else p.text)
        return "".join(out).rstrip()

    anchor = _ANCHOR if latex else ""
    budget = width + measure(anchor)
    lines: list[tuple[int, int, str]] = []  # (start, end, indent)
    start, indent = 0, anchor
    while start < n:
        if measure(indent + content(start, n)) <= budget:
            end = n
        else:
            breaks = [j for j in range(start + 1, n) if items[j].brk]
            size = partial(_line_size, measure, indent, content, start)
            fits = _fitting(breaks, size, budget)
            if not fits and lines and indent != _SHALLOW[latex]:
                # deep under a bracket, nothing fits: continue under the sum instead
                indent = _SHALLOW[latex]
                fits = _fitting(
                    breaks, partial(_line_size, measure, indent, content, start), budget
                )
            if fits:
                shallow = min(items[j].depth for j in fits)
                end = max(j for j in fits if items[j].depth == shallow)
            else:
                end = breaks[0] if breaks else n
        lines.append((start, end, indent))
        if end < n:
            indent = _indent(items, partner, lines, end, content, latex)
        start = end
    return [(ind if k else "") + content(lo, hi) for k, (lo, hi, ind) in enumerate(lines)]


def _token(p: Piece) -> Token:
    return Token(p.kind, p.latex, p.depth, p.level, p.tall)


def _indent(
    items: Sequence[Piece],
    partner: dict[int, int],
    lines: list[tuple[int, int, str]],
    at: int,
    content: Callable[[int, int], str],
    latex: bool,
) -> str:
    """The indent of a line starting at ``items[at]``: under its innermost open bracket."""
    opener = max(
        (o for o, c in partner.items() if o < at < c and items[o].kind == "open"), default=None
    )
    if opener is None:
        return _SHALLOW[latex]
    lo, _, ind = next(line for line in lines if line[0] <= opener < line[1])
    before = ind + content(lo, opener + 1)
    return rf"\phantom{{{before}}}" if latex else " " * len(before)


def as_math(expr: object, nota: Notation) -> Math:
    """``expr`` printed by ``nota`` in LaTeX and text (a leading minus hugs its term)."""
    return Math(TeX(nota.latex(expr)), nota.text(expr))


def as_decimal(value: sp.Expr, nota: Notation) -> Math:
    """A numeric value as the decimal it was written as (0.8, not 4/5) when it is one."""
    if isinstance(value, sp.Rational) and not value.is_Integer:
        text = exact_decimal(value)
        if text is not None:
            return Math(TeX(text), text)
    return as_math(value, nota)


def word_expr(word: Sequence[Elementary]) -> sp.Expr:
    """A word of elementary transforms as a product ``R_z(θ_i) T_z(d_i) …`` the printers print
    (non-commuting factors, zero factors left out).

    >>> from dhsym.model.table import Elementary
    >>> t = sp.Symbol("theta4", real=True)
    >>> Notation().text(word_expr([Elementary("R", "z", t), Elementary("R", "x", -sp.pi / 2)]))
    'R_z(theta4)*R_x(-pi/2)'
    """
    factors = [_OPS[(e.kind, e.axis)](e.value) for e in word if e.value != 0]
    return sp.Mul(*factors) if factors else sp.Integer(1)


def word_math(word: Sequence[Elementary], nota: Notation) -> Math:
    """A word of elementary transforms as ``R_z(θ_i) T_z(d_i) …`` (zero factors left out)."""
    return as_math(word_expr(word), nota)


def equation(name: Math, expr: sp.Expr, whole: Math, nota: Notation, width: float) -> Equation:
    """``name = expr`` (printed as ``whole``), split into lines when it is too wide."""
    latex_lines: list[str] = [whole.latex]
    text_lines = [whole.text]
    if math_width(whole.latex) > width or len(whole.text) > TEXT_WIDTH - 12:
        ps = pieces(expr, nota)
        if math_width(whole.latex) > width:
            latex_lines = fill(ps, width, latex=True)
        if len(whole.text) > TEXT_WIDTH - 12:
            text_lines = fill(ps, TEXT_WIDTH - 12, latex=False)
    return Equation(name, tuple(TeX(x) for x in latex_lines), tuple(text_lines))


@dataclass(frozen=True)
class Sentence:
    """Words with named math in them, printed by a notation as text or as runs of words and math.

    ``template`` holds plain words and ``{name}`` slots; ``args`` the sympy objects (or
    plain strings) that fill them. A derivation keeps its prose this way, so each format
    prints the math with the printers and escapes only the words.

    >>> d3 = sp.Symbol("d3", real=True)
    >>> s = sentence("The height is linear in {v}.", v=d3)
    >>> s.text()
    'The height is linear in d3.'
    >>> [(r.words, r.math and r.math.latex) for r in sentence_runs(s, Notation())]
    [('The height is linear in ', None), ('', 'd_{3}'), ('.', None)]
    """

    template: str
    args: tuple[tuple[str, object], ...] = ()

    def text(self, nota: Notation | None = None) -> str:
        """The sentence in plain text."""
        runs = sentence_runs(self, nota)
        return "".join(r.words if r.math is None else r.math.text for r in runs)

    def __str__(self) -> str:
        return self.text()


def sentence(template: str, **args: object) -> Sentence:
    """A :class:`Sentence` from a template and its named math."""
    return Sentence(template, tuple(args.items()))


@dataclass(frozen=True)
class Run:
    """A piece of a sentence: words (plain text, escaped by each format) or math."""

    words: str = ""
    math: Math | None = None


def sentence_runs(s: Sentence, nota: Notation | None = None) -> tuple[Run, ...]:
    """The runs of ``s``: its words, and its math printed by ``nota`` (cos/sin by default)."""
    import string

    nota = nota or Notation(compact=False)
    args = dict(s.args)
    out: list[Run] = []
    for words, name, _, _ in string.Formatter().parse(s.template):
        if words:
            out.append(Run(words))
        if name is None:
            continue
        value = args[name]
        out.append(Run(value) if isinstance(value, str) else Run(math=as_math(value, nota)))
    return tuple(out)


def homogeneous_names(r: int, c: int) -> Math | None:
    """``r_{11}`` … ``p_{z}``: the names of a 4×4 pose's entries (None in the last row)."""
    if r == 3:
        return None
    tex, text = _ENTRY_NAMES[3 * r + c] if c < 3 else _ENTRY_NAMES[9 + r]
    return Math(TeX(tex), text)


def indexed_names(
    symbol: str, columns: bool = False, start: tuple[int, int] = (1, 1)
) -> Callable[[int, int], Math | None]:
    """Entry names ``J_{11}``, ``J_{12}`` …; ``columns`` orders them column by column;
    ``start`` is the index of the first entry (``(1, 3)``: a block of column 3).

    >>> indexed_names("J")(0, 1), indexed_names("J", start=(1, 3))(1, 0).text
    (Math(latex='J_{12}', text='J12'), 'J23')
    """

    def name(r: int, c: int) -> Math | None:
        i, j = r + start[0], c + start[1]
        return Math(TeX(f"{symbol}_{{{i}{j}}}"), f"{symbol}{i}{j}")

    name.columns = columns  # type: ignore[attr-defined]  # a flag matrix_equations reads by getattr
    return name


def component_names(label: Math) -> Callable[[int, int], Math | None]:
    """Names of a vector's components: ``(o_{6} - o_{0})_{x}`` … (rows x, y, z, then 4, 5 …).

    >>> component_names(Math(TeX("z_{0}"), "z_0"))(2, 0)
    Math(latex='(z_{0})_{z}', text='(z_0)_z')
    """

    def name(r: int, c: int) -> Math | None:
        k = "xyz"[r] if r < 3 else str(r + 1)
        return Math(TeX(f"({label.latex})_{{{k}}}"), f"({label.text})_{k}")

    return name


def matrix_block(
    label: Math,
    matrix: sp.MatrixBase,
    nota: Notation,
    prefix: Sequence[Math] = (),
    width: float = LATEX_WIDTH,
    names: Callable[[int, int], Math | None] | None = None,
) -> MatrixBlock:
    """``label = prefix… = matrix``, with entry equations when it is too wide for a line.

    ``names`` names the entries for the wide form (``r_{11}`` … ``p_{z}`` for a 4×4 pose by
    default, :func:`indexed_names` for others); an entry named None, or a number, stands
    for itself in the symbolic matrix and gets no equation.

    >>> t = sp.Symbol("theta1", real=True)
    >>> b = matrix_block(Math(TeX("v"), "v"), sp.Matrix([sp.cos(t), 0]),
    ...                  Notation.from_variables([t]), names=indexed_names("v"))
    >>> [[m.text for m in row] for row in b.names], b.wide
    ([['v11'], ['0']], False)
    """
    nr, nc = matrix.shape
    if names is None:
        names = homogeneous_names if (nr, nc) == (4, 4) else indexed_names("M")
    rows = tuple(tuple(as_math(matrix[r, c], nota) for c in range(nc)) for r in range(nr))
    cols = [max(math_width(rows[r][c].latex) for r in range(nr)) for c in range(nc)]
    lead = sum(math_width(m.latex) + 2.2 for m in (label, *prefix))
    wide = lead + sum(cols) + 1.5 * nc > width + 6
    tcols = [max(len(rows[r][c].text) for r in range(nr)) for c in range(nc)]
    wide_text = len(label.text) + sum(tcols) + 4 * nc > TEXT_WIDTH
    named = [
        [None if matrix[r, c].is_number else names(r, c) for c in range(nc)] for r in range(nr)
    ]
    if names is homogeneous_names:
        order = [(r, c) for r in range(3) for c in range(3)] + [(r, 3) for r in range(3)]
    elif getattr(names, "columns", False):
        order = [(r, c) for c in range(nc) for r in range(nr)]
    else:
        order = [(r, c) for r in range(nr) for c in range(nc)]
    if names is homogeneous_names:  # a pose names every entry of R and p, zero or not
        named = [[names(r, c) for c in range(nc)] for r in range(nr)]
    entries = (
        tuple(
            equation(entry, matrix[r, c], rows[r][c], nota, width)
            for r, c in order
            if (entry := named[r][c]) is not None
        )
        if wide or wide_text
        else ()
    )
    symbolic = tuple(tuple(named[r][c] or rows[r][c] for c in range(nc)) for r in range(nr))
    return MatrixBlock(label, tuple(prefix), rows, entries, wide, wide_text, symbolic)


def legend_lines(exprs: Sequence[sp.Expr], nota: Notation) -> tuple[LegendLine, ...]:
    """The abbreviations used in ``exprs`` with their meanings."""
    return tuple(
        LegendLine(Math(TeX(e.latex), e.text), Math(TeX(e.meaning_latex), e.meaning_text))
        for e in nota.legend(exprs)
    )
