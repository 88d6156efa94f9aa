"""Grading a whole class: an assignment, a folder or CSV of submissions, a report folder.

The assignment (YAML, :class:`~dhsym.checking.grading.assignment.Assignment`) names the
key and the questions. Submissions are a folder (one sub-folder per student with files ``q1.md``,
``q2.txt`` …, and/or one ``<student>.yaml`` with ``name:`` and ``answers: {q1: …}``)
or a CSV file (columns ``student``, optional ``name``, one per question id); the
rules for answer files and duplicate ids are in :mod:`dhsym.checking.grading.submissions`.

The report folder gets ``gradebook.csv``, ``feedback/<student>.md|.html``,
``summary.html`` with its chart ``summary.svg``, and ``.dhsym-grading-cache.json`` (rewritten
atomically) so that a rerun skips what is already graded.  Nothing is written
outside it: student ids become safe file names.

Every submission is isolated: it is read inside its own guard and graded in a
process that is killed when it overruns (:mod:`dhsym.checking.grading.sandbox`).  Its
outcome is its ``status``: ``graded``, ``timeout`` (an answer or the whole
submission ran out of time) or ``error: …`` (with the reason); the gradebook and
the summary are written whatever happens.  Only final verdicts are cached: a
timeout or an error is graded again on the next run, and the cache is keyed by the
assignment, its keys and every limit (a corrupted cache is ignored with a warning).

The assignment file is read by :mod:`~dhsym.checking.grading.assignment`, the report
folder's files are written through :mod:`~dhsym.checking.grading.report_files`.
"""

from __future__ import annotations

import hashlib
import json
import math
import statistics
import time
from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import TypedDict

from dhsym.errors import DHError
from dhsym.model.yamlsafe import FileRefused, read_limited

from ..comparing.verdict import CheckResult, Verdict
from ..judging.checker import check_answer
from ..judging.key import AnyKey, Key, PreparedKeys
from ..judging.matrix_key import MatrixPart
from ..reading.limits import AnswerLimits, AnswerTimeout, check_seconds, time_limit
from .assignment import Assignment, AssignmentQuestion
from .assignment_tests import run_assignment_tests
from .backends import Progress, dask_address, run_dask, run_pool, run_serial
from .feedback import QuestionFeedback, load_feedback_templates, render_feedback
from .records import GradeRecord
from .report import write_gradebook, write_summary
from .report_files import CACHE_NAME, inside, inside_folder, safe_name, write_atomic
from .sandbox import JobFailure
from .submissions import Submission, read_submissions
from .variants import ClassList, Variant, class_variants, variant_id

__all__ = [
    "check_submission",
    "GradeReport",
    "grade",
    "grade_submission",
    "prepare_keys",
    "shared_keys",
    "warm_worker",
]

_MAX_CACHE = 500_000_000
_SLACK_SECONDS = 10.0  # reading, rendering and start-up around the answers' own limits


#: what a timed-out answer is told in a class run (the autograder says its own)
RERUN = "The answer is checked again on the next run; nothing is kept for now."


def _timed_out(q: AssignmentQuestion, seconds: float, then: str) -> CheckResult:
    text = f"Checking took longer than the time limit of {seconds:g} s. {then}"
    return CheckResult(q.ask, Verdict.UNREADABLE, text, reason="timeout", key=q.key.name)


