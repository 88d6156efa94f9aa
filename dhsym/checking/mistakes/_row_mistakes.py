"""Mistakes in reading the table's rows: each rewrites the rows, then recomputes.

α and a taken from the neighbouring row, a joint offset left out, degrees read as
radians (or back), and, for tables only, one wrong row named with its wrong cells.

Examples
--------
>>> import dhsym
>>> rows = dhsym.load("puma560_modified").table.rows
>>> [str(r.alpha) for r in rows][:4], [str(r.alpha) for r in shifted(rows, 1, ("alpha",))][:3]
(['0', '-pi/2', '0', '-pi/2'], ['-pi/2', '0', '-pi/2'])
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from typing import cast

import numpy as np
import sympy as sp

from dhsym.model.table import Convention, DHRow, JointType

from ..comparing.table_match import Chain, same_cells
from ..comparing.verdict import Diagnosis
from ._mistake_base import MatrixCase, Mistake, TableCase, cell_text

__all__ = ["DegreesAsRadians", "IndexShift", "OffsetMissing", "SingleWrongRow", "shifted"]


def shifted(rows: tuple[DHRow, ...], step: int, names: tuple[str, ...]) -> tuple[DHRow, ...]:
    """The rows with the cells ``names`` taken from row ``k + step`` (zero past the ends)."""
    out = []
    for k, row in enumerate(rows):
        src = k + step
        new = {n: (getattr(rows[src], n) if 0 <= src < len(rows) else sp.Integer(0)) for n in names}
        out.append(replace(row, **new))
    return tuple(out)


class IndexShift(Mistake):
    """α and a taken from the neighbouring row (α_i where α_{i-1} belongs, or back)."""

    kind, title = "index_shift", "α/a index shifted by one row"

    def _variants(
        self, rows: tuple[DHRow, ...], convention: Convention
    ) -> Iterator[tuple[tuple[DHRow, ...], str]]:
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
                )

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        for rows, detail in self._variants(case.rows, case.convention):
            yield case.chain_values(rows, case.convention), detail

    def table_variants(self, case: TableCase) -> Iterator[tuple[Chain, str, tuple[int, ...]]]:
        for rows, detail in self._variants(case.key.rows, case.key.convention):
            yield Chain(rows, case.key.convention), detail, ()


def _no_offset(row: DHRow) -> DHRow:
    if row.variable is None or row.offset == 0:
        return row
    if row.variable_field == "theta":
        return replace(row, theta=row.variable)
    return replace(row, d=row.variable)


class OffsetMissing(Mistake):
    """A constant joint offset (θ3 + π/2) left out."""

    kind, title = "offset_missing", "joint offset missing"

    def _variants(
        self, rows: tuple[DHRow, ...]
    ) -> Iterator[tuple[tuple[DHRow, ...], str, tuple[int, ...]]]:
        with_offset = [k for k, r in enumerate(rows) if r.variable is not None and r.offset != 0]
        if not with_offset:
            return
        # rows with a variable are joint rows, whose variable_field is "theta" or "d"
        names = ", ".join(
            f"row {k + 1}: {sp.sstr(getattr(rows[k], cast(str, rows[k].variable_field)))}"
            for k in with_offset
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
                    f"{sp.sstr(getattr(rows[k], cast(str, rows[k].variable_field)))}."
                ),
                (k + 1,),
            )

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        for rows, detail, _ in self._variants(case.rows):
            yield case.chain_values(rows, case.convention), detail

    def table_variants(self, case: TableCase) -> Iterator[tuple[Chain, str, tuple[int, ...]]]:
        for rows, detail, where in self._variants(case.key.rows):
            yield Chain(rows, case.key.convention), detail, where


def _angle_terms(expr: sp.Expr, factor: sp.Expr) -> sp.Expr:
    return sp.Add(*[t if t.free_symbols else t * factor for t in sp.Add.make_args(expr)])


class DegreesAsRadians(Mistake):
    """An angle in degrees used as radians (cos 90 for cos 90°), or the other way round."""

    kind, title = "degrees_as_radians", "degrees read as radians"

    def _variants(
        self, rows: tuple[DHRow, ...]
    ) -> Iterator[tuple[tuple[DHRow, ...], str, tuple[int, ...]]]:
        """All rows' angles, then one row's (the degrees in one row of a table)."""
        if not any(_angle_terms(r.alpha, 0) != 0 or _angle_terms(r.theta, 0) != 0 for r in rows):
            return
        both = (
            (180 / sp.pi, "An angle in degrees was used as radians (cos 90 is not cos 90°)."),
            (sp.pi / 180, "An angle in radians was read as degrees (1.57° is not 90°)."),
        )
        for factor, detail in both:
            yield tuple(_scaled(r, factor) for r in rows), detail, ()
        for k, row in enumerate(rows):
            if _angle_terms(row.alpha, 0) == 0 and _angle_terms(row.theta, 0) == 0:
                continue
            factor, detail = both[0]
            yield (
                tuple(_scaled(r, factor) if j == k else r for j, r in enumerate(rows)),
                f"Row {k + 1}: {detail}",
                (k + 1,),
            )

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        for rows, detail, _ in self._variants(case.rows):
            yield case.chain_values(rows, case.convention), detail

    def table_variants(self, case: TableCase) -> Iterator[tuple[Chain, str, tuple[int, ...]]]:
        for rows, detail, where in self._variants(case.key.rows):
            yield Chain(rows, case.key.convention), detail, where


def _scaled(row: DHRow, factor: sp.Expr) -> DHRow:
    """``row`` with the constant parts of θ and α multiplied by ``factor``."""
    return replace(
        row, theta=_angle_terms(row.theta, factor), alpha=_angle_terms(row.alpha, factor)
    )


class SingleWrongRow(Mistake):
    """All rows right but one: that row is named with the cells that differ."""

    kind, title = "single_wrong_row", "one wrong row"

    def explain_table(self, case: TableCase) -> Diagnosis | None:
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
                    _one(key.rows[k], n, key.convention),
                    _one(ans.rows[k], n, key.convention),
                    case.values,
                )
            ]
            if ans.rows[k].joint is not key.rows[k].joint:
                wrong = ["type"]
            cells = ", ".join(
                f"{n} should be {cell_text(n, getattr(key.rows[k], n), key)}"
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
