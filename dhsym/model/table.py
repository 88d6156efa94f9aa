"""The DH table: conventions, joint types, rows and tables as frozen values.

Two conventions are first class (IRob2305 Lecture 5; Mohan, Lecture 9):

* ``standard`` (distal; Spong, Corke): ``A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)``;
* ``modified`` (proximal; Craig, Ghosal): ``^{i-1}T_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)``.
  Row *i* of a modified table holds α_{i-1}, a_{i-1}, d_i, θ_i, as in Craig's tables.

All entries are exact sympy expressions in radians; :func:`to_radians` turns a
degree entry (``q3 + 90``) into radians (``q3 + pi/2``) exactly.

Examples
--------
>>> t = DHTable.from_rows(
...     [DHRow.revolute("theta1", a="a1"), DHRow.revolute("theta2", a="a2")],
...     name="Planar 2R")
>>> t.n, t.convention.value, t.variables
(2, 'standard', (theta1, theta2))
>>> t.rows[0]
DHRow(R: theta=theta1, d=0, a=a1, alpha=0)
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any, TypeAlias

import sympy as sp

from dhsym.errors import TableError

from .angles import AngleSnap, Snapped, snap_entry, snap_note
from .entries import as_expr, check_radians, to_radians
from .inertia import LinkInertia
from .kinds import AngleUnit, Convention, JointType
from .parsing import reserved_symbols, symbol

__all__ = [
    "AngleUnit",
    "Convention",
    "DHRow",
    "DHTable",
    "Elementary",
    "JointType",
    "as_expr",
    "canonical_text",
    "symbol_values",
    "to_radians",
]

Expr: TypeAlias = sp.Expr


@dataclass(frozen=True)
class Elementary:
    """One elementary transform: a rotation ``R`` or translation ``T`` about/along an axis.

    >>> Elementary("R", "z", sp.pi / 2)
    Rz(pi/2)
    >>> Elementary("T", "x", symbol("a1")).inverse()
    Tx(-a1)
    """

    kind: str
    axis: str
    value: Expr

    def __post_init__(self) -> None:
        if self.kind not in ("R", "T") or self.axis not in ("x", "y", "z"):
            raise TableError(f"unknown elementary transform {self.kind}{self.axis}")
        object.__setattr__(self, "value", as_expr(self.value))

    def inverse(self) -> Elementary:
        """The inverse transform (negated angle or distance)."""
        return Elementary(self.kind, self.axis, -self.value)

    def __repr__(self) -> str:
        return f"{self.kind}{self.axis}({self.value})"


_VAR_LIKE = re.compile(r"^(theta|th|q|d|t)_?\d+$")
_VAR_NAMES = {
    "R": ("theta{i}", "theta_{i}", "q{i}", "q_{i}", "th{i}", "t{i}"),
    "P": ("d{i}", "d_{i}", "q{i}", "q_{i}"),
}


@dataclass(frozen=True)
class DHRow:
    """One row of a DH table: joint type, four exact parameters and the joint variable.

    In a modified table, ``a`` and ``alpha`` of row *i* are a_{i-1} and α_{i-1}.
    Angles are in radians. ``limits`` are joint limits (radians or lengths).

    >>> DHRow.prismatic("d3", theta=0, a=0, alpha=0).variable
    d3
    >>> DHRow.revolute("theta3 + pi/2").offset
    pi/2
    """

    joint: JointType
    theta: Expr
    d: Expr
    a: Expr
    alpha: Expr
    variable: sp.Symbol | None = None
    limits: tuple[Expr, Expr] | None = None
    label: str | None = None
    inertia: LinkInertia | None = None  # mass, centre of mass, inertia (dhsym.dynamics)

    @classmethod
    def revolute(
        cls, theta: object, d: object = 0, a: object = 0, alpha: object = 0, **kw: object
    ) -> DHRow:
        """A revolute row; θ holds the variable (and maybe a constant offset)."""
        return cls(JointType.REVOLUTE, theta, d, a, alpha, **kw)  # type: ignore[arg-type]  # __post_init__ converts

    @classmethod
    def prismatic(
        cls, d: object, theta: object = 0, a: object = 0, alpha: object = 0, **kw: object
    ) -> DHRow:
        """A prismatic row; d holds the variable."""
        return cls(JointType.PRISMATIC, theta, d, a, alpha, **kw)  # type: ignore[arg-type]  # __post_init__ converts

    @classmethod
    def fixed(cls, theta: object = 0, d: object = 0, a: object = 0, alpha: object = 0) -> DHRow:
        """A fixed row (constant transform, no joint variable)."""
        return cls(JointType.FIXED, theta, d, a, alpha)

    def __post_init__(self) -> None:
        object.__setattr__(self, "joint", JointType.parse(self.joint))
        for name in ("theta", "d", "a", "alpha"):
            object.__setattr__(self, name, as_expr(getattr(self, name), field=name))
        if isinstance(self.variable, str):
            object.__setattr__(self, "variable", symbol(self.variable))
        own = self.variable_field
        if self.variable is None and own is not None:
            candidates = getattr(self, own).free_symbols
            if len(candidates) == 1:
                object.__setattr__(self, "variable", next(iter(candidates)))
        if self.limits is not None:
            lo, hi = (as_expr(v, field="limits") for v in self.limits)
            object.__setattr__(self, "limits", (lo, hi))
        if isinstance(self.inertia, Mapping):
            object.__setattr__(self, "inertia", LinkInertia.from_data(self.inertia))

    @property
    def variable_field(self) -> str | None:
        """Name of the column that holds the joint variable (``theta`` or ``d``)."""
        return {JointType.REVOLUTE: "theta", JointType.PRISMATIC: "d"}.get(self.joint)

    @property
    def offset(self) -> Expr:
        """Constant part of the variable's entry (``theta3 + pi/2`` gives ``pi/2``; a flipped
        joint's ``pi/2 - theta3`` too)."""
        if self.variable is None or self.variable_field is None:
            return sp.Integer(0)
        return sp.expand(getattr(self, self.variable_field)).subs(self.variable, 0)

    def params(self) -> dict[str, Expr]:
        """The four parameters by name."""
        return {"theta": self.theta, "d": self.d, "a": self.a, "alpha": self.alpha}

    def __repr__(self) -> str:
        return (
            f"DHRow({self.joint.value}: theta={self.theta}, d={self.d}, a={self.a}, "
            f"alpha={self.alpha})"
        )


