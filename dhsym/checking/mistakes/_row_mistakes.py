"""Mistakes in reading the table's rows: each rewrites the rows, then recomputes.

α and a taken from the neighbouring row, a joint offset left out, degrees read as
radians (or back), and, for tables only, one wrong row named with its wrong cells; two of
these slips in one table, both named (:func:`explain_table_pairs`).

Examples
--------
>>> import dhsym
>>> rows = dhsym.load("puma560_modified").table.rows
>>> [str(r.alpha) for r in rows][:4], [str(r.alpha) for r in shifted(rows, 1, ("alpha",))][:3]
(['0', '-pi/2', '0', '-pi/2'], ['-pi/2', '0', '-pi/2'])
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import replace
from typing import TypeAlias, cast

import numpy as np
import sympy as sp

from dhsym.model.table import Convention, DHRow, DHTable, JointType

from ..comparing.table_match import Chain, same_cells
from ..comparing.verdict import Diagnosis
from ..reading.limits import check_time
from ._entry_mistakes import PAIR_BUDGET
from ._mistake_base import (
    MatrixCase,
    Mistake,
    RowFilter,
    RowMemo,
    Rows,
    TableCase,
    TableEdit,
    cell_text,
)

__all__ = [
    "DegreesAsRadians",
    "IndexShift",
    "OffsetMissing",
    "SingleWrongRow",
    "explain_table_pairs",
    "shifted",
]


def shifted(rows: tuple[DHRow, ...], step: int, names: tuple[str, ...]) -> tuple[DHRow, ...]:
    """The rows with the cells ``names`` taken from row ``k + step`` (zero past the ends; a
    row whose cells those are already is kept as it is)."""
    out = []
    for k, row in enumerate(rows):
        src = k + step
        new = {n: (getattr(rows[src], n) if 0 <= src < len(rows) else sp.Integer(0)) for n in names}
        same = all(getattr(row, n) == v for n, v in new.items())
        out.append(row if same else replace(row, **new))
    return tuple(out)


class _RowRewrite(Mistake):
    """A mistake that rewrites the key's rows (:meth:`_rewrites`), then recomputes: the
    matrix of the rewritten rows, the rewritten table, and its slips in a pair."""

    def _rewrites(
        self,
        rows: Rows,
        key: Rows,
        convention: Convention,
        table: bool,
        within: RowFilter,
        memo: RowMemo | None = None,
    ) -> Iterator[TableEdit]:
        """``rows`` under this mistake (the entries named as the ``key``'s rows have
        them; ``table``: a table's variants, else a matrix's), each with what the student
        did and the 1-based rows a table's diagnosis names; only the variants that rewrite
        rows in ``within`` (1-based; None: all) need be given (``memo``: the rows rewritten
        so far in this diagnosis)."""
        raise NotImplementedError

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        for rows, detail, _ in self._rewrites(case.rows, case.rows, case.convention, False, None):
            yield case.chain_values(rows, case.convention), detail

    def table_variants(self, case: TableCase) -> Iterator[tuple[Chain, str, tuple[int, ...]]]:
        key, conv = tuple(case.key.rows), case.key.convention
        for rows, detail, where in self._rewrites(key, key, conv, True, None):
            yield Chain(rows, conv), detail, where

    def table_edits(
        self,
        rows: Rows,
        key: DHTable,
        within: RowFilter = None,
        touching: RowFilter = None,
        memo: RowMemo | None = None,
    ) -> Iterator[TableEdit]:
        conv = key.convention
        for new, detail, _ in self._rewrites(rows, tuple(key.rows), conv, True, within, memo):
            yield from _kept(rows, new, detail, within, touching)


class IndexShift(_RowRewrite):
    """α and a taken from the neighbouring row (α_i where α_{i-1} belongs, or back)."""

    kind, title = "index_shift", "α/a index shifted by one row"

    def _rewrites(
        self,
        rows: Rows,
        key: Rows,
        convention: Convention,
        table: bool,
        within: RowFilter,
        memo: RowMemo | None = None,
    ) -> Iterator[TableEdit]:
        own = "α_{i-1}, a_{i-1}" if convention is Convention.MODIFIED else "α_i, a_i"
        for step in (1, -1):
            for names in (("alpha", "a"), ("alpha",)):
                what = "α and a" if len(names) == 2 else "α"
                yield (
                    shifted(rows, step, names),
                    (
                        f"{what} come from the {'next' if step == 1 else 'previous'} row: in the "
                        f"{convention.value} convention row i holds {own}."
                    ),
                    (),
                )


def _changed(before: tuple[DHRow, ...], after: tuple[DHRow, ...]) -> tuple[int, ...]:
    """The 1-based rows an edit rewrote."""
    return tuple(k + 1 for k, (b, a) in enumerate(zip(before, after, strict=True)) if b != a)


def _kept(
    before: tuple[DHRow, ...],
    after: tuple[DHRow, ...],
    detail: str,
    within: frozenset[int] | None,
    touching: frozenset[int] | None,
) -> Iterator[TableEdit]:
    """The edit (rows, detail, the rows it rewrote) unless it rewrites a row outside
    ``within`` or none of ``touching``."""
    where = _changed(before, after)
    if (within is None or within.issuperset(where)) and (
        touching is None or not touching.isdisjoint(where)
    ):
        yield after, detail, where


def _no_offset(row: DHRow) -> DHRow:
    if row.variable is None or row.offset == 0:
        return row
    if row.variable_field == "theta":
        return replace(row, theta=row.variable)
    return replace(row, d=row.variable)


class OffsetMissing(_RowRewrite):
    """A constant joint offset (θ3 + π/2) left out."""

    kind, title = "offset_missing", "joint offset missing"

    def _rewrites(
        self,
        rows: Rows,
        key: Rows,
        convention: Convention,
        table: bool,
        within: RowFilter,
        memo: RowMemo | None = None,
    ) -> Iterator[TableEdit]:
        """The offsets of ``rows`` left out, all and one by one; the entries are named as
        the ``key``'s rows (not ``rows``, when they are under another slip) have them."""
        with_offset = [k for k, r in enumerate(rows) if r.variable is not None and r.offset != 0]
        if not with_offset or not any(_inside([k], within) for k in with_offset):
            return
        # rows with a variable are joint rows, whose variable_field is "theta" or "d"
        names = ", ".join(
            f"row {k + 1}: {sp.sstr(getattr(key[k], cast(str, key[k].variable_field)))}"
            for k in with_offset
        )
        if _inside(with_offset, within):
            yield (
                tuple(_no_offset(r) for r in rows),
                (f"The joint offset is missing ({names}): the variable alone is not the entry."),
                tuple(k + 1 for k in with_offset),
            )
        for k in with_offset:
            if not _inside([k], within):
                continue
            yield (
                tuple(_no_offset(r) if j == k else r for j, r in enumerate(rows)),
                (
                    f"The joint offset of row {k + 1} is missing: the entry is "
                    f"{sp.sstr(getattr(key[k], cast(str, key[k].variable_field)))}."
                ),
                (k + 1,),
            )


