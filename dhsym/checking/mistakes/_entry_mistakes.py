"""Mistakes inside single entries, one edit at any depth of the key's entry.

A wrong sign (of the entry, or of one term of a bracket however deep), a dropped
term, sin and cos swapped (everywhere, for one angle, or in one factor), a wrong
joint index in a sum angle (``C12`` for ``C23``), a missing length factor
(``C2`` for ``a2 C2``). Unlike the other kinds, these rewrite the key's *entries*
instead of recomputing the whole product; a wrong sign is also looked for cell by
cell in a table. The student may have expanded or factored the entry: candidates
are compared by value at the sample points, not by form.

Examples
--------
>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> [c for c, _ in sign_candidates(x - y)]
[-x + y, -x - y, x + y]
>>> a, b, c = sp.symbols("a b c")
>>> sorted(map(str, (e for e, _ in sign_candidates(a * (b - c)))))[:3]
['-a*(b - c)', '-a*b - a*c', 'a*(-b - c)']
>>> sorted({str(e) for e, _ in dropped_candidates(a * (b - c) + x)})
['-a*c + x', 'a*(b - c)', 'a*b + x', 'a*b - a*c', 'x']
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import replace
from typing import TypeAlias, TypeVar, cast

import sympy as sp

from ..comparing.equivalence import close, values
from ..comparing.table_match import Chain, same_cells
from ..comparing.verdict import Diagnosis
from ._mistake_base import MatrixCase, Mistake, TableCase, cell_text

__all__ = [
    "DroppedTerm",
    "EntryMistake",
    "MissingLength",
    "SinCosSwapped",
    "WrongJointIndex",
    "WrongSign",
    "dropped_candidates",
    "one_edit",
    "sign_candidates",
    "swap_candidates",
]

_MAX_CANDIDATES = 24
_MAX_EDITS = 400

Part = TypeVar("Part")
#: A rewrite of one node: yields (new node, what changed).
Edit: TypeAlias = Callable[[sp.Basic], Iterator[tuple[sp.Basic, Part]]]


def one_edit(
    e: sp.Basic, edit: Edit[Part], limit: int = _MAX_EDITS
) -> Iterator[tuple[sp.Expr, Part]]:
    """``e`` with one node rewritten by ``edit`` (which yields (new node, what changed)),
    at any depth; at most ``limit`` candidates.

    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> double = lambda n: iter([(2 * n, n)] if n.is_Symbol else [])
    >>> [str(c) for c, _ in one_edit(sp.cos(x) * y, double)]
    ['2*y*cos(x)', 'y*cos(2*x)']
    """

    def walk(node: sp.Basic) -> Iterator[tuple[sp.Basic, Part]]:
        yield from edit(node)
        if node.is_Atom:
            return
        for i, arg in enumerate(node.args):
            for new, part in walk(arg):
                args = list(node.args)
                args[i] = new
                yield node.func(*args), part

    for n, (cand, part) in enumerate(walk(e)):
        if n >= limit:
            return
        yield cand, part


def _forms(e: sp.Expr) -> list[sp.Expr]:
    """The entry as the key holds it, and expanded (a student may edit either form)."""
    expanded = sp.expand(e)
    return [e] if expanded == e else [e, expanded]


def sign_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, sp.Expr | None]]:
    """``e`` with its sign flipped, then with one term's sign flipped, at any depth (a term
    inside a bracket or a product), with that term."""
    yield -e, None

    def flip(node: sp.Basic) -> Iterator[tuple[sp.Basic, sp.Expr]]:
        if isinstance(node, sp.Add):
            for t in node.args[:_MAX_CANDIDATES]:
                yield node - 2 * t, t

    for form in _forms(e):
        yield from one_edit(form, flip)


def dropped_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, sp.Expr]]:
    """``e`` with one term of a sum left out, at any depth, with that term."""

    def drop(node: sp.Basic) -> Iterator[tuple[sp.Basic, sp.Expr]]:
        if isinstance(node, sp.Add):
            for t in node.args[:_MAX_CANDIDATES]:
                yield node - t, t

    for form in _forms(e):
        yield from one_edit(form, drop)


def swap_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, sp.Expr | None]]:
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

    def one(node: sp.Basic) -> Iterator[tuple[sp.Basic, sp.Expr]]:
        if isinstance(node, (sp.sin, sp.cos)):
            yield swap[node], node

    yield from one_edit(e, one)  # one factor where the same angle occurs several times


class EntryMistake(Mistake):
    """A mistake inside one entry: candidates are rewritten key entries."""

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        raise NotImplementedError

    def message(self, case: MatrixCase, where: str, e: sp.Expr, part: object) -> str:
        raise NotImplementedError

    def explain_matrix(self, case: MatrixCase, partial: bool = True) -> Diagnosis | None:
        hits: list[tuple[int, int]] = []
        details: list[str] = []
        for p in case.wrong:
            e = case.expected[p]
            for cand, part in self.candidates(e, case):
                if close(values(cand, case.sample), case.answer_values[:, p[0], p[1]]):
                    hits.append(case.label(p))
                    where = case.where(p) if len(case.expected) > 1 else "your answer"
                    details.append(_one_cell(self.message(case, where, e, part), where))
                    break
        if not hits:
            return None
        return Diagnosis(self.kind, self.title, " ".join(details), tuple(hits))

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        return None


def _one_cell(text: str, where: str) -> str:
    """The wording of a one-cell answer (an entry question, det J): "your answer", not
    "entry (1,1)"."""
    if where != "your answer":
        return text
    return text.replace("In entry your answer", "In your answer").replace(
        "Entry your answer has", "Your answer has"
    )


class WrongSign(EntryMistake):
    """An entry, or one term of it, with the wrong sign (as the +d_i sin α_{i-1} that one
    slide of Mohan, Lecture 9, prints)."""

    kind, title = "wrong_sign", "wrong sign"

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        return sign_candidates(e)

    def message(self, case: MatrixCase, where: str, e: sp.Expr, part: object) -> str:
        nota = case.notation
        if part is None:
            return f"Entry {where} has the wrong sign: it is {nota.text(e)}, not {nota.text(-e)}."
        inside = "" if part in sp.Add.make_args(e) else " (inside a bracket)"
        return f"In entry {where} the term {nota.text(part)} has the wrong sign{inside}."

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        key = case.key
        for k, row in enumerate(key.rows):
            for name, value in row.params().items():
                if value == 0 or name == row.variable_field and value == row.variable:
                    continue
                # name is the joint's own column here: the entry holds the joint variable
                variable = cast(sp.Expr, row.variable)
                flipped = -value if name != row.variable_field else 2 * variable - value
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

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        return swap_candidates(e)

    def message(self, case: MatrixCase, where: str, e: sp.Expr, part: object) -> str:
        if part is None:
            return f"In entry {where} sin and cos are swapped: it is {case.notation.text(e)}."
        factor = cast(sp.Basic, part)  # swap_candidates: None or the swapped sin/cos factor
        partner = (sp.sin if isinstance(factor, sp.cos) else sp.cos)(factor.args[0])
        return (
            f"In entry {where} sin and cos of the same angle are swapped "
            f"({case.notation.text(part)} and {case.notation.text(partner)}): "
            f"it is {case.notation.text(e)}."
        )


class DroppedTerm(EntryMistake):
    """One term of a sum left out (at any depth: a term of a bracket)."""

    kind, title = "dropped_term", "a term is missing"

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        return dropped_candidates(e)

    def message(self, case: MatrixCase, where: str, e: sp.Expr, part: object) -> str:
        return f"In entry {where} the term {case.notation.text(part)} is missing."


def _joints(case: MatrixCase) -> list[sp.Symbol]:
    """The revolute joints' angles, in joint order (what sum angles are made of)."""
    return [r.variable for r in case.rows if r.variable is not None and r.variable_field == "theta"]


