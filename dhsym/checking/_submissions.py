"""Reading submissions: a folder (a sub-folder or a YAML file per student) or a CSV file.

Nothing is followed or read in full that could be hostile: links and special
files are skipped, and every file is read only up to a size limit (an answer
that is too long becomes a read problem of that question, not an error). The
public names are re-exported by :mod:`dhsym.checking.grading`.

Examples
--------
>>> Submission("alice", "Alice", (("q1", "T = I"),)).answers
(('q1', 'T = I'),)
"""

from __future__ import annotations

import csv
import hashlib
import io
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import yaml

from dhsym.errors import DHError

from ._limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, UnreadableAnswer

if TYPE_CHECKING:
    from .grading import Assignment

__all__ = ["Submission", "read_submissions"]

_MAX_SUBMISSION_FILE = 2_000_000
_MAX_CSV = 500_000_000


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
