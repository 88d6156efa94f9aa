"""Grading a whole class: an assignment, a folder or CSV of submissions, a report folder.

The assignment (YAML) names the key and the questions::

    title: Homework 3, forward kinematics
    key: puma560                  # built-in robot or table file (relative to this file)
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

import csv
import hashlib
import io
import json
import math
import os
import re
import statistics
import time
from collections import Counter
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from dhsym.errors import DHError

from ._limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, UnreadableAnswer
from ._runner import JobFailure, Progress, run_dask, run_pool, run_serial
from .checker import Key, check_answer
from .feedback import QuestionFeedback, render_feedback, render_summary

__all__ = [
    "Assignment",
    "AssignmentQuestion",
    "GradeReport",
    "Submission",
    "grade",
    "grade_submission",
    "read_submissions",
    "safe_name",
]

CACHE_NAME = ".dhsym-grading-cache.json"
_ID = re.compile(r"^[A-Za-z0-9_-]{1,40}$")
_RESERVED = {
    "con",
    "prn",
    "aux",
    "nul",
    *(f"com{i}" for i in range(10)),
    *(f"lpt{i}" for i in range(10)),
}
_MAX_SUBMISSION_FILE = 2_000_000
_MAX_CSV = 500_000_000


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
            try:
                key = Key.load(ref, str(q["ask"]), tool_free=tool)
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


@dataclass(frozen=True)
class Submission:
    """One student's answers (question id → raw text or bytes) and read problems."""

    student: str
    name: str
    answers: tuple[tuple[str, str | bytes], ...] = ()
    problems: tuple[tuple[str, str], ...] = ()

    def fingerprint(self, assignment: Assignment) -> str:
        """Changes when the assignment or any answer changes."""
        h = hashlib.sha256(assignment.fingerprint.encode())
        for qid, text in self.answers + self.problems:
            h.update(qid.encode() + b"\0")
            h.update(text if isinstance(text, bytes) else text.encode("utf-8", "replace"))
            h.update(b"\0")
        h.update(self.name.encode("utf-8", "replace"))
        return h.hexdigest()[:20]


def safe_name(student: str, used: set[str]) -> str:
    """A file name for a student id: ``[A-Za-z0-9._-]``, no leading dot, unique, short."""
    base = re.sub(r"[^A-Za-z0-9._-]+", "_", student).strip("._-")[:60] or "student"
    name = base
    if name != student or name.lower() in used or name.lower() in _RESERVED:
        name = f"{base}-{hashlib.sha1(student.encode('utf-8', 'replace')).hexdigest()[:8]}"
    while name.lower() in used:
        name += "_"
    used.add(name.lower())
    return name


def _read_limited(path: Path, limit: int) -> str | bytes:
    """File content, or a problem text for links, specials and oversized files."""
    if path.is_symlink() or not path.is_file():
        raise UnreadableAnswer(f"{path.name} is not a regular file (links are not read)")
    size = path.stat().st_size
    if size > limit:
        raise UnreadableAnswer(f"the file {path.name} is {size} bytes; at most {limit} are read")
    with path.open("rb") as fh:
        return fh.read(limit + 1)


def _from_folder(folder: Path, qids: list[str], limits: AnswerLimits) -> Submission:
    answers, problems = [], []
    name = folder.name
    for qid in qids:
        files = sorted(p for p in folder.iterdir() if p.name == qid or p.name.startswith(qid + "."))
        if not files:
            continue
        try:
            answers.append((qid, _read_limited(files[0], limits.max_bytes)))
        except (UnreadableAnswer, OSError) as err:
            problems.append((qid, str(err)))
    name_file = folder / "name.txt"
    if name_file.is_file() and not name_file.is_symlink() and name_file.stat().st_size < 1000:
        name = name_file.read_text("utf-8", "replace").strip() or name
    return Submission(folder.name, name, tuple(answers), tuple(problems))


