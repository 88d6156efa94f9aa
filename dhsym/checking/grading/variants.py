r"""A variant per student: the values an assignment draws for each student, and the class list.

An assignment may declare ``variants:``, the quantities drawn per student, each from a
range or a list the instructor writes (exact decimals; degrees as in table files)::

    variants:
      a2: {from: 0.40, to: 0.50, step: 0.01}   # a symbol of the key's table
      d3: [0.10, 0.125, 0.15]                  # a list
      q1: {from: -60, to: 60, step: 15, unit: deg}   # a joint value named in ik@q1,q2
    secret: hw3.secret                         # a file beside the assignment, kept private

A name is either a constant symbol of a question's key table (its value is put into the
table: the student's key has their numbers), a name in an ``ik@`` question
(``ask: "ik@q1,q2"``: the pose these joint values reach) or in a transform asked at joint
values (``ask: "T0_6@q1,q2,0,0,0,0"`` or ``"fk@q1,…"``: the matrix there, in numbers).  The
feedback page and the problem sheet print the student's values (:meth:`Variant.text`);
a sheet's numeric check is at the joint values of its first ``ik@`` or ``T…@`` question.

**Seeding.**  A student's values are drawn with HMAC-SHA256 keyed by the assignment's
secret (the file ``secret:`` names, at least 16 bytes; ``dhsym variants hw.yaml
--new-secret`` writes one) over the assignment's title and variants declaration, the
student id normalised (NFC, case-folded: :func:`variant_id`), a counter and the quantity's name.
Reproducible (the same secret, assignment and id give the same values on any machine),
and without the secret no student's values follow from another's.  An assignment with
``variants:`` and no secret is refused: values derived from the assignment alone could be
computed by anyone who has it.

**No duplicates where the ranges allow.**  :func:`class_variants` takes the students
in the order of their first digest (deterministic, favouring no one) and draws each
again with the counter 1, 2, … while their values are already another's, as long as the
class is not larger than the number of combinations (then each combination is used
once before any is used twice).  A student's values therefore depend on the class list:
fix it before handing out the sheets (a student added later changes at most the students
whose first draw collides with theirs).

Examples
--------
>>> spec = VariantSpec.parse({"a2": {"from": 0.4, "to": 0.5, "step": 0.05}, "d3": [1, 2]},
...                          b"0123456789abcdef", "HW 1")
>>> [q.shown for q in spec.quantities]
[('0.4', '0.45', '0.5'), ('1', '2')]
>>> spec.draw("alice") == spec.draw("ALICE"), spec.combinations
(True, 6)
>>> chosen = class_variants(spec, ["s1", "s2", "s3", "s4", "s5", "s6"])
>>> len({v.values for v in chosen.values()})
6
"""

from __future__ import annotations

import csv
import hmac
import io
import math
import secrets
import unicodedata
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from pathlib import Path

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.entries import exact_decimal
from dhsym.model.parsing import parse_expression
from dhsym.model.table import DHTable
from dhsym.model.yamlsafe import FileRefused, read_limited

from .report_files import csv_cell

__all__ = [
    "ClassList",
    "Quantity",
    "Variant",
    "VariantSpec",
    "class_variants",
    "list_variants",
    "new_secret",
    "read_secret",
    "variant_id",
]

_MAX_CHOICES = 10_000
_MAX_QUANTITIES = 32
_MAX_ROSTER = 5_000_000
_MAX_SECRET = 4_096
_MIN_SECRET = 16
_MAX_TRIES = 64
_DOMAIN = b"dhsym-variant-v1"


def variant_id(student: str) -> str:
    """The id a student's values are drawn for: Unicode NFC, case-folded (``José`` typed on
    a Mac and on Windows, or in capitals, is one student; ``Ann Lee`` and ``ann_lee`` are two).

    >>> variant_id("José") == variant_id("jose\u0301") == variant_id("JOSÉ"), variant_id("Ann Lee")
    (True, 'ann lee')
    """
    return unicodedata.normalize("NFC", student).casefold()


@dataclass(frozen=True)
class Quantity:
    """One drawn quantity: its name, its exact values and how each is printed."""

    name: str
    values: tuple[sp.Expr, ...]
    shown: tuple[str, ...]


@dataclass(frozen=True)
class Variant:
    """One student's values: ``values`` by quantity name (exact), ``shown`` as printed."""

    values: tuple[tuple[str, sp.Expr], ...]
    shown: tuple[tuple[str, str], ...]
    counter: int = 0

    def values_for(self, table: DHTable) -> dict[sp.Symbol, sp.Expr]:
        """The values of ``table``'s constant symbols that this variant draws."""
        mine = dict(self.values)
        return {s: mine[str(s)] for s in table.constants if str(s) in mine}

    def text(self) -> str:
        """``a2 = 0.45, d3 = 1`` (the line of the feedback page and the sheet)."""
        return ", ".join(f"{k} = {v}" for k, v in self.shown)