def _inside(rows: list[int], within: frozenset[int] | None) -> bool:
    """True when the 0-based ``rows`` are all in ``within`` (1-based; None: any)."""
    return within is None or all(k + 1 in within for k in rows)


def _angle_terms(expr: sp.Expr, factor: sp.Expr) -> sp.Expr:
    return sp.Add(*[t if t.free_symbols else t * factor for t in sp.Add.make_args(expr)])


class DegreesAsRadians(_RowRewrite):
    """An angle in degrees used as radians (cos 90 for cos 90°), or the other way round."""

    kind, title = "degrees_as_radians", "degrees read as radians"

    def _rewrites(
        self,
        rows: Rows,
        key: Rows,
        convention: Convention,
        table: bool,
        within: RowFilter,
        memo: RowMemo | None = None,
    ) -> Iterator[TableEdit]:
        """All rows' angles, then one row's (the degrees in one row of a table; with
        ``table``, then the radians written in one row of a table in degrees); only the
        variants that rewrite rows in ``within`` (1-based; None: all).

        A table's rows are those with a constant angle (a fixed θ or α of any joint); a
        matrix's, as before, the rows with a joint angle (a prismatic row's α is scaled
        only with all rows).
        """

        def constant(r: DHRow) -> bool:  # what the scaling rewrites
            return _has_constant(r.alpha) or _has_constant(r.theta)

        def joint_angle(r: DHRow) -> bool:
            return _has_variable(r.alpha) or _has_variable(r.theta)

        one = constant if table else joint_angle
        rows_one = [k for k, r in enumerate(rows) if one(r)]
        if not rows_one:
            return
        rows_all = [k for k, r in enumerate(rows) if constant(r)]
        both = (
            (180 / sp.pi, "An angle in degrees was used as radians (cos 90 is not cos 90°)."),
            (sp.pi / 180, "An angle in radians was read as degrees (1.57° is not 90°)."),
        )
        if _inside(rows_all, within):
            for factor, detail in both:
                yield tuple(_scaled(r, factor, memo) for r in rows), detail, ()
        for factor, detail in both if table else both[:1]:
            for k in rows_one:
                if not _inside([k], within):
                    continue
                yield (
                    tuple(_scaled(r, factor, memo) if j == k else r for j, r in enumerate(rows)),
                    f"Row {k + 1}: {detail}",
                    (k + 1,),
                )


