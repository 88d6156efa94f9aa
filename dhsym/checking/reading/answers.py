r"""Reading answers: text from files or strings, expressions, matrices and DH tables.

Every reader takes untrusted text and either returns sympy objects or raises a
:class:`~dhsym.errors.DHError` (``UnreadableAnswer``, ``ParseError``,
``TableError``) that says what was wrong: size and type are checked first, plain
math goes through :func:`dhsym.model.parsing.parse_expression` with the key's
:class:`~dhsym.checking.reading.answer_names.NameContext` as ``resolve`` hook, LaTeX through
:mod:`dhsym.checking.reading.latex_input`, tables through :mod:`dhsym.model.tablefile` or the
pasted-table reader :mod:`dhsym.checking.reading._table_text`.

Examples
--------
>>> from dhsym import load_table
>>> ctx = NameContext.from_table(load_table("planar2r"))
>>> read_expression("a1*c1 + a2*C12", ctx)
a1*cos(theta1) + a2*cos(theta1 + theta2)
>>> read_expression(r"p_x = a_1 C_1 + a_2 C_{12}", ctx)
a1*cos(theta1) + a2*cos(theta1 + theta2)
>>> read_matrix("[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0,0,1,0]]",
...             ctx)[1, 3]
a1*sin(theta1) + a2*sin(theta1 + theta2)
>>> read_answer_table("| Link | θ | α | a | d |\n|---|---|---|---|---|\n| 1 | θ1 | 0 | a1 | 0 |\n"
...            "| 2 | θ2 | 0 | a2 | 0 |", ctx).rows[1]
DHRow(R: theta=theta2, d=0, a=a2, alpha=0)
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from pathlib import Path

import sympy as sp
import yaml

from dhsym.errors import DHError, ParseError, TableError
from dhsym.model.parsing import parse_expression
from dhsym.model.table import Convention, DHTable
from dhsym.model.yamlsafe import FileRefused, read_limited

from ._table_text import TABLE_FORM, grid_table, yaml_table
from .answer_names import ANGLE_DIFFERENCE, NameContext, angle_difference_name
from .latex_input import (
    answer_side,
    flatten_subscripts,
    is_latex,
    latex_matrix_cells,
    latex_to_text,
)
from .limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, UnreadableAnswer, check_time
from .literals import Literal

__all__ = [
    "NameContext",
    "answer_only",
    "answer_text",
    "cell_literals",
    "expression_cell",
    "jacobian_blocks",
    "matrix_cells",
    "normalize_unicode",
    "parse_cell",
    "read_answer_file",
    "read_answer_table",
    "read_cell",
    "read_expression",
    "read_matrix",
    "split_statements",
    "read_text",
]

_UNICODE = str.maketrans(
    {"−": "-", "–": "-", "·": "*", "×": "*", "⋅": "*", "∗": "*", "÷": "/", "⁄": "/"}
    | {"º": "°", "˚": "°", "\u200b": "", "\u2060": "", "ᵢ": "i", "ⱼ": "j", "₍": "(", "₎": ")"}
    | {"ℓ": "l"}  # Spong's link lengths ℓ1, ℓc2
    | {c: " " for c in "\u00a0\u2002\u2003\u2004\u2005\u2006\u2007\u2008\u2009\u200a\u202f"}
    | {chr(0x2080 + k): str(k) for k in range(10)}  # subscript digits: θ₁ is θ1
    | {"½": "(1/2)", "¼": "(1/4)", "¾": "(3/4)", "⅓": "(1/3)", "√": " sqrt "}
)
# a rate typed with a combining dot above (q̇, θ̇) or diaeresis (q̈): qdot, thetaddot
_RATE_MARK = re.compile("([A-Za-z\u0370-\u03ff])([\u0307\u0308])")
_SUPERSCRIPTS = dict(zip("⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻", "0123456789+-"))
_SUPERSCRIPT_RUN = re.compile("[" + "".join(_SUPERSCRIPTS) + "]+")
_DEGREE_O = re.compile(  # 90^o, 90^{o}: degrees where the base is a number
    r"(?<![A-Za-z_0-9.])([0-9]+(?:\.[0-9]*)?|\.[0-9]+)\s*\^\s*(?:o|\{\s*o\s*\}|\(\s*o\s*\))"
    r"(?![A-Za-z0-9_])"
)
# a matrix as Python writes it: sympy's Matrix, numpy's array (``np.array([[…], […]])``)
_MATRIX_WRAPPER = re.compile(
    r"^\s*(?:(?:sp|sympy|np|numpy)\.)?(?:(?:Immutable)?Matrix|array|asarray|matrix)\s*\((.*)\)\s*$",
    re.DOTALL,
)
# A YAML table: a ``joints:`` key, or a list of rows (``- {theta: …}`` / ``- theta: …``).
# [ \t] and \w stay on one line and no two parts overlap: linear on any text.
_YAML_TABLE = re.compile(r"^[ \t]*(?:joints[ \t]*:|-[ \t]+(?:\{|\w+[ \t]*:))", re.MULTILINE)


def answer_text(value: object) -> str | bytes:
    r"""An answer given as a Python value (or read from a student's YAML file), as the text
    it stands for.

    Text and bytes are kept; a number or a sympy expression is printed by sympy's
    printer (and read back by the whitelist parser, never evaluated); a sympy matrix,
    a numpy array or a list of rows is written ``[[…], […]]`` (cells that are text are
    kept as written); a list of texts is one statement per line; a table as a list of
    rows ``{theta: …, d: …}`` (or a mapping with a ``joints`` list) is written as the YAML
    table it is.  Anything else is :class:`UnreadableAnswer`, saying what was found.

    >>> import sympy as sp
    >>> answer_text(5), answer_text(sp.cos(sp.Symbol("theta1")) / 2)
    ('5', 'cos(theta1)/2')
    >>> answer_text([[1, 0], [0, sp.Symbol("c")]]), answer_text(["theta1 = 0", "theta2 = 1"])
    ('[[1, 0], [0, c]]', 'theta1 = 0\ntheta2 = 1')
    >>> answer_text([["C1", -1], ["S1", 0.5]])
    '[[C1, -1], [S1, 0.5]]'
    >>> print(answer_text([{"theta": "theta1", "d": 0, "a": "a1", "alpha": 90}]), end="")
    - {theta: theta1, d: 0, a: a1, alpha: 90}
    >>> answer_text({1: 2})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dhsym.checking.reading.limits.UnreadableAnswer: expected the answer as text ... a mapping ...
    """
    if isinstance(value, (str, bytes)):
        return value
    shape = getattr(value, "shape", None)
    if isinstance(value, sp.MatrixBase) or (isinstance(shape, tuple) and len(shape) in (1, 2)):
        value = value.tolist()  # type: ignore[attr-defined]  # a sympy matrix or numpy array
    if isinstance(value, Mapping):
        if isinstance(value.get("joints"), list):
            return _yaml_text(value)
        keys = ", ".join(str(k) for k in list(value)[:6])
        raise UnreadableAnswer(f"{_EXPECTED}, got a mapping with the keys {keys}"[:300])
    if isinstance(value, (list, tuple)) and value:
        if all(isinstance(v, Mapping) for v in value):
            return _yaml_text(list(value))  # a table: a list of rows
        if all(isinstance(v, str) for v in value):
            return "\n".join(value)
        if all(isinstance(v, (list, tuple)) for v in value):
            return (
                "[" + ", ".join("[" + ", ".join(_cell(c) for c in row) + "]" for row in value) + "]"
            )
        if any(isinstance(v, (list, tuple, Mapping)) for v in value):
            raise UnreadableAnswer(
                "a list that mixes rows and values: write a table as a list of rows "
                "{theta: …, d: …, a: …, alpha: …}, a matrix as a list of lists (its rows)"
            )
        return ", ".join(_cell(v) for v in value)
    return _number_text(value)


_EXPECTED = (
    "expected the answer as text (a string), a number, a sympy expression, a matrix "
    "(a list of rows) or a table (a list of rows {theta: …, d: …})"
)


def _yaml_text(data: object) -> str:
    """A table given as data, as YAML text for the table reader (one flow mapping a row)."""
    try:
        return yaml.safe_dump(
            data, default_flow_style=None, sort_keys=False, allow_unicode=True, width=1_000_000
        )
    except yaml.YAMLError:  # a value YAML cannot write (an object): not a table of values
        raise UnreadableAnswer(
            f"{_EXPECTED}; a row holds a value that is not text or a number"
        ) from None


def _cell(value: object) -> str:
    """A cell of a matrix given as a list of rows: text as written, a number printed."""
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple, Mapping)):
        raise UnreadableAnswer(
            "a list or mapping inside a cell of a matrix: a matrix is a list of rows, "
            "each a list of entries"
        )
    return _number_text(value)


def _number_text(value: object) -> str:
    if isinstance(value, bool):
        raise UnreadableAnswer(f"{_EXPECTED}, got the truth value {str(value).lower()}")
    if not isinstance(value, (int, float, complex, sp.Basic)):
        if type(value).__module__ == "numpy" and hasattr(value, "item"):
            return _number_text(value.item())  # a numpy scalar
        raise UnreadableAnswer(f"{_EXPECTED}, got {type(value).__name__}")
    if isinstance(value, float):
        return repr(float(value))  # also numpy's float64, a float
    return str(sp.sstr(value))


def read_text(data: str | bytes, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS) -> str:
    """Check size and encoding of an answer and return it as text.

    >>> read_text(b"\\x00\\x01\\xff")
    Traceback (most recent call last):
    ...
    dhsym.checking.reading.limits.UnreadableAnswer: the answer is not text (binary data)
    >>> read_text("a1 C1".encode("utf-16"))  # with its byte-order mark
    'a1 C1'
    """
    data = answer_text(data)
    size = len(data) if isinstance(data, bytes) else len(data.encode("utf-8", "replace"))
    if size > limits.max_bytes:
        raise UnreadableAnswer(f"the answer is {size} bytes; at most {limits.max_bytes} are read")
    if isinstance(data, bytes) and data[:2] in (b"\xff\xfe", b"\xfe\xff"):
        try:  # UTF-16 with its byte-order mark, as Windows PowerShell's > writes a file
            data = data.decode("utf-16")
        except UnicodeDecodeError:
            raise UnreadableAnswer(
                "the answer is not UTF-16 text (after its byte-order mark)"
            ) from None
    if isinstance(data, bytes):
        if b"\x00" in data:
            raise UnreadableAnswer("the answer is not text (binary data)")
        try:
            data = data.decode("utf-8")
        except UnicodeDecodeError:
            raise UnreadableAnswer("the answer is not UTF-8 text") from None
    if not isinstance(data, str):
        raise UnreadableAnswer(f"expected text, got {type(data).__name__}")
    if "\x00" in data:
        raise UnreadableAnswer("the answer is not text (binary data)")
    text = normalize_unicode(data.lstrip("\ufeff"))
    if not text.strip():
        raise UnreadableAnswer("the answer is empty")
    return text


def normalize_unicode(text: str) -> str:
    """ASCII for the Unicode that answers carry: ``−`` ``·`` ``×`` ``θ₁`` ``sin²`` ``√2`` ``½``.

    Superscript runs become ``^(…)`` (``^{…}`` in LaTeX), subscript digits plain digits,
    ``º`` and ``˚`` the degree sign, odd spaces plain spaces, a dot or two above a letter
    its rate (``q̇₁`` → ``qdot1``, ``θ̈₂`` → ``θddot2``).

    >>> normalize_unicode("1 − 2 sin²((θ₁+θ₂)/2) · √2")
    '1 - 2 sin^(2)((θ1+θ2)/2) *  sqrt 2'
    >>> normalize_unicode("q̇₁ + θ̈₂")
    'qdot1 + θddot2'
    """
    text = _RATE_MARK.sub(lambda m: m[1] + ("dot" if m[2] == "\u0307" else "ddot"), text)
    sup = ("^{", "}") if is_latex(text) else ("^(", ")")
    text = _SUPERSCRIPT_RUN.sub(
        lambda m: sup[0] + "".join(_SUPERSCRIPTS[c] for c in m[0]) + sup[1], text
    )
    return text.translate(_UNICODE)


# a Markdown code fence, a whole-line comment (# in Python and Markdown, % in LaTeX and
# MATLAB), a prose label ("Answer:", "**Solution:**"); each bounded: linear on any text
_FENCE_LINE = re.compile(r"^[ \t]*(?:```|~~~)[^\n]*$", re.MULTILINE)
_COMMENT_LINE = re.compile(r"^[ \t]*[#%][^\n]*$", re.MULTILINE)
_PROSE_LABEL = re.compile(r"[ \t*_]*[A-Za-z][A-Za-z ]{0,30}[*_]*:(?!=)[ \t*_]*")
_PROSE = re.compile(r"(?<![A-Za-z])[A-Za-z]{2,}[ \t]+[A-Za-z]{2}")  # two words
_MATH_DELIMITERS = (("$$", "$$"), ("\\[", "\\]"), ("\\(", "\\)"), ("$", "$"))


def answer_only(text: str) -> str | None:
    r"""The answer in a text that also holds other things, as a Markdown answer file does:
    without code fences, whole-line comments (``# px``, ``% px``) and a prose label
    (``Answer:``); of math set in prose (``My answer is $a_1 c_1$.``), the one formula.
    None when nothing is left out, or when the prose holds several formulas (no guess).

    >>> answer_only("```python\na1*cos(theta1)\n```"), answer_only("**Answer:** a1 C1")
    ('a1*cos(theta1)', 'a1 C1')
    >>> answer_only("My answer is $a_1 c_1$."), answer_only("So $x$ is $a_1 c_1$.")
    ('$a_1 c_1$', None)
    """
    bare = _COMMENT_LINE.sub("", _FENCE_LINE.sub("", text)).strip()
    label = _PROSE_LABEL.match(bare)
    if label:
        bare = bare[label.end() :].strip()
    segments = _math_segments(bare)
    if segments:
        gaps = zip([(0, 0), *segments], [*segments, (len(bare), 0)])
        outside = "".join(bare[b:a] for (_, b), (a, _) in gaps)
        if _PROSE.search(outside):
            if len(segments) != 1:
                return None
            a, b = segments[0]
            bare = bare[a:b]
    return bare if bare and bare != text.strip() else None


def _math_segments(text: str) -> list[tuple[int, int]]:
    r"""The (start, end) of each formula in ``$…$``, ``$$…$$``, ``\(…\)`` or ``\[…\]``,
    delimiters included, in order; found by one scan per kind (linear)."""
    found: list[tuple[int, int]] = []
    taken = [False] * (len(text) + 1)
    for open_, close in _MATH_DELIMITERS:
        i = 0
        while (a := text.find(open_, i)) >= 0:
            b = text.find(close, a + len(open_))
            if b < 0:
                break
            end = b + len(close)
            if not any(taken[a:end]):
                found.append((a, end))
                taken[a:end] = [True] * (end - a)
            i = end
    return sorted(found)


def read_answer_file(path: str | Path, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS) -> str:
    """Read an answer file: a regular file only, at most ``limits.max_bytes`` of it."""
    try:
        data = read_limited(path, limits.max_bytes, what=f"the answer file {path}")
    except FileRefused as err:
        raise UnreadableAnswer(err.message) from None
    return read_text(data, limits)


def _cell_text(cell: str) -> str:
    """One cell or expression as parser text (LaTeX translated, subscripts flattened,
    ``[ ]`` and ``{ }`` used as brackets, ``90^o`` as degrees, a closing ``;`` as MATLAB
    ends a statement dropped)."""
    cell = cell.strip().removesuffix(";").rstrip()
    if is_latex(cell):
        return latex_to_text(cell)
    cell = ANGLE_DIFFERENCE.sub(angle_difference_name, cell.replace("**", "^"))  # C[12-4]
    if "=" in cell:
        cell = answer_side(cell)
    cell = _DEGREE_O.sub(r"\1°", flatten_subscripts(cell))
    return cell.translate(_BRACKETS)


_BRACKETS = str.maketrans("[]{}", "()()")


def _parse(cell: str, ctx: NameContext, limits: AnswerLimits, where: str) -> sp.Expr:
    return _parse_text(_cell_text(cell), ctx, limits, where)


def _parse_text(
    text: str,
    ctx: NameContext,
    limits: AnswerLimits,
    where: str,
    *,
    literal: Callable[[str, sp.Rational], sp.Expr] | None = None,
) -> sp.Expr:
    """Parser text (see :func:`_cell_text`) through the whitelist parser."""
    try:
        return parse_expression(
            text, resolve=ctx.resolve, limits=limits.parse, textbook=True, literal=literal
        )
    except ParseError as err:
        raise ParseError(f"{where}: {err.message}") from None


def _template(
    text: str, ctx: NameContext, limits: AnswerLimits
) -> tuple[sp.Expr, tuple[Literal, ...]]:
    """Parser text with each numeric literal as a placeholder, and the literals."""
    found: list[Literal] = []

    def placeholder(text: str, value: sp.Rational) -> sp.Expr:
        found.append(Literal(sp.Dummy(f"n{len(found)}", real=True), text, value))
        return found[-1].symbol

    template = _parse_text(text, ctx, limits, "the answer", literal=placeholder)
    return template, tuple(found)


#: a cell written with decimals (a point or an exponent): only these carry rounding
DECIMAL = re.compile(r"[0-9]\.|\.[0-9]|[0-9][eE]")


def read_cell(
    cell: str, ctx: NameContext, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS, where: str = ""
) -> tuple[sp.Expr, tuple[sp.Expr, tuple[Literal, ...]] | None]:
    """One cell, translated once: its exact value and, when it is written with decimals,
    its literals as written (the cell with placeholders, the literals; None when the
    placeholder reading fails, as the rounding of such a cell is then not judged).

    The whitelist parser reads a decimal cell twice from the one translated text: once
    exact (its checks, such as division by zero, see the values) and once with
    placeholders.

    >>> from dhsym import load_table
    >>> ctx = NameContext.from_table(load_table("planar2r"))
    >>> value, (template, lits) = read_cell(r"0.7071 \\cos\\theta_1", ctx)
    >>> value, [lit.text for lit in lits]
    (7071*cos(theta1)/10000, ['0.7071'])
    >>> read_cell("a1*C1", ctx)
    (a1*cos(theta1), None)
    """
    check_time()  # the answer's deadline (see reading.limits.time_limit)
    text = _cell_text(cell)
    value = _parse_text(text, ctx, limits, where or "the answer")
    if not DECIMAL.search(cell):
        return value, None
    try:
        return value, _template(text, ctx, limits)
    except DHError:
        return value, None


def cell_literals(
    cell: str, ctx: NameContext, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS
) -> tuple[sp.Expr, tuple[Literal, ...]]:
    """The cell with each numeric literal as a placeholder symbol, and the literals.

    >>> from dhsym import load_table
    >>> t, lits = cell_literals("0.7071 C1 + 2", NameContext.from_table(load_table("planar2r")))
    >>> [(lit.text, lit.value) for lit in lits], t.subs({lit.symbol: lit.value for lit in lits})
    ([('0.7071', 7071/10000), ('2', 2)], 7071*cos(theta1)/10000 + 2)
    """
    return _template(_cell_text(cell), ctx, limits)


def expression_cell(text: str | bytes, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS) -> str:
    """The text of a single-entry answer (a 1×1 LaTeX matrix is unwrapped)."""
    text = read_text(text, limits)
    cells = latex_matrix_cells(text) if is_latex(text) else None
    if cells is not None:
        if len(cells) != 1 or len(cells[0]) != 1:
            raise UnreadableAnswer("expected a single expression, got a matrix")
        text = cells[0][0]
    return text


def read_expression(
    text: str, ctx: NameContext, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS
) -> sp.Expr:
    """One entry (``p_x``, an element of a matrix) in plain math or LaTeX."""
    return parse_cell(expression_cell(text, limits), ctx, limits)


def parse_cell(
    cell: str, ctx: NameContext, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS, where: str = ""
) -> sp.Expr:
    """One cell (plain math or LaTeX) as an expression, names resolved by ``ctx``."""
    check_time()  # the answer's deadline (see reading.limits.time_limit)
    return _parse(cell, ctx, limits, where or "the answer")


def _split_top(text: str, seps: str) -> list[str]:
    """Split at separators that are outside parentheses and brackets."""
    out, depth, start = [], 0, 0
    for k, ch in enumerate(text):
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch in seps and depth == 0:
            out.append(text[start:k])
            start = k + 1
    out.append(text[start:])
    return out


def _plain_cells(text: str, widths: frozenset[int] = frozenset({4})) -> list[list[str]]:
    """Cells of a plain-text matrix: ``[[…], […]]``, ``[a, b; c, d]`` or one row per line,
    in Python's ``Matrix(…)`` or ``np.array(…)`` or not, labelled (``T = …``) or not; a
    vector as a tuple ``(a, b, c)``; transposed by a closing ``^T``, ``.T`` or ``'``;
    MATLAB rows of ``widths`` cells split at spaces (``[c1 -s1 0 0; …]``)."""
    if "=" in text:
        text = answer_side(text)
    body, transposed = _untransposed(text.strip())
    if transposed:
        return [list(col) for col in zip(*_plain_cells(body, widths), strict=False)]
    m = _MATRIX_WRAPPER.match(body)
    if m:
        body = m[1].strip()
    if body.startswith("(") and body.endswith(")") and len(_split_top(body[1:-1], ",")) > 1:
        body = f"[{body[1:-1]}]"  # Lynch and Park's screw (0, 0, 1, 0, -a1, 0)
    if body.startswith("[") and body.endswith("]"):
        inner = body[1:-1].strip()
        if inner.startswith("["):
            rows = [r.strip() for r in _split_top(inner, ",") if r.strip()]
            if not all(r.startswith("[") and r.endswith("]") for r in rows):
                raise UnreadableAnswer("expected rows in brackets: [[a, b, …], [c, d, …], …]")
            return [_split_top(r[1:-1], ",") for r in rows]
        body = inner
    lines = [ln for ln in re.split(r"[;\n]|\\\\", body) if ln.strip()]
    out: list[list[str]] = []
    for line in lines:
        line = line.strip().strip("|")
        for seps in ("&", "\t", "|", ","):
            parts = _split_top(line, seps)
            if len(parts) > 1:
                break
        else:
            parts = re.split(r"\s{2,}", line)
            if len(parts) == 1:
                words = line.split()
                if all(re.fullmatch(r"[-+]?[0-9.]+(?:e[-+]?[0-9]+)?", w) for w in words):
                    parts = words
        out.append(parts)
    if any(len(r) == 1 for r in out):  # MATLAB rows: [c1 -s1 0 0; s1 c1 0 0; 0 0 1 0]
        split = [r[0].split() if len(r) == 1 else r for r in out]
        width = {len(w) for w in split}
        if len(width) == 1 and width <= widths and all(_whole_cell(t) for w in split for t in w):
            return split
    return out


# a transpose mark closing a matrix or vector (compared with the text's end, no pattern)
_TRANSPOSE_MARKS = ("^T", "^{T}", "^\\top", "^{\\top}", "^\\intercal", "^{\\intercal}", ".T", "'")


def _untransposed(text: str) -> tuple[str, bool]:
    """``text`` without a closing transpose mark after its bracket, and whether it had one.

    >>> _untransposed("[0 0 1 0 -a1 0]^T"), _untransposed("[a, b]")
    (('[0 0 1 0 -a1 0]', True), ('[a, b]', False))
    """
    body = text.rstrip()
    for mark in _TRANSPOSE_MARKS:
        head = body[: -len(mark)].rstrip()
        if body.endswith(mark) and head.endswith(("]", ")")):
            return head, True
    return text, False


def _whole_cell(word: str) -> bool:
    """True when a space-free word can be a cell by itself (no dangling operator or bracket)."""
    if word[-1] in "+-*/^(" or word[0] in "*/^)":
        return False
    depth = 0
    for ch in word:
        depth += (ch == "(") - (ch == ")")
        if depth < 0:
            return False
    return depth == 0


def read_matrix(
    text: str, ctx: NameContext, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS
) -> sp.ImmutableMatrix:
    r"""A 4×4 homogeneous matrix (or its top three rows) in plain math or LaTeX.

    >>> from dhsym import load_table
    >>> ctx = NameContext.from_table(load_table("planar2r"))
    >>> read_matrix("C1 -S1 0 0", ctx)
    Traceback (most recent call last):
    ...
    dhsym.checking.reading.limits.UnreadableAnswer: expected a 4×4 matrix (or its top 3 rows), got 1 row of 4 cells
    """  # noqa: E501
    cells = matrix_cells(text, limits)
    entries = [
        [_parse(c, ctx, limits, f"entry ({i},{j})") for j, c in enumerate(row, 1)]
        for i, row in enumerate(cells, 1)
    ]
    if len(cells) == 3:
        entries.append([sp.Integer(0)] * 3 + [sp.Integer(1)])
    return sp.ImmutableMatrix(entries)


def matrix_cells(
    text: str | bytes,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    shapes: tuple[tuple[int, int], ...] = ((4, 4), (3, 4)),
    *,
    symmetric: bool = False,
) -> list[list[str]]:
    """The cells of a matrix answer as the student wrote them (3 or 4 rows of 4, or ``shapes``),
    or entry by entry as Spong writes the inertia matrix (``d11 = …; d12 = …``, 1-based; an
    entry may be another's name, ``d21 = d12``; of a ``symmetric`` matrix, ``d21`` may be
    left out).

    >>> matrix_cells(r"$\\begin{pmatrix} c_1 & -s_1 & 0 & 0 \\\\ s_1 & c_1 & 0 & 0 \\\\"
    ...              r" 0&0&1&0 \\end{pmatrix}$")[1]
    ['s_1', 'c_1', '0', '0']
    >>> matrix_cells("d11 = a + b; d12 = c; d22 = e", shapes=((2, 2),), symmetric=True)
    [['a + b', 'c'], ['c', 'e']]
    """
    text = read_text(text, limits)
    cells = latex_matrix_cells(text) if is_latex(text) else None
    if cells is None:
        cells = _named_entries(text, shapes, symmetric)
    if cells is None:
        cells = _named_columns(text, shapes)
    if cells is None:
        cells = _plain_cells(text, frozenset(c for _, c in shapes))
    if len(cells) > limits.max_rows or any(len(r) > limits.max_columns for r in cells):
        raise UnreadableAnswer("the matrix has too many rows or columns")
    shape = (len(cells), len({len(r) for r in cells}) == 1 and len(cells[0]) or 0)
    if shape not in shapes:
        widths = sorted({len(r) for r in cells})
        got = f"{len(cells)} row{'s' * (len(cells) != 1)} of " + "/".join(map(str, widths))
        wanted = (
            "a 4×4 matrix (or its top 3 rows)"
            if shapes == ((4, 4), (3, 4))
            else "a " + " or ".join(f"{r}×{c}" for r, c in shapes) + " matrix"
        )
        raise UnreadableAnswer(f"expected {wanted}, got {got} cell" + ("s" * (widths != [1])))
    return cells


#: LaTeX around statements: environments, display brackets, dollars, alignment marks
_WRAPPERS = re.compile(r"\\(?:begin|end)\{[A-Za-z*]+\}|\\\[|\\\]|\$|&")


def split_statements(text: str) -> list[str]:
    """The statements of an answer: one per line, ``;`` or LaTeX row, and a line of
    ``name = value`` pieces split at its top-level commas.

    >>> split_statements("d11 = f(a, b), d12 = c; d22 = e")
    ['d11 = f(a, b)', 'd12 = c', 'd22 = e']
    """
    if is_latex(text):
        text = _WRAPPERS.sub(" ", text)
        parts = re.split(r"\\\\|\n|;", text)
    else:
        parts = re.split(r"\n|;", text)
    out = []
    for part in (p.strip().strip(",") for p in parts):
        if not part:
            continue
        pieces = _split_top(part, ",")
        if len(pieces) > 1 and all("=" in p for p in pieces):
            out += [p.strip() for p in pieces]
        else:
            out.append(part)
    return out


# the label of a block of the Jacobian at the start of a line (after $, \[ or \begin{align}):
# J_v, Jv, J_{v}, J_\omega, Jω, J_w, optionally (q), then = or &=; each part bounded and
# distinct: linear on any text
_JACOBIAN_BLOCK = re.compile(
    r"^[ \t$]*(?:\\[\[(][ \t]*)?(?:\\begin\{[a-z]+\*?\}[ \t]*)?"
    r"J_?\{?[ \t]*(v|\\omega|omega|ω|w)[ \t]*(?:\}[ \t]*)?(?:\(q\)[ \t]*)?&?=",
    re.MULTILINE,
)


def jacobian_blocks(
    text: str | bytes,
    cols: int,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    *,
    linear: bool = False,
) -> list[list[str]] | None:
    r"""The cells of a Jacobian written as its two blocks, ``J_v = …`` and ``J_\omega = …``
    (each 3×n, in either order, each on a line of its own), stacked as J = [J_v; J_ω];
    None when the answer is not written so.  When J is ``linear`` (ω is zero in every
    configuration: a Cartesian arm), ``J_v`` alone is its 3 rows.

    >>> J = jacobian_blocks("Jw = [0, 0; 0, 0; 1, 1]\nJv = [[-a1 S1, 0], [a1 C1, 0], [0, 0]]", 2)
    >>> [[cell.strip() for cell in row] for row in J]
    [['-a1 S1', '0'], ['a1 C1', '0'], ['0', '0'], ['0', '0'], ['0', '0'], ['1', '1']]
    """
    text = read_text(text, limits)
    found = list(_JACOBIAN_BLOCK.finditer(text))
    if not found:
        return None
    kinds = ["v" if m[1] == "v" else "w" for m in found]
    if linear and kinds == ["v"]:
        return matrix_cells(text, limits, ((3, cols),))
    if sorted(kinds) != ["v", "w"]:
        raise UnreadableAnswer(
            "expected the Jacobian as one matrix, or as its two blocks J_v = … and J_ω = …,"
            f" each once; found {', '.join(m[0].strip(' =$') for m in found)}"
        )
    blocks = {}
    for k, m in enumerate(found):
        end = found[k + 1].start() if k + 1 < len(found) else len(text)
        blocks[kinds[k]] = matrix_cells(text[m.start() : end], limits, ((3, cols),))
    return blocks["v"] + blocks["w"]


# one entry by name, 1-based: d11, d_12, M_{21}, m_{1,2}
_ENTRY_NAME = re.compile(r"\s*[A-Za-z]{1,3}_?\{?([1-9]),?([1-9])\}?\s*")
# a name with one 1-based index: a vector's entry (g1, g_1, \phi_{1}, φ1, τ_1) or a
# column (S1, S_2, \mathcal{S}_3, B_{1})
_ONE_INDEX = re.compile(r"\s*(?:\\mathcal\{)?\\?[A-Za-z\u0370-\u03ff]{1,5}\}?_?\{?([1-9])\}?\s*")


def _named_columns(text: str, shapes: tuple[tuple[int, int], ...]) -> list[list[str]] | None:
    r"""The cells of a matrix written column by column, each a vector by name (Lynch and
    Park's ``S1 = (0, 0, 1, 0, 0, 0)``, ``S2 = …``; 1-based), or None if it is not.

    >>> _named_columns("S1 = (0, 1)\nS2 = [a; b]", ((2, 2),))
    [['0', 'a'], ['1', 'b']]
    """
    if "=" not in text:
        return None
    statements = []
    for line in (p.strip() for p in _split_top(text, "\n;")):
        pieces = _split_top(line, ",")  # S1 = (…), S2 = (…) on one line
        statements += pieces if len(pieces) > 1 and all("=" in p for p in pieces) else [line]
    statements = [p.strip() for p in statements if p.strip()]
    if len(statements) < 2:
        return None
    columns: dict[int, list[str]] = {}
    for statement in statements:
        name, eq, value = statement.partition("=")
        m = _ONE_INDEX.fullmatch(name)
        if not eq or m is None or int(m[1]) in columns or "=" in value:
            return None
        cells = _plain_cells(value.strip().rstrip(","), frozenset({1}) | {c for _, c in shapes})
        if len(cells) == 1 or all(len(row) == 1 for row in cells):
            columns[int(m[1])] = [c.strip() for row in cells for c in row]
        else:
            return None
    n = len(columns)
    if sorted(columns) != list(range(1, n + 1)) or len({len(c) for c in columns.values()}) != 1:
        return None
    rows = len(columns[1])
    if (rows, n) not in shapes and (n, rows) in shapes:
        return [columns[j] for j in range(1, n + 1)]  # each vector a row, as the key lists them
    return [[columns[j][i] for j in range(1, n + 1)] for i in range(rows)]


def _entry_at(name: str) -> tuple[int, int] | None:
    """The 1-based (row, column) a matrix entry's name gives (``d12``, ``M_{21}``), or None."""
    m = _ENTRY_NAME.fullmatch(name)
    return (int(m[1]), int(m[2])) if m else None


def _named_entries(
    text: str, shapes: tuple[tuple[int, int], ...], symmetric: bool
) -> list[list[str]] | None:
    """The cells of a matrix written entry by entry (``d11 = …``), or None if it is not."""
    if "=" not in text:
        return None
    statements = split_statements(text)
    if len(statements) < 2:  # one statement is a labelled answer: T12 = [[…]]
        return None
    vector = any(1 in shape for shape in shapes)  # g1 = …; g2 = … for g(q), τ
    named: dict[tuple[int, int], str] = {}
    for statement in statements:
        *names, value = _split_top(statement, "=")  # d12 = d21 = …
        if not names:
            return None
        for name in names:
            m = _ONE_INDEX.fullmatch(name) if vector else None
            at = (int(m[1]), 1) if m else _entry_at(name)
            if at is None or at in named:
                return None
            named[at] = value.strip()
    if vector and all(j == 1 for _, j in named) and not any(sh[1] == 1 for sh in shapes):
        named = {(1, i): v for (i, _), v in named.items()}  # a row vector's entries
    rows = max((i for i, _ in named), default=0)
    cols = max((j for _, j in named), default=0)
    shape = next((sh for sh in shapes if sh[0] >= rows and sh[1] >= cols), None)
    if not named or shape is None:
        return None
    grid: list[list[str]] = []
    for i in range(1, shape[0] + 1):
        row = []
        for j in range(1, shape[1] + 1):
            cell = named.get((i, j)) or (named.get((j, i)) if symmetric else None)
            if cell is None:
                raise UnreadableAnswer(f"the entry ({i},{j}) is missing")
            ref = _entry_at(cell)  # d21 = d12
            if ref is not None and ref in named:
                cell = named[ref]
            row.append(cell)
        grid.append(row)
    return grid


def read_answer_table(
    text: str | bytes,
    ctx: NameContext,
    convention: Convention | str = Convention.STANDARD,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
) -> DHTable:
    """A student's DH table: the YAML table format, CSV, or a pasted Markdown / plain-text table.

    The text is untrusted and names the key's symbols (``ctx``); a teacher's table *file* is
    read by :func:`dhsym.read_table` instead.

    Columns may come in any order with headers like ``theta``, ``θ``, ``$\\theta_i$``,
    ``alpha_{i-1}``, ``Link``, ``J``; angles in degrees or radians.  Headers with
    ``i-1`` mean the modified convention, otherwise ``convention`` (the key's).
    """
    text = read_text(text, limits)
    try:
        if _YAML_TABLE.search(text):
            return yaml_table(text, ctx, Convention.parse(convention), limits)
        return grid_table(text, ctx, Convention.parse(convention), limits)
    except TableError as err:
        if err.row is None:  # the form itself was not recognised: say what is expected
            raise TableError(f"{err.message}; {TABLE_FORM}", field=err.field) from None
        raise
    except UnreadableAnswer as err:
        if err.message.startswith("expected a table"):
            raise UnreadableAnswer(f"{err.message}; {TABLE_FORM}") from None
        raise
    except ParseError:
        raise
    except DHError as err:
        raise TableError(str(err)) from None
