r"""A derivation as plain data, in the order the lectures teach it (seeds 001 and 002).

:func:`derive` builds a :class:`Derivation` from a robot: the DH table with
the convention's own headers, the general link matrix as the product of its
four elementary transforms, each link matrix, the successive products
``^0T_1 … ^0T_n`` with the sum-angle identities named where joints combine
(``C_1 C_2 - S_1 S_2 = C_{12}``), the arm matrix in ``[n s a p; 0 0 0 1]`` form,
the legend of abbreviations and an optional numeric check. Every formula is
printed twice, LaTeX and plain text, by the project's
:class:`~dhsym.notation.Notation`; the templates of :mod:`dhsym.rendering` only
arrange these strings. Entries too wide for a line are split at their ``+``/``-``
signs (outermost first) into aligned lines.

Examples
--------
>>> d = derive("planar2r")
>>> d.result.rows[0][3].latex
'a_{1} C_{1} + a_{2} C_{12}'
>>> [(t.sign, t.math.text) for t in d.products[0].identities[0].terms]
[('+', 'C1*C2'), ('-', 'S1*S2')]
>>> d.legend[4].abbrev.text, d.legend[4].meaning.text
('C12', 'cos(theta1 + theta2)')
>>> [x.text for x in derive("puma560", check=True).check.rows[1]]
['0', '1', '0', '-0.15']
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path
from types import MappingProxyType

import sympy as sp

from .errors import DHError
from .latex import TeX, math_width
from .notation import Notation, format_angle
from .pose import Pose
from .robot import Robot
from .table import AngleUnit, Convention, DHTable, Elementary
from .transforms import chain_word, elementary_matrix

__all__ = [
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
    "as_robot",
    "derive",
    "general_link",
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


# --- the general link matrix ------------------------------------------------------------


class _General(sp.Symbol):
    """θ_i, α_{i-1}, …: a parameter with a symbolic index (prints as in the lectures)."""

    def _latex(self, printer: object) -> str:
        return _GENERAL_TEX[self.name]


_GENERAL_TEX = MappingProxyType(
    {
        "theta_i": r"\theta_{i}",
        "d_i": "d_{i}",
        "a_i": "a_{i}",
        "alpha_i": r"\alpha_{i}",
        "a_{i-1}": "a_{i-1}",
        "alpha_{i-1}": r"\alpha_{i-1}",
    }
)


def _decimal(value: sp.Expr, nota: Notation) -> Math:
    """A numeric value as the decimal it was written as (0.8, not 4/5) when it is one."""
    if isinstance(value, sp.Rational) and not value.is_Integer:
        q = int(value.q)
        for f in (2, 5):
            while q % f == 0:
                q //= f
        if q == 1:
            text = format(Decimal(int(value.p)) / Decimal(int(value.q)), "f")
            return Math(TeX(text), text)
    return _math(value, nota)


def _general_row(modified: bool) -> tuple[_General, ...]:
    names = ("alpha_{i-1}", "a_{i-1}") if modified else ("alpha_i", "a_i")
    return tuple(_General(n, real=True) for n in ("theta_i", "d_i", names[1], names[0]))


# --- printing helpers ---------------------------------------------------------------------

_OPS = MappingProxyType(
    {(k, a): sp.Function(f"{k}_{a}", commutative=False) for k in "RT" for a in "xyz"}
)


def _tight(latex: str) -> str:
    """``- S_{12}`` → ``-S_{12}`` (a leading unary minus hugs its term)."""
    return "-" + latex[2:] if latex.startswith("- ") else latex


def _math(expr: object, nota: Notation) -> Math:
    return Math(TeX(_tight(nota.latex(expr))), nota.text(expr))


def _word(word: Sequence[Elementary], nota: Notation) -> Math:
    factors = [_OPS[(e.kind, e.axis)](e.value) for e in word if e.value != 0]
    return _math(sp.Mul(*factors) if factors else sp.Integer(1), nota)


def _label(pose: Pose) -> Math:
    return Math(TeX(pose.label_latex), pose.label_text)


def _product(left: Pose, right: Pose) -> Math:
    """``^iT_{k-1} ^{k-1}T_k`` as written in a derivation step."""
    return Math(
        TeX(rf"{left.label_latex}\,{right.label_latex}"), f"{left.label_text}*{right.label_text}"
    )


def _inverse(pose: Pose) -> Math:
    """``(^jT_i)^{-1}``, where the inverse result comes from."""
    return Math(TeX(rf"\left({pose.label_latex}\right)^{{-1}}"), f"({pose.label_text})^-1")


# --- splitting long entries ------------------------------------------------------------------


@dataclass(frozen=True)
class _Piece:
    latex: str
    text: str
    depth: int
    brk: bool


def _pieces(expr: sp.Expr, nota: Notation, depth: int = 0, star: bool = False) -> list[_Piece]:
    """Flatten ``expr`` into printable pieces; a line may start at an operator (``brk``)."""
    pre = "*" if star else ""
    if expr.is_Add:
        out: list[_Piece] = []
        for k, term in enumerate(expr.as_ordered_terms()):
            neg = term.could_extract_minus_sign()
            body = -term if neg else term
            if k == 0 and neg:
                out.append(_Piece("-", pre + "-", depth, False))
            elif k > 0:
                out.append(_Piece("- " if neg else "+ ", " - " if neg else " + ", depth, True))
            out.extend(_pieces(body, nota, depth, star=pre != "" and k == 0 and not neg))
        return out
    if expr.is_Mul and any(f.is_Add for f in expr.args):
        coeff, rest = expr.as_coeff_Mul()
        out = []
        if coeff.could_extract_minus_sign():
            out.append(_Piece("-", pre + "-", depth, False))
            coeff, pre = -coeff, ""
        factors = ([coeff] if coeff != 1 else []) + list(rest.as_ordered_factors())
        for k, f in enumerate(factors):
            lead = pre if k == 0 else "*"
            if f.is_Add:
                out.append(_Piece("(", lead + "(", depth + 1, False))
                out.extend(_pieces(f, nota, depth + 1))
                out.append(_Piece(")", ")", depth + 1, False))
            else:
                out.append(_Piece(_tight(nota.latex(f)), lead + nota.text(f), depth, False))
        return out
    return [_Piece(_tight(nota.latex(expr)), pre + nota.text(expr), depth, False)]


def _fill(pieces: list[_Piece], width: float, measure: object, join: str) -> list[str]:
    """Pack pieces into lines no wider than ``width``, breaking at the shallowest depth."""
    size = measure  # type: ignore[assignment]

    def chunks(level: int) -> list[list[_Piece]]:
        out: list[list[_Piece]] = [[]]
        for p in pieces:
            if p.brk and p.depth <= level and out[-1]:
                out.append([])
            out[-1].append(p)
        return out

    def text(ps: list[_Piece]) -> str:
        return join.join(p.latex if join == " " else p.text for p in ps).strip()

    deepest = max((p.depth for p in pieces), default=0)
    level = 0
    parts = chunks(level)
    while level < deepest and max(size(text(c)) for c in parts) > width:  # type: ignore[operator]
        level += 1
        parts = chunks(level)
    lines: list[list[_Piece]] = [[]]
    for c in parts:
        if lines[-1] and size(text(lines[-1] + c)) > width:  # type: ignore[operator]
            lines.append([])
        lines[-1].extend(c)
    return [text(line) for line in lines]


def _equation(name: Math, expr: sp.Expr, whole: Math, nota: Notation, width: float) -> Equation:
    """``name = expr`` (printed as ``whole``), split into lines when it is too wide."""
    latex_lines = [whole.latex]
    text_lines = [whole.text]
    if math_width(whole.latex) > width or len(whole.text) > TEXT_WIDTH - 12:
        ps = _pieces(expr, nota)
        if math_width(whole.latex) > width:
            latex_lines = _fill(ps, width, math_width, " ")
        if len(whole.text) > TEXT_WIDTH - 12:
            text_lines = _fill(ps, TEXT_WIDTH - 12, len, "")
    return Equation(name, tuple(TeX(x) for x in latex_lines), tuple(text_lines))


_ENTRY_NAMES = [
    (f"r_{{{r + 1}{c + 1}}}", f"r{r + 1}{c + 1}") for r in range(3) for c in range(3)
] + [(f"p_{{{ax}}}", f"p_{ax}") for ax in "xyz"]


def _block(
    label: Math,
    matrix: sp.MatrixBase,
    nota: Notation,
    prefix: Sequence[Math] = (),
    width: float = LATEX_WIDTH,
) -> MatrixBlock:
    rows = tuple(tuple(_math(matrix[r, c], nota) for c in range(4)) for r in range(4))
    cols = [max(math_width(rows[r][c].latex) for r in range(4)) for c in range(4)]
    lead = sum(math_width(m.latex) + 2.2 for m in (label, *prefix))
    wide = lead + sum(cols) + 6 > width + 6
    tcols = [max(len(rows[r][c].text) for r in range(4)) for c in range(4)]
    wide_text = len(label.text) + sum(tcols) + 16 > TEXT_WIDTH
    order = [(r, c) for r in range(3) for c in range(3)] + [(r, 3) for r in range(3)]
    entries = (
        tuple(
            _equation(Math(TeX(tn), nn), matrix[r, c], rows[r][c], nota, width)
            for (tn, nn), (r, c) in zip(_ENTRY_NAMES, order, strict=True)
        )
        if wide or wide_text
        else ()
    )
    return MatrixBlock(label, tuple(prefix), rows, entries, wide, wide_text)


def _legend(exprs: Sequence[sp.Expr], nota: Notation) -> tuple[LegendLine, ...]:
    return tuple(
        LegendLine(Math(TeX(e.latex), e.text), Math(TeX(e.meaning_latex), e.meaning_text))
        for e in nota.legend(exprs)
    )


# --- sections ---------------------------------------------------------------------------------


def _table(table: DHTable) -> TableData:
    modified = table.convention is Convention.MODIFIED
    deg = table.angles is AngleUnit.DEG
    if modified:
        heads = [
            ("i", "i"),
            (r"\alpha_{i-1}", "alpha_{i-1}"),
            ("a_{i-1}", "a_{i-1}"),
            ("d_i", "d_i"),
            (r"\theta_i", "theta_i"),
            (r"\text{joint}", "joint"),
        ]
        order = ["alpha", "a", "d", "theta"]
    else:
        heads = [
            ("i", "i"),
            (r"\theta_i", "theta_i"),
            ("d_i", "d_i"),
            ("a_i", "a_i"),
            (r"\alpha_i", "alpha_i"),
            (r"\text{joint}", "joint"),
        ]
        order = ["theta", "d", "a", "alpha"]
    plain = Notation()
    rows = []
    for i, row in enumerate(table.rows, start=1):
        cells = [TableCell(Math(TeX(str(i)), str(i)))]
        for name in order:
            value = getattr(row, name)
            if name in ("theta", "alpha"):
                m = Math(TeX(format_angle(value, deg)), format_angle(value, deg, latex=False))
            else:
                m = Math(TeX(plain.latex(value)), plain.text(value))
            cells.append(TableCell(m, row.variable_field == name))
        cells.append(TableCell(Math(TeX(row.joint.value), row.joint.value)))
        rows.append(tuple(cells))
    values = tuple((_math(s, plain), _decimal(v, plain)) for s, v in table.values)
    return TableData(
        tuple(Math(TeX(a), b) for a, b in heads),
        tuple(rows),
        deg,
        values,
        tuple(_math(v, plain) for v in table.variables),
    )


def general_link(convention: Convention | str, nota: Notation | None = None) -> GeneralLink:
    """The general link matrix of a convention, from its four elementary factors.

    >>> general_link("standard").result.rows[0][1].text
    '-Si*c_alpha_i'
    """
    convention = Convention.parse(convention)
    nota = nota or Notation()
    from .table import DHRow
    from .transforms import link_word, plain_product

    modified = convention is Convention.MODIFIED
    theta, d, a, alpha = _general_row(modified)
    gnota = Notation(((theta, "i"),), compact=nota.compact, upper=nota.upper)
    row = DHRow.fixed(theta, d, a, alpha)
    word = link_word(row, convention)
    factors = tuple(
        Factor(
            e.kind,
            e.axis,
            _math(e.value, gnota),
            _block(_word([e], gnota), elementary_matrix(e), gnota),
        )
        for e in word
    )
    matrix = plain_product(word)
    params = (alpha, a, d, theta) if modified else (theta, d, a, alpha)
    return GeneralLink(
        tuple(_math(p, gnota) for p in params),
        _word(word, gnota),
        factors,
        _block(Math(TeX("{}^{i-1}T_{i}"), "T(i-1)_i"), matrix, gnota),
        _legend(list(matrix), gnota),
    )


def _angles(matrix: sp.MatrixBase) -> set[sp.Expr]:
    return {f.args[0] for f in matrix.atoms(sp.sin, sp.cos)}


def _identity(
    result: sp.Expr,
    terms: Sequence[tuple[str, tuple[sp.Expr, sp.Expr]]],
    nota: Notation,
    width: float,
) -> Identity:
    """``±f(A)g(B) ± … = result``, each product printed factor by factor in textbook order."""
    ts = tuple(
        Term(sign, Math(TeX(" ".join(nota.latex(f) for f in fs)), "*".join(map(nota.text, fs))))
        for sign, fs in terms
    )
    rhs = _math(result, nota)
    size = sum(math_width(t.math.latex) + 2.2 for t in ts) + math_width(rhs.latex)
    return Identity(ts, rhs, size > width / 2, size > width)


def _identities(
    left: sp.MatrixBase,
    right: sp.MatrixBase,
    result: sp.MatrixBase,
    nota: Notation,
    width: float = LATEX_WIDTH,
) -> tuple[Identity, ...]:
    """The sum-angle identities that turn ``left · right`` into ``result``.

    An angle of ``result`` found in neither factor is ``A ± B`` with ``A`` an angle of
    ``left`` and ``B`` one of ``right`` (``θ_2 + θ_3``; ``θ_{12} - θ_4`` after a flip).
    """
    la, ra = _angles(left), _angles(right)
    trig = result.atoms(sp.sin, sp.cos)
    found = []
    for x in sorted(_angles(result) - la - ra, key=sp.default_sort_key):
        for A in sorted(la, key=sp.default_sort_key):
            B = sp.expand(x - A)
            sign = 1 if B in ra else (-1 if -B in ra else 0)
            if sign:
                break
        else:
            continue
        B = B * sign
        cA, sA, cB, sB = sp.cos(A), sp.sin(A), sp.cos(B), sp.sin(B)
        minus, plus = ("-", "+") if sign > 0 else ("+", "-")
        if sp.cos(x) in trig:
            found.append(_identity(sp.cos(x), [("+", (cA, cB)), (minus, (sA, sB))], nota, width))
        if sp.sin(x) in trig:
            found.append(_identity(sp.sin(x), [("+", (sA, cB)), (plus, (cA, sB))], nota, width))
    return tuple(found)


def _check(robot: Robot, frm: int, to: int, q: Sequence[float]) -> NumericCheck:
    missing = [str(s) for s in robot.table.constants if s not in robot.table.value_map]
    if missing:
        raise DHError(
            f"the numeric check needs values for {', '.join(missing)} "
            f"(add them under 'values:' in the table)"
        )
    if len(q) != len(robot.variables):
        raise DHError(f"the numeric check needs {len(robot.variables)} joint values, got {len(q)}")
    T = robot.fk_function(frm, to)([float(x) for x in q])
    plain = Notation()

    def num(x: float) -> Math:
        s = f"{x:.4f}".rstrip("0").rstrip(".")
        s = "0" if s in ("-0", "") else s
        return Math(TeX(s), s)

    return NumericCheck(
        tuple((_math(v, plain), num(float(x))) for v, x in zip(robot.variables, q, strict=True)),
        tuple(tuple(num(float(T[r, c])) for c in range(4)) for r in range(4)),
    )


def as_robot(name_or_robot: object) -> Robot:
    """A Robot from a built-in name, a table file, a DHTable or a Robot (returned as is)."""
    if isinstance(name_or_robot, Robot):
        return name_or_robot
    if isinstance(name_or_robot, DHTable):
        return Robot(name_or_robot)
    if isinstance(name_or_robot, (str, Path)):
        from .library import load

        return load(name_or_robot)
    raise DHError(
        f"expected a robot name, table file, DHTable or Robot; got {type(name_or_robot).__name__}"
    )


def _steps(robot: Robot, lo: int, hi: int, final: bool, width: float) -> list[Step]:
    """``^{lo}T_k = ^{lo}T_{k-1} ^{k-1}T_k`` for k = lo + 2 … hi, with their identities."""
    steps = []
    for k in range(lo + 2, hi + 1):
        left, right, res = (
            robot.transform(lo, k - 1),
            robot.transform(k - 1, k),
            robot.transform(lo, k),
        )
        block = _block(_label(res), res.matrix, robot.notation, [_product(left, right)], width)
        ids = _identities(left.matrix, right.matrix, res.matrix, robot.notation, width)
        steps.append(Step(block, ids, final and k == hi))
    return steps


def derive(
    name_or_robot: str | Path | DHTable | Robot,
    *,
    frm: int = 0,
    to: int | None = None,
    factors: bool = True,
    numeric: bool = False,
    compact: bool | None = None,
    check: bool | Sequence[float] | None = None,
    width: float = LATEX_WIDTH,
) -> Derivation:
    r"""Derive ``^{frm}T_{to}`` of a robot step by step, as the lectures do.

    Parameters
    ----------
    name_or_robot
        A built-in name (``"puma560"``), a table file, a DHTable or a Robot.
    frm, to
        The frames of ``^iT_j`` (default ``0`` and ``n``: the arm matrix);
        ``-1`` is the world and ``n + 1`` the tool frame; ``to < frm`` gives
        the inverse.
    factors
        Include the general link matrix built from its four elementary factors.
    numeric
        Substitute the table's numeric values for the symbolic lengths.
    compact
        ``C_{12}`` notation (default: the robot's own setting) or full cos/sin.
    check
        Evaluate the result numerically at these joint values (``True``: at zero).
    width
        Line width of the LaTeX output in :func:`~dhsym.latex.math_width` units: the
        default fits the handout's 17 cm text; about 40 fits the 12 cm of a default
        ``article`` when a fragment is included in your own document.

    >>> d = derive("puma560_modified", factors=True)
    >>> print(d.general.result.rows[1][3].latex)
    -d_{i} s_{\alpha_{i-1}}
    >>> [e.name.text + " = " + e.text_lines[0] for e in d.result.entries][9]
    'p_x = -d3*S1 + (a2*C2 + a3*C23 - d4*S23)*C1'
    """
    robot = as_robot(name_or_robot)
    table = robot.table.substituted() if numeric else robot.table
    compact = robot.notation.compact if compact is None else compact
    robot = Robot(table, compact=compact, upper=robot.notation.upper)
    nota, n = robot.notation, robot.n
    to = n if to is None else to
    for k in (frm, to):
        if not -1 <= k <= n + 1:
            raise DHError(
                f"frames of {robot.name or 'this robot'} are -1 (world), 0 … {n}, "
                f"{n + 1} (tool); got {k}"
            )
    if frm == to:
        raise DHError(f"^{frm}T_{to} is the identity: choose two different frames")
    lo, hi = min(frm, to), max(frm, to)
    links = []
    for k in range(lo + 1, hi + 1):
        pose, word = robot.transform(k - 1, k), chain_word(table, k - 1, k)
        links.append(_block(_label(pose), pose.matrix, nota, [_word(word, nota)], width))
    pose = robot.transform(frm, to)
    prefix = [_inverse(robot.transform(to, frm))] if frm > to else []
    shown = list(pose.matrix)
    for k in range(lo + 1, hi + 1):
        shown += list(robot.transform(k - 1, k).matrix) + list(robot.transform(lo, k).matrix)
    q = None if check is None or check is False else check
    if q is True:
        q = [0.0] * len(robot.variables)
    name = robot.name or "robot"
    return Derivation(
        name=name,
        key=re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-") or "robot",
        source=table.source,
        notes=table.notes,
        convention=robot.convention.value,
        n=n,
        compact=compact,
        numeric=numeric,
        table=_table(table),
        general=general_link(robot.convention, nota) if factors else None,
        links=tuple(links),
        products=tuple(_steps(robot, lo, hi, frm < to, width)),
        result=_block(_label(pose), pose.matrix, nota, prefix, width),
        inverse=frm > to,
        legend=_legend(shown, nota),
        check=_check(robot, frm, to, list(q)) if q is not None else None,  # type: ignore[arg-type]
        width=width,
    )
