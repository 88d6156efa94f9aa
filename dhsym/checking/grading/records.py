"""The record of one graded submission, as :func:`~dhsym.checking.grading.batch.grade` keeps it.

A :class:`GradeRecord` is what a worker sends back (it pickles), what the gradebook,
the summary and the LMS imports read, and, through :meth:`GradeRecord.to_dict` and
:meth:`GradeRecord.from_dict`, what the grading cache stores as JSON.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = ["GradeRecord"]


@dataclass(frozen=True)
class GradeRecord:
    """One submission's outcome: who, its status, and per question points and verdicts.

    Parameters
    ----------
    uid, student, name, source : str
        The submission's unique id, its student id and name, and where it was read
        from (``alice/``, ``alice.yaml``, ``row 3``).
    flags : tuple of str
        What a teacher should look at (a duplicate id, a file that was not graded).
    status : str
        ``graded``, ``timeout`` or ``error: reason``.
    scores, verdicts : Mapping
        Per question id its points and its verdict (``correct``, ``incorrect``,
        ``unreadable``, ``missing``, ``timeout`` or ``error``).
    kinds : tuple of str
        The mistake kinds of all answers, one per mistake (for the summary's chart).
    score, max_score : float
        The total points and the assignment's maximum.
    wrong : Mapping
        Per answered question ``(where, example)`` pairs: a wrong matrix entry and the
        student's entry, or a wrong table row and the mistake (empty for a failure).
    mistakes : Mapping
        Per answered question its mistake kinds (empty for a failure).
    error : str
        Why a failed submission has no verdicts (empty when graded).
    fingerprint : str
        What the verdicts depend on (answers, assignment, limits); set on a graded
        record before it is cached.
    pages : Mapping
        The feedback pages (``md`` and ``html``) while they travel from the worker to
        the report folder; not part of :meth:`to_dict`, empty once written.

    Examples
    --------
    >>> r = GradeRecord("bob", "bob", "Bob", "bob/", (), "graded", {"q1": 2.0},
    ...                 {"q1": "correct"}, (), 2.0, 2.0, wrong={"q1": ()},
    ...                 mistakes={"q1": ()})
    >>> d = r.to_dict()
    >>> list(d)[:6], d["wrong"], d["score"]
    (['uid', 'student', 'name', 'source', 'flags', 'status'], {'q1': []}, 2.0)
    >>> GradeRecord.from_dict(d) == r
    True
    >>> GradeRecord.from_dict({**d, "scores": "all of them"})
    Traceback (most recent call last):
    ...
    ValueError: a grade record needs scores as a mapping of question ids to finite numbers
    """

    uid: str
    student: str
    name: str
    source: str
    flags: tuple[str, ...]
    status: str
    scores: Mapping[str, float]
    verdicts: Mapping[str, str]
    kinds: tuple[str, ...]
    score: float
    max_score: float
    wrong: Mapping[str, tuple[tuple[str, str], ...]] = field(default_factory=dict)
    mistakes: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    error: str = ""
    fingerprint: str = ""
    pages: Mapping[str, str] = field(default_factory=dict, repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready dict of the grading cache: lists for tuples, no ``pages``;
        ``error`` (and then no ``wrong`` and ``mistakes``) and ``fingerprint`` only when set."""
        out: dict[str, Any] = {
            "uid": self.uid,
            "student": self.student,
            "name": self.name,
            "source": self.source,
            "flags": list(self.flags),
            "status": self.status,
            "scores": dict(self.scores),
            "verdicts": dict(self.verdicts),
            "kinds": list(self.kinds),
        }
        if not self.error:  # a failure has no answers to point at
            out["wrong"] = {q: [list(p) for p in parts] for q, parts in self.wrong.items()}
            out["mistakes"] = {q: list(kinds) for q, kinds in self.mistakes.items()}
        out["score"], out["max"] = self.score, self.max_score
        if self.error:
            out["error"] = self.error
        if self.fingerprint:
            out["fingerprint"] = self.fingerprint
        return out

    @classmethod
    def from_dict(cls, data: object) -> GradeRecord:
        """The record of a dict written by :meth:`to_dict` (read back from JSON).

        Raises ``ValueError`` naming the first field that does not have its shape;
        ``wrong``, ``mistakes``, ``error`` and ``fingerprint`` may be left out.
        """
        if not isinstance(data, Mapping):
            raise ValueError("a grade record is a mapping")
        for key in ("uid", "student", "name", "source", "status"):
            _need(isinstance(data.get(key), str), key, "a string")
        for key in ("error", "fingerprint"):
            _need(isinstance(data.get(key, ""), str), key, "a string")
        for key in ("flags", "kinds"):
            _need(_strings(data.get(key)), key, "a list of strings")
        for key in ("score", "max"):
            _need(_number(data.get(key)), key, "a finite number")
        scores, verdicts = data.get("scores"), data.get("verdicts")
        wrong, mistakes = data.get("wrong", {}), data.get("mistakes", {})
        need = "a mapping of question ids to"
        _need(_keyed(scores, _number), "scores", f"{need} finite numbers")
        _need(_keyed(verdicts, lambda v: isinstance(v, str)), "verdicts", f"{need} strings")
        _need(_keyed(wrong, _pairs), "wrong", f"{need} lists of [where, example] pairs")
        _need(_keyed(mistakes, _strings), "mistakes", f"{need} lists of strings")
        return cls(
            uid=data["uid"],
            student=data["student"],
            name=data["name"],
            source=data["source"],
            flags=tuple(data["flags"]),
            status=data["status"],
            scores=dict(data["scores"]),  # a mapping: checked by _need above
            verdicts=dict(data["verdicts"]),
            kinds=tuple(data["kinds"]),
            score=data["score"],
            max_score=data["max"],
            wrong={q: tuple(tuple(pair) for pair in parts) for q, parts in wrong.items()},
            mistakes={q: tuple(kinds) for q, kinds in mistakes.items()},
            error=data.get("error", ""),
            fingerprint=data.get("fingerprint", ""),
        )


def _need(ok: bool, key: str, what: str) -> None:
    if not ok:
        raise ValueError(f"a grade record needs {key} as {what}")


def _number(x: object) -> bool:
    return isinstance(x, (int, float)) and math.isfinite(x)


def _strings(x: object) -> bool:
    return isinstance(x, (list, tuple)) and all(isinstance(s, str) for s in x)


def _pairs(x: object) -> bool:
    return isinstance(x, (list, tuple)) and all(_strings(p) and len(p) == 2 for p in x)


def _keyed(x: object, ok: Callable[[object], bool]) -> bool:
    return isinstance(x, Mapping) and all(isinstance(k, str) and ok(v) for k, v in x.items())