def _has_constant(expr: sp.Expr) -> bool:
    """True when ``expr`` has a constant term (``_angle_terms(expr, 0) != expr``), without
    building the sum when every term has a symbol (the sum of its own terms is ``expr``).

    >>> q = sp.Symbol("q")
    >>> [_has_constant(e) for e in (q, q + sp.pi / 2, sp.pi / 2, sp.Integer(0), 2 * q)]
    [False, True, True, False, False]
    """
    if all(t.free_symbols for t in sp.Add.make_args(expr)):
        return False
    return bool(_angle_terms(expr, 0) != expr)


def _has_variable(expr: sp.Expr) -> bool:
    """True when ``expr`` has a term with a symbol (``_angle_terms(expr, 0) != 0``), without
    building the sum when no term or every term has one.

    >>> q = sp.Symbol("q")
    >>> [_has_variable(e) for e in (q, q + sp.pi / 2, sp.pi / 2, sp.Integer(0), 2 * q)]
    [True, True, False, False, True]
    """
    terms = [bool(t.free_symbols) for t in sp.Add.make_args(expr)]
    if all(terms) or not any(terms):
        return all(terms)
    return bool(_angle_terms(expr, 0) != 0)


def _scaled(row: DHRow, factor: sp.Expr, memo: RowMemo | None = None) -> DHRow:
    """``row`` with the constant parts of θ and α multiplied by ``factor`` (``row`` itself
    when it has none: the same row), taken from ``memo`` when this diagnosis scaled the same
    row object by ``factor`` before (and kept there)."""
    done = memo.get((id(row), factor)) if memo is not None else None
    if done is not None:
        return done[1]
    if not _has_constant(row.theta) and not _has_constant(row.alpha):
        new = row
    else:
        theta, alpha = _angle_terms(row.theta, factor), _angle_terms(row.alpha, factor)
        new = replace(row, theta=theta, alpha=alpha)
    if memo is not None:  # a row without a constant angle is kept too: it is itself
        memo[(id(row), factor)] = (row, new)
    return new


class SingleWrongRow(Mistake):
    """All rows right but one: that row is named with the cells that differ."""

    kind, title = "single_wrong_row", "one wrong row"

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        key, ans = case.key, case.answer
        if key.n != ans.n:
            return None
        for k in range(key.n):
            rows = tuple(ans.rows[k] if j == k else r for j, r in enumerate(key.rows))
            if not same_cells(
                Chain(rows, key.convention), ans, case.values, verdicts=case.verdicts
            ):
                continue
            if _same_row(key.rows[k], ans.rows[k], key.convention, case.values):
                continue
            wrong = _wrong_cells(key.rows[k], ans.rows[k], key.convention, case.values)
            return Diagnosis(
                self.kind,
                self.title,
                f"Row {k + 1} is wrong: {_cells_text(key, k, wrong)}.",
                rows=(k + 1,),
            )
        return None


def _same_row(
    right: DHRow, given: DHRow, convention: Convention, values: Mapping[sp.Symbol, sp.Expr]
) -> bool:
    """True when two rows have the same cells (a one-row :func:`same_cells`)."""
    return same_cells(Chain((right,), convention), Chain((given,), convention), values)