def joint_index_candidates(
    e: sp.Expr, joints: list[sp.Symbol]
) -> Iterator[tuple[sp.Expr, tuple[sp.Basic, sp.Basic]]]:
    """``e`` with one sine or cosine of a sum angle on other joints (θ1 + θ2 for θ2 + θ3,
    one joint more or fewer), with (the wrong factor, the right one).

    >>> import sympy as sp
    >>> t1, t2, t3 = sp.symbols("theta1:4")
    >>> sorted(str(c) for c, _ in joint_index_candidates(sp.cos(t2 + t3), [t1, t2, t3]))
    ['cos(theta1 + theta2 + theta3)', 'cos(theta1 + theta2)', 'cos(theta1)', 'cos(theta2)',
     'cos(theta3)']
    """
    where = {v: k for k, v in enumerate(joints)}

    def change(node: sp.Basic) -> Iterator[tuple[sp.Basic, tuple[sp.Basic, sp.Basic]]]:
        if not isinstance(node, (sp.sin, sp.cos)):
            return
        arg = node.args[0]
        terms = sp.Add.make_args(arg)
        used = sorted(where[t] for t in terms if t in where)
        rest = sp.Add(*[t for t in terms if t not in where])
        if not used or rest.free_symbols or used != list(range(used[0], used[-1] + 1)):
            return
        seen = {tuple(used)}
        for size in (len(used), len(used) - 1, len(used) + 1):
            for start in range(max(0, used[0] - 2), min(len(joints), used[0] + 3)):
                run = tuple(range(start, start + size))
                if size < 1 or run[-1] >= len(joints) or run in seen:
                    continue
                seen.add(run)
                new = node.func(sp.Add(*[joints[j] for j in run]) + rest)
                yield new, (new, node)

    yield from one_edit(e, change)


