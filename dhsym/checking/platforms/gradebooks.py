"""Gradebook import files for learning management systems: Canvas, Moodle, generic.

``dhsym grade … --gradebook canvas|moodle|generic --roster ROSTER.csv`` writes
``<kind>-import.csv`` into the report folder: one row per graded student with the
total score of the assignment, the student named by the ids the LMS matches on.

**Roster.** A CSV file mapping each submission (the folder name or the ``student``
column ``dhsym grade`` read) to the student in the LMS.  Columns (any order, header
case and ``_``/space do not matter): ``submission`` (required), ``name``,
``canvas_id`` (or ``ID``), ``sis_user_id``, ``sis_login_id``, ``section``, ``email``,
``username``, ``idnumber``.  A graded submission missing from the roster is an
error naming it (its grade would be lost); a roster student without a submission is
left out of the import (the LMS keeps what it has) and listed in a note.  Two graded
submissions of one student (ids equal up to Unicode NFC form and case) refuse the
import, listing them: an LMS file never has two rows for one student.

**Canvas** (the Gradebook's *Import* of a CSV; guide "How do I import grades in the
Gradebook?", https://community.canvaslms.com/t5/Instructor-Guide/How-do-I-import-grades-in-the-Gradebook/ta-p/807,
and Canvas's ``GradebookImporter``): header ``Student, ID, SIS User ID, SIS Login
ID, Section`` then one column per assignment, ``Name`` or ``Name (assignment id)``
(the id makes Canvas update that assignment instead of matching by title); a second
row starting ``Points Possible`` gives the assignment's points.  Canvas finds the
student by ``ID`` (Canvas user id), else ``SIS User ID``, else ``SIS Login ID``, else
the name, so every row needs one of the three ids.

**Moodle** (*Grade administration > Import > CSV file*; docs "Grade import",
https://docs.moodle.org/en/Grade_import): any columns; on the import page the
teacher maps one identifying column to ``useridnumber``, ``useremail`` or
``username`` ("Map from"/"Map to") and the grade column to a grade item.  Moodle
aborts the whole import when one row's user is not found, so only identifier
columns that every row has are written: ``ID number``, ``Email address``,
``Username``; then ``Full name`` and the grade column.  Grades must be plain numbers.

**Generic**: ``student, name, email, lms_id, <question ids…>, total, max, status``.

Every cell that a spreadsheet would run as a formula is neutralised (names, section,
title: :func:`~dhsym.checking.grading.report_files.csv_cell`); an LMS *identifier* that starts
like a formula is refused instead (changing it would make the LMS miss the student).  The
``submission`` column is only matched, never written, so it may start with anything.

Examples
--------
>>> r = Roster.from_text("submission,name,email\\nalice,Alice A,alice@uni.edu\\n")
>>> r.entries[0].email
'alice@uni.edu'
>>> Roster.from_text("submission,email\\nbob,=cmd|' /C calc'!A0\\n", "roster.csv")
Traceback (most recent call last):
...
dhsym.errors.DHError: roster.csv: row 2, field email: a value starting with '=' ...
"""

from __future__ import annotations

import csv
import io
import unicodedata
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from dhsym.errors import DHError
from dhsym.model.yamlsafe import read_limited

from ..grading.report_files import csv_cell, inside, write_atomic

if TYPE_CHECKING:
    from ..grading.assignment import Assignment
    from ..grading.batch import GradeReport
    from ..grading.records import GradeRecord

__all__ = [
    "CANVAS_HEADER",
    "KINDS",
    "LmsGradebook",
    "Roster",
    "RosterEntry",
    "canvas_rows",
    "generic_rows",
    "moodle_rows",
    "write_lms_gradebook",
]

KINDS = ("canvas", "moodle", "generic")
#: The student columns of a Canvas gradebook CSV, in Canvas's order.
CANVAS_HEADER = ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")
_MOODLE_IDS = (("idnumber", "ID number"), ("email", "Email address"), ("username", "Username"))
_ALIASES = {
    "submission": "submission",
    "name": "name",
    "student": "name",
    "full name": "name",
    "canvas id": "canvas_id",
    "id": "canvas_id",
    "sis user id": "sis_user_id",
    "sis login id": "sis_login_id",
    "section": "section",
    "email": "email",
    "email address": "email",
    "username": "username",
    "idnumber": "idnumber",
    "id number": "idnumber",
}
_IDENTIFIERS: tuple[str, ...] = (
    "submission",
    "canvas_id",
    "sis_user_id",
    "sis_login_id",
    "email",
    "username",
    "idnumber",
)
#: the identifiers written as they are into an LMS file (``submission`` never is)
_WRITTEN = frozenset(_IDENTIFIERS) - {"submission"}
_MAX_ROSTER = 50_000_000