def _infer_variable(row: DHRow, index: int) -> sp.Symbol | None:
    """Find the joint variable of a row, or explain why there is none."""
    if row.joint is JointType.FIXED:
        return None
    own = row.variable_field
    assert own is not None
    other = "d" if own == "theta" else "theta"
    entry = getattr(row, own)
    if row.variable is not None:
        if row.variable not in entry.free_symbols:
            raise TableError(
                f"joint variable {row.variable} does not appear in {own}", row=index, field=own
            )
        return row.variable
    candidates = sorted(entry.free_symbols, key=lambda s: s.name)
    if not candidates:
        kind = "revolute" if own == "theta" else "prismatic"
        hint = ""
        if getattr(row, other).free_symbols:
            hint = (
                f"; {other} = {getattr(row, other)} has a symbol: is this joint "
                f"{'prismatic (type: P)' if own == 'theta' else 'revolute (type: R)'}?"
            )
        raise TableError(
            f"{kind} joint has no variable in {own} (got {entry}){hint}", row=index, field=own
        )
    if len(candidates) == 1:
        return candidates[0]
    names = {p.format(i=index) for p in _VAR_NAMES[row.joint.value]}
    preferred = [s for s in candidates if s.name in names]
    looks_like_variable = [s for s in candidates if _VAR_LIKE.match(s.name)]
    if len(preferred) == 1 and looks_like_variable == preferred:
        return preferred[0]
    raise TableError(
        f"{own} = {entry} has {len(candidates)} candidate joint variables "
        f"({', '.join(s.name for s in candidates)}): a joint has exactly one; "
        "name it with q: NAME",
        row=index,
        field=own,
    )


def _refuse_reserved(
    entry: Expr, reserved: Mapping[sp.Symbol, str], *, row: int | None, field: str
) -> None:
    """A constant entry may not use the name of a joint's rate or acceleration."""
    used = entry.free_symbols & set(reserved)
    if used:
        s = min(used, key=str)
        raise TableError(
            f"{s} is reserved, {reserved[s]} (a constant entry cannot use it): rename this symbol",
            row=row,
            field=field,
        )