class WrongJointIndex(EntryMistake):
    """A sum angle on the wrong joints: ``C12`` written where ``C23`` belongs."""

    kind, title = "wrong_joint_index", "wrong joint index in a sum angle"

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        return joint_index_candidates(e, _joints(case)) if case is not None else iter(())

    def message(self, case: MatrixCase, where: str, e: sp.Expr, part: object) -> str:
        # joint_index_candidates: (the wrong factor, the right one)
        pair = cast(tuple[sp.Basic, sp.Basic], part)
        wrong, right = (case.notation.text(x) for x in pair)
        return (
            f"In entry {where} {wrong} is written where {right} belongs: count the joints "
            "whose angles add up in that factor."
        )


def length_candidates(
    e: sp.Expr, joints: list[sp.Symbol]
) -> Iterator[tuple[sp.Expr, tuple[sp.Basic, sp.Basic]]]:
    """``e`` with one length factor left out of one product, with (the length, the product).

    >>> import sympy as sp
    >>> a2, t2 = sp.symbols("a2 theta2")
    >>> [str(c) for c, _ in length_candidates(a2 * sp.cos(t2) + 1, [t2])]
    ['cos(theta2) + 1']
    """
    skip = set(joints)

    def drop(node: sp.Basic) -> Iterator[tuple[sp.Basic, tuple[sp.Basic, sp.Basic]]]:
        if isinstance(node, sp.Mul):
            for f in node.args:
                if f.is_Symbol and f not in skip:
                    yield node / f, (f, node)

    yield from one_edit(e, drop)


class MissingLength(EntryMistake):
    """A length left out of one product (``C2`` for ``a2 C2``)."""

    kind, title = "missing_length", "a length factor is missing"

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        if case is None:
            return iter(())
        return length_candidates(e, [r.variable for r in case.rows if r.variable is not None])

    def message(self, case: MatrixCase, where: str, e: sp.Expr, part: object) -> str:
        length, product = cast(tuple[sp.Basic, sp.Basic], part)  # length_candidates' pair
        return (
            f"In entry {where} the length {case.notation.text(length)} is missing "
            f"from {case.notation.text(product)}."
        )
