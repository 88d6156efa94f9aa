"""Grading a whole class: an assignment, a folder or CSV of submissions, a report folder.

The assignment (YAML) names the key and the questions::

    title: Homework 3, forward kinematics
    key: puma560                  # built-in robot or table file (relative to this file)
    rounding: digits=3            # accepted rounding of decimals (Rounding); per question too
    questions:
      - {id: q1, ask: table, points: 4, tool: free}   # tool: free accepts another tool frame
      - {id: q2, ask: T0_2, points: 2}
      - {id: q3, ask: A1, points: 1, key: generic_modified_link.yaml}

Submissions are a folder (one sub-folder per student with files ``q1.md``,
``q2.txt`` …, and/or one ``<student>.yaml`` with ``name:`` and ``answers: {q1: …}``)
or a CSV file (columns ``student``, optional ``name``, one per question id).

The report folder gets ``gradebook.csv``, ``feedback/<student>.md|.html``,
``summary.html`` with ``summary.png``, and ``.dhsym-grading-cache.json`` (rewritten
atomically) so that a rerun skips what is already graded.  Nothing is written
outside it: student ids become safe file names.

Examples
--------
>>> safe_name("../../etc/passwd", set()).startswith("etc_passwd-")
True
>>> safe_name("alice", set())
'alice'
"""

from __future__ import annotations

import hashlib
import json
import re
import statistics
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from dhsym.errors import DHError

from ._limits import AnswerLimits
from ._report import inside, safe_name, write_atomic, write_gradebook, write_summary
from ._runner import JobFailure, Progress, run_dask, run_pool, run_serial
from ._submissions import Submission, read_submissions
from .checker import Key, check_answer
from .feedback import QuestionFeedback, render_feedback
from .verdict import CheckResult, Verdict

__all__ = [
    "Assignment",
    "AssignmentQuestion",
    "GradeReport",
    "Submission",
    "check_submission",
    "grade",
    "grade_submission",
    "read_submissions",
    "safe_name",
]

CACHE_NAME = ".dhsym-grading-cache.json"
_ID = re.compile(r"^[A-Za-z0-9_-]{1,40}$")


@dataclass(frozen=True)
class AssignmentQuestion:
    """One question: its id, what is asked, points, the key and whether the tool frame is free."""

    id: str
    ask: str
    points: float
    key: Key


@dataclass(frozen=True)
class Assignment:
    """A title and questions; ``seconds`` is the time limit of one answer."""

    title: str
    questions: tuple[AssignmentQuestion, ...]
    seconds: float = 5.0
    fingerprint: str = ""

    @property
    def max_score(self) -> float:
        """Sum of the points."""
        return sum(q.points for q in self.questions)

    @classmethod
    def load(cls, path: str | Path) -> Assignment:
        """Read an assignment YAML file (keys given as files are relative to it)."""
        p = Path(path)
        try:
            text = p.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as err:
            raise DHError(f"cannot read the assignment: {err}", file=str(p)) from None
        data = yaml.safe_load(text)
        if not isinstance(data, Mapping) or not isinstance(data.get("questions"), list):
            raise DHError("expected 'questions: [...]' (and 'key:') in the assignment", file=str(p))
        default = data.get("key")
        questions, seen, digest = [], set(), [text]
        for k, q in enumerate(data["questions"], 1):
            if not isinstance(q, Mapping) or "ask" not in q or "id" not in q:
                raise DHError("each question needs 'id' and 'ask'", file=str(p), row=k)
            qid = str(q["id"])
            if not _ID.match(qid) or qid in seen or qid in ("student", "name"):
                raise DHError(
                    f"question id {qid!r}: use letters, digits, '_' or '-', once",
                    file=str(p),
                    row=k,
                )
            seen.add(qid)
            ref = q.get("key", default)
            if ref is None:
                raise DHError(
                    "no key: give 'key:' for the assignment or the question", file=str(p), row=k
                )
            local = p.parent / str(ref)
            ref = local if local.suffix.lower() in (".yaml", ".yml") or local.exists() else str(ref)
            tool = str(q.get("tool", "fixed")).lower() in ("free", "any", "true")
            rounding = q.get("rounding", data.get("rounding"))
            try:
                key = Key.load(ref, str(q["ask"]), tool_free=tool, rounding=rounding)
                points = float(q.get("points", 1))
            except (DHError, ValueError) as err:
                raise DHError(str(err), file=str(p), row=k) from None
            digest.append(repr(key))
            questions.append(AssignmentQuestion(qid, str(q["ask"]), points, key))
        fp = hashlib.sha256("\n".join(digest).encode()).hexdigest()[:16]
        return cls(
            str(data.get("title") or p.stem),
            tuple(questions),
            float(data.get("time_limit", 5.0)),
            fp,
        )