@dataclass(frozen=True)
class VariantSpec:
    """The quantities an assignment draws per student, its secret and what seeds them."""

    quantities: tuple[Quantity, ...]
    secret: bytes
    label: str

    @classmethod
    def parse(
        cls, data: object, secret: bytes, title: str, *, file: str = "assignment"
    ) -> VariantSpec:
        """Read the ``variants:`` mapping; every problem names ``file`` and the field."""
        if not isinstance(data, Mapping) or not data:
            raise DHError(
                "'variants:' is a mapping of names to ranges or lists, e.g. "
                "{a2: {from: 0.4, to: 0.5, step: 0.01}, d3: [0.1, 0.15]}",
                file=file,
                field="variants",
            )
        if len(data) > _MAX_QUANTITIES:
            raise DHError(
                f"at most {_MAX_QUANTITIES} quantities are drawn", file=file, field="variants"
            )
        quantities = []
        for name, value in data.items():
            where = f"variants.{str(name)[:40]}"
            if not isinstance(name, str) or not name.isidentifier() or len(name) > 40:
                raise DHError("a variant's name is a symbol like a2 or q1", file=file, field=where)
            values, shown = _choices(value, file, where)
            quantities.append(Quantity(name, values, shown))
        declared = "\n".join(f"{q.name}: {', '.join(q.shown)}" for q in quantities)
        return cls(tuple(quantities), secret, f"{title}\n{declared}")

    @property
    def names(self) -> tuple[str, ...]:
        """The quantities' names, in the order declared."""
        return tuple(q.name for q in self.quantities)

    @property
    def combinations(self) -> int:
        """How many distinct variants the ranges allow."""
        return math.prod(len(q.values) for q in self.quantities)

    def sample(self) -> Variant:
        """The first value of every quantity (checks the assignment without a student)."""
        return self._variant([0] * len(self.quantities), 0)

    def draw(self, student: str, counter: int = 0) -> Variant:
        """``student``'s values at ``counter`` (0: the first draw), from the keyed HMAC."""
        message = b"\0".join(
            [_DOMAIN, self.label.encode(), variant_id(student).encode(), str(counter).encode()]
        )
        picks = []
        for q in self.quantities:
            digest = hmac.new(self.secret, message + b"\0" + q.name.encode(), "sha256").digest()
            picks.append(int.from_bytes(digest[:8], "big") % len(q.values))
        return self._variant(picks, counter)

    def order(self, student: str) -> bytes:
        """Where ``student`` stands when duplicates are drawn again (their first digest)."""
        message = b"\0".join([_DOMAIN, b"order", self.label.encode(), variant_id(student).encode()])
        return hmac.new(self.secret, message, "sha256").digest()

    def _variant(self, picks: Sequence[int], counter: int) -> Variant:
        qs = self.quantities
        return Variant(
            tuple((q.name, q.values[k]) for q, k in zip(qs, picks, strict=True)),
            tuple((q.name, q.shown[k]) for q, k in zip(qs, picks, strict=True)),
            counter,
        )


def class_variants(spec: VariantSpec, students: Iterable[str]) -> dict[str, Variant]:
    """Each student's variant (by normalised id), duplicates drawn again where possible."""
    ids = {variant_id(s): s for s in students}
    taken: set[tuple[tuple[str, sp.Expr], ...]] = set()
    out: dict[str, Variant] = {}
    for norm in sorted(ids, key=lambda k: spec.order(ids[k])):
        if len(taken) >= spec.combinations:
            taken.clear()  # every combination used once: the next round may repeat them
        variant = spec.draw(ids[norm])
        counter = 0
        while variant.values in taken and counter < _MAX_TRIES:
            counter += 1
            variant = spec.draw(ids[norm], counter)
        if variant.values in taken:  # a long run of bad luck: the first free combination
            variant = _first_free(spec, taken, counter)
        taken.add(variant.values)
        out[norm] = variant
    return out


def _first_free(
    spec: VariantSpec, taken: set[tuple[tuple[str, sp.Expr], ...]], counter: int
) -> Variant:
    """The first combination (in declaration order) that no one has yet."""
    sizes = [len(q.values) for q in spec.quantities]
    for flat in range(spec.combinations):
        picks = []
        for size in reversed(sizes):
            flat, k = divmod(flat, size)
            picks.append(k)
        variant = spec._variant(picks[::-1], counter)
        if variant.values not in taken:
            return variant
    raise AssertionError("no free combination although fewer are taken than exist")


