"""Writing the report folder: safe file names, atomic writes, the gradebook and the summary.

Every path is checked to stay inside the report folder, every file is written
to a temporary name and renamed, and CSV cells that a spreadsheet would run as
a formula are quoted. The summary page (HTML, from a template) shows a chart
of the scores and of the mistake kinds.

Examples
--------
>>> safe_name("con", set())
'con-...'
>>> csv_cell("=HYPERLINK()")
"'=HYPERLINK()"
"""

from __future__ import annotations

import csv
import hashlib
import io
import math
import os
import re
import statistics
from collections import Counter
from pathlib import Path
from typing import TYPE_CHECKING

from dhsym.errors import DHError

from .feedback import render_summary

if TYPE_CHECKING:
    from .grading import Assignment

__all__ = [
    "CACHE_NAME",
    "csv_cell",
    "inside",
    "name_base",
    "safe_name",
    "write_atomic",
    "write_gradebook",
    "write_summary",
]

CACHE_NAME = ".dhsym-grading-cache.json"

_RESERVED = frozenset(
    {
        "con",
        "prn",
        "aux",
        "nul",
        *(f"com{i}" for i in range(10)),
        *(f"lpt{i}" for i in range(10)),
    }
)


def name_base(student: str) -> str:
    """The file-name form of a student id before it is made unique (ids equal here collide).

    >>> name_base("Ann Lee"), name_base("ann_lee"), name_base("../..")
    ('Ann_Lee', 'ann_lee', 'student')
    """
    return re.sub(r"[^A-Za-z0-9._-]+", "_", student).strip("._-")[:60] or "student"


def safe_name(student: str, used: set[str]) -> str:
    """A file name for a student id: ``[A-Za-z0-9._-]``, no leading dot, unique, short."""
    base = name_base(student)
    name = base
    if name != student or name.lower() in used or name.lower() in _RESERVED:
        name = f"{base}-{hashlib.sha1(student.encode('utf-8', 'replace')).hexdigest()[:8]}"
    while name.lower() in used:
        name += "_"
    used.add(name.lower())
    return name


def inside(root: Path, *parts: str) -> Path:
    """``root / parts``, resolved; an error if that leaves the (resolved) report folder."""
    path = root.joinpath(*parts).resolve()
    if not path.is_relative_to(root):
        raise DHError(f"refusing to write outside the report folder: {path}")
    return path


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to a temporary file beside ``path``, then rename it over ``path``.

    Text that is not valid Unicode (a lone surrogate from a file name that is not
    UTF-8) is written with ``\\x`` escapes, never an encoding error.
    """
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_bytes(text.encode("utf-8", "backslashreplace"))
    os.replace(tmp, path)


def csv_cell(value: object) -> str:
    """``value`` as a CSV cell that a spreadsheet shows as text, never runs as a formula."""
    s = str(value)
    return "'" + s if s[:1] in ("=", "+", "-", "@", "\t", "\r") else s


def write_gradebook(root: Path, a: Assignment, records: list[dict], files: dict) -> Path:
    """``gradebook.csv``: a row per student, the points per question, total and feedback file."""
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(
        [
            "student",
            "name",
            *[q.id for q in a.questions],
            "total",
            "max",
            "status",
            "flags",
            "source",
            "feedback",
        ]
    )
    for r in records:
        w.writerow(
            [
                csv_cell(r["student"]),
                csv_cell(r["name"]),
                *[f"{r['scores'].get(q.id, 0):g}" for q in a.questions],
                f"{r['score']:g}",
                f"{a.max_score:g}",
                csv_cell(r["status"]),
                csv_cell("; ".join(r.get("flags", ()))),
                csv_cell(r.get("source", "")),
                f"feedback/{files[r['uid']]}.md",
            ]
        )
    path = inside(root, "gradebook.csv")
    write_atomic(path, buf.getvalue())
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
    path = inside(root, "summary.png")
    fig.savefig(path, dpi=100)
    return path


def write_summary(root: Path, a: Assignment, records: list[dict], files: dict) -> Path:
    """``summary.html`` and its chart ``summary.png``: scores, verdicts and mistake kinds."""
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
                "missing": v["missing"] + v["error"],
                "timeout": v["timeout"],
            }
        )
    scores = [r["score"] for r in records]
    rows = [
        {
            "student": r["student"],
            "name": r["name"],
            "score": r["score"],
            "status": r["status"],
            "flags": list(r.get("flags", ())),
            "source": r.get("source", ""),
            "feedback_html": f"feedback/{files[r['uid']]}.html",
            "feedback_md": f"feedback/{files[r['uid']]}.md",
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
            "flagged": sum(bool(r.get("flags")) for r in records),
            "chart": chart.name,
            "per_question": per_q,
            "kinds": kinds.most_common(),
            "rows": rows,
        }
    )
    path = inside(root, "summary.html")
    write_atomic(path, html)
    return path
