"""Writing the report folder: the gradebook and the summary.

Files are written through :mod:`~dhsym.checking.grading.report_files` (paths that stay
inside the folder, atomic writes, CSV cells that a spreadsheet never runs). The summary
page (HTML, from a template) shows a chart of the scores and of the mistake kinds (an SVG
from its own template, :func:`chart_data`), and
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

from .feedback import render_chart, render_summary
from .report_files import csv_cell, inside, write_atomic

if TYPE_CHECKING:
    from .assignment import Assignment
    from .records import GradeRecord

__all__ = [
    "chart_data",
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


def _step(top: int, most: int = 8) -> int:
    """The step of whole-number ticks from 0 to ``top``: 1, 2, 5, 10, 20, 50 … with at most
    ``most`` steps.

    >>> _step(3), _step(9), _step(40), _step(41), _step(0)
    (1, 2, 5, 10, 1)
    """
    scale = 1
    while True:
        for step in (scale, 2 * scale, 5 * scale):
            if top <= step * most:
                return step
        scale *= 10


def _ticks(top: float, whole: bool = True) -> list[int]:
    """Whole-number ticks from 0 to at least ``top`` (``whole``: the last at or above it)."""
    step = _step(math.ceil(top))
    end = step * max(1, math.ceil(top / step)) if whole else top
    return list(range(0, int(end) + 1, step))


#: the chart's size and its two panels' plot areas, in SVG units (pixels): left, top, right,
#: bottom; the mistake kinds' names are written left of the second one
_CHART = (1000, 400)
_SCORES_BOX = (70.0, 40.0, 470.0, 340.0)
_KINDS_BOX = (720.0, 40.0, 970.0, 340.0)


def chart_data(
    a: Assignment, records: Sequence[GradeRecord], kinds: Counter[str]
) -> dict[str, Any]:
    """The summary's chart as numbers placed on the page: a histogram of the scores (up to
    20 bins from 0 to the maximum score) and bars of the 12 most common mistake kinds,
    each axis with whole-number ticks (counts of students and answers).

    >>> from types import SimpleNamespace as NS
    >>> recs = [NS(score=s) for s in (0, 1, 2, 2)]
    >>> c = chart_data(NS(max_score=2.0), recs, Counter({"wrong_sign": 3, "transposed": 1}))
    >>> [b["count"] for b in c["bins"]], [t["label"] for t in c["bins_y"]]
    ([1, 3], ['0', '1', '2', '3'])
    >>> [(b["label"], b["count"]) for b in c["bars"]], [t["label"] for t in c["bars_x"]]
    ([('wrong_sign', 3), ('transposed', 1)], ['0', '1', '2', '3'])
    """
    top = max(a.max_score, 1.0)
    n = min(20, max(1, int(math.ceil(top))))
    counts = [0] * n
    for r in records:
        if 0 <= r.score <= top:  # the last bin holds the maximum, as numpy's histogram
            counts[min(n - 1, int(r.score * n / top))] += 1
    x0, y0, x1, y1 = _SCORES_BOX
    ys = _ticks(max(counts, default=0))
    per, width = (y1 - y0) / ys[-1], (x1 - x0) / n
    bins = [
        {"x": x0 + k * width, "width": width, "y": y1 - c * per, "height": c * per, "count": c}
        for k, c in enumerate(counts)
    ]
    xs = [t for t in _ticks(top, whole=False) if t <= top]
    bins_x = [{"at": x0 + t * (x1 - x0) / top, "label": str(t)} for t in xs]
    bins_y = [{"at": y1 - t * per, "label": str(t)} for t in ys]
    named = kinds.most_common(12) or [("none", 0)]
    bx0, by0, bx1, by1 = _KINDS_BOX
    xs = _ticks(max(c for _, c in named))
    scale, slot = (bx1 - bx0) / xs[-1], (by1 - by0) / len(named)
    bars = [
        {
            "label": label,
            "count": c,
            "y": by0 + k * slot + 0.1 * slot,
            "height": 0.8 * slot,
            "width": c * scale,
            "middle": by0 + (k + 0.5) * slot,
        }
        for k, (label, c) in enumerate(named)  # the most common at the top
    ]
    return {
        "width": _CHART[0],
        "height": _CHART[1],
        "scores_box": _SCORES_BOX,
        "kinds_box": _KINDS_BOX,
        "max_score": f"{a.max_score:g}",
        "bins": bins,
        "bins_x": bins_x,
        "bins_y": bins_y,
        "bars": bars,
        "bars_x": [{"at": bx0 + t * scale, "label": str(t)} for t in xs],
    }


def _chart(root: Path, a: Assignment, records: Sequence[GradeRecord], kinds: Counter[str]) -> Path:
    """``summary.svg``: :func:`chart_data` drawn by its template (no plotting library)."""
    path = inside(root, "summary.svg")
    write_atomic(path, render_chart(chart_data(a, records, kinds)))
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
    """``summary.html`` and its chart ``summary.svg``: scores, verdicts, mistake kinds, and
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
