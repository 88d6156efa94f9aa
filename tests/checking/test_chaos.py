"""Chaos: honest students and one submission of every hostile kind, graded as one class.

Through the process pool and through a local Dask cluster the honest students get
exactly the scores of a clean run, every hostile submission gets a status and a
feedback page, nothing outside the report folder is written, no code runs (the
canary file of the hostile answers never appears), and the run ends within a fixed
budget.  (The budget is generous: it catches a hang, not a slowdown — speed lives in
``benchmarks/``.)
"""

from __future__ import annotations

import csv
import os
import time
from pathlib import Path

import pytest

from dhsym.checking import grade

from .chaos_class import CANARY, HW, build


def _rows(out: Path) -> dict[str, dict]:
    rows = csv.DictReader((out / "gradebook.csv").open(encoding="utf-8"))
    return {r["source"]: r for r in rows}


@pytest.fixture(scope="module")
def chaos(tmp_path_factory):
    root = tmp_path_factory.mktemp("chaos")
    honest, hostile = build(root / "class")
    clean = root / "clean"
    for source in honest:
        (clean / source).parent.mkdir(parents=True, exist_ok=True)
    import shutil

    for source in honest:
        shutil.copytree(root / "class" / source, clean / source)
    grade(HW / "assignment.yaml", clean, root / "clean-report", workers=0, progress=False)
    baseline = {s: r["total"] for s, r in _rows(root / "clean-report").items()}
    assert len(baseline) == len(honest) == 10
    return root, honest, hostile, baseline


def _check(root: Path, out: Path, honest: list, hostile: list, baseline: dict, seconds: float):
    rows = _rows(out)
    assert {s: rows[s]["total"] for s in honest} == baseline
    assert set(rows) == set(honest) | set(hostile)
    for source in hostile:
        status = rows[source]["status"]
        assert status in ("graded", "timeout") or status.startswith("error: "), (source, status)
        assert (out / rows[source]["feedback"]).is_file()
    assert rows["spaces/"]["total"] == "4"  # 99 kB of spaces before a right table: still right
    assert (
        "duplicate id" in rows["alice.yaml"]["flags"] and "duplicate id" in rows["alice/"]["flags"]
    )
    assert "not graded: q5.txt" in rows["twofiles/"]["flags"]
    pages = "".join(p.read_text(encoding="utf-8") for p in (out / "feedback").iterdir())
    assert "TOPSECRET" not in pages and "root:x:" not in pages
    assert not CANARY.exists() and not Path("/tmp/dhsym-pwned").exists()
    print(f"{out.name}: {len(rows)} submissions graded in {seconds:.1f} s")


@pytest.mark.slow
def test_chaos_class_through_the_process_pool(chaos):
    root, honest, hostile, baseline = chaos
    out = root / "class" / "report-pool"  # inside the submissions: must not become a student
    before = set(os.listdir(root))
    start = time.monotonic()
    report = grade(HW / "assignment.yaml", root / "class", out, workers=2, progress=False)
    _check(root, out, honest, hostile, baseline, time.monotonic() - start)
    assert report.students == len(honest) + len(hostile)
    assert set(os.listdir(root)) == before


@pytest.mark.slow
def test_chaos_class_through_a_local_dask_cluster(chaos):
    distributed = pytest.importorskip("dask.distributed")
    root, honest, hostile, baseline = chaos
    out = root / "report-dask"
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=2, processes=True, dashboard_address=None
    ) as cluster:
        start = time.monotonic()
        grade(
            HW / "assignment.yaml",
            root / "class",
            out,
            dask=cluster.scheduler_address,
            progress=False,
        )
        seconds = time.monotonic() - start
    _check(root, out, honest, hostile, baseline, seconds)
