r"""The catalogue of classic DH mistakes, each recognised by recomputing the key under it.

A :class:`Mistake` takes the key (its table rows, the frames asked, the random
sample) and produces *variants*: what a student who made that mistake would have
written.  When the student's wrong entries (or wrong table) equal a variant, the
mistake is the diagnosis.  Matrix variants are numbers at the sample points
(:func:`dhsym.checking._numeric.word_product` of the core's link words); table
variants are tables compared cell by cell or as robots
(:func:`dhsym.checking.tables.compare_tables`).

Kinds: ``wrong_sign``, ``sin_cos_swapped``, ``transposed``, ``other_convention``,
``degrees_as_radians``, ``index_shift``, ``offset_missing``, ``reverse_order``,
``single_wrong_row``.

Examples
--------
>>> [m.kind for m in MATRIX_MISTAKES][:3]
['transposed', 'other_convention', 'reverse_order']
>>> OffsetMissing().title
'joint offset missing'
"""

from __future__ import annotations

from abc import ABC
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np
import sympy as sp

from dhsym.notation import Notation, format_angle
from dhsym.table import Convention, DHRow, DHTable, JointType
from dhsym.transforms import link_word

from ._numeric import word_product
from .equivalence import Sample, close, values
from .tables import Chain, compare_tables, same_cells
from .verdict import Diagnosis

__all__ = [
    "DegreesAsRadians",
    "IndexShift",
    "MATRIX_MISTAKES",
    "MatrixCase",
    "Mistake",
    "OffsetMissing",
    "OtherConvention",
    "ReverseOrder",
    "SinCosSwapped",
    "SingleWrongRow",
    "TABLE_MISTAKES",
    "TableCase",
    "Transposed",
    "WrongSign",
    "diagnose_matrix",
    "diagnose_table",
]

_FORMULA = {
    Convention.STANDARD: "A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)",
    Convention.MODIFIED: "^{i-1}T_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)",
}
_MAX_CANDIDATES = 24


@dataclass(frozen=True, eq=False)
class MatrixCase:
    """A wrong matrix (or entry) answer and the key it is judged against.

    ``expected``/``answer`` are 4×4 (or 1×1 for an entry question at ``entry``,
    0-based); ``wrong`` lists the 0-based positions that differ; ``cache`` keeps
    the variants of one key between answers.
    """

    rows: tuple[DHRow, ...]
    convention: Convention
    frm: int
    to: int
    entry: tuple[int, int] | None
    expected: sp.ImmutableMatrix
    answer: sp.ImmutableMatrix
    sample: Sample
    key_values: np.ndarray
    answer_values: np.ndarray
    wrong: tuple[tuple[int, int], ...]
    notation: Notation = field(default_factory=Notation)
    cache: dict = field(default_factory=dict)

    def chain_values(
        self, rows: tuple[DHRow, ...], convention: Convention, reverse: str = ""
    ) -> np.ndarray:
        """Values of ``^frm T_to`` of ``rows`` at the sample (``reverse``: links or factors)."""
        lo, hi = sorted((self.frm, self.to))
        links = [list(link_word(rows[k - 1], convention)) for k in range(lo + 1, hi + 1)]
        if reverse == "links":
            links = links[::-1]
        word = [e for link in links for e in link]
        if reverse == "factors":
            word = word[::-1]
        if self.frm > self.to:
            word = [e.inverse() for e in reversed(word)]
        return self.project(word_product(word, self.sample.env, self.sample.size))

    def project(self, full: np.ndarray) -> np.ndarray:
        """Cut full 4×4 values down to the asked entry (if any)."""
        if self.entry is None:
            return full
        r, c = self.entry
        return full[:, r : r + 1, c : c + 1]

    def label(self, pos: tuple[int, int]) -> tuple[int, int]:
        """The 1-based (row, column) of a position, in the full matrix."""
        if self.entry is not None:
            return self.entry[0] + 1, self.entry[1] + 1
        return pos[0] + 1, pos[1] + 1

    def where(self, pos: tuple[int, int]) -> str:
        """``(2,4)``: a 1-based position as the lectures write it."""
        r, c = self.label(pos)
        return f"({r},{c})"


@dataclass(frozen=True, eq=False)
class TableCase:
    """A wrong table answer and the key table."""

    key: DHTable
    answer: DHTable
    tool_free: bool = False
    values: Mapping[sp.Symbol, sp.Expr] = field(default_factory=dict)


