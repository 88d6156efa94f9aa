"""Reading submissions: a folder (a sub-folder or a YAML file per student) or a CSV file.

Nothing is followed or read in full that could be hostile: symbolic links,
hard-linked files and special files are refused, and every file is read only up
to a size limit (:func:`dhsym.model.yamlsafe.read_limited`; an answer that cannot be
read becomes a read problem of that question). Each submission is read inside
its own guard: whatever goes wrong becomes that submission's ``error`` and the
others are read on. The rules a teaching assistant relies on:

- **Answer files.** The answer to question ``q5`` is the file ``q5`` or
  ``q5.<anything>`` in the student's folder. With several (``q5.md`` and
  ``q5.txt``) the first in alphabetical order of the file name is graded and the
  others are named in the feedback and the gradebook's ``flags``.
- **Duplicate ids.** Two submissions with the same student id (a folder
  ``alice/`` and a file ``alice.yaml``, two CSV rows, or ids that differ only in
  case, in Unicode normal form or in characters a file name cannot hold:
  :func:`identity`) are never merged: both are graded, each under its own feedback
  file, and both are flagged ``duplicate id``; an LMS import refuses them.
- **Names.** Ids are in Unicode's NFC form; a folder or file name that is not UTF-8
  becomes an id with ``\\xNN`` escapes.
- **No silent drops.** Every entry of the folder is a submission or a refusal with
  its reason (hidden entries, symbolic links, other files, report folders), listed
  in the summary page and on standard error.

The public names are re-exported by :mod:`dhsym.checking.grading.batch`.

Examples
--------
>>> Submission("alice", "Alice", (("q1", "T = I"),)).answers
(('q1', 'T = I'),)
>>> student_id("caf\\udce9")
'caf\\\\xe9'
"""

from __future__ import annotations

import csv
import hashlib
import io
import os
import unicodedata
from collections import defaultdict
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

from dhsym.errors import DHError
from dhsym.model.yamlsafe import FileRefused, YAMLLimits, load_yaml, read_limited

from ..reading.answers import answer_text
from ..reading.limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, UnreadableAnswer
from .report_files import CACHE_NAME, name_base

if TYPE_CHECKING:
    from .assignment import Assignment

__all__ = [
    "Submission",
    "identity",
    "read_submission_file",
    "read_submission_folder",
    "read_submissions",
    "student_id",
]

_MAX_SUBMISSION_FILE = 2_000_000
_MAX_CSV = 500_000_000
_MAX_NAME_FILE = 1_000
_SUBMISSION_YAML = YAMLLimits(max_bytes=_MAX_SUBMISSION_FILE, max_nodes=20_000, max_depth=32)


@dataclass(frozen=True)
class Submission:
    """One student's answers (question id → raw text or bytes), read problems and flags.

    ``source`` says where it came from (``alice/``, ``alice.yaml``, ``row 3``);
    ``uid`` is unique in a run (the student id, or ``id [source]`` for a
    duplicate id); ``flags`` are notes for the teaching assistant (duplicate id,
    answer files not graded); ``error`` is set when the submission could not be
    read at all.
    """

    student: str
    name: str
    answers: tuple[tuple[str, str | bytes], ...] = ()
    problems: tuple[tuple[str, str], ...] = ()
    source: str = ""
    flags: tuple[str, ...] = ()
    error: str = ""
    uid: str = ""

    def __post_init__(self) -> None:
        if not self.uid:
            object.__setattr__(self, "uid", self.student)

    def fingerprint(self, assignment: Assignment, salt: str = "") -> str:
        """Changes when the assignment, ``salt`` (the limits), an answer, a flag or the name do."""
        h = hashlib.sha256(assignment.fingerprint.encode() + b"\0" + salt.encode())
        for qid, text in self.answers + self.problems:
            h.update(qid.encode() + b"\0")
            h.update(text if isinstance(text, bytes) else text.encode("utf-8", "replace"))
            h.update(b"\0")
        for part in (self.name, self.uid, self.error, *self.flags):
            h.update(part.encode("utf-8", "replace") + b"\0")
        return h.hexdigest()[:20]


