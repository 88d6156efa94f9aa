"""Results of checking an answer: frozen values that print as JSON.

Examples
--------
>>> d = Diagnosis("wrong_sign", "wrong sign", "entry (2,4) has the wrong sign", ((2, 4),))
>>> r = CheckResult("A1", Verdict.INCORRECT, "1 of 16 entries is wrong", diagnoses=(d,))
>>> r.to_json()["diagnosis"][0]["entries"]
[[2, 4]]
>>> r.correct, r.kinds
(False, ('wrong_sign',))
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Any

__all__ = ["CheckResult", "Diagnosis", "EntryResult", "JSON_SCHEMA_VERSION", "Verdict"]

JSON_SCHEMA_VERSION = 1


class Verdict(str, Enum):
    """The three outcomes of a check (``check`` exits 0, 1, 2)."""

    CORRECT = "correct"
    INCORRECT = "incorrect"
    UNREADABLE = "unreadable"

    @property
    def exit_code(self) -> int:
        """0 correct, 1 incorrect, 2 unreadable."""
        return {"correct": 0, "incorrect": 1, "unreadable": 2}[self.value]


@dataclass(frozen=True)
class Diagnosis:
    """One explained mistake: its kind (a :class:`~dhsym.checking.mistakes.registry.Mistake` kind),
    a short title, a message the student can act on, and where (1-based entries or rows)."""

    kind: str
    title: str
    detail: str
    entries: tuple[tuple[int, int], ...] = ()
    rows: tuple[int, ...] = ()

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict."""
        return {
            "kind": self.kind,
            "title": self.title,
            "detail": self.detail,
            "entries": [list(e) for e in self.entries],
            "rows": list(self.rows),
        }


@dataclass(frozen=True)
class EntryResult:
    """One entry of a matrix answer (1-based row and column).

    ``proof`` says how a correct entry was established: ``exact`` (symbolic proof),
    ``numeric`` (random points only), ``rounding`` (equal up to rounded decimals, and
    ``rounding`` says how: ``to 4 significant digits``).
    Texts are plain math in the key's notation; ``*_latex`` the same in LaTeX.
    """

    row: int
    col: int
    correct: bool
    answer: str
    expected: str
    answer_latex: str = ""
    expected_latex: str = ""
    proof: str = ""
    rounding: str = ""
    #: the expected entry as MathML when the key has it converted (a wrong entry's; the
    #: HTML feedback shows it), else ``""`` and the page converts ``expected_latex``
    expected_mathml: str = field(default="", compare=False, repr=False)

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict."""
        return {
            "row": self.row,
            "col": self.col,
            "verdict": "correct" if self.correct else "incorrect",
            "answer": self.answer,
            "expected": self.expected,
            "answer_latex": self.answer_latex,
            "expected_latex": self.expected_latex,
            "proof": self.proof,
            "rounding": self.rounding,
        }


@dataclass(frozen=True)
class CheckResult:
    """The verdict on one answer to one question.

    Parameters
    ----------
    question
        The question as asked (``table``, ``T0_2``, ``A3``, ``T0_6[0,3]``).
    verdict
        :class:`Verdict`.
    message
        One paragraph for the student (why, and what to look at).
    entries
        Per-entry results of a matrix or entry answer.
    diagnoses
        Explained mistakes, most likely first.
    alternative
        For a table that is right but not the key's table: how it differs.
    reason
        For an unreadable answer: what could not be read.
    key
        Name of the key robot.
    expected_table, answer_table
        For a table question: the key's and the student's table as text cells
        (header row first).
    branches
        For an answer to ``ik all``: each key branch that exists at the poses checked,
        by name, and whether the answer gives it (partial credit per branch).
    """

    question: str
    verdict: Verdict
    message: str
    entries: tuple[EntryResult, ...] = ()
    diagnoses: tuple[Diagnosis, ...] = ()
    alternative: str | None = None
    reason: str | None = None
    key: str = ""
    expected_table: tuple[tuple[str, ...], ...] = ()
    answer_table: tuple[tuple[str, ...], ...] = ()
    branches: tuple[tuple[str, bool], ...] = ()

    @property
    def correct(self) -> bool:
        """True for a correct answer."""
        return self.verdict is Verdict.CORRECT

    @property
    def kinds(self) -> tuple[str, ...]:
        """The mistake kinds of the diagnoses."""
        return tuple(d.kind for d in self.diagnoses)

    def to_json(self) -> dict[str, object]:
        """The documented JSON object of ``dhsym check --json`` (docs/reference/json.md);
        ``branches`` only for an ``ik all`` answer."""
        out: dict[str, object] = {
            "schema": JSON_SCHEMA_VERSION,
            "key": self.key,
            "question": self.question,
            "verdict": self.verdict.value,
            "message": self.message,
            "reason": self.reason,
            "alternative": self.alternative,
            "diagnosis": [d.to_json() for d in self.diagnoses],
            "entries": [e.to_json() for e in self.entries],
            "expected_table": [list(r) for r in self.expected_table],
            "answer_table": [list(r) for r in self.answer_table],
        }
        if self.branches:
            out["branches"] = [{"name": n, "given": ok} for n, ok in self.branches]
        return out

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> CheckResult:
        """Rebuild a result from :meth:`to_json` output (the grading cache)."""
        return cls(
            question=str(data["question"]),
            verdict=Verdict(data["verdict"]),
            message=str(data["message"]),
            entries=tuple(
                EntryResult(
                    e["row"],
                    e["col"],
                    e["verdict"] == "correct",
                    e["answer"],
                    e["expected"],
                    e.get("answer_latex", ""),
                    e.get("expected_latex", ""),
                    e.get("proof", ""),
                    e.get("rounding", ""),
                )
                for e in data.get("entries", [])
            ),
            diagnoses=tuple(
                Diagnosis(
                    d["kind"],
                    d["title"],
                    d["detail"],
                    tuple(tuple(x) for x in d.get("entries", [])),
                    tuple(d.get("rows", [])),
                )
                for d in data.get("diagnosis", [])
            ),
            alternative=data.get("alternative"),
            reason=data.get("reason"),
            key=str(data.get("key", "")),
            expected_table=tuple(tuple(r) for r in data.get("expected_table", [])),
            answer_table=tuple(tuple(r) for r in data.get("answer_table", [])),
            branches=tuple((str(b["name"]), bool(b["given"])) for b in data.get("branches", [])),
        )