class Mistake(ABC):  # noqa: B024 - every hook has a default; kinds override some
    """One kind of mistake: a name, a title, and how to recompute the key under it.

    Subclasses override :meth:`matrix_variants` and/or :meth:`table_variants`
    (or the ``explain_*`` methods for entry-wise mistakes).
    """

    kind: ClassVar[str] = ""
    title: ClassVar[str] = ""

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        """(values of the recomputed key at the sample, what the student did)."""
        return iter(())

    def table_variants(self, case: TableCase) -> Iterator[tuple[Chain, str, tuple[int, ...]]]:
        """(the key table under this mistake, what the student did, rows involved)."""
        return iter(())

    def _cached_variants(self, case: MatrixCase) -> list[tuple[np.ndarray, str]]:
        key = (self.kind, id(case.sample), case.entry)
        if key not in case.cache:
            found = []
            for vals, detail in self.matrix_variants(case):
                if not close(vals, case.key_values):
                    found.append((vals, detail))
            case.cache[key] = found
        return case.cache[key]

    def explain_matrix(self, case: MatrixCase, partial: bool = False) -> Diagnosis | None:
        """A diagnosis when a variant equals the whole answer (or, with ``partial``, the
        answer at some of its wrong entries)."""
        for vals, detail in self._cached_variants(case):
            hits = [
                p
                for p in case.wrong
                if close(vals[:, p[0], p[1]], case.answer_values[:, p[0], p[1]])
            ]
            whole = len(hits) == len(case.wrong) and close(vals, case.answer_values)
            if hits and (partial or whole):
                entries = tuple(case.label(p) for p in hits)
                return Diagnosis(self.kind, self.title, detail, entries)
        return None

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        """A diagnosis when the answer table equals a variant of the key table."""
        for chain, detail, rows in self.table_variants(case):
            if same_cells(chain, case.answer, case.values):
                return Diagnosis(self.kind, self.title, detail, rows=rows)
        return None


def _without(rows: tuple[DHRow, ...], **change: object) -> tuple[DHRow, ...]:
    return tuple(replace(r, **change) for r in rows)


class Transposed(Mistake):
    """The matrix (or its rotation part) written transposed."""

    kind, title = "transposed", "matrix transposed"

    def matrix_variants(self, case):
        full = np.asarray(case.cache.setdefault(("full", id(case.sample)), _full(case)))
        yield (
            case.project(np.swapaxes(full, 1, 2)),
            (
                "Rows and columns are exchanged: the columns of ^iT_j are the axes n, s, a of "
                "frame j and its position p, written in frame i."
            ),
        )
        rot = full.copy()
        rot[:, :3, :3] = np.swapaxes(full[:, :3, :3], 1, 2)
        yield (
            case.project(rot),
            (
                "The rotation part is transposed (that is the inverse rotation, R^T = R^-1); "
                "the columns of R are the axes of the new frame in the old one."
            ),
        )


def _full(case: MatrixCase) -> np.ndarray:
    """Values of the full 4×4 key matrix at the sample (also for entry questions)."""
    lo, hi = sorted((case.frm, case.to))
    word = [e for k in range(lo + 1, hi + 1) for e in link_word(case.rows[k - 1], case.convention)]
    if case.frm > case.to:
        word = [e.inverse() for e in reversed(word)]
    return word_product(word, case.sample.env, case.sample.size)


class ReverseOrder(Mistake):
    """Link matrices (or the four elementary factors) multiplied in reverse order."""

    kind, title = "reverse_order", "product in reverse order"

    def matrix_variants(self, case):
        if abs(case.to - case.frm) > 1:
            yield (
                case.chain_values(case.rows, case.convention, "links"),
                (
                    f"The link matrices are multiplied in reverse order: ^{case.frm}T_{case.to} = "
                    f"A_{min(case.frm, case.to) + 1} ⋯ A_{max(case.frm, case.to)}, first link on "
                    "the left (each factor is expressed in the frame before it)."
                ),
            )
        yield (
            case.chain_values(case.rows, case.convention, "factors"),
            (
                "The elementary transforms are multiplied in reverse order: for this convention "
                f"{_FORMULA[case.convention]}, left to right."
            ),
        )