def student_id(name: str) -> str:
    """A printable id for a file or folder name: bytes that are not UTF-8 become ``\\xNN``;
    the text is in Unicode's NFC form (``josé`` typed on a Mac and on Windows is one id)."""
    text = unicodedata.normalize("NFC", os.fsencode(name).decode("utf-8", "backslashreplace"))
    return "".join(ch if ch.isprintable() else f"\\x{ord(ch):02x}" for ch in text)


def identity(student: str) -> str:
    """What two ids must share to be one student: NFC, case-folded, as a file name.

    >>> identity("José") == identity("jose\u0301") == identity("JOSÉ")
    True
    """
    return name_base(unicodedata.normalize("NFC", student)).casefold()


def _read_answer(path: Path, limit: int) -> bytes:
    try:
        what = f"the file {student_id(path.name)}"
        return read_limited(path, limit, follow_links=False, hard_links=False, what=what)
    except FileRefused as err:
        raise UnreadableAnswer(err.message) from None


def _answer_files(names: list[str], qid: str) -> list[str]:
    """The files that answer ``qid``, in the documented order (alphabetical by name)."""
    return sorted(n for n in names if n == qid or n.startswith(qid + "."))


def read_submission_folder(folder: Path, qids: list[str], limits: AnswerLimits) -> Submission:
    """One student's folder: the answer file of each question in ``qids`` (the first in
    alphabetical order when there are several, the others flagged), each read up to
    ``limits``; a file that cannot be read is that question's read problem."""
    student = student_id(folder.name)
    answers, problems, flags = [], [], []
    names = sorted(os.listdir(folder))
    for qid in qids:
        files = _answer_files(names, qid)
        if not files:
            continue
        if len(files) > 1:
            others = ", ".join(student_id(n) for n in files[1:])
            flags.append(
                f"{qid}: graded {student_id(files[0])}; not graded: {others} "
                "(one answer file per question: the first in alphabetical order counts)"
            )
        try:
            answers.append((qid, _read_answer(folder / files[0], limits.max_bytes)))
        except UnreadableAnswer as err:
            problems.append((qid, str(err)))
    name = student
    if "name.txt" in names:
        try:
            raw = _read_answer(folder / "name.txt", _MAX_NAME_FILE)
            name = " ".join(raw.decode("utf-8", "replace").split())[:200] or student
        except UnreadableAnswer:
            pass
    return Submission(student, name, tuple(answers), tuple(problems), f"{student}/", tuple(flags))


def read_submission_file(path: Path, qids: list[str]) -> Submission:
    """One student's YAML file: ``q1: …`` per question (or the same under ``answers:``),
    with an optional ``name:``.  An answer may be text, a number, a table as a list of rows
    (``- {theta: theta1, d: 0, a: 0, alpha: 90}``) or a matrix as a list of rows
    (:func:`~dhsym.checking.reading.answers.answer_text`); an answer present in another
    form is that question's read problem, with the reason.  A file that cannot be read,
    or holds no question of the assignment, is a read problem of every question.
    """
    student = student_id(path.stem)
    source = student_id(path.name)
    try:
        raw = _read_answer(path, _MAX_SUBMISSION_FILE)
        data = load_yaml(raw, limits=_SUBMISSION_YAML)
        if not isinstance(data, Mapping):
            raise UnreadableAnswer(_FILE_FORM)
        given = data.get("answers", data)
        if not isinstance(given, Mapping):
            raise UnreadableAnswer(f"'answers' is not a mapping; {_FILE_FORM}")
        by_id = {str(k): v for k, v in given.items()}
        if not set(by_id) & set(qids):
            raise UnreadableAnswer(f"no question of the assignment was found; {_FILE_FORM}")
    except DHError as err:  # unreadable, refused, or YAML over a limit
        reason = err.message if isinstance(err, FileRefused) else str(err)
        return Submission(student, student, (), tuple((q, reason) for q in qids), source)
    answers, problems = [], []
    for qid in qids:
        if qid not in by_id:
            continue
        try:
            text = answer_text("" if by_id[qid] is None else by_id[qid])
        except UnreadableAnswer as err:
            problems.append((qid, err.message))
            continue
        answers.append((qid, text))
    flags = []
    extra = sorted(set(by_id) - set(qids) - ({"name"} if given is data else set()))
    if extra:
        shown = ", ".join(student_id(k) for k in extra[:10])[:300]
        flags.append(f"not questions of the assignment, not graded: {shown}")
    name = data.get("name")
    shown = " ".join(str(name).split())[:200] if isinstance(name, (str, int)) else ""
    return Submission(
        student, shown or student, tuple(answers), tuple(problems), source, tuple(flags)
    )


