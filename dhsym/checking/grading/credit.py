"""Partial credit: how many of a question's points a wrong answer earns, and why.

A question of the assignment may say::

    - {id: q2, ask: T0_2, points: 2, credit: entries}                 # the share of right entries
    - {id: q6, ask: M, points: 3, deduct: {wrong_sign: 25%, parallel_axis: 50%}, floor: 10%}

``credit: all`` (the default) is all or nothing.  ``credit: entries`` gives the share of
the right entries of a matrix or vector (rows of a table; for ``ik all`` the key's
branches: each branch a part, the share of the branches the answer gives).  ``deduct``
names mistakes of the catalogue (:mod:`dhsym.checking.mistakes.registry`; ``sign`` is
``wrong_sign``) and what each costs: a wrong answer whose every wrong entry is explained by
those mistakes earns the points less the deductions, never less than ``floor``.  When both
apply the better counts.

Examples
--------
>>> c = Credit.parse({"credit": "entries", "deduct": {"sign": "25%"}, "floor": 0.1})
>>> c
Credit(mode='entries', deduct=(('wrong_sign', 0.25),), floor=0.1)
>>> Credit().award(2.0, None)
(0.0, '')
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache

from dhsym.errors import DHError

from ..comparing.verdict import CheckResult, Verdict
from ..mistakes.registry import (
    DET_MISTAKES,
    ENTRY_MISTAKES,
    IK_MISTAKES,
    JACOBIAN_MISTAKES,
    MATRIX_MISTAKES,
    SCREW_MISTAKES,
    TABLE_MISTAKES,
    TRAJECTORY_MISTAKES,
    dynamics_mistakes,
)
from ..reading.limits import echoed

__all__ = ["Credit", "mistake_kind", "mistake_kinds"]

_SHARE = re.compile(r"^\s*([0-9]+(?:\.[0-9]*)?)\s*%\s*$")


@cache
def mistake_kinds() -> frozenset[str]:
    """Every kind of mistake the checker can name (what ``deduct`` may list).

    >>> {"wrong_sign", "parallel_axis", "transposed", "kd_without_two"} <= mistake_kinds()
    True
    """
    lists = (
        MATRIX_MISTAKES,
        ENTRY_MISTAKES,
        TABLE_MISTAKES,
        JACOBIAN_MISTAKES,
        DET_MISTAKES,
        IK_MISTAKES,
        dynamics_mistakes(),
        SCREW_MISTAKES,
        TRAJECTORY_MISTAKES,
    )
    return frozenset(m.kind for ms in lists for m in ms) | {"missing_column"}


def mistake_kind(name: object, what: str = "deduct") -> str:
    """The catalogue's kind a name stands for (``sign`` is ``wrong_sign``), or a
    :class:`~dhsym.errors.DHError` listing the catalogue (``what`` names the field).

    >>> mistake_kind("sign"), mistake_kind("parallel_axis")
    ('wrong_sign', 'parallel_axis')
    """
    known = mistake_kinds()
    kind = str(name).strip()
    kind = kind if kind in known or f"wrong_{kind}" not in known else f"wrong_{kind}"
    if kind not in known:
        raise DHError(
            f"{what}: unknown mistake {echoed(name)}; the catalogue: " + ", ".join(sorted(known))
        )
    return kind


def _share(value: object, what: str) -> float:
    """``25%`` or ``0.25`` as 0.25: a share from 0 to 1."""
    number: float | None = None
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        number = float(value)
    elif isinstance(value, str) and (m := _SHARE.match(value)):
        number = float(m[1]) / 100
    if number is None or not 0 <= number <= 1:
        raise DHError(f"{what}: expected a share like 25% or 0.25, got {echoed(value)}")
    return number


@dataclass(frozen=True)
class Credit:
    """How a question gives partial credit: ``mode`` ``all`` or ``entries``, the
    deductions per mistake kind, and the floor of a deducted score (shares of the points)."""

    mode: str = "all"
    deduct: tuple[tuple[str, float], ...] = ()
    floor: float = 0.0

    @classmethod
    def parse(cls, question: Mapping[object, object]) -> Credit:
        """The ``credit``, ``deduct`` and ``floor`` of a question of the assignment."""
        mode = str(question.get("credit", "all")).strip().lower()
        if mode not in ("all", "entries"):
            raise DHError(f"credit: expected 'all' or 'entries', got {echoed(mode)}")
        raw = question.get("deduct", {}) or {}
        if not isinstance(raw, Mapping):
            raise DHError("deduct: expected a mapping like {wrong_sign: 25%}")
        deduct = []
        for name, value in raw.items():
            kind = mistake_kind(name)
            deduct.append((kind, _share(value, f"deduct {kind}")))
        floor = _share(question.get("floor", 0), "floor")
        return cls(mode, tuple(deduct), floor)

    def award(self, points: float, result: CheckResult | None) -> tuple[float, str]:
        """The points ``result`` earns of ``points``, and why (``""``: all or nothing).

        >>> from dhsym.checking.comparing.verdict import Diagnosis, EntryResult
        >>> e = [EntryResult(1, k, k != 4, "x", "y") for k in range(1, 5)]
        >>> wrong = CheckResult("T0_1", Verdict.INCORRECT, "1 of 4 entries is wrong.",
        ...                     tuple(e), (Diagnosis("wrong_sign", "wrong sign", "", ((1, 4),)),))
        >>> Credit("entries").award(2.0, wrong)
        (1.5, 'partial credit: 3 of 4 entries right, 1.5 of 2 points')
        >>> Credit(deduct=(("wrong_sign", 0.25),)).award(2.0, wrong)
        (1.5, 'partial credit: wrong sign (25% deducted), 1.5 of 2 points')
        >>> Credit(deduct=(("transposed", 0.25),)).award(2.0, wrong)
        (0.0, '')

        ``ik all``: each key branch is a part.

        >>> ik = CheckResult("ik all", Verdict.INCORRECT, "Not every solution is given.",
        ...                  branches=(("elbow up", True), ("elbow down", False)))
        >>> Credit("entries").award(3.0, ik)
        (1.5, 'partial credit: 1 of 2 branches right (not given: elbow down), 1.5 of 3 points')

        Two mistakes in one entry: only deducted kinds may explain it.

        >>> swapped = Diagnosis("sin_cos_swapped", "sin and cos swapped", "", ((1, 4),))
        >>> both = CheckResult("T0_1", Verdict.INCORRECT, "", tuple(e), (*wrong.diagnoses, swapped))
        >>> Credit(deduct=(("wrong_sign", 0.25),)).award(2.0, both)
        (0.0, '')
        >>> Credit(deduct=(("wrong_sign", 0.25), ("sin_cos_swapped", 0.25))).award(2.0, both)[0]
        1.0
        """
        if result is None:
            return 0.0, ""
        if result.correct:
            return points, ""
        if result.verdict is not Verdict.INCORRECT:
            return 0.0, ""
        options = [o for o in (self._entries(result), self._deducted(result)) if o is not None]
        if not options:
            return 0.0, ""
        share, why = max(options, key=lambda o: o[0])
        score = round(points * share, 6)
        if score <= 0:
            return 0.0, ""
        return score, f"partial credit: {why}, {score:g} of {points:g} points"

    def _entries(self, result: CheckResult) -> tuple[float, str] | None:
        if self.mode != "entries":
            return None
        if result.branches:  # ik all: each key branch a part
            right = sum(ok for _, ok in result.branches)
            missing = ", ".join(name for name, ok in result.branches if not ok)
            why = f"{right} of {len(result.branches)} branches right"
            return right / len(result.branches), why + (
                f" (not given: {missing})" if missing else ""
            )
        if len(result.entries) > 1:
            right = sum(e.correct for e in result.entries)
            return right / len(result.entries), f"{right} of {len(result.entries)} entries right"
        total = len(result.expected_table) - 1  # the first line of the table is its header
        wrong = {r for d in result.diagnoses for r in d.rows}
        if total > 1 and wrong and all(d.rows for d in result.diagnoses):
            right = total - len(wrong)
            return right / total, f"{right} of {total} rows right"
        return None

    def _deducted(self, result: CheckResult) -> tuple[float, str] | None:
        costs = dict(self.deduct)
        if not costs or not result.diagnoses:
            return None
        hits = [d for d in result.diagnoses if d.kind in costs]
        wrong = {(e.row, e.col) for e in result.entries if not e.correct}
        if wrong:
            # each wrong entry explained, and only by deducted kinds: an entry with two
            # mistakes (a sign and a swapped sine) loses nothing less than both
            covering = [[d for d in result.diagnoses if e in d.entries] for e in wrong]
            explained = all(c and all(d.kind in costs for d in c) for c in covering)
        else:  # a table or a whole answer: every mistake named must be a deducted one
            explained = bool(hits) and len(hits) == len(result.diagnoses)
        if not explained:
            return None
        kinds = {d.kind: d.title for d in hits}
        share = max(self.floor, 1 - sum(costs[k] for k in kinds))
        why = "; ".join(f"{title} ({costs[k]:.0%} deducted)" for k, title in kinds.items())
        return share, why