def check_submission(
    assignment: Assignment, sub: Submission, limits: AnswerLimits
) -> tuple[QuestionFeedback, ...]:
    """Check every question of one submission: its result (``None`` if missing) and score.

    An answer scores the question's points when it is correct and 0 otherwise; an
    answer that could not be read from its file is ``unreadable``.
    """
    answers, problems = dict(sub.answers), dict(sub.problems)
    out = []
    for q in assignment.questions:
        if q.id in answers:
            result = check_answer(q.key, answers[q.id], limits=limits)
        elif q.id in problems:
            result = CheckResult(
                q.ask,
                Verdict.UNREADABLE,
                f"The answer could not be read: {problems[q.id]}",
                reason=problems[q.id],
                key=q.key.name,
            )
        else:
            result = None
        score = q.points if result is not None and result.correct else 0.0
        out.append(QuestionFeedback(q.id, q.ask, q.points, score, result))
    return tuple(out)


def _wrong_parts(result: CheckResult) -> list[list[str]]:
    """Where an incorrect answer went wrong, for the class summary: ``[where, example]``
    per wrong matrix entry (the student's entry) or per wrong table row (the mistake)."""
    if result.correct:
        return []
    out = [[f"({e.row},{e.col})", e.answer[:120]] for e in result.entries if not e.correct]
    if not out:
        for d in result.diagnoses:
            out.extend([f"row {r}", d.title] for r in d.rows)
    return out[:16]


def grade_submission(job: tuple[Assignment, Submission, AnswerLimits]) -> dict:
    """Grade one submission (runs in a worker): scores, verdicts, kinds and both feedback pages."""
    assignment, sub, limits = job
    feedback = check_submission(assignment, sub, limits)
    scores, verdicts, kinds, wrong, mistakes = {}, {}, [], {}, {}
    for qf in feedback:
        result = qf.result
        scores[qf.id] = qf.score
        verdicts[qf.id] = result.verdict.value if result is not None else "missing"
        if result is not None:
            unread = ["unreadable"] if verdicts[qf.id] == "unreadable" else []
            kinds.extend(result.kinds or unread)
            wrong[qf.id] = _wrong_parts(result)
            mistakes[qf.id] = list(result.kinds)
    student = {"id": sub.student, "name": sub.name}
    pages = {
        fmt: render_feedback(student, feedback, title=assignment.title, fmt=fmt)
        for fmt in ("md", "html")
    }
    return {
        "student": sub.student,
        "name": sub.name,
        "fingerprint": sub.fingerprint(assignment),
        "status": "graded",
        "scores": scores,
        "verdicts": verdicts,
        "kinds": kinds,
        "wrong": wrong,
        "mistakes": mistakes,
        "score": sum(scores.values()),
        "max": assignment.max_score,
        "pages": pages,
    }


@dataclass(frozen=True)
class GradeReport:
    """What :func:`grade` did and where it wrote."""

    out_dir: Path
    students: int
    graded: int
    skipped: int
    failed: int
    mean: float
    gradebook: Path
    summary: Path
    records: tuple[dict, ...] = field(default=(), repr=False)


