"""Reading and writing DH tables as YAML files.

The format (every key but ``joints`` optional)::

    name: Planar 2R
    source: IRob2305 Lecture 5, Example 2   # where the numbers come from
    convention: standard                 # or modified (Craig): rows hold alpha_{i-1}, a_{i-1}
    angles: deg                          # or rad
    joints:
      - {type: R, theta: theta1, d: 0, a: a1, alpha: 0}
      - {type: R, theta: theta2, d: 0, a: a2, alpha: 0, limits: [-150, 150]}
      - {type: P, theta: 0, d: a5 + d3, a: 0, alpha: 180, q: d3}
    values: {a1: 1.0, a2: 0.8}           # numbers for symbolic lengths
    snap_angles: true                    # 1.5708 -> pi/2 (false: keep; a number: tolerance)
    base: [{Tz: 0.5}]                    # constant transforms before joint 1 ...
    tool: [{Tz: t}]                      # ... and after the last frame
    gravity: [0, 0, -9.81]               # in the base frame (default), e.g. [0, -g, 0]

Rows may carry inertial parameters with roboticstoolbox's ``Link`` names
(:mod:`dhsym.model.inertia`): ``m``, ``r`` (centre of mass in link frame i), ``I``
(about the centre of mass: ``[Ixx, Iyy, Izz, Ixy, Iyz, Ixz]`` or 3×3), ``Jm``, ``G``,
``B``, ``Tc`` (one value or ``[Tc+, Tc-]``), e.g.
``{type: R, theta: q1, d: 0, a: l1, alpha: 0, m: m1, r: [lc1 - l1, 0, 0], I: [0, 0, I1]}``.

Entries are numbers or expressions read by the whitelist parser
(:mod:`dhsym.model.parsing`): never ``eval`` or ``sympify``. Every error names the
file, the row and the field.

Examples
--------
>>> t = read_table_text('''
... name: Planar 2R
... angles: deg
... joints:
...   - {type: R, theta: theta1, d: 0, a: a1, alpha: 0}
...   - {type: R, theta: theta2, d: 0, a: a2, alpha: 0}
... values: {a1: 1.0, a2: 0.8}
... ''')
>>> t.name, t.n, t.value_map
('Planar 2R', 2, {a1: 1, a2: 4/5})
>>> read_table_text("joints: [{type: R, theta: q1, d: 0, a: 0, alfa: 0}]", file="arm.yaml")
Traceback (most recent call last):
...
dhsym.errors.TableError: arm.yaml: row 1, field alfa: unknown column 'alfa': expected type, ...
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import sympy as sp
import yaml
from sympy.printing.str import StrPrinter

from dhsym.errors import DHError, TableError

from .angles import AngleSnap, snap_entry
from .entries import exact_decimal as _exact_decimal
from .inertia import INERTIA_KEYS, LinkInertia
from .parsing import DEFAULT_LIMITS
from .table import (
    AngleUnit,
    Convention,
    DHRow,
    DHTable,
    Elementary,
    Expr,
    JointType,
    as_expr,
    to_radians,
)
from .yamlsafe import FileRefused, YAMLInputError, YAMLLimits, load_yaml, read_limited

__all__ = [
    "MAX_FILE_BYTES",
    "dump_table",
    "read_steps",
    "read_table",
    "read_table_text",
    "read_entry",
    "read_text_file",
    "read_values",
    "read_yaml_text",
    "table_from_data",
]

MAX_FILE_BYTES = 1_000_000
_ROW_KEYS = (
    "type",
    "theta",
    "d",
    "a",
    "alpha",
    "q",
    "limits",
    "qlim",
    "offset",
    "name",
    *INERTIA_KEYS,
)
_TOP_KEYS = (
    "name",
    "source",
    "convention",
    "angles",
    "joints",
    "values",
    "base",
    "tool",
    "notes",
    "snap_angles",
    "gravity",
    "physical",
)
_ALIASES = {"θ": "theta", "α": "alpha", "joint": "type", "variable": "q", "th": "theta"}
_CASED = {k.lower(): k for k in INERTIA_KEYS if k != k.lower()}  # I, Jm, G, B, Tc keep case


def read_table(path: str | Path) -> DHTable:
    """Read a table file (YAML). Errors name the file, row and field.

    Only a regular file is read (``/dev/zero`` or a FIFO is refused at once), and
    at most :data:`MAX_FILE_BYTES` of it.
    """
    return read_table_text(read_text_file(path, "table file"), file=str(Path(path)))


def read_text_file(path: str | os.PathLike[str], what: str) -> str:
    """The UTF-8 text of a regular file of at most :data:`MAX_FILE_BYTES` (a table file, a
    PoE file); anything else is a :class:`~dhsym.errors.TableError` naming the file."""
    p = Path(path)
    try:
        data = read_limited(p, MAX_FILE_BYTES, what=what)
    except FileRefused as err:
        raise TableError(err.message, file=str(p)) from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise TableError("not a UTF-8 text file", file=str(p)) from None


def read_table_text(text: str, *, file: str | None = None) -> DHTable:
    """Read a table from YAML text (through the bounded loader :func:`.yamlsafe.load_yaml`)."""
    if len(text) > MAX_FILE_BYTES:
        raise TableError("table text is too large", file=file)
    return table_from_data(read_yaml_text(text, file=file), file=file)


def read_yaml_text(text: str, *, file: str | None = None) -> object:
    """The data of a robot file's YAML text (a table or a PoE), read by the bounded loader
    (:func:`.yamlsafe.load_yaml`, at most :data:`MAX_FILE_BYTES`); what it refuses is a
    :class:`~dhsym.errors.TableError` naming the ``file``.

    >>> read_yaml_text("joints: [{type: R}]")
    {'joints': [{'type': 'R'}]}
    """
    try:
        return load_yaml(text, limits=YAMLLimits(max_bytes=MAX_FILE_BYTES))
    except YAMLInputError as err:
        raise TableError(err.message, file=file) from None


_LONG_NUMBER = "a number with thousands of digits: numbers have at most 40 digits"


def _canon(key: object) -> str:
    k = str(key).strip()
    return _ALIASES.get(k, _ALIASES.get(k.lower(), _CASED.get(k.lower(), k.lower())))


def table_from_data(data: object, *, file: str | None = None) -> DHTable:
    """Build a table from parsed YAML/JSON data (dicts, lists, numbers, strings)."""
    try:
        return _from_data(data, file)
    except DHError as err:
        raise err.located(file=file) from None


def _from_data(data: object, file: str | None) -> DHTable:
    if not isinstance(data, Mapping):
        raise TableError("expected a mapping with a 'joints' list at the top level")
    top = {_canon(k): v for k, v in data.items()}
    if "joints" not in top:  # not a table: its content is never echoed (it may be any file)
        raise TableError(
            "missing 'joints': the list of rows (this is not a DH table file)", field="joints"
        )
    unknown = sorted(set(top) - set(_TOP_KEYS))
    if unknown:
        raise TableError(
            f"unknown key {unknown[0]!r}: expected {', '.join(_TOP_KEYS)}", field=unknown[0]
        )
    convention = Convention.parse(top.get("convention", "standard"))
    unit = AngleUnit.parse(top.get("angles", "rad"))
    joints = top.get("joints")
    if joints is None:
        raise TableError("missing 'joints': the list of rows", field="joints")
    if not isinstance(joints, list):
        raise TableError("'joints' must be a list of rows", field="joints")
    if not joints:
        raise TableError("the table has no joints: give at least one row", field="joints")
    physical = top.get("physical", True)
    if not isinstance(physical, bool):
        raise TableError("physical must be true or false", field="physical")
    rows = [_row(entry, i, physical) for i, entry in enumerate(joints, start=1)]
    checked = read_values(top.get("values") or None)
    base = _elementaries(top.get("base"), "base", unit)
    tool = _elementaries(top.get("tool"), "tool", unit)
    _check_variables(rows, base, tool)
    return DHTable.from_rows(
        rows,
        convention=convention,
        angles=unit,
        values=checked,
        name=str(top.get("name") or ""),
        source=str(top.get("source") or ""),
        notes=str(top.get("notes") or ""),
        base=base,
        tool=tool,
        snap_angles=AngleSnap.parse(top.get("snap_angles", True)),
        **_gravity(top),
        **({} if physical else {"physical": False}),
    )


def read_values(values: object) -> dict[str, sp.Expr]:
    """A file's ``values:`` (symbol name → number) read exactly, by name (``None``: none);
    a non-number names its field (``values.a2``).

    >>> read_values({"a2": 0.4318, "d3": "pi/20"})
    {'a2': 2159/5000, 'd3': pi/20}
    >>> read_values({"a2": "l2"})
    Traceback (most recent call last):
    ...
    dhsym.errors.TableError: field values.a2: value of a2 must be a number, got 'l2'
    """
    if values is None:
        return {}
    if not isinstance(values, Mapping):
        raise TableError("'values' must map symbol names to numbers", field="values")
    out = {}
    for k, v in values.items():
        expr = as_expr(v, field=f"values.{k}")
        if expr.free_symbols:
            raise TableError(f"value of {k} must be a number, got {v!r}", field=f"values.{k}")
        out[str(k)] = expr
    return out


def _check_variables(
    rows: list[DHRow], base: tuple[Elementary, ...], tool: tuple[Elementary, ...]
) -> None:
    """Joint variables move only their own joint: a fixed row (type F) and the constant
    ``base``/``tool`` transforms contain none of them."""
    variables = {r.variable for r in rows if r.variable is not None}
    for i, r in enumerate(rows, start=1):
        if r.variable is None:
            used = set().union(*(v.free_symbols for v in (r.theta, r.d, r.a, r.alpha)))
            if used & variables:
                name = sorted(str(v) for v in used & variables)[0]
                raise TableError(
                    f"a fixed row (type F) has no joint variable, but uses {name}, the "
                    "variable of another joint",
                    row=i,
                )
    for where, steps in (("base", base), ("tool", tool)):
        for k, step in enumerate(steps, start=1):
            used = step.value.free_symbols & variables
            if used:
                raise TableError(
                    f"step {k} uses the joint variable {sorted(map(str, used))[0]}: "
                    f"'{where}' is a constant transform",
                    field=where,
                )


def _gravity(top: Mapping[str, Any]) -> dict[str, object]:
    if "gravity" not in top:
        return {}
    g = top["gravity"]
    if not (isinstance(g, list) and len(g) == 3):
        raise TableError("gravity must be a list of 3 values [gx, gy, gz]", field="gravity")
    return {"gravity": tuple(as_expr(v, field="gravity") for v in g)}


def read_entry(
    entry: object,
    i: int,
    canon: Callable[[object], str],
    keys: tuple[str, ...],
    *,
    like: str,
    what: str = "row",
    key: str = "column",
) -> dict[str, object]:
    """Row ``i`` of a file (a ``what`` written ``like``) by its ``canon`` key names, each one
    of ``keys``; a row that is no mapping, or a ``key`` it does not know, names the row.

    >>> read_entry({"Theta": 0}, 1, str.lower, ("theta",), like="{theta: ...}")
    {'theta': 0}
    >>> read_entry({"x": 0}, 2, str, ("theta", "d"), like="{theta: ...}")
    Traceback (most recent call last):
    ...
    dhsym.errors.TableError: row 2, field x: unknown column 'x': expected theta, d
    """
    if not isinstance(entry, Mapping):
        raise TableError(f"each {what} must be a mapping like {like}", row=i)
    row = {canon(k): v for k, v in entry.items()}
    for name in row:
        if name not in keys:
            raise TableError(
                f"unknown {key} {name!r}: expected {', '.join(keys)}", row=i, field=name
            )
    return row


def _row(entry: object, i: int, physical: bool = True) -> DHRow:
    row = read_entry(entry, i, _canon, _ROW_KEYS, like="{type: R, theta: ..., ...}")
    for key in ("theta", "d", "a", "alpha"):
        if key not in row:
            raise TableError(f"missing column {key!r}", row=i, field=key)
    kw: dict[str, object] = {}
    params = {k: as_expr(row[k], field=k, row=i) for k in ("theta", "d", "a", "alpha")}
    if "type" not in row:  # inferred from which of theta and d holds the variable
        row["type"] = (
            "R" if params["theta"].free_symbols else "P" if params["d"].free_symbols else "F"
        )
    try:
        return _build_row(row, params, kw, i, physical)
    except DHError as err:
        raise err.located(row=i) from None


def _build_row(
    row: dict[str, Any],
    params: dict[str, sp.Expr],
    kw: dict[str, Any],
    i: int,
    physical: bool = True,
) -> DHRow:
    from .parsing import symbol

    joint = row["type"]
    if "q" in row:
        if str(joint).strip().upper().startswith("F"):
            raise TableError("a fixed row (type F) has no joint variable: remove q", field="q")
        if not isinstance(row["q"], str):
            raise TableError("q must name the joint variable, e.g. q: d3", row=i, field="q")
        kw["variable"] = symbol(row["q"].strip())
    if "offset" in row:
        own = "d" if str(joint).strip().upper().startswith("P") else "theta"
        params[own] = params[own] + as_expr(row["offset"], field="offset", row=i)
    if "limits" in row and "qlim" in row:
        raise TableError("give limits or qlim (its roboticstoolbox name), not both", row=i)
    for key in ("limits", "qlim"):  # qlim: roboticstoolbox's name for the same limits
        if key not in row:
            continue
        lim = row[key]
        if not (isinstance(lim, list) and len(lim) == 2):
            raise TableError(f"{key} must be a list [low, high]", row=i, field=key)
        lo, hi = (as_expr(v, field=key, row=i) for v in lim)
        if lo.free_symbols or hi.free_symbols or not (lo.is_real and hi.is_real):
            raise TableError(
                f"{key} must be two numbers [low, high] (in the table's angle unit for θ)",
                row=i,
                field=key,
            )
        if (lo - hi).is_positive:
            raise TableError(f"{key} [{lo}, {hi}]: low is above high", row=i, field=key)
        kw["limits"] = (lo, hi)
    if "name" in row:
        kw["label"] = str(row["name"])
    given = {k: row[k] for k in INERTIA_KEYS if k in row}
    if given:
        kw["inertia"] = LinkInertia.from_data(given, row=i, physical=physical)
    return DHRow(joint, params["theta"], params["d"], params["a"], params["alpha"], **kw)


def _elementaries(data: object, where: str, unit: AngleUnit) -> tuple[Elementary, ...]:
    if data is None:
        return ()
    if not isinstance(data, list):
        raise TableError(f"'{where}' must be a list like [{{Tz: 0.5}}, {{Rx: 90}}]", field=where)
    out = []
    for k, step in enumerate(data, start=1):
        if not (isinstance(step, Mapping) and len(step) == 1):
            raise TableError(f"step {k} must be one of {{Rx|Ry|Rz|Tx|Ty|Tz: value}}", field=where)
        ((name, value),) = step.items()
        name = str(name)
        if len(name) != 2 or name[0] not in "RT" or name[1].lower() not in "xyz":
            raise TableError(
                f"step {k}: unknown transform {name!r}: expected Rx, Ry, Rz, Tx, Ty or Tz",
                field=where,
            )
        expr = as_expr(value, field=f"{where}[{k}]")
        if name[0] == "R":
            expr = to_radians(expr, unit)
        out.append(Elementary(name[0], name[1].lower(), expr))
    return tuple(out)


def read_steps(data: object, where: str, unit: AngleUnit | str) -> tuple[Elementary, ...]:
    """A list of constant steps like a table's ``base`` (``[{Tz: 0.5}, {Rx: 90}]``), angles
    in ``unit``; errors name ``where`` as the field (the PoE files' ``M`` reads so too).

    >>> read_steps([{"Tz": 0.5}, {"Rx": 90}], "base", "deg")
    (Tz(1/2), Rx(pi/2))
    """
    return _elementaries(data, where, AngleUnit.parse(unit))


class _Reader(StrPrinter):
    """sympy's text, in the words the table reader knows (``atan(x)`` as ``atan2(x, 1)``)."""

    def _print_atan(self, expr: sp.Expr) -> str:
        return f"atan2({self._print(expr.args[0])}, 1)"

    def _print_Rational(self, expr: sp.Rational) -> str:
        # a measured decimal in a sum (a URDF's offset, ``theta2 + 0.0145832199750``) as the
        # decimal it is; fractions of small denominators (``q1 + 1/2``) stay fractions
        dec = _exact_decimal(expr) if expr.q > 10**6 else None
        return dec if dec is not None else str(super()._print_Rational(expr))


def _text(value: sp.Expr) -> str:
    """Text of an entry that :func:`read_table_text` reads back to the same value.

    >>> _text(sp.atan(sp.Rational(1, 3)) + sp.Symbol("q1"))
    'q1 + atan2(1/3, 1)'
    """
    return str(_Reader().doprint(value))


def _plain(value: sp.Expr) -> object:
    """A YAML scalar that reads back as ``value``: 0.4318 stays 0.4318, not 2159/5000.

    A number with more digits than the reader takes (the exact forms of measured
    geometry) is written to 17 significant digits instead.
    """
    limit = DEFAULT_LIMITS.max_digits
    if any(len(str(abs(n))) > limit for r in value.atoms(sp.Rational) for n in (r.p, r.q)):
        value = value.evalf(17)
        return float(value) if value.is_Number else _text(value)
    if value.is_Integer:
        return int(value)
    dec = _exact_decimal(value)
    if dec is None:
        return _text(value)
    as_float = float(dec)
    return as_float if sp.Rational(repr(as_float)) == value else dec


def _would_snap(table: DHTable) -> bool:
    entries: list[tuple[Expr, ...]] = [(r.theta, r.alpha) for r in table.rows]
    entries += [(e.value,) for e in table.base + table.tool if e.kind == "R"]
    return any(snap_entry(v, AngleSnap(), "", None)[1] for vs in entries for v in vs)


def dump_table(table: DHTable, *, angles: str | None = None) -> str:
    """Write a table as YAML text that :func:`read_table_text` reads back to the same table.

    >>> row = "{type: R, theta: q1 + 90, d: 0, a: 1, alpha: -90}"
    >>> t = read_table_text(f"angles: deg\\njoints: [{row}]")
    >>> print(dump_table(t), end="")
    convention: standard
    angles: deg
    joints:
    - {type: R, theta: q1 + 90, d: 0, a: 1, alpha: -90}
    >>> read_table_text(dump_table(t)) == t
    True

    An angle that is no rational number of degrees (a measured limit of -2.8973 rad) is
    written as its degrees to 12 significant digits, which the reader takes:

    >>> from dataclasses import replace
    >>> limited = replace(t, rows=(replace(t.rows[0], limits=(sp.Rational("-2.8973"), 1)),))
    >>> dump_table(limited).splitlines()[-1]
    '- {type: R, theta: q1 + 90, d: 0, a: 1, alpha: -90, limits: [-166.003061983, 57.2957795131]}'
    >>> read_table_text(dump_table(limited)).rows[0].limits[0].evalf(8)
    -2.8973000
    """
    unit = AngleUnit.parse(angles or table.angles)

    def ang(v: sp.Expr) -> object:
        if unit is AngleUnit.RAD:
            return _plain(v)
        sym = sp.Add(*[t for t in sp.Add.make_args(v) if t.free_symbols])
        const = sp.expand((v - sym) * 180 / sp.pi)
        if const.has(sp.Float):  # a decimal that may be a whole number of degrees (90.0)
            const = sp.nsimplify(const)
        if not const.is_Rational:  # a measured angle (a URDF limit): degrees, 12 digits
            const = sp.Rational(f"{float(const):.12g}")
        if sym == 0:
            return _plain(const)
        return _text(sym) if const == 0 else f"{_text(sym)} + {const}".replace("+ -", "- ")

    lines = []
    for key in ("name", "source"):
        if getattr(table, key):
            lines.append(f"{key}: {json.dumps(getattr(table, key), ensure_ascii=False)}")
    lines += [f"convention: {table.convention.value}", f"angles: {unit.value}"]
    if _would_snap(table):  # decimals kept on purpose stay decimals when read back
        lines.append("snap_angles: false")
    lines.append("joints:")
    for row in table.rows:
        cells = {
            "type": row.joint.value,
            "theta": ang(row.theta),
            "d": _plain(row.d),
            "a": _plain(row.a),
            "alpha": ang(row.alpha),
        }
        own = row.variable_field
        if row.variable is not None and own and len(getattr(row, own).free_symbols) > 1:
            cells["q"] = str(row.variable)
        if row.limits is not None:
            conv = ang if row.joint is JointType.REVOLUTE else _plain
            cells["limits"] = [conv(v) for v in row.limits]
        if row.label:
            cells["name"] = row.label
        if row.inertia is not None:
            for key, value in row.inertia.data().items():
                cells[key] = (
                    [_plain(v) for v in value] if isinstance(value, list) else _plain(value)
                )
        lines.append(
            "- "
            + yaml.safe_dump(cells, default_flow_style=True, sort_keys=False, width=10**6).strip()
        )
    if table.notes:
        lines.append(f"notes: {json.dumps(table.notes, ensure_ascii=False)}")
    if table.values:
        vals = {str(k): _plain(v) for k, v in table.values}
        lines.append(
            "values: " + yaml.safe_dump(vals, default_flow_style=True, sort_keys=False).strip()
        )
    if not table.physical:
        lines.append("physical: false")
    if table.gravity != DHTable.__dataclass_fields__["gravity"].default:
        lines.append(
            "gravity: "
            + yaml.safe_dump([_plain(v) for v in table.gravity], default_flow_style=True).strip()
        )
    for where, seq in (("base", table.base), ("tool", table.tool)):
        if seq:
            steps = [
                {f"{e.kind}{e.axis}": ang(e.value) if e.kind == "R" else _plain(e.value)}
                for e in seq
            ]
            lines.append(f"{where}: " + yaml.safe_dump(steps, default_flow_style=True).strip())
    return "\n".join(lines) + "\n"