@dataclass(frozen=True)
class DHTable:
    """An ordered, validated DH table.

    Parameters
    ----------
    rows
        The rows, joint 1 first.
    convention
        :class:`Convention` (``standard`` or ``modified``).
    name, source
        A title and where the numbers come from (a citation).
    values
        Optional numbers for symbolic lengths, as ``(symbol, value)`` pairs.
    base, tool
        Optional constant transforms before joint 1 and after the last frame,
        as sequences of :class:`Elementary`.
    angles
        The unit the table was *written* in (for display); entries are radians.
    notes
        Free text from the table file.
    gravity
        The gravitational acceleration in the base (world) frame, exact; default
        ``(0, 0, -9.81)`` as in roboticstoolbox.
    physical
        False when the inertias were accepted without the triangle inequality
        (published data that breaks it, :mod:`dhsym.model.inertia`).
    warnings
        What the reader did to the input that the user should know, one
        sentence each (decimal angles read as multiples of π/12).
    """

    rows: tuple[DHRow, ...]
    convention: Convention = Convention.STANDARD
    name: str = ""
    source: str = ""
    values: tuple[tuple[sp.Symbol, Expr], ...] = ()
    base: tuple[Elementary, ...] = ()
    tool: tuple[Elementary, ...] = ()
    angles: AngleUnit = AngleUnit.RAD
    notes: str = field(default="", compare=False)
    gravity: tuple[Expr, Expr, Expr] = (sp.Integer(0), sp.Integer(0), sp.Rational(-981, 100))
    physical: bool = True
    warnings: tuple[str, ...] = field(default=(), compare=False)

    @classmethod
    def from_rows(
        cls,
        rows: Iterable[DHRow],
        *,
        convention: Convention | str = Convention.STANDARD,
        angles: AngleUnit | str = AngleUnit.RAD,
        values: Mapping[Any, object] | None = None,
        snap_angles: AngleSnap | bool | float | None = True,
        **kw: object,
    ) -> DHTable:
        """Build a table from rows; with ``angles='deg'`` θ, α and revolute limits are degrees.

        Decimal angles in radians that stand for a multiple of π/12 (``1.5708``)
        are read as that multiple, and :attr:`warnings` says so
        (:mod:`dhsym.model.angles`); ``snap_angles=False`` keeps the decimals,
        a number sets the tolerance in radians.

        >>> t = DHTable.from_rows([DHRow.revolute("q1", alpha=90)], angles="deg")
        >>> t.rows[0].alpha
        pi/2
        >>> t = DHTable.from_rows([DHRow.revolute("q1", alpha=-1.5708)])
        >>> t.rows[0].alpha, t.warnings[0][:60]
        (-pi/2, 'Decimal angles read as exact: alpha -1.5708 in row 1 as -π/2')
        """
        unit = AngleUnit.parse(angles)
        rule = AngleSnap.parse(snap_angles)
        converted = []
        found: list[Snapped] = []
        for i, row in enumerate(rows, start=1):
            try:
                changes: dict[str, object] = {}
                for name in ("theta", "alpha"):
                    entry, snapped = snap_entry(to_radians(getattr(row, name), unit), rule, name, i)
                    changes[name] = entry
                    found += [snapped] if snapped else []
                if row.limits is not None and row.joint is JointType.REVOLUTE:
                    changes["limits"] = tuple(to_radians(v, unit) for v in row.limits)
            except TableError as err:
                raise err.located(row=i) from None
            converted.append(replace(row, **changes))  # type: ignore[arg-type]  # Expr entries and limits
        for where in ("base", "tool"):
            if kw.get(where):
                steps = []
                for e in kw[where]:  # type: ignore[attr-defined]  # base/tool: Elementary steps (kw is **object)
                    snapped = None
                    if e.kind == "R":
                        value, snapped = snap_entry(e.value, rule, f"{where} R{e.axis}", None)
                        e = Elementary(e.kind, e.axis, value)
                    found += [snapped] if snapped else []
                    steps.append(e)
                kw[where] = tuple(steps)
        pairs = tuple(symbol_values(values).items())
        extra = kw.pop("warnings", ())
        if not isinstance(extra, Iterable):
            raise TypeError(f"warnings must be an iterable of str, got {extra!r}")
        warnings: tuple[str, ...] = (snap_note(found),) if found else ()
        return cls(
            tuple(converted),
            Convention.parse(convention),
            values=pairs,
            angles=unit,
            warnings=warnings + tuple(extra),
            **kw,  # type: ignore[arg-type]  # the remaining fields, checked by __post_init__
        )

    def __post_init__(self) -> None:
        object.__setattr__(self, "convention", Convention.parse(self.convention))
        object.__setattr__(self, "angles", AngleUnit.parse(self.angles))
        rows = tuple(self.rows)
        if not rows:
            raise TableError("the table has no joints: give at least one row", field="joints")
        fixed_rows = []
        seen: dict[sp.Symbol, int] = {}
        for i, row in enumerate(rows, start=1):
            if not isinstance(row, DHRow):
                raise TableError(f"expected a DHRow, got {type(row).__name__}", row=i)
            for name in ("theta", "alpha"):
                check_radians(getattr(row, name), row=i, field=name)
            var = _infer_variable(row, i)
            if var is not None:
                for name, entry in row.params().items():
                    if name != row.variable_field and var in entry.free_symbols:
                        raise TableError(
                            f"joint variable {var} of this {row.joint.name.lower()} joint "
                            f"appears in {name}; it belongs in {row.variable_field} only",
                            row=i,
                            field=name,
                        )
                if var in seen:
                    raise TableError(
                        f"joint variable {var} is already the variable of row {seen[var]}",
                        row=i,
                        field=row.variable_field,
                    )
                seen[var] = i
            fixed_rows.append(row if row.variable == var else replace(row, variable=var))
        variables = tuple(seen)
        derivatives = {k: v for k, v in reserved_symbols(variables).items() if k not in seen}
        for i, row in enumerate(fixed_rows, start=1):
            for name, entry in row.params().items():
                stray = (entry.free_symbols & set(seen)) - {row.variable}
                if stray:
                    s = sorted(stray, key=str)[0]
                    raise TableError(
                        f"{s} is the joint variable of row {seen[s]} and cannot appear here",
                        row=i,
                        field=name,
                    )
                _refuse_reserved(entry, derivatives, row=i, field=name)
            if row.inertia is not None:
                row.inertia.check_constant(variables, row=i)
        object.__setattr__(self, "rows", tuple(fixed_rows))
        object.__setattr__(self, "base", tuple(self.base))
        object.__setattr__(self, "tool", tuple(self.tool))
        gravity = tuple(as_expr(v, field="gravity") for v in self.gravity)
        if len(gravity) != 3:
            raise TableError("gravity must be 3 values [gx, gy, gz]", field="gravity")
        object.__setattr__(self, "gravity", gravity)
        constants = {**derivatives, **{v: f"the joint variable {v}" for v in variables}}
        for e in gravity:
            _refuse_reserved(e, constants, row=None, field="gravity")
        known = set().union(*(e.free_symbols for r in fixed_rows for e in r.params().values()))
        known |= set().union(*(r.inertia.free_symbols for r in fixed_rows if r.inertia))
        known |= set().union(*(e.free_symbols for e in gravity))
        known |= set().union(*(e.value.free_symbols for e in self.base + self.tool))
        for sym, value in self.values:
            if sym in seen:
                raise TableError(
                    f"{sym} is a joint variable; values are for constant symbols",
                    field="values",
                )
            if sym not in known:
                raise TableError(f"symbol {sym} does not appear in the table", field="values")
            if value.free_symbols or not value.is_number:
                raise TableError(f"value of {sym} must be a number, got {value}", field="values")

    @property
    def n(self) -> int:
        """Number of rows."""
        return len(self.rows)

    @property
    def variables(self) -> tuple[sp.Symbol, ...]:
        """Joint variables, in row order (fixed rows have none)."""
        return tuple(r.variable for r in self.rows if r.variable is not None)

    @property
    def joint_rows(self) -> tuple[int, ...]:
        """1-based indices of the rows that have a joint variable."""
        return tuple(i for i, r in enumerate(self.rows, start=1) if r.variable is not None)

    @property
    def constants(self) -> tuple[sp.Symbol, ...]:
        """Constant symbols (lengths, offsets, symbolic twists), sorted by name."""
        syms: set[sp.Symbol] = set()
        for r in self.rows:
            for e in r.params().values():
                syms |= e.free_symbols
        for e in self.base + self.tool:
            syms |= e.value.free_symbols
        return tuple(sorted(syms - set(self.variables), key=lambda s: s.name))

    @property
    def value_map(self) -> dict[sp.Symbol, Expr]:
        """The numeric values of constant symbols as a dict."""
        return dict(self.values)

    def with_values(self, values: Mapping[Any, object]) -> DHTable:
        """A copy with more (or replaced) numeric values for constant symbols."""
        return replace(self, values=tuple({**self.value_map, **symbol_values(values)}.items()))

    def substituted(self) -> DHTable:
        """A copy with the numeric values substituted into the rows (values emptied)."""
        vm = self.value_map
        rows = tuple(
            replace(r, **{k: v.subs(vm) for k, v in r.params().items()}) for r in self.rows
        )
        rows = tuple(replace(r, inertia=r.inertia.subs(vm)) if r.inertia else r for r in rows)
        base = tuple(Elementary(e.kind, e.axis, e.value.subs(vm)) for e in self.base)
        tool = tuple(Elementary(e.kind, e.axis, e.value.subs(vm)) for e in self.tool)
        gravity = tuple(v.subs(vm) for v in self.gravity)
        return replace(self, rows=rows, base=base, tool=tool, values=(), gravity=gravity)

    def _repr_latex_(self) -> str:
        return "$$" + self._latex(None) + "$$"

    def _latex(self, printer: object) -> str:
        """``sympy.latex(table)``: the table as a LaTeX ``array``."""
        from dhsym.notation.tables import table_latex

        return table_latex(self)

    def _repr_markdown_(self) -> str:
        from dhsym.notation.tables import table_markdown

        return table_markdown(self)