def _failed_record(sub: Submission, assignment: Assignment, failure: JobFailure) -> dict:
    student = {"id": sub.student, "name": sub.name}
    qs = [QuestionFeedback(q.id, q.ask, q.points, 0.0, None) for q in assignment.questions]
    status = "timeout" if failure.kind == "timeout" else "error"
    pages = {
        fmt: render_feedback(student, qs, title=assignment.title, fmt=fmt, status=status)
        for fmt in ("md", "html")
    }
    return {
        "student": sub.student,
        "name": sub.name,
        "fingerprint": "",
        "status": status,
        "scores": {q.id: 0.0 for q in assignment.questions},
        "verdicts": {q.id: status for q in assignment.questions},
        "kinds": [status],
        "score": 0.0,
        "max": assignment.max_score,
        "pages": pages,
        "error": failure.message,
    }


def grade(
    assignment: str | Path | Assignment,
    submissions: str | Path,
    out_dir: str | Path,
    *,
    workers: int = 2,
    timeout: float | None = None,
    dask: object = None,
    progress: bool = True,
    limits: AnswerLimits | None = None,
) -> GradeReport:
    """Grade every submission and write the report folder (see the module docstring).

    ``workers`` processes (0: in this process), or a Dask cluster with ``dask``
    (an address or a ``Client``).  ``timeout`` is the time limit of one answer.
    """
    a = assignment if isinstance(assignment, Assignment) else Assignment.load(assignment)
    seconds = float(timeout if timeout is not None else a.seconds)
    lim = limits or AnswerLimits(seconds=seconds)
    subs = read_submissions(submissions, a, lim)
    root = Path(out_dir).resolve()
    root.mkdir(parents=True, exist_ok=True)
    (root / "feedback").mkdir(exist_ok=True)
    cache_path = inside(root, CACHE_NAME)
    cache = {}
    if cache_path.is_file():
        try:
            data = json.loads(cache_path.read_text(encoding="utf-8"))
            if data.get("assignment") == a.fingerprint:
                cache = data.get("records", {})
        except (OSError, ValueError):
            cache = {}
    used: set[str] = set()
    files = {s.student: safe_name(s.student, used) for s in subs}
    todo, records = [], {}
    for s in subs:
        old = cache.get(s.student)
        names = [inside(root, "feedback", files[s.student] + ext) for ext in (".md", ".html")]
        if old and old.get("fingerprint") == s.fingerprint(a) and all(p.is_file() for p in names):
            records[s.student] = old
        else:
            todo.append(s)
    jobs = [(a, s, lim) for s in todo]
    deadline = seconds * max(1, len(a.questions)) + 10.0
    if dask is not None:
        runner = run_dask(grade_submission, jobs, dask, deadline)
    elif workers > 0:
        runner = run_pool(grade_submission, jobs, workers, deadline)
    else:
        runner = run_serial(grade_submission, jobs)
    bar = Progress(len(jobs), enabled=progress)
    last_save = time.monotonic()

    def save() -> None:
        write_atomic(cache_path, json.dumps({"assignment": a.fingerprint, "records": records}))

    failed = 0
    try:
        for k, outcome in runner:
            sub = todo[k]
            if isinstance(outcome, JobFailure):
                outcome = _failed_record(sub, a, outcome)
                failed += 1
            pages = outcome.pop("pages")
            for ext, fmt in ((".md", "md"), (".html", "html")):
                write_atomic(inside(root, "feedback", files[sub.student] + ext), pages[fmt])
            records[sub.student] = outcome
            bar.step()
            if time.monotonic() - last_save > 5.0:
                save()
                last_save = time.monotonic()
    finally:
        save()
    ordered = [records[s.student] for s in subs if s.student in records]
    gradebook = write_gradebook(root, a, ordered, files)
    summary = write_summary(root, a, ordered, files)
    scores = [r["score"] for r in ordered]
    return GradeReport(
        root,
        len(subs),
        len(jobs),
        len(subs) - len(jobs),
        failed,
        statistics.fmean(scores) if scores else 0.0,
        gradebook,
        summary,
        tuple(ordered),
    )