class OtherConvention(Mistake):
    """The other DH convention's link matrix (or table) used."""

    kind, title = "other_convention", "other DH convention"

    def matrix_variants(self, case):
        other = _other(case.convention)
        yield (
            case.chain_values(case.rows, other),
            (
                f"This is the {other.value} link matrix ({_FORMULA[other]}); the question uses "
                f"the {case.convention.value} convention: {_FORMULA[case.convention]}."
            ),
        )

    def explain_table(self, case):
        key_conv, other = case.key.convention, _other(case.key.convention)
        declared = case.answer.convention is not key_conv
        valid = (
            f"Your table is a valid {other.value}-convention table of this robot, but the "
            f"question asks for the {key_conv.value} convention ({_FORMULA[key_conv]})."
        )
        tries = [(Chain(case.answer.rows, other), valid)]
        if declared:
            tries = [
                (case.answer, valid),
                (
                    Chain(case.answer.rows, key_conv),
                    (
                        f"The columns are labelled for the {other.value} convention, "
                        "but the values "
                        f"are those of the {key_conv.value} convention ({_FORMULA[key_conv]})."
                    ),
                ),
            ]
        for target, detail in tries:
            m = compare_tables(case.key, target, tool_free=case.tool_free, values=case.values)
            if m.same_robot:
                return Diagnosis(self.kind, self.title, detail)
        return None


def _other(c: Convention) -> Convention:
    return Convention.MODIFIED if c is Convention.STANDARD else Convention.STANDARD


def _shifted(rows: tuple[DHRow, ...], step: int, names: tuple[str, ...]) -> tuple[DHRow, ...]:
    out = []
    for k, row in enumerate(rows):
        src = k + step
        new = {n: (getattr(rows[src], n) if 0 <= src < len(rows) else sp.Integer(0)) for n in names}
        out.append(replace(row, **new))
    return tuple(out)


class IndexShift(Mistake):
    """α and a taken from the neighbouring row (α_i where α_{i-1} belongs, or back)."""

    kind, title = "index_shift", "α/a index shifted by one row"

    def _variants(self, rows, convention):
        own = "α_{i-1}, a_{i-1}" if convention is Convention.MODIFIED else "α_i, a_i"
        for step in (1, -1):
            for names in (("alpha", "a"), ("alpha",)):
                what = "α and a" if len(names) == 2 else "α"
                yield (
                    _shifted(rows, step, names),
                    (
                        f"{what} come from the {'next' if step == 1 else 'previous'} row: in the "
                        f"{convention.value} convention row i holds {own}."
                    ),
                )

    def matrix_variants(self, case):
        for rows, detail in self._variants(case.rows, case.convention):
            yield case.chain_values(rows, case.convention), detail

    def table_variants(self, case):
        for rows, detail in self._variants(case.key.rows, case.key.convention):
            yield Chain(rows, case.key.convention), detail, ()


def _no_offset(row: DHRow) -> DHRow:
    if row.variable is None or row.offset == 0:
        return row
    return replace(row, **{row.variable_field: row.variable})  # type: ignore[arg-type]


class OffsetMissing(Mistake):
    """A constant joint offset (θ3 + π/2) left out."""

    kind, title = "offset_missing", "joint offset missing"

    def _variants(self, rows):
        with_offset = [k for k, r in enumerate(rows) if r.variable is not None and r.offset != 0]
        if not with_offset:
            return
        names = ", ".join(
            f"row {k + 1}: {sp.sstr(getattr(rows[k], rows[k].variable_field))}" for k in with_offset
        )
        yield (
            tuple(_no_offset(r) for r in rows),
            (f"The joint offset is missing ({names}): the variable alone is not the entry."),
            tuple(k + 1 for k in with_offset),
        )
        for k in with_offset:
            yield (
                tuple(_no_offset(r) if j == k else r for j, r in enumerate(rows)),
                (
                    f"The joint offset of row {k + 1} is missing: the entry is "
                    f"{sp.sstr(getattr(rows[k], rows[k].variable_field))}."
                ),
                (k + 1,),
            )

    def matrix_variants(self, case):
        for rows, detail, _ in self._variants(case.rows):
            yield case.chain_values(rows, case.convention), detail

    def table_variants(self, case):
        for rows, detail, where in self._variants(case.key.rows):
            yield Chain(rows, case.key.convention), detail, where


def _angle_terms(expr: sp.Expr, factor: sp.Expr) -> sp.Expr:
    return sp.Add(*[t if t.free_symbols else t * factor for t in sp.Add.make_args(expr)])