@dataclass(frozen=True)
class RosterEntry:
    """One student: the submission name and the LMS's ids (empty when not known)."""

    submission: str
    name: str = ""
    canvas_id: str = ""
    sis_user_id: str = ""
    sis_login_id: str = ""
    section: str = ""
    email: str = ""
    username: str = ""
    idnumber: str = ""
    row: int = 0


@dataclass(frozen=True)
class Roster:
    """The students of a course as the LMS knows them (see the module docstring)."""

    entries: tuple[RosterEntry, ...]
    file: str = ""

    @classmethod
    def load(cls, path: str | Path) -> Roster:
        """Read a roster CSV file (UTF-8, a byte-order mark is fine)."""
        p = Path(path)
        data = read_limited(p, _MAX_ROSTER, what="the roster")  # regular files only, capped
        try:
            text = data.decode("utf-8-sig")
        except UnicodeDecodeError as err:
            raise DHError(f"cannot read the roster: {err}", file=str(p)) from None
        return cls.from_text(text, str(p))

    @classmethod
    def from_text(cls, text: str, file: str = "roster") -> Roster:
        """A roster from CSV text; errors name ``file``, the row and the field."""
        reader = csv.reader(io.StringIO(text.lstrip("\ufeff"), newline=""))
        header = next(reader, None)
        if not header:
            raise DHError("the roster is empty: expected a header with 'submission'", file=file)
        cols: dict[int, str] = {}
        for k, h in enumerate(header):
            key = _ALIASES.get(" ".join(h.replace("_", " ").lower().split()))
            if key is not None and key not in cols.values():
                cols[k] = key
        if "submission" not in cols.values():
            raise DHError(
                "the roster needs a 'submission' column (the submission folder or CSV "
                f"student id); its columns are: {', '.join(header)}",
                file=file,
            )
        entries: list[RosterEntry] = []
        seen: dict[tuple[str, str], int] = {}  # (identifier, value) -> its row
        for row_no, row in enumerate(reader, 2):
            if not any(c.strip() for c in row):
                continue
            values = {key: row[k].strip() if k < len(row) else "" for k, key in cols.items()}
            if not values["submission"]:
                raise DHError("empty submission name", file=file, row=row_no, field="submission")
            for key in _IDENTIFIERS:
                v = values.get(key, "")
                if v and key in _WRITTEN and csv_cell(v) != v:
                    raise DHError(
                        f"a value starting with {v[0]!r} would run as a spreadsheet formula; "
                        "an LMS id cannot be changed to neutralise it",
                        file=file,
                        row=row_no,
                        field=key,
                    )
                if v and (key, v) in seen:
                    raise DHError(
                        f"{v!r} is already the {key} of row {seen[(key, v)]}",
                        file=file,
                        row=row_no,
                        field=key,
                    )
                if v:
                    seen[(key, v)] = row_no
            entries.append(RosterEntry(**values, row=row_no))
        return cls(tuple(entries), file)

    def match(self, students: Iterable[str]) -> tuple[list[RosterEntry], list[RosterEntry]]:
        """The roster entry of each graded student (in order), and the entries with no
        submission.  A graded student missing from the roster is an error."""
        by_sub = {unicodedata.normalize("NFC", e.submission): e for e in self.entries}
        students = [unicodedata.normalize("NFC", s) for s in students]
        missing = [s for s in students if s not in by_sub]
        if missing:
            shown = ", ".join(repr(s) for s in missing[:10])
            more = f" and {len(missing) - 10} more" if len(missing) > 10 else ""
            raise DHError(
                f"{len(missing)} graded submission(s) are not in the roster: {shown}{more}. "
                "Add a row for each (column 'submission'; names are compared exactly).",
                file=self.file,
            )
        graded = set(students)
        return [by_sub[s] for s in students], [
            e for e in self.entries if unicodedata.normalize("NFC", e.submission) not in graded
        ]


def _refuse_duplicates(records: Sequence[GradeRecord]) -> None:
    """Refuse an import with two submissions for one student (the LMS would keep whichever
    row came last): the message lists them, with their scores, to be resolved first."""
    from ..grading.submissions import identity

    groups: dict[str, list[GradeRecord]] = {}
    for r in records:
        groups.setdefault(identity(r.student), []).append(r)
    shared = [g for g in groups.values() if len(g) > 1]
    if shared:
        shown = "; ".join(
            ", ".join(f"{r.student!r} from {r.source} ({r.score:g} points)" for r in g)
            for g in shared[:10]
        )
        raise DHError(
            f"{len(shared)} student id(s) have more than one submission: {shown}. An LMS keeps "
            "one row per student: remove or rename the extra submissions (ids are compared "
            "in Unicode NFC form, ignoring case) and grade again; no import file was written"
        )


def _roster_for(records: Sequence[GradeRecord], roster: Roster | None) -> Roster:
    if roster is not None:
        return roster
    return Roster(tuple(RosterEntry(r.student, r.name) for r in records), "")


