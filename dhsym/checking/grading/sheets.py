"""Each student's problem sheet of an assignment with variants: their tables and pose.

:func:`student_sheets` gives, for every student of the class list, the key tables of the
assignment with the student's values (as the table's ``values:``, which the problem sheet
prints as "Lengths: a1 = 0.37, …") and the joint values of its first ``ik@`` question (a
profile's drawn values, which have no table, are in the line of the student's values);
:func:`write_sheets` writes one LaTeX problem sheet per student (``dhsym handout hw.yaml
--variants class.csv -o FOLDER``), compiled to PDF on request; :func:`write_merged` all of
them as one document from the same template, each student's sheet on new pages
(``--merged class.pdf``).

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> folder = Path(tempfile.mkdtemp())
>>> _ = (folder / "s").write_text("0123456789abcdef0123")
>>> _ = (folder / "hw.yaml").write_text(
...     "key: planar2r\\nsecret: s\\nvariants: {a1: [0.4, 0.5]}\\n"
...     "questions: [{id: q1, ask: T0_2}, {id: q2, ask: T0_1}]\\n")
>>> sheets = student_sheets(Assignment.load(folder / "hw.yaml"), ClassList((("ada", "Ada"),)))
>>> [(s.student, len(s.tables), s.variant.text() in ("a1 = 0.4", "a1 = 0.5")) for s in sheets]
[('ada', 1, True)]
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from dhsym.errors import DHError
from dhsym.model.table import DHTable

from ..judging.trajectory_key import TrajectoryKey
from .assignment import Assignment
from .report_files import safe_name
from .variants import ClassList, Variant, class_variants, variant_id

__all__ = ["StudentSheet", "student_sheets", "write_merged", "write_sheets"]


@dataclass(frozen=True)
class StudentSheet:
    """One student's sheet: who, their values, the tables (with their values) and the
    joint values of the first ``ik@`` question (None without one)."""

    student: str
    name: str
    variant: Variant
    tables: tuple[DHTable, ...]
    pose: tuple[float, ...] | None


def student_sheets(assignment: Assignment, roster: ClassList) -> tuple[StudentSheet, ...]:
    """Every student's sheet, in the class list's order."""
    if assignment.variants is None:
        raise DHError("the assignment draws no values per student (no variants:)")
    drawn = class_variants(assignment.variants, roster.ids)
    out = []
    for sid, name in roster.students:
        variant = drawn[variant_id(sid)]
        tables: list[DHTable] = []
        for q in assignment.questions:
            if isinstance(q.key, TrajectoryKey):  # a profile: its values are in the title
                continue
            own = variant.values_for(q.key.table)
            table = q.key.table.with_values(own) if own else q.key.table
            if table not in tables:
                tables.append(table)
        mine = assignment.for_variant(variant)
        poses = [q.key.question.pose for q in mine.questions if q.key.question.pose]
        out.append(StudentSheet(sid, name, variant, tuple(tables), poses[0] if poses else None))
    return tuple(out)


def write_sheets(
    assignment: Assignment,
    roster: ClassList,
    folder: str | Path,
    *,
    pdf: bool = False,
    sections: Sequence[str] = ("fk",),
    **options: Any,  # write_handout's keywords (course, date, template_dir, notation, ...)
) -> list[Path]:
    """One problem sheet per student in ``folder`` (``<student>.tex``, and ``.pdf`` with
    ``pdf``), titled with the assignment and the student, their values printed under the
    title; returns the files written (the PDFs when compiled)."""
    from dhsym.explain.documents import write_handout
    from dhsym.robot import Robot

    root = Path(folder)
    root.mkdir(parents=True, exist_ok=True)
    used: set[str] = set()
    written = []
    for sheet in student_sheets(assignment, roster):
        if not sheet.tables:
            raise DHError(
                "a problem sheet prints the key robots' tables, and every question of this "
                "assignment is about a profile: list each student's values with dhsym variants "
                "ASSIGNMENT --roster CLASS.csv"
            )
        path = root / (safe_name(sheet.student, used) + ".tex")
        written.append(
            write_handout(
                [Robot(t) for t in sheet.tables],
                path,
                pdf=pdf,
                title=assignment.title,
                author=_author(sheet),
                mode="problems",
                sections=_sections(assignment, sections),
                check=list(sheet.pose) if sheet.pose is not None else None,
                **options,
            )
        )
    return written


def write_merged(
    assignment: Assignment,
    roster: ClassList,
    output: str | Path,
    *,
    sections: Sequence[str] = ("fk",),
    **options: Any,  # render_sheets' keywords (course, date, template_dir, notation, ...)
) -> Path:
    """Every student's problem sheet in one document (``output``: ``.tex``, or ``.pdf``:
    the ``.tex`` beside it, compiled), from the handout template, in the class list's
    order, each sheet on new pages numbered from 1; the file written."""
    from dhsym.explain.documents import HandoutSheet, render_sheets
    from dhsym.explain.latex import compile_pdf
    from dhsym.robot import Robot

    out = Path(output)
    if out.suffix.lower() not in (".tex", ".pdf"):
        raise DHError(f"--merged: the merged sheets are a .tex or .pdf file, got {out.name}")
    sheets = [
        HandoutSheet(
            tuple(Robot(t) for t in sheet.tables),
            assignment.title,
            _author(sheet),
            list(sheet.pose) if sheet.pose is not None else None,
        )
        for sheet in student_sheets(assignment, roster)
    ]
    tex = out.with_suffix(".tex")
    tex.parent.mkdir(parents=True, exist_ok=True)
    text = render_sheets(
        sheets, mode="problems", sections=_sections(assignment, sections), **options
    )
    tex.write_text(text, encoding="utf-8")
    return compile_pdf(tex) if out.suffix.lower() == ".pdf" else tex


def _author(sheet: StudentSheet) -> str:
    """The line under a sheet's title: who, and their values."""
    who = sheet.name if sheet.name == sheet.student else f"{sheet.name} ({sheet.student})"
    return f"{who}. Your values: {sheet.variant.text()}"


def _sections(assignment: Assignment, sections: Sequence[str]) -> list[str]:
    """The sheet's sections: those asked, and the inverse kinematics when a question asks it."""
    asks_ik = any(q.key.question.kind == "ik" for q in assignment.questions)
    return list(dict.fromkeys([*sections, *(["ik"] if asks_ik else [])]))