def _wrong_cells(
    right: DHRow, given: DHRow, convention: Convention, values: Mapping[sp.Symbol, sp.Expr]
) -> list[str]:
    """The cells of ``given`` that differ from ``right`` (``["type"]``: the joint's kind)."""
    if given.joint is not right.joint:
        return ["type"]
    return [
        n
        for n in ("theta", "d", "a", "alpha")
        if not same_cells(_one(right, n, convention), _one(given, n, convention), values)
    ]


def _cells_text(
    key: DHTable, k: int, wrong: list[str], under: tuple[DHRow, ...] | None = None
) -> str:
    """``theta should be θ2, a should be a2``: row ``k``'s wrong cells as the key has them
    (and, for a cell another slip rewrote in ``under``, as that slip has it)."""
    out = []
    for n in wrong:
        if n == "type":
            out.append(f"the joint is {key.rows[k].joint.name.lower()}")
            continue
        right = getattr(key.rows[k], n)
        text = f"{n} should be {cell_text(n, right, key)}"
        if under is not None and getattr(under[k], n) != right:
            text += f" ({cell_text(n, getattr(under[k], n), key)} with the other slip)"
        out.append(text)
    return ", ".join(out)


def _one(row: DHRow, name: str, convention: Convention) -> Chain:
    """A one-row chain with only cell ``name`` of ``row`` kept (the others zeroed)."""
    keep = {
        n: (getattr(row, n) if n == name else sp.Integer(0)) for n in ("theta", "d", "a", "alpha")
    }
    joint = JointType.FIXED
    return Chain((DHRow(joint, keep["theta"], keep["d"], keep["a"], keep["alpha"]),), convention)


#: (the kind, its title, what the student did, the rows it names) of one slip of a pair
_Slip: TypeAlias = tuple[str, str, str, tuple[int, ...]]


def explain_table_pairs(
    case: TableCase,
    mistakes: tuple[Mistake, ...],
    budget: int = PAIR_BUDGET,
) -> tuple[Diagnosis, ...]:
    """Two catalogued slips that together give the answer's table, both named (a twist's
    sign flipped in one row and the degrees written as radians, an index shift and an
    offset left out, two slips of one kind in two rows), or ``()``.

    Each slip of ``mistakes`` (their :meth:`~Mistake.table_edits`) is applied to the key's
    rows and each slip of the same or a later kind to the result (two of one kind only in
    different rows); a pair is compared with the answer only when the rows the two slips
    rewrite cover every row the answer has wrong; the first rewrites one of them (a slip
    the other undoes is not in the answer), the second only rows the answer has wrong or
    the first rewrote. Then the second slip is one wrong cell in one row
    (:class:`SingleWrongRow` with a single cell; not the only cell the first slip rewrote),
    after a slip of ``mistakes``, or after another wrong cell in another row. At most ``budget``
    tables are compared with the answer (a count, not a time: the diagnosis does not
    depend on the machine's load).

    >>> import dhsym
    >>> from dataclasses import replace
    >>> from dhsym.checking.mistakes.registry import TABLE_PAIR_MISTAKES
    >>> key = dhsym.load_table("puma560")
    >>> rows = list(key.rows)
    >>> rows[2] = replace(rows[2], alpha=sp.Integer(90))  # -90° flipped, and no ° mark
    >>> found = explain_table_pairs(TableCase(key, Chain(tuple(rows), key.convention)),
    ...                             TABLE_PAIR_MISTAKES)
    >>> [(d.kind, d.rows) for d in found]
    [('degrees_as_radians', (3,)), ('wrong_sign', (3,))]
    """
    key, ans = case.key, case.answer
    if key.n != ans.n or ans.convention is not key.convention:
        return ()
    base, conv = tuple(key.rows), key.convention
    bad = {k + 1 for k in range(key.n) if not _same_row(base[k], ans.rows[k], conv, case.values)}
    if not bad:
        return ()
    left = budget
    memo: RowMemo = {}  # the rows the slips rewrote, each built once in this diagnosis
    # each slip is seen in the answer: it rewrites a row the answer has wrong
    firsts = [
        (m, [e for e in m.table_edits(base, key, None, frozenset(bad), memo) if e[0] != base])
        for m in mistakes
    ]
    for i, (a, edits_a) in enumerate(firsts):
        for b, _ in firsts[i:]:
            for rows_a, detail_a, where_a in edits_a:
                check_time()
                # the second slip rewrites only rows the answer has wrong or the first
                # rewrote (it may put one of those back); of the same kind, only other rows
                within = frozenset(bad - set(where_a) if a is b else bad | set(where_a))
                need = frozenset(bad - set(where_a))  # the second slip rewrites these
                if not within:
                    continue
                second = b.table_edits(rows_a, key, within, need or None, memo)
                for rows_b, detail_b, where_b in second:
                    if not bad <= set(where_a) | set(where_b) or rows_b == base:
                        continue
                    left -= 1
                    if left < 0:
                        return ()
                    if same_cells(Chain(rows_b, conv), ans, case.values, verdicts=case.verdicts):
                        return _pair(
                            (a.kind, a.title, detail_a, where_a),
                            (b.kind, b.title, detail_b, where_b),
                        )
    starts: list[tuple[_Slip | None, tuple[DHRow, ...]]] = [
        ((m.kind, m.title, e[1], e[2]), e[0]) for m, edits in firsts for e in edits
    ]
    starts.append((None, base))  # two rows with one wrong cell each: the least named
    for first, rows in starts:
        check_time()
        left -= 1
        if left < 0:
            return ()
        found = _one_wrong_cell(case, rows, first, bad)
        if found:
            return found
    return ()