class DegreesAsRadians(Mistake):
    """An angle in degrees used as radians (cos 90 for cos 90°), or the other way round."""

    kind, title = "degrees_as_radians", "degrees read as radians"

    def _variants(self, rows):
        if not any(_angle_terms(r.alpha, 0) != 0 or _angle_terms(r.theta, 0) != 0 for r in rows):
            return
        for factor, detail in (
            (180 / sp.pi, "An angle in degrees was used as radians (cos 90 is not cos 90°)."),
            (sp.pi / 180, "An angle in radians was read as degrees (1.57° is not 90°)."),
        ):
            yield (
                tuple(
                    replace(
                        r, theta=_angle_terms(r.theta, factor), alpha=_angle_terms(r.alpha, factor)
                    )
                    for r in rows
                ),
                detail,
            )

    def matrix_variants(self, case):
        for rows, detail in self._variants(case.rows):
            yield case.chain_values(rows, case.convention), detail

    def table_variants(self, case):
        for rows, detail in self._variants(case.key.rows):
            yield Chain(rows, case.key.convention), detail, ()


def _sign_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, str | None]]:
    yield -e, None
    terms = sp.Add.make_args(e)
    if len(terms) > 1:
        for t in terms[:_MAX_CANDIDATES]:
            yield e - 2 * t, t


def _swap_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, str | None]]:
    atoms = sorted(e.atoms(sp.sin, sp.cos), key=sp.default_sort_key)
    if not atoms:
        return
    swap = {a: (sp.cos if isinstance(a, sp.sin) else sp.sin)(a.args[0]) for a in atoms}
    yield e.xreplace(swap), None
    args = sorted({a.args[0] for a in atoms}, key=sp.default_sort_key)
    if len(args) > 1:
        for x in args[:_MAX_CANDIDATES]:
            yield e.xreplace({a: swap[a] for a in atoms if a.args[0] == x}), sp.cos(x)
    if len(atoms) > 1:
        for a in atoms[:_MAX_CANDIDATES]:
            yield e.xreplace({a: swap[a]}), a


class _EntryMistake(Mistake):
    """A mistake inside one entry: candidates are rewritten key entries."""

    def candidates(self, e: sp.Expr) -> Iterator[tuple[sp.Expr, object]]:
        raise NotImplementedError

    def message(self, case: MatrixCase, where: tuple[int, int], e: sp.Expr, part: object) -> str:
        raise NotImplementedError

    def explain_matrix(self, case, partial=True):
        hits, details = [], []
        for p in case.wrong:
            e = case.expected[p]
            for cand, part in self.candidates(e):
                if close(values(cand, case.sample), case.answer_values[:, p[0], p[1]]):
                    hits.append(case.label(p))
                    details.append(self.message(case, case.where(p), e, part))
                    break
        if not hits:
            return None
        return Diagnosis(self.kind, self.title, " ".join(details), tuple(hits))

    def explain_table(self, case):
        return None


class WrongSign(_EntryMistake):
    """An entry, or one term of it, with the wrong sign (seed 002's +d_i sin α_{i-1})."""

    kind, title = "wrong_sign", "wrong sign"

    def candidates(self, e):
        return _sign_candidates(e)

    def message(self, case, where, e, part):
        nota = case.notation
        if part is None:
            return f"Entry {where} has the wrong sign: it is {nota.text(e)}, not {nota.text(-e)}."
        return f"In entry {where} the term {nota.text(part)} has the wrong sign."

    def explain_table(self, case):
        key = case.key
        for k, row in enumerate(key.rows):
            for name, value in row.params().items():
                if value == 0 or name == row.variable_field and value == row.variable:
                    continue
                flipped = -value if name != row.variable_field else 2 * row.variable - value
                rows = tuple(
                    replace(r, **{name: flipped}) if j == k else r for j, r in enumerate(key.rows)
                )
                if same_cells(Chain(rows, key.convention), case.answer, case.values):
                    shown = _cell(name, value, key)
                    return Diagnosis(
                        self.kind,
                        self.title,
                        f"Row {k + 1}: {name} has the wrong sign; it is {shown}.",
                        rows=(k + 1,),
                    )
        return None


