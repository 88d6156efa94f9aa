"""Grading a class: gradebook, feedback, summary, rerun cache, pool, Dask, safety."""

from __future__ import annotations

import csv
import json
import os
import shutil
from pathlib import Path

import pytest

from dhsym.checking import Assignment, grade, read_submissions
from dhsym.checking.grading import CACHE_NAME, safe_name

HW = Path(__file__).resolve().parents[2] / "examples" / "homework"
EXPECTED = {
    "alice": 10,
    "bob": 10,
    "carol": 6,
    "dave": 2,
    "erin": 7,
    "frank": 7,
    "grace": 3,
    "heidi": 6,
    "ivan": 6,
    "mallory": 0,
}


def tree(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def test_example_class_in_process(tmp_path):
    before = tree(tmp_path)
    out = tmp_path / "report"
    report = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert report.graded == 10 and report.failed == 0
    rows = list(csv.DictReader((out / "gradebook.csv").open(encoding="utf-8")))
    assert {r["student"]: float(r["total"]) for r in rows} == EXPECTED
    assert (out / "feedback" / "carol.md").read_text(encoding="utf-8").count("wrong sign") >= 1
    summary = (out / "summary.html").read_text(encoding="utf-8")
    assert "<script>alert" not in summary and "&lt;script&gt;alert" in summary
    assert (out / "summary.png").stat().st_size > 1000
    assert tree(tmp_path) - before <= {str(Path("report") / p) for p in tree(out)} | {"report"}
    # a rerun skips everything; a changed answer is graded again
    again = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert (again.graded, again.skipped) == (0, 10)
    subs = tmp_path / "subs"
    shutil.copytree(HW / "submissions", subs)
    (subs / "ivan" / "q5.txt").write_text("a2*C1*C2\n", encoding="utf-8")
    third = grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    assert (third.graded, third.skipped) == (1, 9)
    cache = json.loads((out / CACHE_NAME).read_text(encoding="utf-8"))
    assert set(cache["records"]) == set(EXPECTED)


def test_process_pool_and_hostile_csv(tmp_path):
    out = tmp_path / "r"
    report = grade(HW / "assignment.yaml", HW / "class.csv", out, workers=2, progress=False)
    assert report.students == 3 and report.failed == 0
    names = sorted(p.name for p in (out / "feedback").iterdir())
    assert all(".." not in n and "/" not in n for n in names)
    assert any(n.startswith("etc_passwd-") for n in names)
    book = (out / "gradebook.csv").read_text(encoding="utf-8")
    assert "'=HYPERLINK" in book  # no spreadsheet formula injection
    assert not (tmp_path / "etc").exists()


def test_submission_reading_skips_links_and_limits_size(tmp_path):
    a = Assignment.load(HW / "assignment.yaml")
    s = tmp_path / "subs"
    (s / "eve").mkdir(parents=True)
    (s / "eve" / "q1.md").write_bytes(b"x" * 10_000_000)
    (s / "eve" / "q2.txt").symlink_to("/etc/passwd")
    (s / "eve" / "q5.txt").write_bytes(os.urandom(256))
    (s / "link").symlink_to(HW / "submissions" / "alice")
    (s / "zoe.yaml").write_text("name: Zoe\nanswers: {q5: a2*C1}\n", encoding="utf-8")
    subs = read_submissions(s, a)
    assert [x.student for x in subs] == ["eve", "zoe"]
    problems = dict(subs[0].problems)
    assert "10000000 bytes" in problems["q1"] and "not a regular file" in problems["q2"]
    report = grade(a, s, tmp_path / "out", workers=0, progress=False)
    verdicts = report.records[0]["verdicts"]
    assert verdicts["q1"] == verdicts["q2"] == verdicts["q5"] == "unreadable"


def test_safe_names_are_unique_and_plain():
    used: set[str] = set()
    names = [safe_name(s, used) for s in ("a/b", "a_b", "a_b", "..", "CON", "ok")]
    assert len(set(names)) == 6 and names[-1] == "ok"
    assert all(n and n[0] not in "." and "/" not in n for n in names)


def test_bad_assignment_is_an_error(tmp_path):
    from dhsym.errors import DHError

    bad = tmp_path / "a.yaml"
    bad.write_text("key: puma560\nquestions: [{id: '../x', ask: table}]\n", encoding="utf-8")
    with pytest.raises(DHError, match="question id"):
        Assignment.load(bad)


@pytest.mark.slow
def test_dask_local_cluster(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        report = grade(
            HW / "assignment.yaml",
            HW / "submissions",
            tmp_path / "d",
            dask=cluster.scheduler_address,
            progress=False,
        )
    rows = list(csv.DictReader((tmp_path / "d" / "gradebook.csv").open(encoding="utf-8")))
    assert report.graded == 10 and {r["student"]: float(r["total"]) for r in rows} == EXPECTED
