r"""Pasted DH tables (Markdown, CSV, tab or space separated) and YAML answers, as DHTable.

Headers are matched loosely (``θ``, ``$\Theta$``, ``theta_i``, ``alpha_{i-1}``,
``Link``, ``J``, ``joint angle``); a header with ``i-1`` means the modified
convention.  Angle cells may carry ``°``/``^\circ``; unmarked numbers are degrees
when the header says so, when another cell is marked, or when one is above 2π.
"""

from __future__ import annotations

import csv
import math
import re
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import sympy as sp

from dhsym.errors import DHError, ParseError, TableError
from dhsym.model.parsing import normalize_name, parse_expression
from dhsym.model.table import AngleUnit, Convention, DHRow, DHTable, JointType, to_radians
from dhsym.model.tablefile import table_from_data
from dhsym.model.yamlsafe import YAMLInputError, YAMLLimits, load_yaml

from .answer_names import NameContext
from .latex_input import flatten_subscripts, is_latex, latex_matrix_cells, latex_to_text
from .limits import AnswerLimits, UnreadableAnswer, echoed

__all__ = ["TABLE_FORM", "grid_table", "yaml_table"]

_COLUMNS = {
    "theta": {"theta", "th", "jointangle", "angle", "θ"},
    "d": {"d", "jointdistance", "linkoffset", "jointoffset", "distance"},
    "a": {"a", "r", "linklength", "length"},
    "alpha": {"alpha", "twist", "linktwist"},
    "label": {"", "link", "joint", "j", "l", "n", "no", "#", "frame", "axis", "linkjoint"},
    "type": {"type", "jointtype", "kind", "rp", "r/p", "sigma"},
    "offset": {"offset"},
    "q": {"q", "variable", "var", "jointvariable"},
}
_LOOKUP = {alias: col for col, aliases in _COLUMNS.items() for alias in aliases}
# Every pattern here runs on student text: none may backtrack more than linearly (no two
# neighbouring parts that can match the same characters); tests feed each 1 MB worst cases.
_SEPARATOR_CELL = re.compile(r":?-{2,}:?")
_DEGREE_MARK = re.compile(
    r"\^\s*(?:\{\s*)?\\circ(?:\s*\})?|[°º˚]|\\(?:text)?degree|\bdeg(rees?)?\b"
    r"|(?<=[0-9.])\s*\^\s*(?:o|\{\s*o\s*\})(?![A-Za-z0-9_])",  # 90^o
    re.IGNORECASE,
)
_RAD = re.compile(r"rad", re.IGNORECASE)
_BRACKETED = re.compile(r"[(\[]([^()\[\]]*)[)\]]")
_UNIT = re.compile(r"deg|rad|°|m|mm|cm|in", re.IGNORECASE)
_COMMAND = re.compile(r"\\(?:var)?([A-Za-z]+)")
_MINUS_ONE = re.compile(r"i\s*-\s*1|im1")
_INDEX_I = re.compile(r"_\{?\s*i\s*\}?$")
_KEY_JUNK = re.compile(r"[_{}\s()\[\]$.^]")
_INDEX_SUFFIX = re.compile(r"(i-1|im1|i\+1|i)$")
_TOKENS = re.compile(r"\$[^$]*\$|\S+")
_CONVENTION_LINE = re.compile(r"^\s*convention\s*[:=]\s*(\S+)\s*$", re.IGNORECASE)
_WIDE_GAP = re.compile(r"\s{2,}")
_TWO_PI = 2 * math.pi + 1e-6
_YAML = YAMLLimits(max_bytes=200_000, max_nodes=20_000, max_chars=200_000, max_depth=16)


def _is_separator(line: str) -> bool:
    """A Markdown rule line like ``|---|:--:|``, read without a regular expression over the line."""
    body = line.strip()
    if body.startswith("|"):
        body = body[1:]
    if body.endswith("|"):
        body = body[:-1]
    cells = body.split("|")
    return bool(cells) and all(_SEPARATOR_CELL.fullmatch(c.strip()) for c in cells)


def _column(header: str) -> tuple[str, str | None, bool | None]:
    """(column name, unit, modified?) of one header cell."""
    t = header.strip().strip("$").strip()
    unit = "deg" if _DEGREE_MARK.search(t) else ("rad" if _RAD.search(t) else None)
    t = _BRACKETED.sub(lambda m: "" if _UNIT.search(m[1]) else m[0], t)
    t = _COMMAND.sub(r"\1", t)
    t = normalize_name(t)
    modified = True if _MINUS_ONE.search(t) else None
    if modified is None and _INDEX_I.search(t.rstrip()):
        modified = False
    key = _KEY_JUNK.sub("", t).lower()
    key = _INDEX_SUFFIX.sub("", key) if key not in ("i",) else ""
    if key not in _LOOKUP:
        shown = header.strip()[:40]
        raise TableError(
            f"unknown column {shown!r}: expected θ (theta), d, a, α (alpha), "
            "and optionally Link, type, offset"
        )
    return _LOOKUP[key], unit, modified


