"""The class picture: per-question difficulty and the most common wrong entries."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from dhsym.checking import Assignment, grade
from dhsym.checking.grading.records import GradeRecord
from dhsym.checking.grading.report import question_picture, write_summary

ROOT = Path(__file__).resolve().parents[3]
HW = ROOT / "examples" / "homework"


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    a = Assignment.load(HW / "assignment.yaml")
    out = tmp_path_factory.mktemp("grades")
    return a, grade(a, HW / "submissions", out, workers=0, progress=False)


def test_difficulty_is_the_share_of_the_class_right(report):
    a, rep = report
    records = list(rep.records)
    files = {r.uid: r.student for r in records}
    for q in question_picture(a, records, files):
        right = sum(r.verdicts[q["id"]] == "correct" for r in records)
        assert q["share"] == right / len(records)
        assert q["difficulty"] == ("easy" if right >= 8 else "medium" if right >= 5 else "hard")
        wrong = [w for r in records for w in r.wrong.get(q["id"], ())]
        for w in q["wrong"]:
            assert w["count"] == sum(place == w["where"] for place, _ in wrong)
            first = next(r for r in records if w["where"] in [p for p, _ in r.wrong[q["id"]]])
            assert w["student"] == first.student  # the example comes from that student


def test_summary_page_lists_what_to_reteach_hardest_first(report):
    a, rep = report
    html = rep.summary.read_text(encoding="utf-8")
    section = html.split("<h2>What to re-teach</h2>", 1)[1].split("<h2>", 1)[0]
    shares = [int(s) for s in re.findall(r"\((\d+)% right", section)]
    assert shares == sorted(shares) and shares[0] < 100
    assert "Most likely mistakes: transposed" in section  # carol's q2
    # the example of q2's most common wrong entry links to that student's feedback page
    assert re.search(r'<a href="feedback/\w+\.html">\w+</a>', section)


def test_wrong_examples_are_escaped(tmp_path):
    a = Assignment.load(HW / "assignment.yaml")
    rec = GradeRecord(
        uid="<img src=x>",
        student="<img src=x>",
        name="n",
        source="",
        flags=(),
        status="graded",
        scores={q.id: 0.0 for q in a.questions},
        verdicts={q.id: "incorrect" for q in a.questions},
        kinds=("wrong_sign",),
        score=0.0,
        max_score=a.max_score,
        wrong={"q2": (("(1,4)", "<script>alert(1)</script>"),)},
        mistakes={"q2": ("wrong_sign",)},
    )
    page = write_summary(tmp_path, a, [rec], {"<img src=x>": "img_src_x"}).read_text()
    assert "<script>alert" not in page and "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    assert "<img src=x>" not in page


def test_the_mean_score_is_rounded_sensibly(tmp_path):
    """Issue 34, item 8: 14/3 is shown as 4.67, not 4.66667."""
    a = Assignment.load(HW / "assignment.yaml")

    def rec(student: str, score: float) -> GradeRecord:
        return GradeRecord(
            uid=student,
            student=student,
            name=student,
            source=f"{student}/",
            flags=(),
            status="graded",
            scores={"q1": score},
            verdicts={q.id: "correct" for q in a.questions},
            kinds=(),
            score=score,
            max_score=a.max_score,
        )

    records = [rec("ann", 4.0), rec("bo", 4.0), rec("cy", 6.0)]
    page = write_summary(tmp_path, a, records, {r.uid: r.uid for r in records}).read_text()
    assert "mean score 4.67 / 10" in page and "4.66667" not in page
