"""Mistakes inside single entries, one edit at any depth of the key's entry.

A wrong sign (of the entry, or of one term of a bracket however deep), a dropped
term, sin and cos swapped (everywhere, for one angle, or in one factor), a wrong
joint index in a sum angle (``C12`` for ``C23``), a missing length factor
(``C2`` for ``a2 C2``). Unlike the other kinds, these rewrite the key's *entries*
instead of recomputing the whole product; a wrong sign is also looked for cell by
cell in a table. The student may have expanded or factored the entry: candidates
are compared by value at the sample points, not by form. Two slips in one entry are
found by what each changes (:func:`explain_pairs`).

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

from collections.abc import Callable, Iterable, Iterator
from dataclasses import replace
from itertools import islice
from typing import ClassVar, TypeAlias, TypeVar, cast

import numpy as np
import sympy as sp

from dhsym.model.table import DHTable

from ..comparing.equivalence import close, values
from ..comparing.table_match import Chain, same_cells
from ..comparing.verdict import Diagnosis
from ..reading.limits import check_time
from ._mistake_base import (
    MatrixCase,
    Mistake,
    RowFilter,
    RowMemo,
    Rows,
    TableCase,
    TableEdit,
    cell_text,
    listed,
)

__all__ = [
    "DroppedTerm",
    "EntryMistake",
    "MissingLength",
    "SinCosSwapped",
    "WrongJointIndex",
    "WrongSign",
    "PAIR_BUDGET",
    "dropped_candidates",
    "explain_pairs",
    "grouped",
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


#: One slip at one place of an entry: (the path from the entry's root to the node it
#: rewrites, by argument index; that node as the slip writes it; what changed, as the
#: kind's candidates tell it).
Site: TypeAlias = tuple[tuple[int, ...], sp.Basic, object]


def _walk(e: sp.Basic, path: tuple[int, ...] = ()) -> Iterator[tuple[tuple[int, ...], sp.Basic]]:
    """Every node of ``e`` with its path, in the order :func:`one_edit` visits them."""
    yield path, e
    if not e.is_Atom:
        for i, arg in enumerate(e.args):
            yield from _walk(arg, (*path, i))


def _forms(e: sp.Expr) -> list[sp.Expr]:
    """The entry as the key holds it, and expanded (a student may edit either form)."""
    expanded = sp.expand(e)
    return [e] if expanded == e else [e, expanded]


def _negated(t: sp.Expr) -> sp.Expr:
    """A term with its sign flipped."""
    return -t


def _left_out(t: sp.Expr) -> sp.Expr:
    """A term left out."""
    return sp.S.Zero


def _in_sum(rewrite: Callable[[sp.Expr], sp.Expr]) -> Edit[sp.Expr]:
    """The edit rewriting one term of a sum by ``rewrite``, with that term."""

    def edit(node: sp.Basic) -> Iterator[tuple[sp.Basic, sp.Expr]]:
        if isinstance(node, sp.Add):
            for t in node.args[:_MAX_CANDIDATES]:
                yield node - t + rewrite(t), t

    return edit


_flip, _drop = _in_sum(_negated), _in_sum(_left_out)


def _swap_one(node: sp.Basic) -> Iterator[tuple[sp.Basic, sp.Expr]]:
    """A sine as the cosine of its angle (or the other way round), with the factor."""
    if isinstance(node, (sp.sin, sp.cos)):
        yield (sp.cos if isinstance(node, sp.sin) else sp.sin)(node.args[0]), node


def sign_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, sp.Expr | None]]:
    """``e`` with its sign flipped, then with one term's sign flipped, at any depth (a term
    inside a bracket or a product), with that term."""
    yield -e, None
    for form in _forms(e):
        yield from one_edit(form, _flip)


def dropped_candidates(e: sp.Expr) -> Iterator[tuple[sp.Expr, sp.Expr]]:
    """``e`` with one term of a sum left out, at any depth, with that term."""
    for form in _forms(e):
        yield from one_edit(form, _drop)


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

    yield from one_edit(e, _swap_one)  # one factor where the same angle occurs several times


class EntryMistake(Mistake):
    """A mistake inside one entry: candidates are rewritten key entries.

    ``writes_trig``: the mistake may write a sine or cosine the key's entry does not have
    (the others only remove or keep them), which prunes the search of pairs.
    ``in_sums``: its one-place edit (:meth:`node_edit`) rewrites one term of a sum, and is
    placed at that term; ``whole``: the whole entry is one of its places (its sign).
    """

    writes_trig: ClassVar[bool] = False
    in_sums: ClassVar[bool] = False
    whole: ClassVar[bool] = False

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        raise NotImplementedError

    def node_edit(self, case: MatrixCase) -> Edit[object] | None:
        """The slip at one place of an entry (one node rewritten, as the candidates make
        it), for the search of two slips by their differences (:func:`explain_pairs`);
        None for a kind without one."""
        return None

    def sites(self, e: sp.Expr, case: MatrixCase) -> Iterator[Site]:
        """Each slip of this kind at one place of ``e`` (:data:`Site`), in the order of the
        candidates; the entry's sign (a sign's first candidate) is the place ``()``."""
        edit = self.node_edit(case)
        if edit is None:
            return
        if self.whole:
            yield (), -e, None
        for path, node in _walk(e):
            if self.in_sums:  # placed at the term
                if isinstance(node, sp.Add):
                    for k, t in enumerate(node.args[:_MAX_CANDIDATES]):
                        yield (*path, k), self.rewrite_term(t), t
                continue
            for new, part in edit(node):
                yield path, new, part

    def rewrite_term(self, t: sp.Expr) -> sp.Expr:
        """The term ``t`` of a sum as this slip writes it (a kind ``in_sums``)."""
        raise NotImplementedError

    def again(self, node: sp.Basic, part: object) -> sp.Basic | None:
        """The slip told by ``part`` made on ``node``, its place as another slip below it
        rewrote it, for a slip that scales its place (a sign, a length left out); None
        for the others."""
        return None

    def scale(self, part: object, case: MatrixCase) -> np.ndarray | float | None:
        """What :meth:`again` multiplies its place by, at the sample (None: no such slip)."""
        return None

    def message(self, case: MatrixCase, where: str, e: sp.Expr, part: object) -> str:
        raise NotImplementedError

    def explain_matrix(self, case: MatrixCase, partial: bool = True) -> Diagnosis | None:
        found: list[tuple[tuple[int, int], str]] = []
        for p in case.wrong:
            e = case.expected[p]
            for cand, part in self.candidates(e, case):
                if close(values(cand, case.sample), case.answer_values[:, p[0], p[1]]):
                    found.append((p, self.message(case, _HERE, e, part)))
                    break
        if not found:
            return None
        return Diagnosis(
            self.kind, self.title, grouped(case, found), tuple(case.label(p) for p, _ in found)
        )

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        return None


#: Where a message names its entry, filled in by :func:`grouped` (one entry or several).
_HERE = "\x00"


def grouped(case: MatrixCase, found: list[tuple[tuple[int, int], str]]) -> str:
    """The messages of one mistake, each said once: the same slip in several entries
    ("the length a2 is missing from a2*C2") names them together ("in entries (1,4) and
    (2,4)"); ``found`` holds (position, message with :data:`_HERE` for its entry).

    >>> from types import SimpleNamespace
    >>> case = SimpleNamespace(expected=[0, 0], where=lambda p: f"({p[0] + 1},{p[1] + 1})")
    >>> print(grouped(case, [((0, 3), f"In entry {_HERE} l2 is written for lc2."),
    ...                      ((1, 3), f"In entry {_HERE} l2 is written for lc2."),
    ...                      ((2, 3), f"Entry {_HERE} has the wrong sign.")]))
    In entries (1,4) and (2,4) l2 is written for lc2. Entry (3,4) has the wrong sign.
    """
    by_text: dict[str, list[tuple[int, int]]] = {}
    for p, text in found:
        by_text.setdefault(text, []).append(p)
    out = []
    for text, where in by_text.items():
        if len(case.expected) == 1:
            out.append(_one_cell(text))
        elif len(where) == 1:
            out.append(text.replace(_HERE, case.where(where[0])))
        else:
            names = listed([case.where(p) for p in where])
            text = text.replace(f"entry {_HERE}", f"entries {names}")
            text = text.replace(f"Entry {_HERE} has", f"Entries {names} have")
            out.append(text.replace(_HERE, names))
    return " ".join(out)


def _one_cell(text: str) -> str:
    """The wording of a one-cell answer (an entry question, det J): "your answer", not
    "entry (1,1)"."""
    return (
        text.replace(f"In entry {_HERE}", "In your answer")
        .replace(f"Entry {_HERE} has", "Your answer has")
        .replace(_HERE, "your answer")
    )


class WrongSign(EntryMistake):
    """An entry, or one term of it, with the wrong sign (as the +d_i sin α_{i-1} that one
    slide of Mohan, Lecture 9, prints)."""

    kind, title = "wrong_sign", "wrong sign"
    in_sums = whole = True

    def node_edit(self, case: MatrixCase) -> Edit[object] | None:
        return _flip

    def rewrite_term(self, t: sp.Expr) -> sp.Expr:
        return _negated(t)

    def again(self, node: sp.Basic, part: object) -> sp.Basic | None:
        return -node

    def scale(self, part: object, case: MatrixCase) -> np.ndarray | float | None:
        return -1.0

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

    def table_edits(
        self,
        rows: Rows,
        key: DHTable,
        within: RowFilter = None,
        touching: RowFilter = None,
        memo: RowMemo | None = None,
    ) -> Iterator[TableEdit]:
        """Each cell of ``rows`` with its sign flipped (a joint's entry: its offset), told
        with the key's value of that cell (a cell another slip wrote: its sign flipped too;
        ``memo`` is not used: each edit flips one cell)."""
        for k, row in enumerate(rows):
            if within is not None and k + 1 not in within:
                continue
            if touching is not None and k + 1 not in touching:
                continue
            for name, value in row.params().items():
                if value == 0 or name == row.variable_field and value == row.variable:
                    continue
                # name is the joint's own column here: the entry holds the joint variable
                variable = cast(sp.Expr, row.variable)
                flipped = -value if name != row.variable_field else 2 * variable - value
                new = tuple(
                    replace(r, **{name: flipped}) if j == k else r for j, r in enumerate(rows)
                )
                if value != getattr(key.rows[k], name):  # another slip wrote this cell
                    yield new, f"Row {k + 1}: {name} has the wrong sign too.", (k + 1,)
                    continue
                shown = cell_text(name, value, key)
                yield new, f"Row {k + 1}: {name} has the wrong sign; it is {shown}.", (k + 1,)

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        for rows, detail, where in self.table_edits(tuple(case.key.rows), case.key):
            chain = Chain(rows, case.key.convention)
            if same_cells(chain, case.answer, case.values, verdicts=case.verdicts):
                return Diagnosis(self.kind, self.title, detail, rows=where)
        return None


class SinCosSwapped(EntryMistake):
    """sin written where cos belongs (or the other way round)."""

    kind, title = "sin_cos_swapped", "sin and cos swapped"
    writes_trig = True

    def node_edit(self, case: MatrixCase) -> Edit[object] | None:
        return _swap_one

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
            f"In entry {where} sin and cos of the same angle are swapped: "
            f"{case.notation.text(partner)} is written where {case.notation.text(part)} belongs."
        )


class DroppedTerm(EntryMistake):
    """One term of a sum left out (at any depth: a term of a bracket)."""

    kind, title = "dropped_term", "a term is missing"
    in_sums = True

    def node_edit(self, case: MatrixCase) -> Edit[object] | None:
        return _drop

    def rewrite_term(self, t: sp.Expr) -> sp.Expr:
        return _left_out(t)

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
    yield from one_edit(e, _index_edit(joints))


def _index_edit(joints: list[sp.Symbol]) -> Edit[tuple[sp.Basic, sp.Basic]]:
    """The edit of :func:`joint_index_candidates` on one node."""
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

    return change


class WrongJointIndex(EntryMistake):
    """A sum angle on the wrong joints: ``C12`` written where ``C23`` belongs."""

    kind, title = "wrong_joint_index", "wrong joint index in a sum angle"
    writes_trig = True

    def node_edit(self, case: MatrixCase) -> Edit[object] | None:
        return _index_edit(_joints(case))

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
    yield from one_edit(e, _length_edit(joints))


def _length_edit(joints: list[sp.Symbol]) -> Edit[tuple[sp.Basic, sp.Basic]]:
    """The edit of :func:`length_candidates` on one node."""
    skip = set(joints)

    def drop(node: sp.Basic) -> Iterator[tuple[sp.Basic, tuple[sp.Basic, sp.Basic]]]:
        if isinstance(node, sp.Mul):
            for f in node.args:
                if f.is_Symbol and f not in skip:
                    yield node / f, (f, node)

    return drop


class MissingLength(EntryMistake):
    """A length left out of one product (``C2`` for ``a2 C2``)."""

    kind, title = "missing_length", "a length factor is missing"

    def node_edit(self, case: MatrixCase) -> Edit[object] | None:
        return _length_edit([r.variable for r in case.rows if r.variable is not None])

    def again(self, node: sp.Basic, part: object) -> sp.Basic | None:
        return node / cast(tuple[sp.Basic, sp.Basic], part)[0]  # length_candidates' pair

    def scale(self, part: object, case: MatrixCase) -> np.ndarray | float | None:
        return 1.0 / values(cast(tuple[sp.Basic, sp.Basic], part)[0], case.sample)

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


#: The most (first slip, second slip) candidates one answer's search of pairs evaluates,
#: shared among its unexplained entries and among the pairs of kinds (a count, not a time,
#: so that a diagnosis does not depend on the machine's load).
PAIR_BUDGET = 2400
#: The most first slips of one kind tried in one entry (of the first ``_FIRST_TRIED``).
_FIRST = 48
_FIRST_TRIED = 400
_BUILT = 6


def _trig(e: sp.Basic, memo: dict[sp.Basic, frozenset[sp.Basic]]) -> frozenset[sp.Basic]:
    """The sines and cosines in ``e`` (``memo``: of the subtrees seen, which the edits of
    one entry share)."""
    found = memo.get(e)
    if found is None:
        if isinstance(e, (sp.sin, sp.cos)):
            found = frozenset((e,))
        elif not e.args:
            found = frozenset()
        else:
            found = frozenset().union(*(_trig(a, memo) for a in e.args))
        memo[e] = found
    return found


def explain_pairs(
    case: MatrixCase,
    mistakes: tuple[EntryMistake, ...],
    budget: int = PAIR_BUDGET,
    *,
    same: bool = False,
) -> tuple[Diagnosis, ...]:
    """Entries that two catalogued slips of different kinds explain together (a sign and
    sin for cos, a dropped term and a missing length), two diagnoses per pair of kinds,
    each entry named once; with ``same``, two slips of one kind instead (two terms with
    the wrong sign, two lengths left out).

    In the entries still wrong (``case.wrong``) only, each entry is searched first by
    what each slip changes (:func:`_by_differences`: the places of each kind are matched
    by their changes against the answer minus the key, in the entry as the key writes it
    and expanded, so a long entry is searched whole, not within a budget), then by
    composing the second slip on each candidate of the first (the pairs whose changes do
    not combine so: a sign inside a sum angle, sin and cos swapped for a whole angle),
    within ``budget`` candidates shared evenly by the entries and the pairs of kinds; the
    values of one entry's candidates share their unchanged subtrees (one memo per entry),
    so a candidate costs about the depth of its edit. Either way a pair is named only
    when both slips together give the answer at the sample.

    >>> import sympy as sp
    >>> from dhsym.checking.judging.key import Key, prepare
    >>> from dhsym.checking.mistakes.registry import ENTRY_MISTAKES
    >>> from dhsym.checking.reading.answer_value import read_answer_value
    >>> from dhsym.checking.judging.matrix_judge import check_matrix
    >>> from dhsym.checking.reading.limits import DEFAULT_ANSWER_LIMITS as LIMITS
    >>> pk = prepare(Key.load("planar2r", "T0_2[0,3]"))
    >>> r = check_matrix(pk, read_answer_value(pk.form(), "a1*S1 - a2*C12"), LIMITS)
    >>> r.kinds
    ('wrong_sign', 'sin_cos_swapped')
    >>> print(r.diagnoses[0].detail)
    In your answer the term a2*C12 has the wrong sign. (One of two slips there; the other:
    sin and cos swapped.)

    Two slips of one kind (``same``): both terms' signs flipped.

    >>> pk = prepare(Key.load("puma560", "T0_6[0,3]"))  # C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1
    >>> r = check_matrix(pk, read_answer_value(pk.form(), "C1*(a2*C2 - a3*C23 - d4*S23) - d3*S1"),
    ...                  LIMITS)
    >>> r.kinds
    ('wrong_sign', 'wrong_sign')
    >>> for d in r.diagnoses:
    ...     print(d.detail)
    In your answer the term d3*S1 has the wrong sign. (One of two slips of this kind there.)
    In your answer the term a3*C23 has the wrong sign (inside a bracket). (The second slip of
    this kind.)
    """
    if same:
        kinds = [(a, a) for a in mistakes]
    else:
        kinds = [(a, b) for i, a in enumerate(mistakes) for b in mistakes[i + 1 :]]
    if not case.wrong or not kinds:
        return ()
    share = max(1, budget // (len(case.wrong) * len(kinds)))
    found: dict[tuple[str, str], list[tuple[tuple[int, int], str, str]]] = {}
    for p in case.wrong:
        hit = _pair_at(case, p, kinds, share)
        if hit is not None:
            a, b, first, second = hit
            found.setdefault((a.kind, b.kind), []).append((p, first, second))
    out: list[Diagnosis] = []
    by_kind = {m.kind: m for m in mistakes}
    for (ka, kb), hits in found.items():
        entries = tuple(case.label(p) for p, _, _ in hits)
        a_text = grouped(case, [(p, t) for p, t, _ in hits])
        b_text = grouped(case, [(p, t) for p, _, t in hits])
        ta, tb = by_kind[ka].title, by_kind[kb].title
        if ka == kb:
            tail_a, tail_b = "One of two slips of this kind there.", "The second slip of this kind."
        else:
            tail_a, tail_b = (
                f"One of two slips there; the other: {tb}.",
                f"The second slip there, with: {ta}.",
            )
        out.append(Diagnosis(ka, ta, f"{a_text} ({tail_a})", entries))
        out.append(Diagnosis(kb, tb, f"{b_text} ({tail_b})", entries))
    return tuple(out)


def _pair_at(
    case: MatrixCase,
    p: tuple[int, int],
    kinds: list[tuple[EntryMistake, EntryMistake]],
    share: int,
) -> tuple[EntryMistake, EntryMistake, str, str] | None:
    """The first pair of slips (and their messages) that gives the answer's entry ``p``."""
    e = case.expected[p]
    target = case.answer_values[:, p[0], p[1]]
    # the sines and cosines a slip may bring in: those of the answer (a slip that writes
    # one the student did not write is not theirs); the key's own are always there
    seen: dict[sp.Basic, frozenset[sp.Basic]] = {}
    written = _trig(case.answer[p], seen)
    for form in _forms(e):  # first by differences: slips at two places, or one place twice
        hit = _by_differences(case, e, form, kinds, target, written, seen)
        if hit is not None:
            return hit
        check_time()
    allowed = written | _trig(e, seen)
    memo: dict[object, np.ndarray] = {}
    firsts: dict[str, list[tuple[sp.Expr, object]]] = {}
    for a, b in kinds:
        if a.kind not in firsts:
            firsts[a.kind] = [
                (c, part)
                for c, part in islice(a.candidates(e, case), _FIRST_TRIED)
                if _trig(c, seen) <= allowed
            ][:_FIRST]
        left = share
        for n, (cand, part) in enumerate(firsts[a.kind]):
            if left <= 0:
                break
            if not b.writes_trig and not written <= _trig(cand, seen):
                continue  # the second slip writes no sine or cosine: the answer's are missing
            # the rest of this pair's share, spread over the first slips still to come
            each = max(1, left // (len(firsts[a.kind]) - n))
            # a pair that leaves other sines and cosines than the answer's costs only its
            # construction (a student who expanded C12 is not searched: no diagnosis is
            # better than a guess); at most _BUILT candidates built per one evaluated
            for cand2, part2 in islice(b.candidates(cand, case), _BUILT * each):
                if _trig(cand2, seen) != written:
                    continue
                left -= 1
                each -= 1
                if each < 0:
                    break
                if close(values(cand2, case.sample, memo), target):
                    # the second slip is told against the key's entry, as the first is
                    return a, b, a.message(case, _HERE, e, part), b.message(case, _HERE, e, part2)
            check_time()
    return None


#: The most places of one kind in one form of an entry, and the most pairs of places of
#: one pair of kinds whose differences add up (built and evaluated to be sure).
_SITES = 400
_MATCHES = 16


def _weights(
    form: sp.Expr, case: MatrixCase, memo: dict[object, np.ndarray]
) -> dict[tuple[int, ...], tuple[np.ndarray, np.ndarray | None]]:
    """Each node's values at the sample, and how the entry changes with it (its weight: the
    product of the factors beside it on the way up; None below a node that is no sum or
    product, where the entry does not change in proportion)."""
    out: dict[tuple[int, ...], tuple[np.ndarray, np.ndarray | None]] = {}
    ones = np.ones(case.sample.size)

    def visit(node: sp.Basic, path: tuple[int, ...], weight: np.ndarray | None) -> None:
        out[path] = (values(node, case.sample, memo), weight)
        if node.is_Atom:
            return
        if weight is None or not isinstance(node, (sp.Add, sp.Mul)):
            for k, arg in enumerate(node.args):
                visit(arg, (*path, k), None)
            return
        if isinstance(node, sp.Add):
            for k, arg in enumerate(node.args):
                visit(arg, (*path, k), weight)
            return
        own = [values(arg, case.sample, memo) for arg in node.args]
        for k, arg in enumerate(node.args):
            beside = (
                np.prod([v for i, v in enumerate(own) if i != k], axis=0) if len(own) > 1 else ones
            )
            visit(arg, (*path, k), weight * beside)

    visit(form, (), ones)
    return out


#: Slips made at once: path → (the node a slip writes there, or None with the slip that
#: scales its place and what it changed, made on what the slips below wrote).
Edits: TypeAlias = dict[tuple[int, ...], tuple[sp.Basic | None, "EntryMistake | None", object]]


def _composed(node: sp.Basic, edits: Edits, path: tuple[int, ...] = ()) -> sp.Basic:
    """``node`` with the slips ``edits`` made at once."""
    here = edits.get(path)
    if here is not None and here[0] is not None:
        return here[0]
    if any(len(q) > len(path) and q[: len(path)] == path for q in edits):
        node = node.func(*(_composed(a, edits, (*path, k)) for k, a in enumerate(node.args)))
    if here is not None and here[1] is not None:
        again = here[1].again(node, here[2])
        return node if again is None else again
    return node


def _inside(outer: tuple[int, ...], inner: tuple[int, ...]) -> bool:
    """True when the place ``inner`` is ``outer`` or below it."""
    return inner[: len(outer)] == outer


def _by_differences(
    case: MatrixCase,
    e: sp.Expr,
    form: sp.Expr,
    kinds: list[tuple[EntryMistake, EntryMistake]],
    target: np.ndarray,
    written: frozenset[sp.Basic],
    seen: dict[sp.Basic, frozenset[sp.Basic]],
) -> tuple[EntryMistake, EntryMistake, str, str] | None:
    """Two slips in ``form`` (the key's entry ``e`` as written, or expanded) found by what
    each changes (``d1``, ``d2``: the entry's change under each slip alone). The answer
    minus the key is ``d1 + d2`` when the slips are at two places of one sum (a slip's
    change inside a product is its change times the factors beside it); ``d1 + d2 + d1 d2
    / (w m)`` when they are in two factors of one product ``m`` (``w``: how the entry
    changes with ``m``); ``d1 + s d2`` when the second is inside the place of a first that
    scales it by ``s`` (a sign: -1; a length left out: 1/length); ``d`` of the one
    rewrite when both rewrite one sine or cosine (``S23`` written ``C34``: swapped and
    moved). Each pair whose changes fit is then built and must give the answer at the
    sample, with the answer's sines and cosines, as a pair found by composing
    (:func:`_pair_at`).

    >>> import sympy as sp
    >>> from dhsym.checking.judging.key import Key, prepare
    >>> from dhsym.checking.judging.matrix_judge import check_matrix
    >>> from dhsym.checking.reading.answer_value import read_answer_value
    >>> from dhsym.checking.reading.limits import DEFAULT_ANSWER_LIMITS as LIMITS
    >>> pk = prepare(Key.load("puma560", "J[4,3]"))  # -S1*S23: S23 swapped and moved
    >>> r = check_matrix(pk, read_answer_value(pk.form(), "-S1*C34"), LIMITS)
    >>> r.kinds
    ('sin_cos_swapped', 'wrong_joint_index')
    """
    memo: dict[object, np.ndarray] = {}
    nodes = _weights(form, case, memo)
    change = target - nodes[()][0]
    if not np.all(np.isfinite(change)):  # an answer without a finite value: no slips fit it
        return None
    sites: dict[EntryMistake, list[tuple[Site, np.ndarray]]] = {}
    for m in {m for pair in kinds for m in pair}:
        found = []
        for site in islice(m.sites(form, case), _SITES):
            value, weight = nodes[site[0]]
            if weight is not None:
                found.append((site, weight * (values(site[1], case.sample, memo) - value)))
        sites[m] = found
    direction = np.random.default_rng(0).standard_normal(case.sample.size)
    goal = float(change @ direction)
    # the products the slips are in: product's path -> [(kind, site's index, factor)]
    products: dict[tuple[int, ...], list[tuple[EntryMistake, int, int]]] = {}
    for m, found in sites.items():
        for i, ((path, _, _), _) in enumerate(found):
            for k in range(len(path)):
                if isinstance(_node_at(form, path[:k]), sp.Mul):
                    products.setdefault(path[:k], []).append((m, i, path[k]))

    def made(
        a: EntryMistake, b: EntryMistake, i: int, j: int
    ) -> tuple[EntryMistake, EntryMistake, str, str] | None:
        (pa, na, part_a), _ = sites[a][i]
        (pb, nb, part_b), _ = sites[b][j]
        edits: Edits
        if pa == pb:  # one slip where the other scales
            again = a.again(nb, part_a)
            edits = {pa: (again if again is not None else b.again(na, part_b), None, None)}
        elif _inside(pa, pb):
            edits = {pa: (None, a, part_a), pb: (nb, None, None)}
        elif _inside(pb, pa):
            edits = {pb: (None, b, part_b), pa: (na, None, None)}
        else:
            edits = {pa: (na, None, None), pb: (nb, None, None)}
        cand = _composed(form, edits)
        if _trig(cand, seen) != written or not close(values(cand, case.sample, memo), target):
            return None
        return a, b, a.message(case, _HERE, e, part_a), b.message(case, _HERE, e, part_b)

    def first(
        a: EntryMistake, b: EntryMistake, near: Iterable[tuple[int, int]]
    ) -> tuple[EntryMistake, EntryMistake, str, str] | None:
        tried = 0
        for i, j in near:
            if tried >= _MATCHES:
                return None
            if a is b and i == j:
                continue
            tried += 1
            hit = made(a, b, int(i), int(j))
            if hit is not None:
                return hit
        return None

    for a, b in kinds:
        check_time()
        sa, sb = sites[a], sites[b]
        if not sa or not sb:
            continue
        da = np.array([d for _, d in sa])
        db = np.array([d for _, d in sb])
        pa_, pb_ = da @ direction, db @ direction
        scale = [np.abs(x[np.isfinite(x)]) for x in (pa_, pb_)]
        tol = 1e-7 * (1.0 + abs(goal) + sum(float(x.max(initial=0.0)) for x in scale))
        # two places of one sum
        with np.errstate(invalid="ignore"):
            near = np.argwhere(np.abs(pa_[:, None] + pb_[None, :] - goal) <= tol)

        hit = first(
            a,
            b,
            (
                (i, j)
                for i, j in near
                if (a is not b or i < j) and _in_one_sum(form, sa[i][0][0], sb[j][0][0])
            ),
        )
        if hit is not None:
            return hit
        # two factors of one product m: (w m + d1)(w m + d2) = w m (w m + change)
        for path, inside in products.items():
            value, weight = nodes[path]
            if weight is None:
                continue
            wm = weight * value
            k = int(np.argmax(np.where(np.isfinite(wm), np.abs(wm), -1.0)))
            if not np.isfinite(wm[k]) or abs(wm[k]) < 1e-9:
                continue
            ia = [(i, f) for m, i, f in inside if m is a]
            jb = [(j, f) for m, j, f in inside if m is b]
            if not ia or not jb:
                continue
            xa = wm[k] + da[[i for i, _ in ia], k]
            xb = wm[k] + db[[j for j, _ in jb], k]
            want = wm[k] * (wm[k] + change[k])
            size = 1e-7 * (abs(want) + np.abs(xa).max() * np.abs(xb).max() + 1.0)
            with np.errstate(invalid="ignore"):
                pairs = np.argwhere(np.abs(xa[:, None] * xb[None, :] - want) <= size)
            hit = first(
                a,
                b,
                (
                    (ia[x][0], jb[y][0])
                    for x, y in pairs
                    if ia[x][1] != jb[y][1] and (a is not b or ia[x][0] < jb[y][0])
                ),
            )
            if hit is not None:
                return hit
        # one slip inside the place of the other, which scales it: d1 + s d2
        for outer, inner, projected, swapped in ((sa, sb, pb_, False), (sb, sa, pa_, True)):
            if a is b and swapped:
                continue
            outer_kind = b if swapped else a
            for i, ((place, _, part), d) in enumerate(outer):
                s_ = outer_kind.scale(part, case)
                if s_ is None:
                    continue
                with np.errstate(all="ignore"):
                    want = float(((change - d) / s_) @ direction)
                found = np.argwhere(np.abs(projected - want) <= tol).ravel().tolist()
                near_ = [
                    (j, i) if swapped else (i, j) for j in found if _inside(place, inner[j][0][0])
                ]
                hit = first(a, b, near_)
                if hit is not None:
                    return hit
        if a is b or not (a.writes_trig and b.writes_trig):
            continue
        # one sine or cosine rewritten by both slips
        edit = b.node_edit(case)
        if edit is None:
            continue
        for (pa, na, part_a), _ in sa:
            value, weight = nodes[pa]
            for nb, part_b in edit(na):
                assert weight is not None  # sa holds the places with a weight only
                if not close(weight * (values(nb, case.sample, memo) - value), change):
                    continue
                cand = _composed(form, {pa: (nb, None, None)})
                if _trig(cand, seen) == written and close(values(cand, case.sample, memo), target):
                    return (
                        a,
                        b,
                        a.message(case, _HERE, e, part_a),
                        b.message(case, _HERE, e, part_b),
                    )
    return None


def _in_one_sum(form: sp.Basic, x: tuple[int, ...], y: tuple[int, ...]) -> bool:
    """True when the places ``x`` and ``y`` are in two terms of one sum (neither inside the
    other, and the node where their paths part is a sum)."""
    if _inside(x, y) or _inside(y, x):
        return False
    k = next(n for n, (u, v) in enumerate(zip(x, y)) if u != v)
    return isinstance(_node_at(form, x[:k]), sp.Add)


def _node_at(e: sp.Basic, path: tuple[int, ...]) -> sp.Basic:
    """The node of ``e`` at ``path``."""
    for k in path:
        e = e.args[k]
    return e