def check_submission(
    assignment: Assignment,
    sub: Submission,
    limits: AnswerLimits,
    *,
    on_timeout: str = RERUN,
    keys: PreparedKeys | None = None,
) -> tuple[QuestionFeedback, ...]:
    """Check every question of one submission: its result (``None`` if missing) and score.

    An answer scores the question's points when it is correct and 0 otherwise; an
    answer that could not be read from its file is ``unreadable``. Each answer runs
    under the time limit ``limits.seconds``; one that runs out gets an unreadable
    result whose ``reason`` is ``timeout`` (see :func:`grade_submission`), told
    ``on_timeout``.  Each key is prepared before its answer's clock starts (its solvers
    and variants are built once per worker, in the worker's ``keys``, never on a
    student's time).
    """
    keys = keys if keys is not None else PreparedKeys()
    answers, problems = dict(sub.answers), dict(sub.problems)
    inner = replace(limits, seconds=0)  # the limit is the one below: a timeout stays one
    out = []
    for q in assignment.questions:
        if q.id in answers:
            keys.get(q.key)  # the worker's first answer to this key pays it, off the clock
            try:
                with time_limit(limits.seconds, AnswerTimeout):
                    result = check_answer(q.key, answers[q.id], limits=inner, keys=keys)
            except AnswerTimeout:
                result = _timed_out(q, limits.seconds, on_timeout)
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
        score, why = q.credit.award(q.points, result)
        if why and result is not None:  # the feedback says where partial points come from
            result = replace(result, message=f"{result.message} {why[0].upper()}{why[1:]}.")
        out.append(QuestionFeedback(q.id, q.ask, q.points, score, result))
    return tuple(out)


def shared_keys(assignments: Iterable[Assignment]) -> tuple[AnyKey, ...]:
    """The keys that more than one submission is graded against, in the assignment's
    order: what a grading run prepares once, before its workers fork (a variant's own
    key is prepared by the worker that grades it).

    >>> from dhsym.checking.grading.assignment import AssignmentQuestion
    >>> from dhsym.checking.judging.key import Key
    >>> qs = [AssignmentQuestion(f"q{k}", ask, 1, Key.load("planar2r", ask))
    ...       for k, ask in enumerate(("T0_2", "table"))]
    >>> a = Assignment("hw", tuple(qs))
    >>> [k.question.spec for k in shared_keys([a, a])], shared_keys([a])
    (['T0_2', 'table'], ())
    """
    # counted by object first (a class's jobs share their assignment's key objects), then
    # by value over the distinct objects: a key is hashed once per object, not per job
    # (hashing a key hashes its whole table)
    by_object: dict[int, tuple[AnyKey, int]] = {}
    for a in assignments:
        for q in a.questions:
            seen = by_object.get(id(q.key))
            by_object[id(q.key)] = (q.key, 1 if seen is None else seen[1] + 1)
    counts: Counter[AnyKey] = Counter()
    for key, n in by_object.values():
        counts[key] += n
    return tuple(k for k, n in counts.items() if n > 1)


def prepare_keys(keys: tuple[AnyKey, ...], prepared: PreparedKeys) -> None:
    """Prepare ``keys`` into a worker's map (a key that cannot be prepared is left for the
    job that meets it, which reports it)."""
    for k in keys:
        try:
            prepared.get(k)
        except Exception:  # noqa: BLE001, S112 - the job that needs the key says why
            continue


def warm_worker(keys: tuple[AnyKey, ...], prepared: PreparedKeys) -> None:
    """What a grading run does once before its sandbox children fork: prepare ``keys``
    (:func:`prepare_keys`), convert their entries to MathML for the feedback pages
    (:class:`~dhsym.checking.judging.matrix_key.KeyMathML`) and compile the pages'
    templates (:func:`~dhsym.checking.grading.feedback.load_feedback_templates`)."""
    prepare_keys(keys, prepared)
    for k in keys:
        if isinstance(k, Key):
            try:
                part = prepared.get(k).part
            except Exception:  # noqa: BLE001, S112 - the job that needs the key says why
                continue
            if isinstance(part, MatrixPart):
                part.expected_mathml.convert_all()
    load_feedback_templates()


def _wrong_parts(result: CheckResult) -> tuple[tuple[str, str], ...]:
    """Where an incorrect answer went wrong, for the class summary: ``[where, example]``
    per wrong matrix entry (the student's entry) or per wrong table row (the mistake)."""
    if result.correct:
        return ()
    out = [(f"({e.row},{e.col})", e.answer[:120]) for e in result.entries if not e.correct]
    if not out:
        for d in result.diagnoses:
            out.extend((f"row {r}", d.title) for r in d.rows)
    return tuple(out[:16])