def _split(line: str, mode: str) -> list[str]:
    if mode == "|":
        return line.strip().strip("|").split("|")
    if mode == "\t":
        return line.rstrip("\r\n ").split("\t")
    if mode in ",;":
        return next(csv.reader([line], delimiter=mode))
    return _TOKENS.findall(line)


def _mode(header: str) -> str:
    for mode in ("|", "\t", ",", ";"):
        if mode in header:
            return mode
    return " "


def _cell(
    text: str, ctx: NameContext, limits: AnswerLimits, row: int, field: str
) -> tuple[sp.Expr, bool]:
    """(expression, degree-marked?) of one cell."""
    raw = text.strip()
    if not raw:
        raise TableError("empty cell", row=row, field=field)
    raw = _unmarked(raw)
    marked = bool(_DEGREE_MARK.search(raw))
    if marked:
        raw = _DEGREE_MARK.sub("", raw)
    src = latex_to_text(raw) if is_latex(raw) else flatten_subscripts(raw.replace("**", "^"))
    try:
        expr = parse_expression(src, resolve=ctx.table_resolve, limits=limits.parse, textbook=True)
    except ParseError as err:
        raise TableError(err.message, row=row, field=field) from None
    return expr, marked


def _unmarked(cell: str) -> str:
    r"""A cell without the star Spong's tables put on the joint variable (``θ1*``,
    ``\theta_1^*``, ``\theta_1^{*}``): a mark, not part of the value.

    >>> _unmarked("θ1*"), _unmarked(r"$\theta_1^{*}$"), _unmarked("d3 ^*"), _unmarked("*")
    ('θ1', '$\\theta_1$', 'd3', '*')
    """
    if len(cell) > 2 and cell[0] == cell[-1] == "$":
        return f"${_unmarked(cell[1:-1].strip())}$"
    for mark in ("^{*}", "^*", "*"):
        if cell.endswith(mark) and cell[: -len(mark)].strip():
            return cell[: -len(mark)].rstrip()
    return cell


def _constant(expr: sp.Expr) -> float:
    const = sum((t for t in sp.Add.make_args(expr) if not t.free_symbols), sp.Integer(0))
    return abs(float(const)) if not const.has(sp.pi) else 0.0


def _to_rad(expr: sp.Expr, degrees: bool, row: int, field: str) -> sp.Expr:
    # a cell with pi is in radians whatever the table says; a joint variable alone is an
    # angle in any unit (``to_radians`` gives it back as it is)
    if not degrees or expr.is_Symbol or expr.has(sp.pi):
        return expr
    try:
        return to_radians(expr, "deg")
    except DHError as err:
        raise TableError(err.message, row=row, field=field) from None


def _joint(cells: Mapping[str, sp.Expr], typed: str | None, row: int) -> JointType:
    if typed is not None:
        try:
            return JointType.parse(typed.strip().strip("$"))
        except TableError as err:
            raise err.located(row=row) from None
    if cells["theta"].free_symbols:
        return JointType.REVOLUTE
    if cells["d"].free_symbols:
        return JointType.PRISMATIC
    return JointType.FIXED


def grid_table(
    text: str, ctx: NameContext, convention: Convention, limits: AnswerLimits
) -> DHTable:
    r"""Read a Markdown, CSV, tab- or space-separated table with a header row, or a LaTeX
    ``tabular`` (or ``array``) with one.

    >>> from dhsym import load_table
    >>> from dhsym.checking.reading.limits import DEFAULT_ANSWER_LIMITS
    >>> t = grid_table(r"\begin{tabular}{c|c|c|c} $a_i$ & $\alpha_i$ & $d_i$ & $\theta_i$"
    ...                r" \\ \hline $a_1$ & 0 & 0 & $\theta_1^*$ \end{tabular}",
    ...                NameContext.from_table(load_table("planar2r")), Convention.STANDARD,
    ...                DEFAULT_ANSWER_LIMITS)
    >>> t.rows[0].a, t.rows[0].theta
    (a1, theta1)
    """
    latex = latex_matrix_cells(text) if is_latex(text) else None
    if latex is not None and len(latex) >= 2:
        return _grid(latex[0], latex[1:], ctx, convention, limits)
    lines = []
    for line in text.splitlines():
        stripped = line.strip()
        if not stripped or stripped.startswith("```") or stripped in ("$$",) or _is_separator(line):
            continue
        m = _CONVENTION_LINE.match(line)
        if m:
            convention = Convention.parse(m[1])
            continue
        lines.append(line)
    if len(lines) < 2:
        raise UnreadableAnswer("expected a table: a header row (θ, d, a, α) and one row per joint")
    mode = _mode(lines[0])
    headers = _split(lines[0], mode)
    rows: list[list[str]] = []
    for line in lines[1:]:
        cells = _split(line, mode)
        if len(cells) != len(headers) and mode == " ":
            cells = _WIDE_GAP.split(line.strip())
        rows.append(cells)
    return _grid(headers, rows, ctx, convention, limits)