def _from_file(path: Path, qids: list[str]) -> Submission:
    student = path.stem
    try:
        raw = _read_limited(path, _MAX_SUBMISSION_FILE)
        data = yaml.safe_load(raw)
        if not isinstance(data, Mapping) or not isinstance(data.get("answers"), Mapping):
            raise UnreadableAnswer("expected 'answers: {q1: …}' in the submission file")
    except (UnreadableAnswer, yaml.YAMLError, OSError) as err:
        return Submission(student, student, (), tuple((q, str(err)) for q in qids))
    answers = []
    for qid in qids:
        value = data["answers"].get(qid)
        if isinstance(value, (str, int, float)) and not isinstance(value, bool):
            answers.append((qid, str(value)))
    name = data.get("name")
    return Submission(
        student, str(name) if isinstance(name, (str, int)) else student, tuple(answers)
    )


def _from_csv(path: Path, qids: list[str]) -> Iterator[Submission]:
    if path.stat().st_size > _MAX_CSV:
        raise DHError(f"the CSV file is larger than {_MAX_CSV} bytes", file=str(path))
    text = path.read_bytes().decode("utf-8", "replace")
    old = csv.field_size_limit()
    csv.field_size_limit(_MAX_CSV)
    try:
        reader = csv.DictReader(io.StringIO(text, newline=""))
        fields = reader.fieldnames or []
        idcol = next((f for f in fields if f.strip().lower() in ("student", "id")), None)
        if idcol is None:
            raise DHError("the CSV needs a 'student' column", file=str(path))
        namecol = next((f for f in fields if f.strip().lower() == "name"), None)
        for k, row in enumerate(reader, 2):
            student = (row.get(idcol) or "").strip() or f"row{k}"
            answers = tuple((q, row[q]) for q in qids if row.get(q))
            yield Submission(
                student, (row.get(namecol) or student).strip() if namecol else student, answers
            )
    finally:
        csv.field_size_limit(old)


def read_submissions(
    source: str | Path, assignment: Assignment, limits: AnswerLimits = DEFAULT_ANSWER_LIMITS
) -> list[Submission]:
    """All submissions of a folder or CSV file, sorted by student id."""
    src = Path(source)
    qids = [q.id for q in assignment.questions]
    if src.is_file():
        subs = list(_from_csv(src, qids))
    elif src.is_dir():
        subs = []
        for p in sorted(src.iterdir()):
            if p.name.startswith(".") or p.is_symlink():
                continue
            if p.is_dir():
                subs.append(_from_folder(p, qids, limits))
            elif p.suffix.lower() in (".yaml", ".yml", ".json"):
                subs.append(_from_file(p, qids))
    else:
        raise DHError(f"no submissions folder or CSV file at {src}")
    return sorted(subs, key=lambda s: s.student)


def grade_submission(job: tuple[Assignment, Submission, AnswerLimits]) -> dict:
    """Grade one submission (runs in a worker): scores, verdicts, kinds and both feedback pages."""
    assignment, sub, limits = job
    answers, problems = dict(sub.answers), dict(sub.problems)
    feedback, scores, verdicts, kinds = [], {}, {}, []
    for q in assignment.questions:
        if q.id in answers:
            result = check_answer(q.key, answers[q.id], limits=limits)
        elif q.id in problems:
            from .verdict import CheckResult, Verdict

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
        scores[q.id] = score
        verdicts[q.id] = result.verdict.value if result is not None else "missing"
        if result is not None:
            kinds.extend(result.kinds or (["unreadable"] if verdicts[q.id] == "unreadable" else []))
        feedback.append(QuestionFeedback(q.id, q.ask, q.points, score, result))
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


def _inside(root: Path, *parts: str) -> Path:
    path = root.joinpath(*parts).resolve()
    if not path.is_relative_to(root):
        raise DHError(f"refusing to write outside the report folder: {path}")
    return path


def _write_atomic(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)


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