def symbol_values(values: Mapping[Any, object] | None) -> dict[sp.Symbol, Expr]:
    """Symbol → exact value for values as given: names or symbols; numbers or text, which
    goes through the whitelist parser (never ``sympify``).

    >>> symbol_values({"a2": "0.4318", "d3": 0.15})
    {a2: 2159/5000, d3: 3/20}
    """
    return {
        (symbol(k) if isinstance(k, str) else k): as_expr(v, field="values")
        for k, v in (values or {}).items()
    }


def canonical_text(table: DHTable) -> str:
    """A deterministic text of everything a derivation reads from ``table``: the rows
    (joints, entries, variables, limits, labels, inertial parameters), the convention,
    base and tool, the values, the angle unit, gravity; not its name, file or comments.

    Equal tables give equal texts (values in name order), and the text names every
    expression by ``sympy.srepr`` (symbols with their assumptions), so two tables that
    derive differently never share it. The disk cache (:mod:`dhsym.cache.keys`) hashes it.

    >>> from dhsym.model.library import load_table
    >>> text = canonical_text(load_table("planar2r"))
    >>> text.splitlines()[:2]
    ['dhsym-table 1', 'convention standard']
    >>> canonical_text(replace(load_table("planar2r"), name="other")) == text
    True
    """

    def ex(e: object) -> str:
        return str(sp.srepr(e))

    lines = [
        "dhsym-table 1",
        f"convention {table.convention.value}",
        f"angles {table.angles.value}",
        f"physical {table.physical}",
        "gravity " + " ".join(ex(g) for g in table.gravity),
    ]
    for k, r in enumerate(table.rows, 1):
        lines.append(
            f"row {k} {r.joint.value} theta={ex(r.theta)} d={ex(r.d)} a={ex(r.a)} "
            f"alpha={ex(r.alpha)} variable={ex(r.variable)} "
            f"limits={'' if r.limits is None else ' '.join(ex(v) for v in r.limits)} "
            f"label={r.label!r}"
        )
        if r.inertia is not None:
            i = r.inertia
            lines.append(
                f"inertia {k} m={ex(i.m)} r={ex(i.r)} I={ex(i.I)} Jm={ex(i.Jm)} G={ex(i.G)} "
                f"B={ex(i.B)} Tc={ex(i.Tc)}"
            )
    for where, word in (("base", table.base), ("tool", table.tool)):
        for e in word:
            lines.append(f"{where} {e.kind} {e.axis} {ex(e.value)}")
    for sym, value in sorted(table.values, key=lambda sv: (sv[0].name, ex(sv[0]))):
        lines.append(f"value {ex(sym)} {ex(value)}")
    return "\n".join(lines) + "\n"