def grade_submission(
    job: tuple[Assignment, Submission, AnswerLimits], keys: PreparedKeys | None = None
) -> GradeRecord:
    """Grade one submission (runs in a worker): scores, verdicts, kinds and both feedback pages.

    ``keys`` are the worker's prepared keys (the runners give each worker one
    :class:`~dhsym.checking.judging.key.PreparedKeys`).  An answer that runs out of time gets
    the verdict ``timeout`` and the record the status ``timeout`` (never cached, so the
    next run checks it again).
    """
    assignment, sub, limits = job
    feedback = check_submission(assignment, sub, limits, keys=keys)
    scores, verdicts, kinds, wrong, mistakes = {}, {}, [], {}, {}
    timed_out = False
    for qf in feedback:
        result = qf.result
        scores[qf.id] = qf.score
        if result is not None and result.reason == "timeout":
            timed_out = True
            verdicts[qf.id] = "timeout"
            kinds.append("timeout")
            continue
        verdicts[qf.id] = result.verdict.value if result is not None else "missing"
        if result is not None:
            unread = ["unreadable"] if verdicts[qf.id] == "unreadable" else []
            kinds.extend(result.kinds or unread)
            wrong[qf.id] = _wrong_parts(result)
            mistakes[qf.id] = tuple(result.kinds)
    student = {"id": sub.student, "name": sub.name}
    status = "timeout" if timed_out else "graded"
    values = assignment.variant.shown if assignment.variant is not None else ()
    pages = {
        fmt: render_feedback(
            student,
            feedback,
            title=assignment.title,
            fmt=fmt,
            status=status,
            flags=sub.flags,
            values=values,
        )
        for fmt in ("md", "html")
    }
    return GradeRecord(
        **_identity(sub),
        status=status,
        scores=scores,
        verdicts=verdicts,
        kinds=tuple(kinds),
        score=sum(scores.values()),
        max_score=assignment.max_score,
        wrong=wrong,
        mistakes=mistakes,
        pages=pages,
    )


class _Identity(TypedDict):
    """Who a record is about (the first fields of a :class:`GradeRecord`)."""

    uid: str
    student: str
    name: str
    source: str
    flags: tuple[str, ...]


