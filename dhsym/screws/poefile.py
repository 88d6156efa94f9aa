"""Reading a robot described as a product of exponentials from a YAML file (``*.poe.yaml``).

The format, like the DH table files (:mod:`dhsym.model.tablefile`; every key but ``M``
and ``joints`` optional)::

    name: UR5
    source: Lynch and Park, Modern Robotics, Example 4.5
    frame: space                 # the axes are S_i in the space frame; body: B_i in the tool frame
    M: [[-1, 0, 0, L1 + L2], [0, 0, 1, W1 + W2], [0, 1, 0, H1 - H2], [0, 0, 0, 1]]
    joints:
      - {type: R, w: [0, 0, 1], v: [0, 0, 0]}          # omega and v ...
      - {type: R, w: [0, 1, 0], point: [0, 0, H1]}     # ... or omega and a point on the axis
      - {type: P, v: [0, 0, 1], q: d3}                  # prismatic: omega = 0, v the direction
    values: {L1: 0.425, L2: 0.392}                     # numbers for the symbols

``M`` is a 4×4 matrix, or a list of steps like a table's ``base`` (``[{Tx: L1}, {Rx: 90}]``,
angles in ``angles: deg`` or ``rad``). Entries are numbers or expressions read by the
whitelist parser (:mod:`dhsym.model.parsing`; never ``eval`` or ``sympify``); decimals stay
exact. The axes are validated: a revolute axis has a unit ``ω`` and ``ω·v = 0``, a
prismatic one ``ω = 0`` and ``‖v‖ = 1``; ``M`` must be a rigid transform. Every error names
the file, the joint (as its row) and the field. The joint variables are ``theta<i>``
(revolute) and ``d<i>`` (prismatic) unless ``q`` names them.

Examples
--------
>>> poe = read_poe_text('''
... name: RP
... M: [[1, 0, 0, 2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
... joints:
...   - {type: R, w: [0, 0, 1], point: [0, 0, 0]}
...   - {type: P, v: [1, 0, 0]}
... ''')
>>> poe.variables, poe.screw_matrix().T
((theta1, d2), Matrix([
[0, 0, 1, 0, 0, 0],
[0, 0, 0, 1, 0, 0]]))
>>> bad = "M: [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\\njoints: [{w: [0, 0, 2], v: [0, 0, 0]}]"
>>> read_poe_text(bad, file="arm.poe.yaml")
Traceback (most recent call last):
...
dhsym.errors.TableError: arm.poe.yaml: row 1, field w: a revolute screw axis needs a unit omega: ...
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import sympy as sp

from dhsym.errors import DHError, TableError
from dhsym.kinematics.transforms import plain_product
from dhsym.model.entries import as_expr
from dhsym.model.kinds import AngleUnit
from dhsym.model.parsing import symbol
from dhsym.model.tablefile import (
    read_entry,
    read_steps,
    read_text_file,
    read_values,
    read_yaml_text,
)
from dhsym.notation.printers import Notation, decimal_lengths

from .algebra import ScrewAxis, adjoint, is_zero
from .product import ProductOfExponentials

__all__ = ["is_poe_path", "poe_from_data", "read_poe", "read_poe_text"]

_TOP_KEYS = ("name", "source", "notes", "frame", "angles", "m", "joints", "values")
_JOINT_KEYS = ("type", "w", "v", "point", "q", "name")
_ALIASES = {"omega": "w", "ω": "w", "joint": "type", "variable": "q", "home": "m"}


def is_poe_path(path: str | os.PathLike[str]) -> bool:
    """Whether a path names a PoE file (``*.poe.yaml``, ``*.poe.yml``).

    >>> is_poe_path("ur5.poe.yaml"), is_poe_path("ur5.yaml")
    (True, False)
    """
    return str(path).lower().endswith((".poe.yaml", ".poe.yml"))


def read_poe(path: str | os.PathLike[str]) -> ProductOfExponentials:
    """Read a PoE file (at most :data:`~dhsym.model.tablefile.MAX_FILE_BYTES`, a regular file)."""
    return read_poe_text(read_text_file(path, "PoE file"), file=str(Path(path)))


def read_poe_text(text: str, *, file: str | None = None) -> ProductOfExponentials:
    """Read a PoE description from YAML text (the bounded loader of the table files)."""
    return poe_from_data(read_yaml_text(text, file=file), file=file)


def poe_from_data(data: object, *, file: str | None = None) -> ProductOfExponentials:
    """Build a PoE description from parsed YAML/JSON data."""
    try:
        return _from_data(data)
    except DHError as err:
        raise TableError(err.message, file=file, row=err.row, field=err.field).located(
            file=file
        ) from None


def _canon(key: object) -> str:
    k = str(key).strip()
    return _ALIASES.get(k, _ALIASES.get(k.lower(), k.lower()))


def _from_data(data: object) -> ProductOfExponentials:
    if not isinstance(data, Mapping):
        raise TableError("expected a mapping with 'M' and a 'joints' list at the top level")
    top = {_canon(k): v for k, v in data.items()}
    unknown = sorted(set(top) - set(_TOP_KEYS))
    if unknown:
        raise TableError(
            f"unknown key {unknown[0]!r}: expected name, source, notes, frame, angles, M, "
            "joints, values",
            field=unknown[0],
        )
    for key in ("m", "joints"):
        if key not in top:
            raise TableError(
                f"missing {'M' if key == 'm' else key!r}: a PoE file gives the home "
                "configuration M and the joints' screw axes",
                field="M" if key == "m" else key,
            )
    frame = str(top.get("frame", "space")).strip().lower()
    if frame not in ("space", "body"):
        raise TableError(f"frame must be space or body, got {frame!r}", field="frame")
    unit = AngleUnit.parse(top.get("angles", "rad"))
    home = _home(top["m"], unit)
    joints = top["joints"]
    if not isinstance(joints, list) or not joints:
        raise TableError("'joints' must be a non-empty list of screw axes", field="joints")
    axes, variables = [], []
    for i, entry in enumerate(joints, start=1):
        screw, var = _joint(entry, i)
        axes.append(screw)
        variables.append(var)
    if len(set(variables)) != len(variables):
        raise TableError("two joints have the same variable", field="q")
    if frame == "body":  # S_i = [Ad_M] B_i
        Ad = adjoint(home)
        axes = [ScrewAxis.from_vector((Ad * s.vector).applyfunc(sp.expand)) for s in axes]
    values = _values(top.get("values"))
    used = home.free_symbols.union(*(s.vector.free_symbols for s in axes))
    clash = used & set(variables)
    if clash:
        raise TableError(
            f"the joint variable {sorted(map(str, clash))[0]} appears in M or an axis",
            field="M",
        )
    revolute = [q for q, s in zip(variables, axes) if s.is_revolute]
    notation = Notation.from_variables(
        revolute,
        [str(k) for k, s in enumerate(axes, start=1) if s.is_revolute],
        decimals=decimal_lengths(list(home[:3, 3])),
    )
    return ProductOfExponentials(
        str(top.get("name") or ""),
        tuple(variables),
        tuple(axes),
        home,
        notation,
        values=tuple(values.items()),
    )


def _home(data: object, unit: AngleUnit) -> sp.ImmutableMatrix:
    if isinstance(data, list) and data and all(isinstance(r, Mapping) for r in data):
        M = plain_product(read_steps(data, "M", unit))
    elif isinstance(data, list) and len(data) in (3, 4) and all(isinstance(r, list) for r in data):
        rows = [[as_expr(x, field="M") for x in row] for row in data]
        if any(len(r) != 4 for r in rows):
            raise TableError("M must be 4 rows of 4 entries (or 3 rows: [R | p])", field="M")
        if len(rows) == 3:
            rows.append([sp.Integer(0)] * 3 + [sp.Integer(1)])
        M = sp.ImmutableMatrix(rows)
    else:
        raise TableError(
            "M must be a 4×4 matrix [[...], ...] or a list of steps [{Tx: L1}, {Rz: 90}]",
            field="M",
        )
    R = M[:3, :3]
    if list(M[3, :]) != [0, 0, 0, 1] or not all(is_zero(e) for e in (R.T * R - sp.eye(3))):
        raise TableError("M must be a rigid transform: R orthonormal, last row 0 0 0 1", field="M")
    if not is_zero(R.det() - 1):
        raise TableError("M must be a rigid transform: det R = 1 (a rotation)", field="M")
    return M


def _vec(row: Mapping[str, Any], key: str, i: int) -> sp.ImmutableMatrix:
    value = row[key]
    if not (isinstance(value, list) and len(value) == 3):
        raise TableError(f"{key} must be a list of three entries", row=i, field=key)
    return sp.ImmutableMatrix([as_expr(x, field=key, row=i) for x in value])


def _joint(entry: object, i: int) -> tuple[ScrewAxis, sp.Symbol]:
    like = "{type: R, w: [...], v: [...]}"
    row = read_entry(entry, i, _canon, _JOINT_KEYS, like=like, what="joint", key="key")
    kind = str(row.get("type", "R" if "w" in row else "P")).strip().upper()
    if kind not in ("R", "P"):
        raise TableError(f"type must be R or P, got {kind!r}", row=i, field="type")
    if kind == "R":
        if "w" not in row:
            raise TableError("a revolute joint needs w (omega)", row=i, field="w")
        if ("v" in row) == ("point" in row):
            raise TableError("give v or a point on the axis (one of them)", row=i, field="v")
        w = _vec(row, "w", i)
        try:
            if "point" in row:
                screw = ScrewAxis.revolute(w, _vec(row, "point", i))
            else:
                screw = ScrewAxis(w, _vec(row, "v", i))
                screw.check(revolute=True)
        except DHError as err:
            field = "v" if "omega·v" in err.message else "w"
            raise TableError(err.message, row=i, field=field) from None
    else:
        if "point" in row or "w" in row and any(e != 0 for e in _vec(row, "w", i)):
            raise TableError("a prismatic joint has omega = 0 and no point", row=i, field="w")
        if "v" not in row:
            raise TableError("a prismatic joint needs v (its direction)", row=i, field="v")
        try:
            screw = ScrewAxis.prismatic(_vec(row, "v", i))
        except DHError as err:
            raise TableError(err.message, row=i, field="v") from None
    if "q" in row:
        if not isinstance(row["q"], str):
            raise TableError("q must name the joint variable, e.g. q: theta1", row=i, field="q")
        var = symbol(row["q"].strip())
    else:
        var = symbol(f"{'theta' if kind == 'R' else 'd'}{i}")
    return screw, var


def _values(values: object) -> dict[sp.Symbol, sp.Expr]:
    return {symbol(k): v for k, v in read_values(values).items()}