_FILE_FORM = "expected 'q1: …' per question (or 'answers: {q1: …}') in the submission file"


def _from_csv(path: Path, qids: list[str]) -> Iterator[Submission]:
    try:
        data = read_limited(path, _MAX_CSV, what="the CSV file")
        text = data.decode("utf-8-sig")  # what Excel writes: UTF-8 with a byte-order mark
    except UnicodeDecodeError as err:
        raise DHError(
            f"the CSV file is not UTF-8 text (byte {err.start}); save it as 'CSV UTF-8'",
            file=str(path),
        ) from None
    except FileRefused as err:
        raise DHError(err.message, file=str(path)) from None
    old = csv.field_size_limit()
    csv.field_size_limit(_MAX_CSV)
    try:
        first = text.split("\n", 1)[0]
        delimiter = ";" if first.count(";") > first.count(",") else ","  # Excel in many locales
        reader = csv.DictReader(io.StringIO(text, newline=""), delimiter=delimiter)
        fields = reader.fieldnames or []
        idcol = next((f for f in fields if f.strip().lower() in ("student", "id")), None)
        if idcol is None:
            shown = ", ".join(repr(f.strip()) for f in fields[:12]) or "none"
            raise DHError(
                f"the CSV needs a 'student' column (the student id); its columns are: {shown}",
                file=str(path),
            )
        namecol = next((f for f in fields if f.strip().lower() == "name"), None)
        for k, row in enumerate(reader, 2):
            student = unicodedata.normalize("NFC", (row.get(idcol) or "").strip()) or f"row{k}"
            answers = tuple((q, row[q]) for q in qids if isinstance(row.get(q), str) and row[q])
            name = (row.get(namecol) or "").strip() if namecol else ""
            yield Submission(student, name or student, answers, (), f"row {k}")
    except csv.Error as err:
        raise DHError(f"not a valid CSV file: {err}", file=str(path)) from None
    finally:
        csv.field_size_limit(old)


def _guarded(read: Callable[[], Submission], student: str, source: str) -> Submission:
    """``read()``, or a submission whose ``error`` says why it could not be read."""
    try:
        return read()
    except Exception as err:  # noqa: BLE001 - one submission never stops the others
        reason = f"could not be read ({type(err).__name__}: {err})"
        return Submission(student, student, source=source, error=reason)