def _identity(sub: Submission) -> _Identity:
    return {
        "uid": sub.uid,
        "student": sub.student,
        "name": sub.name,
        "source": sub.source,
        "flags": tuple(sub.flags),
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
    records: tuple[GradeRecord, ...] = field(default=(), repr=False)
    warnings: tuple[str, ...] = ()
    #: entries of the submissions folder that are not submissions: (entry, reason)
    refused: tuple[tuple[str, str], ...] = ()


def _failed_record(sub: Submission, assignment: Assignment, failure: JobFailure) -> GradeRecord:
    """The record of a submission that has no verdicts: ``timeout`` or ``error: reason``."""
    short = "timeout" if failure.kind == "timeout" else "error"
    status = "timeout" if short == "timeout" else f"error: {failure.message}"
    student = {"id": sub.student, "name": sub.name}
    qs = [QuestionFeedback(q.id, q.ask, q.points, 0.0, None) for q in assignment.questions]
    pages = {}
    for fmt in ("md", "html"):
        try:
            pages[fmt] = render_feedback(
                student, qs, title=assignment.title, fmt=fmt, status=status, flags=sub.flags
            )
        except Exception:  # noqa: BLE001 - the page of a failure must never fail in turn
            pages[fmt] = f"Feedback: {status}\n"
    return GradeRecord(
        **_identity(sub),
        status=status,
        scores={q.id: 0.0 for q in assignment.questions},
        verdicts={q.id: short for q in assignment.questions},
        kinds=(short,),
        score=0.0,
        max_score=assignment.max_score,
        error=failure.message,
        pages=pages,
    )


def _run_fingerprint(a: Assignment, limits: AnswerLimits, deadline: float) -> str:
    """What a cached verdict depends on besides the answers: assignment, keys, every limit."""
    from dhsym._version import __version__

    text = "\n".join([a.fingerprint, repr(a.questions), repr(limits), f"{deadline!r}", __version__])
    return hashlib.sha256(text.encode("utf-8", "replace")).hexdigest()[:16]


_FINAL = ("correct", "incorrect", "unreadable", "missing")


def _final(record: GradeRecord, a: Assignment) -> bool:
    """True for a graded record (fingerprinted) with a final verdict for each question of ``a``,
    each score within ``[0, points]`` of its question, and the total their sum."""
    points = {q.id: q.points for q in a.questions}
    return (
        record.status == "graded"
        and bool(record.fingerprint)
        and set(record.scores) == set(points)
        and set(record.verdicts) == set(points)
        and all(v in _FINAL for v in record.verdicts.values())
        and all(0 <= record.scores[q] <= p for q, p in points.items())
        and math.isclose(record.score, sum(record.scores.values()), rel_tol=1e-9, abs_tol=1e-9)
        and math.isclose(record.max_score, a.max_score, rel_tol=1e-9)
    )


def _same_submission(record: GradeRecord, sub: Submission) -> bool:
    """The cached record is this submission's: uid, student, name, source and flags agree."""
    return (record.uid, record.student, record.name, record.source, tuple(record.flags)) == (
        sub.uid,
        sub.student,
        sub.name,
        sub.source,
        tuple(sub.flags),
    )


def _cached_record(value: object, a: Assignment) -> GradeRecord | None:
    """The record of a cache entry, ``None`` unless it is a well-formed final record for ``a``."""
    try:
        record = GradeRecord.from_dict(value)
    except ValueError:
        return None
    return record if _final(record, a) else None


def _load_cache(
    path: Path, run_fp: str, a: Assignment, warnings: list[str]
) -> dict[str, GradeRecord]:
    """The cached records of this run's fingerprint; anything malformed is ignored (a warning)."""
    if not path.exists():
        return {}
    try:
        data = json.loads(read_limited(path, _MAX_CACHE, what="the grading cache"))
    except (FileRefused, ValueError, RecursionError) as err:
        reason = err.message if isinstance(err, DHError) else f"not valid JSON ({err})"
        warnings.append(f"ignoring the grading cache {path.name}: {reason}; grading everything")
        return {}
    if not isinstance(data, dict) or not isinstance(data.get("records"), dict):
        warnings.append(
            f"ignoring the grading cache {path.name}: it is not a cache written by dhsym; "
            "grading everything"
        )
        return {}
    if data.get("assignment") != run_fp:
        return {}  # another assignment, key, limit or dhsym version: everything is regraded
    cached = {k: _cached_record(r, a) for k, r in data["records"].items()}
    records = {k: r for k, r in cached.items() if r is not None and r.uid == k}
    bad = len(cached) - len(records)
    if bad:
        warnings.append(f"ignoring {bad} malformed record(s) of the grading cache {path.name}")
    return records


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
    variants: str | Path | ClassList | None = None,
    keys: PreparedKeys | None = None,
) -> GradeReport:
    """Grade every submission and write the report folder (see the module docstring).

    ``workers`` processes (0: in this process, without isolation), or a Dask cluster
    with ``dask`` (an address or a ``Client``).  ``timeout`` is the time limit of
    one answer (default: the assignment's ``time_limit``); a whole submission gets
    the sum over its questions plus a few seconds before its process is killed.

    An assignment with question tests is refused while one fails
    (:func:`~dhsym.checking.grading.assignment_tests.run_assignment_tests`, the tests only:
    the keys' own answers are ``dhsym check-assignment``'s; ``keys``: the keys already
    prepared, e.g. by :meth:`Assignment.load`).  An assignment with
    ``variants:`` needs the class list ``variants`` (a CSV file or a
    :class:`~dhsym.checking.grading.variants.ClassList`): each student is graded against
    their own key; a submission of a student not on it is an error.
    """
    keys = keys if keys is not None else PreparedKeys()
    a = assignment if isinstance(assignment, Assignment) else Assignment.load(assignment, keys)
    if any(q.tests for q in a.questions):
        tested = run_assignment_tests(a, keys=keys, key_answers=False)
        if not tested.passed:
            bad = tested.failures[0]
            raise DHError(
                f"the assignment's question tests fail ({len(tested.failures)} of "
                f"{len(tested.rows)}; first: question {bad.question}, {bad.case} answer "
                f"expected {bad.expected}, got {bad.got}): run dhsym check-assignment on it "
                "for the table, and fix the key or the tests before grading"
            )
    drawn = _class_variants(a, variants)
    seconds = check_seconds(timeout, "--timeout") if timeout is not None else a.seconds
    lim = limits or AnswerLimits(seconds=seconds)
    if not isinstance(workers, int) or not 0 <= workers <= 1024:
        raise DHError(f"--workers: expected a number of processes from 0 to 1024, got {workers}")
    if dask is not None:
        dask = dask_address(dask)
    root = Path(out_dir).resolve()
    warnings: list[str] = []
    refused: list[tuple[str, str]] = []
    subs = read_submissions(
        submissions, a, lim, exclude=(root,), warnings=warnings, refused=refused
    )
    own: dict[str, Assignment] = {}  # each student's assignment, with their values
    if drawn is not None:
        for k, s in enumerate(subs):
            v = drawn.get(variant_id(s.student))
            if v is None and not s.error:
                subs[k] = replace(s, error="not on the class list of the variants")
            elif v is not None:
                own[s.uid] = a.for_variant(v)
    root.mkdir(parents=True, exist_ok=True)
    (root / "feedback").mkdir(exist_ok=True)
    feedback = inside(root, "feedback")  # resolved once; each page name is a plain name
    deadline = lim.seconds * max(1, len(a.questions)) + _SLACK_SECONDS
    run_fp = _run_fingerprint(a, lim, deadline)
    cache_path = inside(root, CACHE_NAME)
    cache = _load_cache(cache_path, run_fp, a, warnings)
    used: set[str] = set()
    files = {s.uid: safe_name(s.uid, used) for s in subs}
    todo: list[Submission] = []
    records: dict[str, GradeRecord] = {}
    failed = 0
    for s in subs:
        old = cache.get(s.uid)
        names = [inside_folder(root, feedback, files[s.uid] + ext) for ext in (".md", ".html")]
        if s.error:
            records[s.uid] = _failed_record(s, a, JobFailure("error", s.error))
            failed += 1
        elif (
            old
            and _same_submission(old, s)
            and old.fingerprint == s.fingerprint(own.get(s.uid, a), run_fp)
            and all(p.is_file() for p in names)
        ):
            records[s.uid] = old
        else:
            todo.append(s)
    jobs = [(own.get(s.uid, a), s, lim) for s in todo]
    if dask is not None:
        runner = run_dask(grade_submission, jobs, dask, deadline, state=PreparedKeys)
    elif workers > 0:
        warm = partial(warm_worker, shared_keys(j[0] for j in jobs))
        runner = run_pool(
            grade_submission, jobs, workers, deadline, state=PreparedKeys, warm=warm, local=keys
        )
    else:
        runner = run_serial(grade_submission, jobs, state=PreparedKeys)
    bar = Progress(len(jobs), enabled=progress)
    # each final record turned into JSON text once (the cache is those texts joined, the
    # bytes json.dumps gives the whole); the cache is written again after 5 s or 20 times
    # as long as the last write took, whichever is later (a large class's cache is not
    # rewritten all the time)
    final = {k: _record_json(r) for k, r in records.items() if _final(r, a)}
    last_save, pause = time.monotonic(), 5.0

    def save() -> float:
        start = time.monotonic()
        write_atomic(cache_path, _cache_json(run_fp, final))
        return max(5.0, 20 * (time.monotonic() - start))

    for s in subs:  # the pages of submissions that could not be read at all
        if s.error:
            _write_pages(root, feedback, files[s.uid], records[s.uid].pages)
            records[s.uid] = replace(records[s.uid], pages={})
    try:
        for k, outcome in runner:
            sub = todo[k]
            if isinstance(outcome, JobFailure):
                record = _failed_record(sub, a, outcome)
            elif isinstance(outcome, GradeRecord):  # unpickled from the worker
                record = outcome
            else:
                raise TypeError(f"a grading job returned {type(outcome).__name__}")
            if record.status != "graded":
                failed += 1
            else:
                record = replace(record, fingerprint=sub.fingerprint(own.get(sub.uid, a), run_fp))
            _write_pages(root, feedback, files[sub.uid], record.pages)
            records[sub.uid] = replace(record, pages={})
            if _final(records[sub.uid], a):
                final[sub.uid] = _record_json(records[sub.uid])
            bar.step()
            if time.monotonic() - last_save > pause:
                pause = save()
                last_save = time.monotonic()
    finally:
        save()
    ordered = [records[s.uid] for s in subs if s.uid in records]
    gradebook = write_gradebook(root, a, ordered, files)
    summary = write_summary(root, a, ordered, files, refused=refused)
    scores = [r.score for r in ordered]
    return GradeReport(
        root,
        len(subs),
        len(jobs),
        len(subs) - len(jobs) - sum(bool(s.error) for s in subs),
        failed,
        statistics.fmean(scores) if scores else 0.0,
        gradebook,
        summary,
        tuple(ordered),
        tuple(warnings),
        tuple(refused),
    )


