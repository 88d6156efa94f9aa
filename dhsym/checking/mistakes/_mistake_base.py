"""What a mistake detector sees, and the base class of every kind of mistake.

A :class:`MatrixCase` (a wrong matrix or entry and its key, with values at a
random sample) or a :class:`TableCase` (a wrong table and its key) goes to each
:class:`Mistake`, which recomputes the key under that mistake. The public names
are re-exported by :mod:`dhsym.checking.mistakes.registry`.

Examples
--------
>>> import dhsym
>>> table = dhsym.load("puma560").table
>>> cell_text("d", table.rows[2].d, table), cell_text("alpha", table.rows[0].alpha, table)
('d3 (= 0.15005)', 'pi/2')
"""

from __future__ import annotations

from abc import ABC
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, ClassVar, TypeAlias

import numpy as np
import sympy as sp

from dhsym.kinematics.numeric import word_product
from dhsym.kinematics.transforms import inverse_word, link_word
from dhsym.model.table import AngleUnit, Convention, DHRow, DHTable
from dhsym.notation.printers import Notation, format_angle

from ..comparing.equivalence import Sample, close
from ..comparing.table_match import Chain, RowVerdicts, same_cells
from ..comparing.verdict import Diagnosis

if TYPE_CHECKING:
    from dhsym.kinematics.singularities import Singularities
    from dhsym.robot import Robot

__all__ = [
    "MatrixCase",
    "Mistake",
    "RowFilter",
    "RowMemo",
    "Rows",
    "TableCase",
    "TableEdit",
    "Variants",
    "cell_text",
    "listed",
    "prepare_variants",
]

#: a mistake's variants at a sample: (the key's values under the mistake, what the student did)
Variants: TypeAlias = tuple[tuple[np.ndarray, str], ...]
#: one slip in a table's rows: (the rows under it, what the student did, the rows it names)
TableEdit: TypeAlias = tuple[tuple[DHRow, ...], str, tuple[int, ...]]
#: a table's rows, and the 1-based rows a slip may rewrite or must touch (None: any)
Rows: TypeAlias = tuple[DHRow, ...]
RowFilter: TypeAlias = frozenset[int] | None
#: rows a slip rewrote within one diagnosis, by (the row's id, the factor it was scaled by):
#: (the row, kept so that its id is not reused; the rewritten row); a row rewritten the
#: same way again is not built again (a row checks its cells when it is built)
RowMemo: TypeAlias = dict[tuple[int, sp.Expr], tuple[DHRow, DHRow]]


