"""Benchmark of the autograder path: a synthetic class graded one submission at a time.

Run ``python benchmarks/bench_autograder.py`` (1,000 students; every student also
through a fresh ``run_autograder`` process with ``--processes 1000``).  Each student
is a submission folder (``q1.md`` … ``q5.txt``) drawn from the answer pools of
``bench_checking.py`` (right answers, every mistake kind, unreadable and hostile
text).  Measured:

* the zip (``build_autograder``, the wheel built from this tree);
* in one process: ``run_autograder`` per student (read the submission, check five
  answers, write ``results.json``) - the platform's work without interpreter start;
* fresh processes: ``bash run_autograder`` per student, as the platform runs it in
  each container (interpreter start, imports, assignment, keys, grading);
* the reference in the same run: ``dhsym grade`` on the same class, whose scores the
  autograder must reproduce (mismatches are counted).
"""

from __future__ import annotations

import argparse
import json
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
import zipfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HW = ROOT / "examples" / "homework"
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_checking import class_answers  # noqa: E402

from dhsym.checking.grading.batch import grade  # noqa: E402
from dhsym.checking.platforms.autograder import AutograderPaths, build_autograder, run_autograder  # noqa: E402

QIDS = ("q1", "q2", "q3", "q4", "q5")


def write_class(root: Path, n: int) -> list[Path]:
    pools, rng = class_answers(), random.Random(14)
    folders = []
    for k in range(n):
        folder = root / f"s{k:04d}"
        folder.mkdir(parents=True)
        for q in QIDS:
            text = rng.choice(pools[q]) + " " * rng.randrange(3)
            ext = ".md" if text.lstrip().startswith(("|", "$")) or "\\" in text else ".txt"
            (folder / (q + ext)).write_text(text, encoding="utf-8", errors="replace")
        folders.append(folder)
    return folders


def stats(times: list[float]) -> str:
    t = sorted(times)
    p95 = t[min(len(t) - 1, int(0.95 * len(t)))]
    return (
        f"median {statistics.median(t) * 1000:7.1f} ms, p95 {p95 * 1000:7.1f} ms, "
        f"max {t[-1] * 1000:7.1f} ms"
    )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--students", type=int, default=1000)
    p.add_argument("--processes", type=int, default=50, help="students run as fresh processes")
    p.add_argument("--jobs", type=int, default=1, help="fresh processes at once")
    args = p.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-autograder-") as tmp_name:
        tmp = Path(tmp_name)
        t0 = time.perf_counter()
        zpath = build_autograder(HW / "assignment.yaml", tmp / "autograder.zip")
        print(
            f"autograder zip: {zpath.stat().st_size / 1024:.0f} KiB, built in "
            f"{time.perf_counter() - t0:.1f} s (wheel included)"
        )
        source = tmp / "source"
        with zipfile.ZipFile(zpath) as z:
            z.extractall(source)
        folders = write_class(tmp / "class", args.students)

        times, scores = [], {}
        t0 = time.perf_counter()
        for f in folders:
            out = tmp / "results" / f.name
            t1 = time.perf_counter()
            data = run_autograder(AutograderPaths(source, f, out, tmp / "none.json"))
            times.append(time.perf_counter() - t1)
            scores[f.name] = data["score"]
        total = time.perf_counter() - t0
        print(f"\n{args.students} students, in one process (run_autograder per student):")
        print(
            f"  total {total:7.1f} s, {total / args.students * 1000:6.1f} ms per student; "
            + stats(times)
        )

        t0 = time.perf_counter()
        report = grade(HW / "assignment.yaml", tmp / "class", tmp / "grade", progress=False)
        ref = time.perf_counter() - t0
        wrong = sum(abs(r.score - scores[r.student]) > 1e-9 for r in report.records)
        print(
            f"  reference, dhsym grade on the same class (2 workers): {ref:.1f} s; "
            f"score mismatches: {wrong} of {len(report.records)}"
        )

        m = min(args.processes, args.students)
        if m:
            env = {
                **os.environ,
                "DHSYM_AUTOGRADER_SOURCE": str(source),
                "DHSYM_AUTOGRADER_PYTHON": sys.executable,
                "DHSYM_AUTOGRADER_METADATA": str(tmp / "none.json"),
            }

            def one(f: Path) -> tuple[float, float]:
                out = tmp / "proc" / f.name
                out.mkdir(parents=True)
                t1 = time.perf_counter()
                subprocess.run(
                    ["bash", str(source / "run_autograder")],
                    env={
                        **env,
                        "DHSYM_AUTOGRADER_SUBMISSION": str(f),
                        "DHSYM_AUTOGRADER_RESULTS": str(out),
                    },
                    check=True,
                    capture_output=True,
                    cwd=out,
                    timeout=300,
                )
                dt = time.perf_counter() - t1
                return dt, json.loads((out / "results.json").read_text())["score"]

            t0 = time.perf_counter()
            with ThreadPoolExecutor(args.jobs) as pool:
                runs = list(pool.map(one, folders[:m]))
            total = time.perf_counter() - t0
            bad = sum(abs(s - scores[f.name]) > 1e-9 for (_, s), f in zip(runs, folders))
            print(f"\n{m} students as fresh processes (bash run_autograder, {args.jobs} at once):")
            print(
                f"  total {total:7.1f} s, {total / m * 1000:6.1f} ms per student (wall); "
                f"each run {stats([t for t, _ in runs])}; score mismatches: {bad}"
            )


if __name__ == "__main__":
    main()