def _record_json(record: GradeRecord) -> str:
    """One record of the grading cache as JSON text (what :func:`_cache_json` joins)."""
    return json.dumps(record.to_dict())


def _cache_json(run_fp: str, records: Mapping[str, str]) -> str:
    """The grading cache's text from its records' JSON texts (:func:`_record_json`): the
    same text as ``json.dumps({"assignment": run_fp, "records": {uid: record data}})``.

    >>> data = {"s1": {"score": 1.5, "name": "Zoë"}, "s2": {"flags": []}}
    >>> text = _cache_json("fp", {k: json.dumps(v) for k, v in data.items()})
    >>> text == json.dumps({"assignment": "fp", "records": data}), _cache_json("fp", {})
    (True, '{"assignment": "fp", "records": {}}')
    """
    body = ", ".join(f"{json.dumps(uid)}: {text}" for uid, text in records.items())
    return f'{{"assignment": {json.dumps(run_fp)}, "records": {{{body}}}}}'


def _class_variants(
    a: Assignment, variants: str | Path | ClassList | None
) -> dict[str, Variant] | None:
    """Each student's values (by normalised id), or None for an assignment without variants."""
    if a.variants is None:
        if variants is not None:
            raise DHError("--variants: this assignment draws no values per student (no variants:)")
        return None
    if variants is None:
        raise DHError(
            "this assignment draws values per student (variants:): give the class list the "
            "sheets were made for (--variants CLASS.csv)"
        )
    roster = variants if isinstance(variants, ClassList) else ClassList.load(variants)
    return class_variants(a.variants, roster.ids)


def _write_pages(root: Path, folder: Path, name: str, pages: Mapping[str, str]) -> None:
    for ext, fmt in ((".md", "md"), (".html", "html")):
        write_atomic(inside_folder(root, folder, name + ext), pages[fmt])
