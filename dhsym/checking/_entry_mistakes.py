"""Mistakes inside single entries: a wrong sign, sin and cos swapped.

Unlike the other kinds, these rewrite the key's *entries* (one term at a time, or
one angle at a time) instead of recomputing the whole product; a wrong sign is
also looked for cell by cell in a table.

Examples
--------
>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> [c for c, _ in sign_candidates(x - y)]
[-x + y, -x - y, x + y]
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace

import sympy as sp

from ._mistake_base import MatrixCase, Mistake, cell_text
from .equivalence import close, values
from .tables import Chain, same_cells
from .verdict import Diagnosis

__all__ = ["EntryMistake", "SinCosSwapped", "WrongSign", "sign_candidates", "swap_candidates"]

_MAX_CANDIDATES = 24


def sign_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, str | None]]:
    """``e`` with its sign flipped, then with one term's sign flipped (and that term)."""
    yield -e, None
    terms = sp.Add.make_args(e)
    if len(terms) > 1:
        for t in terms[:_MAX_CANDIDATES]:
            yield e - 2 * t, t


def swap_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, str | None]]:
    """``e`` with sin and cos swapped: all, those of one angle, or one factor (and which)."""
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


class EntryMistake(Mistake):
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


class WrongSign(EntryMistake):
    """An entry, or one term of it, with the wrong sign (as the +d_i sin α_{i-1} that one
    slide of Mohan, Lecture 9, prints)."""

    kind, title = "wrong_sign", "wrong sign"

    def candidates(self, e):
        return sign_candidates(e)

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
                    shown = cell_text(name, value, key)
                    return Diagnosis(
                        self.kind,
                        self.title,
                        f"Row {k + 1}: {name} has the wrong sign; it is {shown}.",
                        rows=(k + 1,),
                    )
        return None


class SinCosSwapped(EntryMistake):
    """sin written where cos belongs (or the other way round)."""

    kind, title = "sin_cos_swapped", "sin and cos swapped"

    def candidates(self, e):
        return swap_candidates(e)

    def message(self, case, where, e, part):
        if part is None:
            return f"In entry {where} sin and cos are swapped: it is {case.notation.text(e)}."
        partner = (sp.sin if isinstance(part, sp.cos) else sp.cos)(part.args[0])
        return (
            f"In entry {where} sin and cos of the same angle are swapped "
            f"({case.notation.text(part)} and {case.notation.text(partner)}): "
            f"it is {case.notation.text(e)}."
        )