def list_variants(spec: VariantSpec, roster: ClassList, fmt: str = "text") -> str:
    """Each student's values, in the class list's order: ``text`` (aligned columns),
    ``csv`` (``student,name,<quantities>``, cells safe for a spreadsheet) or ``json``.

    >>> spec = VariantSpec.parse({"a2": [0.4, 0.5]}, b"0123456789abcdef", "HW")
    >>> print(list_variants(spec, ClassList((("ada", "Ada"), ("bo", "Bo"))), "csv"), end="")
    student,name,a2
    ada,Ada,0.4
    bo,Bo,0.5
    """
    drawn = class_variants(spec, roster.ids)
    rows = [(sid, name, dict(drawn[variant_id(sid)].shown)) for sid, name in roster.students]
    if fmt == "json":
        import json

        data = [{"student": s, "name": n, "values": v} for s, n, v in rows]
        return (
            json.dumps(
                {"variants": list(spec.names), "students": data}, ensure_ascii=False, indent=1
            )
            + "\n"
        )
    head = ["student", "name", *spec.names]
    body = [[s, n, *(v[k] for k in spec.names)] for s, n, v in rows]
    if fmt == "csv":
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(head)
        writer.writerows(
            [[csv_cell(r[0]), csv_cell(r[1]), *r[2:]] for r in body]
        )  # values are ours
        return out.getvalue()
    if fmt != "text":
        raise DHError(f"unknown format {fmt!r}: expected text, csv or json")
    widths = [max(len(r[k]) for r in [head, *body]) for k in range(len(head))]
    lines = [
        "  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip()
        for r in [head, *body]
    ]
    distinct = len({tuple(v.items()) for _, _, v in rows})
    lines.append(f"{len(rows)} students, {distinct} distinct variants of {spec.combinations}")
    return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class ClassList:
    """The students a class's variants are drawn for: ids (and names) from a CSV file
    with a ``submission`` or ``student`` column (the submission folder or CSV id)."""

    students: tuple[tuple[str, str], ...]
    file: str = ""

    @classmethod
    def load(cls, path: str | Path) -> ClassList:
        """Read the class list CSV (UTF-8); errors name the file, the row and the field."""
        p = Path(path)
        try:
            text = read_limited(p, _MAX_ROSTER, what="the class list").decode("utf-8-sig")
        except FileRefused as err:
            raise DHError(err.message, file=str(p)) from None
        except UnicodeDecodeError:
            raise DHError("the class list is not UTF-8 text", file=str(p)) from None
        return cls.from_text(text, str(p))

    @classmethod
    def from_text(cls, text: str, file: str = "class list") -> ClassList:
        """The class list from CSV text.

        >>> ClassList.from_text("student,name\\nalice,Alice A\\nbob,\\n").students
        (('alice', 'Alice A'), ('bob', 'bob'))
        """
        rows = list(csv.reader(io.StringIO(text, newline="")))
        header = [" ".join(h.replace("_", " ").lower().split()) for h in rows[0]] if rows else []
        column = next((header.index(h) for h in ("submission", "student") if h in header), None)
        if column is None:
            raise DHError(
                "the class list needs a 'submission' or 'student' column (the submission "
                f"folder or CSV id); its columns are: {', '.join(rows[0]) if rows else 'none'}",
                file=file,
            )
        name_col = header.index("name") if "name" in header else None
        seen: dict[str, int] = {}
        out = []
        for row_no, row in enumerate(rows[1:], 2):
            if not any(c.strip() for c in row):
                continue
            sid = unicodedata.normalize("NFC", row[column].strip()) if column < len(row) else ""
            if not sid:
                raise DHError("empty student id", file=file, row=row_no, field=rows[0][column])
            if variant_id(sid) in seen:
                raise DHError(
                    f"{sid!r} is the student of row {seen[variant_id(sid)]} already "
                    "(ids are compared in NFC, case-folded)",
                    file=file,
                    row=row_no,
                    field=rows[0][column],
                )
            seen[variant_id(sid)] = row_no
            name = row[name_col].strip() if name_col is not None and name_col < len(row) else ""
            out.append((sid, name or sid))
        if not out:
            raise DHError("the class list has no student", file=file)
        return cls(tuple(out), file)

    @property
    def ids(self) -> tuple[str, ...]:
        """The student ids, in the file's order."""
        return tuple(s for s, _ in self.students)


def read_secret(path: Path, *, assignment: str) -> bytes:
    """The secret of an assignment's variants: the bytes of ``path`` (surrounding white
    space stripped), at least 16 of them."""
    try:
        data = read_limited(path, _MAX_SECRET, what="the variants secret").strip()
    except FileRefused as err:
        raise DHError(
            f"{err.message} (write one with: dhsym variants {assignment} --new-secret)",
            file=assignment,
            field="secret",
        ) from None
    if len(data) < _MIN_SECRET:
        raise DHError(
            f"the secret {path.name} has {len(data)} bytes: use at least {_MIN_SECRET} "
            f"(dhsym variants {assignment} --new-secret writes 64 random hex digits)",
            file=assignment,
            field="secret",
        )
    return data