def _csv_cell(value: object) -> str:
    s = str(value)
    return "'" + s if s[:1] in ("=", "+", "-", "@", "\t", "\r") else s


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
    cache_path = _inside(root, CACHE_NAME)
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
        names = [_inside(root, "feedback", files[s.student] + ext) for ext in (".md", ".html")]
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
        _write_atomic(cache_path, json.dumps({"assignment": a.fingerprint, "records": records}))

    failed = 0
    try:
        for k, outcome in runner:
            sub = todo[k]
            if isinstance(outcome, JobFailure):
                outcome = _failed_record(sub, a, outcome)
                failed += 1
            pages = outcome.pop("pages")
            for ext, fmt in ((".md", "md"), (".html", "html")):
                _write_atomic(_inside(root, "feedback", files[sub.student] + ext), pages[fmt])
            records[sub.student] = outcome
            bar.step()
            if time.monotonic() - last_save > 5.0:
                save()
                last_save = time.monotonic()
    finally:
        save()
    ordered = [records[s.student] for s in subs if s.student in records]
    gradebook = _write_gradebook(root, a, ordered, files)
    summary = _write_summary(root, a, ordered, files)
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


def _write_gradebook(root: Path, a: Assignment, records: list[dict], files: dict) -> Path:
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(
        ["student", "name", *[q.id for q in a.questions], "total", "max", "status", "feedback"]
    )
    for r in records:
        w.writerow(
            [
                _csv_cell(r["student"]),
                _csv_cell(r["name"]),
                *[f"{r['scores'].get(q.id, 0):g}" for q in a.questions],
                f"{r['score']:g}",
                f"{a.max_score:g}",
                r["status"],
                f"feedback/{files[r['student']]}.md",
            ]
        )
    path = _inside(root, "gradebook.csv")
    _write_atomic(path, buf.getvalue())
    return path


def _chart(root: Path, a: Assignment, records: list[dict], kinds: Counter) -> Path:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 4))
    FigureCanvasAgg(fig)
    ax1, ax2 = fig.subplots(1, 2)
    scores = [r["score"] for r in records]
    top = max(a.max_score, 1.0)
    bins = min(20, max(1, int(math.ceil(top))))
    ax1.hist(scores, bins=bins, range=(0, top), color="#4a7bb7", edgecolor="white")
    ax1.set_title("Scores")
    ax1.set_xlabel(f"points (of {a.max_score:g})")
    ax1.set_ylabel("students")
    labels = [k for k, _ in kinds.most_common(12)] or ["none"]
    counts = [kinds[k] for k in labels] if kinds else [0]
    ax2.barh(labels[::-1], counts[::-1], color="#b7574a")
    ax2.set_title("Mistake kinds")
    ax2.set_xlabel("answers")
    fig.tight_layout()
    path = _inside(root, "summary.png")
    fig.savefig(path, dpi=100)
    return path


def _write_summary(root: Path, a: Assignment, records: list[dict], files: dict) -> Path:
    kinds: Counter = Counter(k for r in records for k in r["kinds"])
    chart = _chart(root, a, records, kinds)
    per_q = []
    for q in a.questions:
        v = Counter(r["verdicts"].get(q.id, "missing") for r in records)
        per_q.append(
            {
                "id": q.id,
                "ask": q.ask,
                "points": q.points,
                "correct": v["correct"],
                "incorrect": v["incorrect"],
                "unreadable": v["unreadable"],
                "missing": v["missing"] + v["timeout"] + v["error"],
            }
        )
    scores = [r["score"] for r in records]
    rows = [
        {
            "student": r["student"],
            "name": r["name"],
            "score": r["score"],
            "status": r["status"],
            "feedback_html": f"feedback/{files[r['student']]}.html",
            "feedback_md": f"feedback/{files[r['student']]}.md",
        }
        for r in records
    ]
    html = render_summary(
        {
            "title": a.title,
            "students": len(records),
            "max_score": a.max_score,
            "mean": statistics.fmean(scores) if scores else 0.0,
            "median": statistics.median(scores) if scores else 0.0,
            "problems": sum(r["status"] != "graded" for r in records),
            "chart": chart.name,
            "per_question": per_q,
            "kinds": kinds.most_common(),
            "rows": rows,
        }
    )
    path = _inside(root, "summary.html")
    _write_atomic(path, html)
    return path