@dataclass(frozen=True, eq=False)
class MatrixCase:
    """A wrong matrix (or entry) answer and the key it is judged against.

    ``expected``/``answer`` are 4×4 (or 1×1 for an entry question at ``entry``,
    0-based; 6×n for a Jacobian); ``wrong`` lists the 0-based positions that differ;
    ``prepared`` holds each whole-matrix mistake's variants at the sample, built when the
    key was prepared (:func:`prepare_variants`); ``cache`` is scratch shared by the
    mistakes while variants are built (the full matrix, ``J``); ``robot`` is the key's
    robot (Jacobian and determinant variants); ``singularities`` a determinant key's,
    derived once per key; ``dynamics_variants`` a dynamics key's part under each
    catalogued mistake, ``(kind, matrix, detail)``.
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
    cache: dict[tuple[object, ...], Any] = field(default_factory=dict)
    robot: Robot | None = None
    singularities: Singularities | None = None
    dynamics_variants: tuple[tuple[str, sp.ImmutableMatrix, str], ...] = ()
    prepared: Mapping[Mistake, Variants] = field(default_factory=dict)

    def chain_values(
        self, rows: tuple[DHRow, ...], convention: Convention, reverse: str = ""
    ) -> np.ndarray:
        """Values of ``^frm T_to`` of ``rows`` at the sample (``reverse``: links or factors)."""
        return self.project(self.full_values(rows, convention, reverse))

    def full_values(
        self, rows: tuple[DHRow, ...], convention: Convention, reverse: str = ""
    ) -> np.ndarray:
        """Values of the whole 4×4 ``^frm T_to`` (also for entry questions)."""
        lo, hi = sorted((self.frm, self.to))
        links = [list(link_word(rows[k - 1], convention)) for k in range(lo + 1, hi + 1)]
        if reverse == "links":
            links = links[::-1]
        word = [e for link in links for e in link]
        if reverse == "factors":
            word = word[::-1]
        if self.frm > self.to:
            word = list(inverse_word(word))
        return word_product(word, self.sample.env, self.sample.size)

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
    """A wrong table answer and the key table; ``verdicts`` keeps, for this one diagnosis,
    the rows of the key's variants already compared with the answer
    (:class:`~dhsym.checking.comparing.table_match.RowVerdicts`)."""

    key: DHTable
    answer: DHTable
    tool_free: bool = False
    values: Mapping[sp.Symbol, sp.Expr] = field(default_factory=dict)
    verdicts: RowVerdicts = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "verdicts", RowVerdicts(self.answer, self.values))


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

    def table_edits(
        self,
        rows: Rows,
        key: DHTable,
        within: RowFilter = None,
        touching: RowFilter = None,
        memo: RowMemo | None = None,
    ) -> Iterator[TableEdit]:
        """``rows`` (the key's, or the key's under another slip) under one slip of this kind,
        each told against the ``key`` (the search of two slips in one table composes them:
        :func:`~dhsym.checking.mistakes._row_mistakes.explain_table_pairs`); only those that
        rewrite no row outside ``within`` and at least one row of ``touching`` (1-based;
        None: any); none by default. ``memo``: the rows rewritten so far in this diagnosis
        (:data:`RowMemo`), for a kind that rewrites whole rows."""
        return iter(())

    def build_variants(self, case: MatrixCase) -> Variants:
        """This mistake's variants at the case's sample that differ from the key (built
        once per key and sample, when the key is prepared: :func:`prepare_variants`)."""
        return tuple(
            (vals, detail)
            for vals, detail in self.matrix_variants(case)
            if not close(vals, case.key_values)
        )

    def variants(self, case: MatrixCase) -> Variants:
        """The variants the key was prepared with; built here only for a case without them."""
        found = case.prepared.get(self)
        return found if found is not None else self.build_variants(case)

    def explain_matrix(self, case: MatrixCase, partial: bool = False) -> Diagnosis | None:
        """A diagnosis when a variant equals the whole answer (or, with ``partial``, the
        answer at some of its wrong entries: the variant that explains the most of them).

        A variant's detail may name where with ``{entries}`` ("l2 written for lc2 in
        entries (1,1) and (2,1)").
        """
        best: tuple[list[tuple[int, int]], str] | None = None
        for vals, detail in self.variants(case):
            hits = [
                p
                for p in case.wrong
                if close(vals[:, p[0], p[1]], case.answer_values[:, p[0], p[1]])
            ]
            if len(hits) == 1 and not _reproduces(
                *(v[:, hits[0][0], hits[0][1]] for v in (vals, case.key_values))
            ):
                continue  # one constant for a varying entry: a coincidence, not this mistake
            whole = len(hits) == len(case.wrong) and close(vals, case.answer_values)
            if whole:
                best = (hits, detail)
                break
            if hits and partial and (best is None or len(hits) > len(best[0])):
                best = (hits, detail)
        if best is None:
            return None
        hits, detail = best
        return Diagnosis(
            self.kind, self.title, _placed(case, hits, detail), tuple(map(case.label, hits))
        )

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        """A diagnosis when the answer table equals a variant of the key table."""
        for chain, detail, rows in self.table_variants(case):
            if same_cells(chain, case.answer, case.values, verdicts=case.verdicts):
                return Diagnosis(self.kind, self.title, detail, rows=rows)
        return None


def _builds_variants(mistake: Mistake) -> bool:
    """True for a mistake that recomputes the whole matrix (not an entry-wise one)."""
    return type(mistake).matrix_variants is not Mistake.matrix_variants


def prepare_variants(case: MatrixCase, mistakes: Iterable[Mistake]) -> Mapping[Mistake, Variants]:
    """Every whole-matrix mistake's variants at ``case``'s sample, built once, when the key
    is prepared (``case`` is the key's own: its answer is the key), read-only after.

    >>> import dhsym
    >>> from dhsym.checking.comparing.equivalence import Sample, values
    >>> robot = dhsym.load("planar2r")
    >>> T = robot.transform(0, 2).matrix
    >>> s = Sample.random(set(robot.table.variables) | set(robot.table.constants))
    >>> kv = values(T, s)
    >>> rows, conv = tuple(robot.table.rows), robot.table.convention
    >>> case = MatrixCase(rows, conv, 0, 2, None, T, T, s, kv, kv, ())
    >>> from dhsym.checking.mistakes.registry import MATRIX_MISTAKES
    >>> built = prepare_variants(case, MATRIX_MISTAKES)
    >>> [m.kind for m in built][:2], len(built[MATRIX_MISTAKES[0]])
    (['transposed', 'other_convention'], 2)
    """
    return MappingProxyType({m: m.build_variants(case) for m in mistakes if _builds_variants(m)})


def _placed(case: MatrixCase, hits: list[tuple[int, int]], detail: str) -> str:
    """``detail`` with ``{entries}`` replaced by where the mistake is seen."""
    if "{entries}" not in detail:
        return detail
    if case.entry is not None or len(case.expected) == 1:
        return detail.replace("{entries}", "your answer")
    names = [case.where(p) for p in hits]
    if len(names) == 1:
        return detail.replace("{entries}", f"entry {names[0]}")
    return detail.replace("{entries}", f"entries {listed(names)}")


def listed(names: list[str]) -> str:
    """``(1,4), (2,4) and (3,4)``: several entries named in one sentence.

    >>> listed(["(1,4)", "(2,4)", "(3,4)"])
    '(1,4), (2,4) and (3,4)'
    """
    return ", ".join(names[:-1]) + " and " + names[-1]


def _reproduces(variant: np.ndarray, key: np.ndarray) -> bool:
    """A variant explains a single entry only when it is more than a constant standing in
    for a varying key entry (``0`` for ``p_x`` is no transposed matrix: any constant is
    that); a pattern over several entries (a zero column) is explained by its mistake."""
    constant = bool(np.ptp(variant) <= 1e-12 * (1 + np.abs(variant).max()))
    return not constant or bool(np.ptp(key) <= 1e-12 * (1 + np.abs(key).max()))


def cell_text(name: str, value: sp.Expr, table: DHTable) -> str:
    """A table cell as a message shows it: angles in the table's unit, lengths with values."""
    if name in ("theta", "alpha"):
        return format_angle(value, table.angles is AngleUnit.DEG, latex=False)
    if not value.free_symbols:  # a number: nothing to substitute (subs of a map is not free)
        return str(sp.sstr(value))
    given = table.value_map
    number = value.subs({s: given[s] for s in value.free_symbols if s in given})
    if not number.free_symbols:
        return f"{sp.sstr(value)} (= {float(number):g})"
    return str(sp.sstr(value))
