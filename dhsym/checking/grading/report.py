"""Writing the report folder: the gradebook and the summary.

Files are written through :mod:`~dhsym.checking.grading.report_files` (paths that stay
inside the folder, atomic writes, CSV cells that a spreadsheet never runs). The summary
page (HTML, from a template) shows a chart of the scores and of the mistake kinds, and
per question its difficulty (the share of the class that got it right) and the most
common wrong entries, each with one example answer: what to re-teach, in one page.
"""

from __future__ import annotations

import csv
import io
import math
import statistics
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .feedback import render_summary
from .report_files import csv_cell, inside, write_atomic

if TYPE_CHECKING:
    from .assignment import Assignment
    from .records import GradeRecord

__all__ = [
    "question_picture",
    "write_gradebook",
    "write_summary",
]


def write_gradebook(
    root: Path, a: Assignment, records: Sequence[GradeRecord], files: dict[str, str]
) -> Path:
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
                csv_cell(r.student),
                csv_cell(r.name),
                *[f"{r.scores.get(q.id, 0):g}" for q in a.questions],
                f"{r.score:g}",
                f"{a.max_score:g}",
                csv_cell(r.status),
                csv_cell("; ".join(r.flags)),
                csv_cell(r.source),
                f"feedback/{files[r.uid]}.md",
            ]
        )
    path = inside(root, "gradebook.csv")
    write_atomic(path, buf.getvalue())
    return path


def _chart(root: Path, a: Assignment, records: Sequence[GradeRecord], kinds: Counter[str]) -> Path:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    fig = Figure(figsize=(10, 4))
    FigureCanvasAgg(fig)
    ax1, ax2 = fig.subplots(1, 2)
    scores = [r.score for r in records]
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
    for axis in (ax1.yaxis, ax2.xaxis):  # counts of students and answers: whole numbers
        axis.set_major_locator(MaxNLocator(integer=True))
    fig.tight_layout()
    path = inside(root, "summary.png")
    fig.savefig(path, dpi=100)
    return path


def _difficulty(share: float) -> str:
    return "easy" if share >= 0.8 else "medium" if share >= 0.5 else "hard"


def question_picture(
    a: Assignment, records: Sequence[GradeRecord], files: dict[str, str], top: int = 5
) -> list[dict[str, Any]]:
    """Per question: verdict counts, share right, difficulty, and the most common wrong
    entries (matrix entries, or table rows) with one example answer and its student.

    >>> from types import SimpleNamespace as NS
    >>> from dhsym.checking.grading.records import GradeRecord
    >>> a = NS(questions=[NS(id="q1", ask="A1", points=2)])
    >>> recs = [GradeRecord(s, s, s, f"{s}/", (), "graded", {"q1": p}, {"q1": v}, (), p, 2,
    ...                     wrong={"q1": w})
    ...         for s, v, p, w in [("ann", "correct", 2, ()), ("bo", "incorrect", 0,
    ...          (("(1,4)", "d1"),)), ("cy", "incorrect", 0, (("(1,4)", "-d2"),))]]
    >>> q = question_picture(a, recs, {"ann": "ann", "bo": "bo", "cy": "cy"})[0]
    >>> q["share"], q["difficulty"], q["wrong"][0]["where"], q["wrong"][0]["count"]
    (0.333..., 'hard', '(1,4)', 2)
    >>> q["wrong"][0]["example"], q["wrong"][0]["student"]
    ('d1', 'bo')
    """
    out = []
    n = max(len(records), 1)
    for q in a.questions:
        v = Counter(r.verdicts.get(q.id, "missing") for r in records)
        where: Counter[str] = Counter()
        example: dict[str, tuple[str, str, str]] = {}  # place -> (answer, student, uid)
        mistakes = Counter(k for r in records for k in r.mistakes.get(q.id, ()))
        for r in records:
            for place, text in r.wrong.get(q.id, ()):
                where[place] += 1
                example.setdefault(place, (text, r.student, r.uid))
        share = v["correct"] / n
        out.append(
            {
                "id": q.id,
                "ask": q.ask,
                "points": q.points,
                "correct": v["correct"],
                "incorrect": v["incorrect"],
                "unreadable": v["unreadable"],
                "missing": v["missing"] + v["error"],
                "timeout": v["timeout"],
                "share": share,
                "mean_points": sum(r.scores.get(q.id, 0) for r in records) / n,
                "difficulty": _difficulty(share),
                "mistakes": [(k.replace("_", " "), c) for k, c in mistakes.most_common(top)],
                "wrong": [
                    {
                        "where": place,
                        "count": count,
                        "example": example[place][0],
                        "student": example[place][1],
                        "feedback_html": f"feedback/{files[example[place][2]]}.html",
                    }
                    for place, count in where.most_common(top)
                ],
            }
        )
    return out


def write_summary(
    root: Path,
    a: Assignment,
    records: Sequence[GradeRecord],
    files: dict[str, str],
    *,
    refused: Sequence[tuple[str, str]] = (),
) -> Path:
    """``summary.html`` and its chart ``summary.png``: scores, verdicts, mistake kinds, and
    per question its difficulty and most common wrong entries (what to re-teach); the
    entries of the submissions folder that were not graded, each with its reason."""
    kinds: Counter[str] = Counter(k for r in records for k in r.kinds)
    chart = _chart(root, a, records, kinds)
    per_q = question_picture(a, records, files)
    scores = [r.score for r in records]
    rows = [
        {
            "student": r.student,
            "name": r.name,
            "score": r.score,
            "status": r.status,
            "flags": list(r.flags),
            "source": r.source,
            "feedback_html": f"feedback/{files[r.uid]}.html",
            "feedback_md": f"feedback/{files[r.uid]}.md",
        }
        for r in records
    ]
    html = render_summary(
        {
            "title": a.title,
            "students": len(records),
            "max_score": a.max_score,
            "mean": round(statistics.fmean(scores), 2) if scores else 0.0,  # 4.67, not 4.66667
            "median": round(statistics.median(scores), 2) if scores else 0.0,
            "problems": sum(r.status != "graded" for r in records),
            "flagged": sum(bool(r.flags) for r in records),
            "chart": chart.name,
            "per_question": per_q,
            "reteach": sorted(
                (q for q in per_q if q["share"] < 1), key=lambda q: (q["share"], q["id"])
            ),
            "kinds": kinds.most_common(),
            "rows": rows,
            "refused": [{"entry": e, "reason": r} for e, r in refused],
        }
    )
    path = inside(root, "summary.html")
    write_atomic(path, html)
    return path