class SinCosSwapped(_EntryMistake):
    """sin written where cos belongs (or the other way round)."""

    kind, title = "sin_cos_swapped", "sin and cos swapped"

    def candidates(self, e):
        return _swap_candidates(e)

    def message(self, case, where, e, part):
        if part is None:
            return f"In entry {where} sin and cos are swapped: it is {case.notation.text(e)}."
        partner = (sp.sin if isinstance(part, sp.cos) else sp.cos)(part.args[0])
        return (
            f"In entry {where} sin and cos of the same angle are swapped "
            f"({case.notation.text(part)} and {case.notation.text(partner)}): "
            f"it is {case.notation.text(e)}."
        )


def _cell(name: str, value: sp.Expr, table: DHTable) -> str:
    if name in ("theta", "alpha"):
        from dhsym.table import AngleUnit

        return format_angle(value, table.angles is AngleUnit.DEG, latex=False)
    number = value.subs(table.value_map)
    if value.free_symbols and not number.free_symbols:
        return f"{sp.sstr(value)} (= {float(number):g})"
    return sp.sstr(value)


class SingleWrongRow(Mistake):
    """All rows right but one: that row is named with the cells that differ."""

    kind, title = "single_wrong_row", "one wrong row"

    def explain_table(self, case):
        key, ans = case.key, case.answer
        if key.n != ans.n:
            return None
        for k in range(key.n):
            rows = tuple(ans.rows[k] if j == k else r for j, r in enumerate(key.rows))
            if not same_cells(Chain(rows, key.convention), ans, case.values):
                continue
            if same_cells(
                Chain((key.rows[k],), key.convention),
                Chain((ans.rows[k],), key.convention),
                case.values,
            ):
                continue
            wrong = [
                n
                for n in ("theta", "d", "a", "alpha")
                if not same_cells(
                    *(_one(t.rows[k], n, key.convention) for t in (key, ans)), case.values
                )
            ]
            if ans.rows[k].joint is not key.rows[k].joint:
                wrong = ["type"]
            cells = ", ".join(
                f"{n} should be {_cell(n, getattr(key.rows[k], n), key)}"
                if n != "type"
                else f"the joint is {key.rows[k].joint.name.lower()}"
                for n in wrong
            )
            return Diagnosis(
                self.kind, self.title, f"Row {k + 1} is wrong: {cells}.", rows=(k + 1,)
            )
        return None


def _one(row: DHRow, name: str, convention: Convention) -> Chain:
    """A one-row chain with only cell ``name`` of ``row`` kept (the others zeroed)."""
    keep = {
        n: (getattr(row, n) if n == name else sp.Integer(0)) for n in ("theta", "d", "a", "alpha")
    }
    joint = JointType.FIXED
    return Chain((DHRow(joint, keep["theta"], keep["d"], keep["a"], keep["alpha"]),), convention)


MATRIX_MISTAKES: tuple[Mistake, ...] = (
    Transposed(),
    OtherConvention(),
    ReverseOrder(),
    IndexShift(),
    OffsetMissing(),
    DegreesAsRadians(),
)
ENTRY_MISTAKES: tuple[Mistake, ...] = (WrongSign(), SinCosSwapped())
TABLE_MISTAKES: tuple[Mistake, ...] = (
    OtherConvention(),
    IndexShift(),
    OffsetMissing(),
    DegreesAsRadians(),
    WrongSign(),
    SingleWrongRow(),
)


def diagnose_matrix(case: MatrixCase) -> tuple[Diagnosis, ...]:
    """Explain a wrong matrix: one mistake for all wrong entries, else entry by entry."""
    for m in MATRIX_MISTAKES:
        d = m.explain_matrix(case)
        if d is not None:
            return (d,)
    found, left = [], list(case.wrong)
    for m in (*ENTRY_MISTAKES, *MATRIX_MISTAKES):
        if not left:
            break
        sub = replace(case, wrong=tuple(left))
        d = m.explain_matrix(sub, partial=True)
        if d is not None:
            found.append(d)
            done = set(d.entries)
            left = [p for p in left if case.label(p) not in done]
    if left:
        where = ", ".join(case.where(p) for p in left)
        found.append(
            Diagnosis(
                "unexplained",
                "wrong entry",
                (
                    f"Entry {where} is wrong and none of the usual mistakes explains it: "
                    "compare it "
                    "with the correct entry below, term by term."
                ),
                tuple(case.label(p) for p in left),
            )
        )
    return tuple(found)


def diagnose_table(case: TableCase) -> tuple[Diagnosis, ...]:
    """Explain a wrong table with the first table mistake that reproduces it."""
    for m in TABLE_MISTAKES:
        d = m.explain_table(case)
        if d is not None:
            return (d,)
    return ()
