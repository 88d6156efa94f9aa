r"""A student's answer read once, into a typed value that the judging room takes.

:func:`read_answer_value` does all the reading of one answer: size and encoding, LaTeX to
plain math, the cells of a matrix, the whitelist parser
(:func:`dhsym.model.parsing.parse_expression` through
:mod:`~dhsym.checking.reading.answers`), and the decimals each cell was written with.
What it returns is frozen:

- :class:`MatrixAnswer`: the cells in the key's shape (:class:`ReadCell`: the text as
  written, the exact value, the literals of a cell written with decimals), and the
  column that was missing from a Jacobian (the judge says what that means);
- :class:`TableAnswer`: the DH table read, and whether its angles were read as degrees;
- :class:`IKAnswer`: the statements ``q_i = …`` (joints and helpers), and the ``±`` signs.

What the key asks (the shape, the joints, the convention) comes in an
:class:`AnswerForm`; a reading error is a :class:`~dhsym.errors.DHError`
(:class:`~dhsym.checking.reading.limits.UnreadableAnswer`, ``ParseError``, ``TableError``)
with the same message as each reader gives by itself.

Examples
--------
>>> from dhsym import load_table
>>> from dhsym.checking.reading.questions import Question
>>> table = load_table("planar2r")
>>> form = AnswerForm(Question.parse("T0_2[0,3]", 2), NameContext.from_table(table), (1, 1))
>>> a = read_answer_value(form, r"0.5 a_1 \cos\theta_1 + a2 C12")
>>> a.matrix[0, 0], a.cells[0].text, [lit.text for lit in a.cells[0].literals]
(a1*cos(theta1)/2 + a2*cos(theta1 + theta2), '0.5 a_1 \\cos\\theta_1 + a2 C12', ['0.5'])
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass

import sympy as sp

from dhsym.errors import DHError, ParseError
from dhsym.ik.steps import pose_symbols
from dhsym.model.parsing import normalize_name
from dhsym.model.table import AngleUnit, Convention, DHTable

from .answer_names import NameContext
from .answers import (
    _split_top,
    answer_only,
    answer_text,
    expression_cell,
    jacobian_blocks,
    matrix_cells,
    read_answer_table,
    read_cell,
    read_text,
    split_statements,
)
from .latex_input import flatten_subscripts, is_latex, latex_to_text
from .limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, UnreadableAnswer
from .literals import Literal
from .questions import Question

__all__ = [
    "Answer",
    "AnswerForm",
    "IKAnswer",
    "IKStatement",
    "MatrixAnswer",
    "ReadCell",
    "TableAnswer",
    "read_answer_value",
]


@dataclass(frozen=True)
class AnswerForm:
    """What the key asks, as far as reading needs it.

    ``shape`` is the key's matrix (rows, columns); ``prismatic`` the 0-based joints whose
    Jacobian column an answer may leave out; ``convention`` the key's (for a table);
    ``variables`` and ``lengths`` the robot's joint variables and lengths (for an
    inverse-kinematics answer); ``rows``, for a Jacobian with rows that are zero in every
    configuration, the others (a planar arm's ``v_x, v_y, ω_z``: 0, 1, 5), which an
    answer may give alone.
    """

    question: Question
    names: NameContext
    shape: tuple[int, int] = (4, 4)
    prismatic: tuple[int, ...] = ()
    convention: Convention = Convention.STANDARD
    variables: tuple[sp.Symbol, ...] = ()
    lengths: frozenset[sp.Symbol] = frozenset()
    rows: tuple[int, ...] = ()


@dataclass(frozen=True)
class ReadCell:
    """One cell: ``text`` as written, its exact ``value``; for a cell written with
    decimals, ``template`` (the cell with a placeholder for each numeric literal) and the
    ``literals`` as written (:class:`~dhsym.checking.reading.literals.Literal`)."""

    text: str
    value: sp.Expr
    template: sp.Expr | None = None
    literals: tuple[Literal, ...] = ()

    @classmethod
    def read(cls, text: str, names: NameContext, limits: AnswerLimits, where: str) -> ReadCell:
        """Read ``text`` once (:func:`~dhsym.checking.reading.answers.read_cell`)."""
        value, written = read_cell(text, names, limits, where)
        return cls(text, value) if written is None else cls(text, value, *written)


_ZERO = ReadCell("0", sp.Integer(0))
_ONE = ReadCell("1", sp.Integer(1))


@dataclass(frozen=True)
class MatrixAnswer:
    """A matrix (or one entry) read in the key's shape: ``cells`` row by row.

    A homogeneous matrix given as its top three rows gets ``0 0 0 1``; a Jacobian one
    column short gets a zero column at ``missing_column`` (0-based, the first prismatic
    joint's).
    """

    source: str
    shape: tuple[int, int]
    cells: tuple[ReadCell, ...]
    missing_column: int | None = None

    @property
    def matrix(self) -> sp.ImmutableMatrix:
        """The exact values, in the key's shape."""
        return sp.ImmutableMatrix(*self.shape, [c.value for c in self.cells])

    @property
    def texts(self) -> list[str]:
        """Each cell as written, row by row."""
        return [c.text for c in self.cells]


@dataclass(frozen=True)
class TableAnswer:
    """A DH table read from the answer; ``degrees`` when its angles were read as degrees."""

    source: str
    table: DHTable

    @property
    def degrees(self) -> bool:
        """True when the angles were read as degrees (a value above 2π, ° or ``deg``)."""
        return self.table.angles is AngleUnit.DEG


@dataclass(frozen=True)
class IKStatement:
    """``target = …`` from the answer: a joint (``joint`` its index) or a helper.

    ``text`` is the right-hand side as written, ``cell`` it read (with its ``±`` as signs
    σ_K); ``degrees`` when it carries a degree sign.
    """

    target: sp.Symbol
    cell: ReadCell
    text: str
    joint: int | None

    @property
    def expr(self) -> sp.Expr:
        """The right-hand side's exact value."""
        return self.cell.value

    @property
    def degrees(self) -> bool:
        """True when the value is written in degrees (``°``, ``\\circ``, ``\\degree``)."""
        return bool(re.search(r"°|\\circ|\\degree", self.text))


@dataclass(frozen=True)
class IKAnswer:
    """An inverse-kinematics answer: its solutions (joint index → statement), helpers and
    ``±`` signs."""

    source: str
    solutions: tuple[dict[int, IKStatement], ...]
    helpers: tuple[IKStatement, ...]
    signs: tuple[sp.Symbol, ...]

    @property
    def symbols(self) -> set[sp.Symbol]:
        """Every symbol the right-hand sides use."""
        out: set[sp.Symbol] = set()
        for st in (*self.helpers, *(s for sol in self.solutions for s in sol.values())):
            out |= st.expr.free_symbols
        return out


Answer = MatrixAnswer | TableAnswer | IKAnswer


def read_answer_value(
    form: AnswerForm, text: str | bytes, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS
) -> Answer:
    """Read ``text`` once as ``form`` asks: a table, an inverse-kinematics answer, or a
    matrix / one entry (see the module text).  Raises the reader's
    :class:`~dhsym.errors.DHError` on what it cannot read.

    Text that cannot be read as it is is read once more as the answer it holds
    (:func:`~dhsym.checking.reading.answers.answer_only`: without code fences, comment
    lines, a prose label, or the one formula set in prose); when that fails too, the first
    reason is raised.
    """
    try:
        return _read_value(form, text, limits)
    except DHError as err:
        try:
            bare = answer_only(read_text(text, limits))
        except DHError:
            bare = None
        if bare is None:
            raise
        try:
            return _read_value(form, bare, limits)
        except DHError:
            raise err from None


def _read_value(form: AnswerForm, text: str | bytes, limits: AnswerLimits) -> Answer:
    kind = form.question.kind
    if kind == "table":
        table = read_answer_table(text, form.names, form.convention, limits)
        return TableAnswer(_source(text), table)
    if kind == "ik":
        try:
            return _read_ik(form, text, limits)
        except ParseError as err:
            raise ParseError(str(err)) from None
    return _read_matrix(form, text, limits)


# where a matrix begins on a line: a bracket, a LaTeX environment, Python's Matrix( / array(
_MATRIX_START = re.compile(r"\[|\\begin\{|Matrix\s*\(|array\s*\(")
_HELPER_END = " \t\r\\,;$"  # a LaTeX line break, punctuation or a dollar after a definition


def _with_helpers(text: str, names: NameContext, limits: AnswerLimits) -> str:
    r"""A matrix written with helpers defined on the lines before it (Spong's
    ``h = -m2 l1 lc2 s2`` and then ``C = [h q̇2, h q̇2 + h q̇1; -h q̇1, 0]``): each helper's
    text, bracketed, in place of its name in the matrix.  A helper may use the ones before
    it; a name of the robot (or one it abbreviates) is not a helper, and then the text is
    left as it is.

    >>> from dhsym import load_table
    >>> ctx = NameContext.from_table(load_table("planar2r"))
    >>> _with_helpers("h = a2 S2\nk = 2 h\n[h, k]", ctx, DEFAULT_ANSWER_LIMITS)
    '[(a2 S2), (2 (a2 S2))]'
    >>> _with_helpers("a1 = 2\n[a1, 0]", ctx, DEFAULT_ANSWER_LIMITS)  # a1 is the robot's
    'a1 = 2\n[a1, 0]'
    """
    lines = text.split("\n")
    start = next((i for i, line in enumerate(lines) if _MATRIX_START.search(line)), 0)
    helpers: list[tuple[str, str]] = []
    for line in lines[:start]:
        for statement in (p.strip(_HELPER_END) for p in line.split(";")):
            if not statement:
                continue
            lhs, _, rhs = statement.partition("=")
            name = _lhs_name(lhs.strip(_HELPER_END + "&"))
            rhs = rhs.strip(_HELPER_END)
            if not (_IDENTIFIER.match(name) and rhs and "=" not in rhs) or names.resolve(name):
                return text
            helpers.append((name, rhs))
    if not helpers:
        return text
    rest = "\n".join(lines[start:])
    for k, (name, rhs) in enumerate(helpers):
        word = re.compile(rf"(?<![A-Za-z0-9_\\]){re.escape(name)}(?![A-Za-z0-9_])")
        put = functools.partial(_put, f"({rhs})")
        uses = sum(len(word.findall(r)) for _, r in helpers[k + 1 :]) + len(word.findall(rest))
        size = len(rest) + sum(len(r) for _, r in helpers) + uses * (len(rhs) + 2)
        if size > limits.max_bytes:  # measured before it is built
            raise UnreadableAnswer(f"the helper {name} makes the answer too long")
        helpers[k + 1 :] = [(n, word.sub(put, r)) for n, r in helpers[k + 1 :]]
        rest = word.sub(put, rest)
    return rest


def _put(text: str, _match: re.Match[str]) -> str:
    """A replacement taken as it is (``re.sub`` would read its backslashes)."""
    return text


def _pos(k: int, q: Question, cols: int = 4) -> str:
    if q.entry is not None or q.kind == "det" or q.index is not None:
        return "the answer"
    return f"entry ({k // cols + 1},{k % cols + 1})"


def _read_matrix(form: AnswerForm, answer: str | bytes, limits: AnswerLimits) -> MatrixAnswer:
    q, names = form.question, form.names
    rows, cols = form.shape
    if q.entry is not None or q.kind == "det" or form.shape == (1, 1):
        cell = expression_cell(answer, limits)
        return MatrixAnswer(cell, (1, 1), (ReadCell.read(cell, names, limits, "the answer"),))
    text = _with_helpers(answer, names, limits) if isinstance(answer, str) else answer
    if q.kind == "screw" and form.shape != (4, 4):
        return _read_axes(form, text, limits)
    if q.kind == "dynamics":
        shapes = ((rows, cols), (cols, rows)) if cols == 1 else ((rows, cols),)
        grid = matrix_cells(text, limits, shapes, symmetric=q.part == "M")
        texts = [c for row in grid for c in row]  # a row vector is read as the column
        where = [f"entry {k + 1}" if cols == 1 else _pos(k, q, cols) for k in range(len(texts))]
        return MatrixAnswer(_source(answer), form.shape, _read_all(texts, where, form, limits))
    if q.kind != "jacobian":
        grid = matrix_cells(text, limits)
        texts = [c for row in grid for c in row]
        cells = _printed(_read_all(texts, [_pos(k, q) for k in range(len(texts))], form, limits))
        if len(grid) == 3:
            cells += (_ZERO, _ZERO, _ZERO, _ONE)
        return MatrixAnswer(_source(answer), (4, 4), cells)
    taken = [(6, cols)] + [(6, cols - 1)] * bool(form.prismatic)
    if form.rows:  # a planar arm's J in its plane: [v_x; v_y; ω_z]
        taken.append((len(form.rows), cols))
    blocks = jacobian_blocks(text, cols, limits, linear=form.rows == (0, 1, 2))
    grid = blocks or matrix_cells(text, limits, tuple(taken))
    if len(grid) == len(form.rows) != 6:
        where = [f"entry ({i + 1},{j})" for i in form.rows for j in range(1, cols + 1)]
        read = _read_all([c for row in grid for c in row], where, form, limits)
        slices = [read[k * cols : (k + 1) * cols] for k in range(len(form.rows))]
        given = dict(zip(form.rows, slices, strict=True))
        plane = tuple(c for i in range(6) for c in given.get(i, (_ZERO,) * cols))
        return MatrixAnswer(_source(answer), (6, cols), plane)
    width = len(grid[0])
    where = [f"entry ({i},{j})" for i, row in enumerate(grid, 1) for j in range(1, len(row) + 1)]
    read = _read_all([c for row in grid for c in row], where, form, limits)
    if width == cols:
        return MatrixAnswer(_source(answer), (6, cols), read)
    k = form.prismatic[0]  # one column short: the prismatic joint's column left out
    full: list[ReadCell] = []
    for i in range(6):
        row = list(read[i * width : (i + 1) * width])
        row.insert(k, _ZERO)
        full += row
    return MatrixAnswer(_source(answer), (6, cols), tuple(full), missing_column=k)


_PRINTED = re.compile(r"\s*[-+]?\s*[0-9]*(\.(?P<frac>[0-9]*))?\s*")


def _printed(cells: tuple[ReadCell, ...]) -> tuple[ReadCell, ...]:
    """A matrix of plain numbers as numpy and MATLAB print one: when most of its decimals
    show the same number of decimal places, the others are read to that many, their
    trailing zeros dropped (numpy prints -0.15005 rounded to 4 decimals as ``-0.15``
    beside ``0.4521``: it is -0.1500, right to 4 decimals). A matrix rounded to
    significant digits (``0.82`` beside ``-0.006``) is read as written.

    >>> from dhsym.checking.reading.literals import decimal_places
    >>> n = sp.Dummy("n")
    >>> cell = lambda t: ReadCell(t, sp.Rational(t), n, (Literal(n, t.lstrip("-"), 0),))
    >>> [decimal_places(c.literals[0].text) for c in _printed(tuple(map(cell, ["0.4521",
    ...     "-0.15", "0.4318", "1."])))]
    [(4, 0.0001), (4, 0.0001), (4, 0.0001), (5, 0.0001)]
    >>> [c.literals[0].text for c in _printed(tuple(map(cell, ["0.82", "0.19", "-0.006"])))]
    ['0.82', '0.19', '0.006']
    """
    found = [_PRINTED.fullmatch(c.text) for c in cells]
    if not all(found):
        return cells
    places = [len(m["frac"]) for m in found if m is not None and m["frac"]]  # not "1."
    widest = max(places, default=0)
    if 2 * places.count(widest) <= len(places):
        return cells
    return tuple(
        ReadCell(
            c.text,
            c.value,
            c.template,
            tuple(
                Literal(lit.symbol, lit.text + "0" * (widest - len(m["frac"])), lit.value)
                if m is not None and m["frac"] is not None and "." in lit.text
                else lit
                for lit in c.literals
            ),
        )
        for c, m in zip(cells, found, strict=True)
    )


def _read_axes(form: AnswerForm, answer: str | bytes, limits: AnswerLimits) -> MatrixAnswer:
    """Screw axes or a PoE Jacobian in the key's shape (6×n, rows ``[ω; v]``).  Screw axes
    may also be listed one per row (n×6, as ``S_1, …, S_n`` are often written) when that
    cannot be taken for columns (n ≠ 6); one axis is a column or a row."""
    rows, cols = form.shape
    listed = form.question.part in ("S", "B") and rows != cols
    grid = matrix_cells(answer, limits, ((rows, cols), (cols, rows)) if listed else ((rows, cols),))
    if len(grid) != rows:  # the axes as rows: they are the key's columns
        grid = [list(column) for column in zip(*grid, strict=True)]
    where = [f"entry ({i},{j})" for i in range(1, rows + 1) for j in range(1, cols + 1)]
    if cols == 1:
        where = [f"entry {i}" for i in range(1, rows + 1)]
    cells = _read_all([c for row in grid for c in row], where, form, limits)
    return MatrixAnswer(_source(answer), form.shape, cells)


def _source(answer: object) -> str:
    """The answer as the text it stands for (a value, such as a sympy matrix, printed)."""
    text = answer_text(answer)
    return text if isinstance(text, str) else text.decode("utf-8", "replace")


def _read_all(
    texts: list[str], where: list[str], form: AnswerForm, limits: AnswerLimits
) -> tuple[ReadCell, ...]:
    return tuple(ReadCell.read(t, form.names, limits, w) for t, w in zip(texts, where, strict=True))


# --- inverse kinematics -----------------------------------------------------------------------

_MAX_SIGNS = 6  # ± in one answer (2^6 choices)
_SIGN_NAME = "pmsign"
_PLUS_MINUS = re.compile(r"\\pm(?![A-Za-z])|±|\+/-")
_MINUS_PLUS = re.compile(r"\\mp(?![A-Za-z])|∓|-/\+")
_IDENTIFIER = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


def _lhs_name(lhs: str) -> str:
    name = latex_to_text(lhs) if is_latex(lhs) else lhs
    name = flatten_subscripts(name).replace("{", "").replace("}", "").replace(" ", "")
    return normalize_name(name) if name else name


def _signed(rhs: str, latex: bool, signs: list[sp.Symbol]) -> str:
    """``±`` as ``+ pmsignK *``: each is a sign σ_K = ±1 of its own."""

    def sub(m: re.Match[str], sign: str) -> str:
        if len(signs) >= _MAX_SIGNS:
            raise UnreadableAnswer(f"the answer has more than {_MAX_SIGNS} signs ±")
        signs.append(sp.Symbol(f"{_SIGN_NAME}{len(signs) + 1}", real=True))
        times = r" \cdot " if latex else "*"
        return f" {sign} {signs[-1].name}{times}"

    rhs = _PLUS_MINUS.sub(lambda m: sub(m, "+"), rhs)
    return _MINUS_PLUS.sub(lambda m: sub(m, "-"), rhs)


_SIGMA = re.compile(r"(?<![A-Za-z0-9_])(?:\\sigma|σ|sigma)_?\{?([0-9]+)\}?(?![A-Za-z0-9_])")


def _sigmas(rhs: str, signs: list[sp.Symbol], named: dict[str, sp.Symbol]) -> str:
    r"""The branch signs of the derivations (``sigma_1``, ``σ1``, ``\sigma_{1}``) as signs
    ±1 of the answer: one per index, the same wherever it is written.

    >>> signs: list[sp.Symbol] = []
    >>> _sigmas("atan2(sigma_1*sqrt(D), K) + σ_1 + \\sigma_{3}", signs, {})
    'atan2( pmsign1 *sqrt(D), K) +  pmsign1  +  pmsign2'
    >>> signs
    [pmsign1, pmsign2]
    """

    def sub(m: re.Match[str]) -> str:
        index = m.group(1)
        if index not in named:
            if len(signs) >= _MAX_SIGNS:
                raise UnreadableAnswer(f"the answer has more than {_MAX_SIGNS} signs ±")
            signs.append(sp.Symbol(f"{_SIGN_NAME}{len(signs) + 1}", real=True))
            named[index] = signs[-1]
        return f" {named[index].name} "

    return _SIGMA.sub(sub, rhs).strip()


# a branch's name before its statements: "elbow up:", "Solution 2:" (not ":=")
_BRANCH_LABEL = re.compile(r"[ \t]*[A-Za-z][A-Za-z0-9 _()#.+-]{0,40}:(?!=)[ \t]*")
# a unit written after a number: 0.3 rad, 17.2 deg, 17.2 degrees
_UNIT_WORD = re.compile(r"(?<=[0-9.])[ \t]*(rad|radians|deg|degrees?)(?![A-Za-z0-9_])")


def _is_list(text: str, n: int) -> bool:
    """Whether ``text`` is a bracketed list of ``n`` values (a joint vector ``[0.3, 0.7]``)."""
    body = text.strip()
    return (
        len(body) > 1
        and body[0] + body[-1] in ("[]", "()")
        and len(_split_top(body[1:-1], ",")) == n
    )


def _read_ik(form: AnswerForm, answer: str | bytes, limits: AnswerLimits) -> IKAnswer:
    """The statements of an inverse-kinematics answer, one per line or ``;`` (see
    :mod:`dhsym.checking.judging.ik_check`); refuses what it cannot read."""
    text = read_text(answer, limits)
    variables = list(form.variables)
    raw = split_statements(text)
    if len(raw) > 4 * len(variables) + 40:
        raise UnreadableAnswer(f"the answer has {len(raw)} statements; at most a few per joint")
    assignments: list[tuple[int, sp.Symbol, str, int | None]] = []
    tuples: list[tuple[int, str]] = []
    helpers_named: dict[str, sp.Symbol] = {}
    for k, s in enumerate(raw):
        label = _BRANCH_LABEL.match(s)  # elbow up: θ1 = …
        s = s[label.end() :] if label else s
        if "=" not in s:
            tuples.append((k, s))
            continue
        lhs, rhs = s.split("=", 1)
        name = _lhs_name(lhs)
        target = form.names.symbol(name) if name else None
        if target not in variables and _is_list(rhs, len(variables)):  # q = [0.3, 0.7]
            tuples.append((k, rhs))
        elif target in variables:
            assignments.append((k, target, rhs, variables.index(target)))
        elif target in form.lengths:
            raise UnreadableAnswer(f"{lhs.strip()!r} is a length of the robot, not an unknown")
        elif name and _IDENTIFIER.match(name):
            helper = helpers_named.setdefault(name, sp.Symbol(name, real=True))
            assignments.append((k, helper, rhs, None))
        else:
            raise UnreadableAnswer(f"cannot read {lhs.strip()!r} as the name of a joint variable")
    P = pose_symbols()
    # x, y, z for the position, as Spong writes a planar arm's (x, y), unless the robot has them
    extra = [(c, P[i, 3]) for i, c in enumerate("xyz") if form.names.symbol(c) is None]
    extra += [(str(P[i, j]), P[i, j]) for i in range(3) for j in range(4)]
    extra += list(helpers_named.items())
    signs: list[sp.Symbol] = []
    solutions: list[dict[int, IKStatement]] = []
    helpers: list[IKStatement] = []

    sigmas: dict[str, sp.Symbol] = {}

    def statement(target: sp.Symbol, rhs: str, joint: int | None, where: str) -> IKStatement:
        rhs = _UNIT_WORD.sub(lambda m: "°" if m[1].startswith("d") else "", rhs)
        signed = _signed(rhs, is_latex(rhs), signs)
        if not any(_SIGMA.fullmatch(name) for name in helpers_named):  # sigma_1 = … is a helper
            signed = _sigmas(signed, signs, sigmas)
        ctx = form.names.extended([*extra, *((s.name, s) for s in signs)])
        return IKStatement(target, ReadCell.read(signed, ctx, limits, where), rhs.strip(), joint)

    for k, target, rhs, joint in assignments:
        st = statement(target, rhs, joint, f"statement {k + 1}")
        if joint is None:
            helpers.append(st)
        else:
            if not solutions or joint in solutions[-1]:
                solutions.append({})
            solutions[-1][joint] = st
    for k, s in tuples:
        cells = _split_top(s.strip().strip("()[]"), ",")
        if len(cells) != len(variables):
            raise UnreadableAnswer(
                f"statement {k + 1} ({s.strip()[:40]!r}) is not 'name = value' and does not "
                f"list the {len(variables)} joint values in order"
            )
        solutions.append(
            {
                j: statement(variables[j], c, j, f"statement {k + 1}, value {j + 1}")
                for j, c in enumerate(cells)
            }
        )
    if not solutions:
        raise UnreadableAnswer("the answer gives no joint value (write e.g. theta1 = …)")
    return IKAnswer(text, tuple(solutions), tuple(helpers), tuple(signs))