def _one_wrong_cell(
    case: TableCase, rows: tuple[DHRow, ...], first: _Slip | None, bad: set[int]
) -> tuple[Diagnosis, ...]:
    """The pair of ``first`` (None: one wrong cell in another row) and one wrong cell in
    one row, when it gives the answer from ``rows`` (the key's rows under ``first``;
    ``bad``: the 1-based rows where the answer differs from the key)."""
    key, ans, conv = case.key, case.answer, case.key.convention
    touched = set(first[3]) if first is not None else set()
    differ = [
        k
        for k in range(key.n)
        if (
            k + 1 in bad
            if k + 1 not in touched
            else not _same_row(rows[k], ans.rows[k], conv, case.values)
        )
    ]
    if len(differ) != (1 if first is not None else 2):
        return ()
    cells = [_wrong_cells(rows[k], ans.rows[k], conv, case.values) for k in differ]
    if any(len(c) != 1 for c in cells):
        return ()
    if any(c == ["type"] for c in cells):
        return ()
    slipped = {
        (k, n)
        for k in range(key.n)
        for n in ("theta", "d", "a", "alpha")
        if getattr(rows[k], n) != getattr(key.rows[k], n)
    }
    if first is not None and slipped <= {(k, c[0]) for k, c in zip(differ, cells, strict=True)}:
        return ()  # the wrong cell overwrites all the first slip wrote: that slip is not there
    fixed = tuple(ans.rows[j] if j in differ else r for j, r in enumerate(rows))
    if not same_cells(Chain(fixed, conv), ans, case.values, verdicts=case.verdicts):
        return ()
    title = SingleWrongRow.title
    slips = [
        (
            SingleWrongRow.kind,
            title,
            f"Row {k + 1} is wrong: {_cells_text(key, k, c, rows)}.",
            (k + 1,),
        )
        for k, c in zip(differ, cells, strict=True)
    ]
    return _pair(first if first is not None else slips.pop(0), slips[0])


def _pair(a: _Slip, b: _Slip) -> tuple[Diagnosis, Diagnosis]:
    """The two diagnoses of a pair of slips, each naming the other."""
    if a[0] == b[0]:
        tail_a = " (One of two slips of this kind in this table.)"
        tail_b = " (The second slip of this kind in this table.)"
    else:
        tail_a = f" (One of two slips in this table; the other: {b[1]}.)"
        tail_b = f" (The second slip in this table, with: {a[1]}.)"
    return (
        Diagnosis(a[0], a[1], a[2] + tail_a, rows=a[3]),
        Diagnosis(b[0], b[1], b[2] + tail_b, rows=b[3]),
    )