def _flag_duplicates(subs: list[Submission]) -> list[Submission]:
    """Give every submission of a shared id (after NFC, case folding and file-name
    characters: :func:`identity`) its own ``uid`` and a flag naming the others.

    The uid is ``id [source]``; when that too is shared (``josé/`` in NFC and in NFD, a
    byte that is not UTF-8 and its escape typed out as a name) the second and later, in
    the order of ``subs``, get `` #2``, `` #3`` …: every submission keeps its own row and
    feedback page.

    >>> a, b = Submission("ann", "A", source="ann/"), Submission("ANN", "A", source="ANN/")
    >>> [s.uid for s in _flag_duplicates([a, b, a])]
    ['ann [ann/]', 'ANN [ANN/]', 'ann [ann/] #2']
    """
    groups: dict[str, list[int]] = defaultdict(list)
    for k, s in enumerate(subs):
        groups[identity(s.student)].append(k)
    out = list(subs)
    for members in groups.values():
        if len(members) < 2:
            continue
        uids: dict[int, str] = {}
        seen: dict[str, int] = defaultdict(int)
        for k in members:
            base = f"{subs[k].student} [{subs[k].source}]"
            seen[base] += 1
            uids[k] = base if seen[base] == 1 else f"{base} #{seen[base]}"
        shown = ", ".join(uids[k] for k in members)
        note = f"duplicate id: {len(members)} submissions: {shown} (each graded on its own)"
        for k in members:
            out[k] = replace(subs[k], uid=uids[k], flags=(note, *subs[k].flags))
    return out


def read_submissions(
    source: str | Path,
    assignment: Assignment,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    *,
    exclude: tuple[Path, ...] = (),
    warnings: list[str] | None = None,
    refused: list[tuple[str, str]] | None = None,
) -> list[Submission]:
    """All submissions of a folder or CSV file, sorted by student id (then source).

    Every entry of a folder becomes a submission or a refusal ``(entry, reason)`` in
    ``refused`` (also a line of ``warnings``): hidden entries, symbolic links, files
    that are not submissions, the report folder (``exclude``) and earlier report
    folders (a grading cache, ``gradebook.csv`` and ``feedback/``).  Nothing is
    dropped silently.
    """
    src = Path(source)
    qids = [q.id for q in assignment.questions]
    notes = warnings if warnings is not None else []
    refusals = refused if refused is not None else []
    skip = {p.resolve() for p in exclude}
    if src.is_file():
        subs = list(_from_csv(src, qids))
    elif src.is_dir():
        if src.resolve() in skip:
            raise DHError(
                f"the report folder is the submissions folder {src}: its feedback/ would be "
                "read as a student on the next run; write the report elsewhere (-o report)"
            )
        subs = []
        for entry in sorted(os.scandir(src), key=lambda e: e.name):
            path = Path(entry.path)
            student, shown = student_id(Path(entry.name).stem), student_id(entry.name)
            reason = _refusal(entry, path, skip)
            if reason:
                shown += "/" if entry.is_dir(follow_symlinks=False) else ""
                refusals.append((shown, reason))
                notes.append(f"not graded: {shown}: {reason}")
            elif entry.is_dir(follow_symlinks=False):
                subs.append(
                    _guarded(
                        partial(read_submission_folder, path, qids, limits),
                        student_id(entry.name),
                        shown,
                    )
                )
            else:
                subs.append(_guarded(partial(read_submission_file, path, qids), student, shown))
    else:
        raise DHError(f"no submissions folder or CSV file at {src}")
    return sorted(_flag_duplicates(subs), key=lambda s: (s.student, s.source, s.uid))


def _refusal(entry: os.DirEntry[str], path: Path, reports: set[Path]) -> str:
    """Why a folder entry is not a submission, or ``""`` when it is one."""
    if entry.is_symlink():
        return "a symbolic link (never followed: make it a real folder or file)"
    if entry.name.startswith("."):
        return "a hidden entry"
    if entry.is_dir(follow_symlinks=False):
        if path.resolve() in reports:
            return "the report folder of this run"
        if all((path / n).exists() for n in (CACHE_NAME, "gradebook.csv", "feedback")):
            return "a grading report folder (grading cache, gradebook.csv and feedback/)"
        return ""
    if not entry.is_file(follow_symlinks=False):
        return "not a regular file or folder"
    if path.suffix.lower() not in (".yaml", ".yml", ".json"):
        return "not a submission (expected a student folder or a .yaml/.yml/.json file)"
    return ""
