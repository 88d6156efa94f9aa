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
    """A mistake inside one entry: candidates are rewritten key entries.

    ``writes_trig``: the mistake may write a sine or cosine the key's entry does not have
    (the others only remove or keep them), which prunes the search of pairs.
    """

    writes_trig: ClassVar[bool] = False

    def candidates(
        self, e: sp.Expr, case: MatrixCase | None = None
    ) -> Iterator[tuple[sp.Expr, object]]:
        raise NotImplementedError

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
    writes_trig = True

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

    The search composes the second slip on each candidate of the first, in the entries
    still wrong (``case.wrong``) only, within ``budget`` candidates shared evenly by the
    entries and the pairs of kinds; the values of one entry's candidates share their
    unchanged subtrees (one memo per entry), so a candidate costs about the depth of its
    edit.

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