def _grid(
    headers: list[str],
    rows: list[list[str]],
    ctx: NameContext,
    convention: Convention,
    limits: AnswerLimits,
) -> DHTable:
    """The table of a header row and its rows of cells, however they were written."""
    if len(rows) > limits.max_rows:
        raise UnreadableAnswer(f"the table has {len(rows)} rows; at most {limits.max_rows}")
    if len(headers) > limits.max_columns:
        raise UnreadableAnswer(
            f"the table has {len(headers)} columns; at most {limits.max_columns}"
        )
    columns = [_column(h) for h in headers]
    names = [c[0] for c in columns]
    for need in ("theta", "d", "a", "alpha"):
        if need not in names:
            raise TableError(f"missing column {need!r}: a DH table has θ, d, a and α")
    dup = {n for n in names if names.count(n) > 1 and n != "label"}
    if dup:
        raise TableError(f"column {sorted(dup)[0]!r} appears twice")
    hints = {c[2] for c in columns if c[0] in ("a", "alpha") and c[2] is not None}
    if hints == {True}:
        convention = Convention.MODIFIED
    elif hints == {False}:
        convention = Convention.STANDARD
    units = {c[0]: c[1] for c in columns}
    raw_rows = []
    for r, cells in enumerate(rows, start=1):
        if len(cells) != len(headers):
            raise TableError(f"{len(cells)} cells, but the header has {len(headers)}", row=r)
        raw_rows.append(dict(zip(names, cells)))
    return _assemble(raw_rows, units, convention, ctx, limits)


def _assemble(
    raw_rows: list[dict[str, str]],
    units: Mapping[str, str | None],
    convention: Convention,
    ctx: NameContext,
    limits: AnswerLimits,
) -> DHTable:
    """The table from its cells as text, one mapping per row (column name to cell).

    Angles are degrees when a column's unit says so, when a cell is marked (``°``,
    ``deg``) or when a constant angle is above 2π; ``type`` is inferred from which
    of θ and d holds the variable when no cell gives it.
    """
    for r, raw in enumerate(raw_rows, start=1):
        for need in ("theta", "d", "a", "alpha"):
            if need not in raw:
                raise TableError(
                    f"missing column {need!r}: a DH table has θ, d, a and α", row=r, field=need
                )
    parsed: list[dict[str, tuple[sp.Expr, bool]]] = []
    for r, raw in enumerate(raw_rows, start=1):
        parsed.append(
            {
                k: _cell(raw[k], ctx, limits, r, k)
                for k in ("theta", "d", "a", "alpha", "offset")
                if k in raw
            }
        )
    degrees = {}
    for field in ("theta", "alpha"):
        marked = any(p[field][1] for p in parsed)
        big = any(_constant(p[field][0]) > _TWO_PI for p in parsed)
        degrees[field] = units.get(field) == "deg" or (
            units.get(field) != "rad" and (marked or big)
        )
    shared = degrees["theta"] or degrees["alpha"]
    rows = []
    for r, (raw, p) in enumerate(zip(raw_rows, parsed), start=1):
        vals = {}
        for field in ("theta", "d", "a", "alpha"):
            expr, marked = p[field]
            if field in ("theta", "alpha"):
                deg = marked or degrees[field] or (shared and units.get(field) != "rad")
                expr = _to_rad(expr, deg, r, field)
            vals[field] = expr
        joint = _joint(vals, raw.get("type"), r)
        if "offset" in p:
            own = "d" if joint is JointType.PRISMATIC else "theta"
            off = p["offset"][0]
            if own == "theta":
                off = _to_rad(off, p["offset"][1] or degrees["theta"], r, "offset")
            vals[own] = vals[own] + off
        kw = {}
        if "q" in raw and raw["q"].strip():
            kw["variable"] = _cell(raw["q"], ctx, limits, r, "q")[0]
        try:
            rows.append(DHRow(joint, vals["theta"], vals["d"], vals["a"], vals["alpha"], **kw))
        except DHError as err:
            raise TableError(err.message, row=r, field=err.field) from None
    try:
        return DHTable(
            tuple(rows),
            convention,
            name="answer",
            angles=AngleUnit.DEG if shared else AngleUnit.RAD,
        )
    except DHError as err:
        raise TableError(err.message, row=err.row, field=err.field) from None