def new_secret(path: Path) -> Path:
    """Write a new random secret (64 hex digits, mode 0600) to ``path``; never overwrite."""
    try:
        with open(path, "x", encoding="ascii", opener=_private) as fh:
            fh.write(secrets.token_hex(32) + "\n")
    except FileExistsError:
        raise DHError(
            "the secret exists already; a new one would change every student's values",
            file=str(path),
        ) from None
    return path


def _private(path: str, flags: int) -> int:
    import os

    return os.open(path, flags, 0o600)


def _choices(value: object, file: str, where: str) -> tuple[tuple[sp.Expr, ...], tuple[str, ...]]:
    """A quantity's exact values and their printed forms, from a list or a range."""
    unit = "rad"
    if isinstance(value, Mapping):
        unit = str(value.get("unit", "rad")).lower()
        if unit not in ("rad", "deg"):
            raise DHError("unit is deg or rad", file=file, field=f"{where}.unit")
        if "values" in value:
            items = value["values"]
        elif {"from", "to", "step"} <= set(value):
            items = _range(value["from"], value["to"], value["step"], file, where)
        else:
            raise DHError(
                "a range is {from: A, to: B, step: S} (or values: [...])", file=file, field=where
            )
    else:
        items = value
    if not isinstance(items, list) or not items:
        raise DHError(
            "expected a list of values or a range {from: A, to: B, step: S}",
            file=file,
            field=where,
        )
    if len(items) > _MAX_CHOICES:
        raise DHError(f"at most {_MAX_CHOICES} values per quantity", file=file, field=where)
    values, shown = [], []
    for k, item in enumerate(items, 1):
        exact, text = _value(item, unit, file, f"{where}[{k}]")
        if exact in values:
            raise DHError(f"{text} is listed twice", file=file, field=f"{where}[{k}]")
        values.append(exact)
        shown.append(text)
    return tuple(values), tuple(shown)


def _range(start: object, stop: object, step: object, file: str, where: str) -> list[object]:
    """The exact decimals from ``start`` to ``stop`` (both included) by ``step``."""
    a, b, s = (
        _decimal(x, file, f"{where}.{f}")
        for x, f in ((start, "from"), (stop, "to"), (step, "step"))
    )
    if s <= 0 or b < a:
        raise DHError("a range needs from <= to and a step above 0", file=file, field=where)
    count = int((b - a) / s) + 1
    if count > _MAX_CHOICES:
        raise DHError(
            f"the range has {count} values: at most {_MAX_CHOICES}", file=file, field=where
        )
    return [a + k * s for k in range(count)]


def _decimal(value: object, file: str, where: str) -> Decimal:
    """An exact decimal as written (a YAML float is read from its shortest repr)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str, Decimal)):
        raise DHError(f"expected a number, got {str(value)[:40]!r}", file=file, field=where)
    try:
        d = Decimal(repr(value) if isinstance(value, float) else str(value).strip())
    except InvalidOperation:
        raise DHError(
            f"expected a decimal number, got {str(value)[:40]!r}", file=file, field=where
        ) from None
    if not d.is_finite() or abs(d) > 10**9:
        raise DHError(f"expected a finite number, got {str(value)[:40]!r}", file=file, field=where)
    return d


def _value(item: object, unit: str, file: str, where: str) -> tuple[sp.Expr, str]:
    """One value: exact (radians for an angle) and as it is printed (``0.45``, ``30°``)."""
    text = str(item).strip() if isinstance(item, str) else ""
    degrees = unit == "deg"
    for mark in ("°", "deg"):
        if text.endswith(mark):
            text, degrees = text[: -len(mark)].strip(), True
    if isinstance(item, str) and not _is_decimal(text):
        try:
            expr = parse_expression(text, field=where)
        except DHError as err:
            raise DHError(err.message, file=file, field=where) from None
        if expr.free_symbols or not expr.is_real:
            raise DHError(f"{item!r} is not a real number", file=file, field=where)
        shown = str(expr)
    else:
        d = _decimal(text if isinstance(item, str) else item, file, where)
        expr = sp.Rational(str(d))
        shown = exact_decimal(expr) or str(d)
    if degrees:
        return expr * sp.pi / 180, f"{shown}°"
    return expr, shown


def _is_decimal(text: str) -> bool:
    try:
        return Decimal(text).is_finite()
    except InvalidOperation:
        return False