def _need(entries: Sequence[RosterEntry], what: Sequence[str], lms: str, file: str) -> None:
    bad = [e for e in entries if not any(getattr(e, w) for w in what)]
    if bad:
        shown = ", ".join(f"{e.submission!r} (row {e.row})" for e in bad[:10])
        raise DHError(
            f"{lms} needs {' or '.join(what)} for every student; missing for {shown}", file=file
        )


def canvas_rows(
    records: Sequence[GradeRecord], entries: Sequence[RosterEntry], column: str, points: float
) -> list[list[str]]:
    """The Canvas import: header, the ``Points Possible`` row, one row per student."""
    rows = [[*CANVAS_HEADER, csv_cell(column)], ["Points Possible", "", "", "", "", f"{points:g}"]]
    for r, e in zip(records, entries):
        name = e.name or r.name
        rows.append(
            [
                csv_cell(name),
                e.canvas_id,
                e.sis_user_id,
                e.sis_login_id,
                csv_cell(e.section),
                f"{r.score:g}",
            ]
        )
    return rows


def moodle_rows(
    records: Sequence[GradeRecord], entries: Sequence[RosterEntry], column: str
) -> list[list[str]]:
    """The Moodle import: the identifier columns every student has, name, grade."""
    ids = [(key, head) for key, head in _MOODLE_IDS if all(getattr(e, key) for e in entries)]
    rows = [[*(head for _, head in ids), "Full name", csv_cell(column)]]
    for r, e in zip(records, entries):
        rows.append(
            [*(getattr(e, key) for key, _ in ids), csv_cell(e.name or r.name), f"{r.score:g}"]
        )
    return rows


def generic_rows(
    records: Sequence[GradeRecord], entries: Sequence[RosterEntry], question_ids: Sequence[str]
) -> list[list[str]]:
    """The generic import: ids, per-question points, total, maximum and status."""
    rows = [["student", "name", "email", "lms_id", *question_ids, "total", "max", "status"]]
    for r, e in zip(records, entries):
        lms_id = e.canvas_id or e.sis_user_id or e.idnumber or e.username or e.sis_login_id
        rows.append(
            [
                csv_cell(r.student),
                csv_cell(e.name or r.name),
                e.email,
                lms_id,
                *(f"{r.scores.get(q, 0):g}" for q in question_ids),
                f"{r.score:g}",
                f"{r.max_score:g}",
                r.status,
            ]
        )
    return rows


@dataclass(frozen=True)
class LmsGradebook:
    """What :func:`write_lms_gradebook` wrote, and notes for the teacher."""

    path: Path
    students: int
    notes: tuple[str, ...] = ()


def write_lms_gradebook(
    kind: str,
    report: GradeReport,
    assignment: Assignment,
    roster: Roster | None = None,
    *,
    column: str | None = None,
) -> LmsGradebook:
    """Write ``<kind>-import.csv`` into the report folder of a :func:`grade` run."""
    if kind not in KINDS:
        raise DHError(f"unknown gradebook {kind!r}: expected one of {', '.join(KINDS)}")
    records = list(report.records)
    r = _roster_for(records, roster)
    if kind != "generic" and roster is None:
        raise DHError(f"the {kind} import needs a roster (LMS ids per student)")
    _refuse_duplicates(records)
    entries, absent = r.match(x.student for x in records)
    title = column or assignment.title
    if kind == "canvas":
        _need(entries, ("canvas_id", "sis_user_id", "sis_login_id"), "Canvas", r.file)
        rows = canvas_rows(records, entries, title, assignment.max_score)
    elif kind == "moodle":
        _need(entries, ("idnumber", "email", "username"), "Moodle", r.file)
        rows = moodle_rows(records, entries, title)
        if len(rows[0]) == 2:
            raise DHError(
                "Moodle needs one identifier (idnumber, email or username) that every "
                "graded student has in the roster",
                file=r.file,
            )
    else:
        rows = generic_rows(records, entries, [q.id for q in assignment.questions])
    buf = io.StringIO()
    csv.writer(buf).writerows(rows)
    path = inside(report.out_dir, f"{kind}-import.csv")
    write_atomic(path, buf.getvalue())
    notes = []
    if absent:
        shown = ", ".join(e.submission for e in absent[:10])
        notes.append(
            f"{len(absent)} roster student(s) have no submission and are not in the import "
            f"(the LMS keeps their grade): {shown}"
        )
    if kind == "moodle":
        notes.append(
            f"Moodle's import page: Map from '{rows[0][0]}' to the same user field "
            f"(ID number: useridnumber, Email address: useremail, Username: username); "
            f"map '{title}' to the grade item (maximum grade {assignment.max_score:g})"
        )
    return LmsGradebook(path, len(records), tuple(notes))