def _renamed(table: DHTable, ctx: NameContext) -> DHTable:
    """The table with the student's spellings of symbols (``a_2``, ``q1``) as the key's."""
    syms = set(table.variables) | set(table.constants)
    mapping = {s: ctx.symbol(s.name) for s in syms}
    mapping = {s: k for s, k in mapping.items() if k is not None and k != s}
    if not mapping:
        return table
    rows = []
    for row in table.rows:
        new = {k: v.xreplace(mapping) for k, v in row.params().items()}
        var = mapping.get(row.variable, row.variable) if row.variable is not None else None
        rows.append(replace(row, **new, variable=var))
    values = tuple((mapping.get(k, k), v) for k, v in table.values)
    return replace(table, rows=tuple(rows), values=values)


_ROWS_KEYS = frozenset({"joints", "convention", "angles", "name", "notes", "source"})
TABLE_FORM = (
    "write one row per joint with the columns θ, d, a and α, for example the YAML line "
    "'- {theta: theta1, d: d1, a: 0, alpha: 90}' or the Markdown table "
    "'| θ | d | a | α |' with a row '| θ1 | d1 | 0 | 90° |'"
)


def _yaml_cell(value: object, row: int, field: str) -> str:
    """A YAML scalar as the text of a cell (``90`` and ``"90°"`` alike); lists are refused."""
    if value is None:
        return ""
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise TableError(
            f"expected a number or an expression, got {echoed(value)}", row=row, field=field
        )
    return str(value)


def yaml_table(
    text: str, ctx: NameContext, convention: Convention, limits: AnswerLimits
) -> DHTable:
    """Read a YAML table: a list of rows, or a mapping with a ``joints`` list.

    Rows are read like the rows of a pasted table (:func:`grid_table`): ``type`` may be
    left out (inferred from which of θ and d holds the variable), angles are degrees
    when a value says so (``90``, ``90°``, ``90 deg``) or the file says ``angles: deg``.
    A file with instructors' keys (``values``, ``base``, ``tool``) is read as a table
    file (:mod:`dhsym.model.tablefile`). No convention means the key's.
    """
    try:
        data = load_yaml(text, limits=_YAML)
    except YAMLInputError as err:
        if "too large" in err.message or "nested" in err.message:
            raise UnreadableAnswer(f"the YAML answer: {err.message}") from None
        raise TableError(err.message) from None
    if isinstance(data, list):
        top: Mapping[object, Any] = {"joints": data}
    elif isinstance(data, Mapping) and isinstance(data.get("joints"), list):
        top = data
    else:
        raise TableError("expected a list of rows, or a mapping with a 'joints' list")
    rows = top["joints"]
    if len(rows) > limits.max_rows:
        raise UnreadableAnswer(f"the table has more than {limits.max_rows} rows")
    if not rows:
        raise TableError("the table has no rows")
    if not {str(k) for k in top} <= _ROWS_KEYS:
        full = dict(top)
        full.setdefault("convention", convention.value)
        full.pop("name", None), full.pop("notes", None), full.pop("source", None)
        return _renamed(table_from_data(full), ctx)
    if "convention" in top:
        convention = Convention.parse(str(top["convention"]))
    unit = AngleUnit.parse(str(top["angles"])).value if "angles" in top else None
    units: dict[str, str | None] = {"theta": unit, "alpha": unit}
    raw_rows = []
    hints = set()
    for r, entry in enumerate(rows, start=1):
        if not isinstance(entry, Mapping):
            raise TableError("each row must be a mapping like {theta: theta1, d: d1}", row=r)
        raw = {}
        for key, value in entry.items():
            name, col_unit, modified = _column(str(key))
            if col_unit is not None and unit is None:
                units[name] = col_unit
            if name in ("a", "alpha") and modified is not None:
                hints.add(modified)
            if name != "label":
                raw[name] = _yaml_cell(value, r, name)
        raw_rows.append(raw)
    if hints == {True}:
        convention = Convention.MODIFIED
    elif hints == {False}:
        convention = Convention.STANDARD
    return _renamed(_assemble(raw_rows, units, convention, ctx, limits), ctx)
