"""Benchmark of homework checking: one PUMA-size answer, a synthetic class, the example class.

Run ``python benchmarks/bench_checking.py`` (10,000 submissions) or with ``--quick``
(300); ``--class20`` instead times the example class of ``examples/homework`` copied
20 times (200 submissions x 5 questions) through ``dhsym grade --quiet`` with 2
workers, as a user runs it (a fresh process: start-up, sandboxes, report included).

Targets: a PUMA arm-matrix answer in <= 50 ms median (issue 5); the example class
x 20 in <= 20 ms per submission, and 10,000 mixed submissions (right, every kind of
wrong, unreadable, hostile) in <= 60 s on 2 cores (issue 19; issue 5 asked <= 300 s).
Ratios are against a baseline measured in the same run: parsing the answer's 16
cells with the core whitelist parser and nothing else (single answer), and reading
each submission's five answers with the checking readers, no comparison
(``selfcheck.read_answer``; the example class).  Load matters on a shared machine:
the script prints ``os.getloadavg()`` with the figures.
"""

from __future__ import annotations

import argparse
import csv
import os
import random
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import sympy as sp

import dhsym
from dhsym.checking import Key, check_answer, grade
from dhsym.kinematics.transforms import link_word, plain_product
from dhsym.model.parsing import parse_expression

ROOT = Path(__file__).resolve().parents[1]
HW = ROOT / "examples" / "homework"


def median_ms(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times) * 1000


def matrix_text(M, nota) -> str:
    return (
        "["
        + ", ".join("[" + ", ".join(nota.text(M[i, j]) for j in range(4)) + "]" for i in range(4))
        + "]"
    )


def bench_single(repeat: int) -> None:
    puma = dhsym.load("puma560")
    T = puma.arm_matrix().matrix
    right = matrix_text(T, puma.notation)
    expanded = str(sp.expand(T).tolist())
    W = sp.Matrix(T)
    W[1, 3] = -W[1, 3]
    wrong = matrix_text(W, puma.notation)
    key = Key.load("puma560", "T0_6")
    try:  # the key prepared once, as a grading worker does (PreparedKeys)
        from dhsym.checking import PreparedKeys

        keys = PreparedKeys()

        def check(text: str) -> object:
            return check_answer(key, text, keys=keys)

    except ImportError:  # a dhsym that memoises prepared keys per process

        def check(text: str) -> object:
            return check_answer(key, text)

    check(right)  # prepare the key once, as a class run does
    cells = [puma.notation.text(e) for e in T]
    base = median_ms(lambda: [parse_expression(c) for c in cells], repeat)
    print(f"PUMA 560 arm matrix (^0T_6), median of {repeat} checks:")
    print(f"  baseline: parse the 16 cells only         {base:8.1f} ms")
    for name, text in (
        ("right, lecture notation", right),
        ("right, expanded cos/sin", expanded),
        ("wrong sign in (2,4)", wrong),
    ):
        ms = median_ms(lambda t=text: check(t), repeat)
        flag = "ok" if ms <= 50 else "SLOW"
        print(f"  {name:28s}          {ms:8.1f} ms  ({ms / base:4.1f}x baseline) [{flag} <= 50 ms]")


def class_answers() -> dict[str, list[str]]:
    """Answer pools per question: right forms, each mistake kind, unreadable, hostile."""
    puma, ex4 = dhsym.load("puma560"), dhsym.load("example4_6dof")
    nota = puma.notation
    T02 = puma.transform(0, 2).matrix
    rows = puma.table.rows

    def prod(rs, conv, rev=False):
        links = [list(link_word(r, conv)) for r in rs]
        return plain_product([e for lk in (links[::-1] if rev else links) for e in lk])

    sys.path.insert(0, str(HW))
    import make_class  # the example class's answers (tables, seed 002 slides)

    data, _ = make_class.answers()
    right = data["alice"][1]
    hostile = [
        "__import__('os').system('true')",
        "(" * 3000 + "x" + ")" * 3000,
        "x**9999999",
        r"\input{/etc/passwd}",
        "\x00\x01junk",
        "9" * 50_000,
    ]
    T = sp.Matrix(T02)
    T[0, 3] = -T[0, 3]
    deg = [r.__class__(r.joint, r.theta, r.d, r.a, r.alpha * 180 / sp.pi) for r in rows[:2]]
    px = right["q5"]
    return {
        "q1": [right["q1"]] * 3
        + [
            data["bob"][1]["q1"],
            data["dave"][1]["q1"],
            data["grace"][1]["q1"],
            data["heidi"][1]["q1"],
            "| θ | d |\n| 1 | 2 |",
            hostile[5],
            data["mallory"][1]["q1"],
        ],
        "q2": [
            right["q2"],
            matrix_text(T02, nota),
            data["bob"][1]["q2"],
            matrix_text(T02.T, nota),
            matrix_text(prod(rows[:2], dhsym.Convention.MODIFIED), nota),
            matrix_text(prod(rows[:2], "standard", True), nota),
            matrix_text(T, nota),
            str(prod(deg, "standard").tolist()),
            "C12 -S12 ??",
            hostile[0],
            hostile[1],
        ],
        "q3": [right["q3"], data["bob"][1]["q3"], data["erin"][1]["q3"], hostile[2]],
        "q4": [
            right["q4"],
            data["bob"][1]["q4"],
            data["carol"][1]["q4"],
            data["dave"][1]["q4"],
            hostile[3],
        ],
        "q5": [
            px,
            px.replace("C", "c").replace("S", "s"),
            data["frank"][1]["q5"],
            data["grace"][1]["q5"],
            hostile[2],
            hostile[4],
        ],
        "_ex4": [str(ex4.n)],
    }


def bench_class(n: int, workers: int) -> None:
    pools = class_answers()
    rng = random.Random(5)
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "class.csv"
        with src.open("w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(["student", "name", "q1", "q2", "q3", "q4", "q5"])
            for k in range(n):
                answers = [rng.choice(pools[q]) for q in ("q1", "q2", "q3", "q4", "q5")]
                # vary the text so that nothing is a copy of another submission
                answers = [a + " " * rng.randrange(3) for a in answers]
                name = "<script>x</script>" if k % 97 == 0 else f"Student {k}"
                w.writerow([f"s{k:05d}", name, *answers])
        t0 = time.perf_counter()
        report = grade(
            HW / "assignment.yaml", src, Path(tmp) / "report", workers=workers, progress=False
        )
        dt = time.perf_counter() - t0
    per = dt / n * 1000
    projected = per * 10_000 / 1000
    print(f"\nSynthetic class: {n} submissions x 5 questions, {workers} worker processes")
    print(
        f"  total {dt:7.1f} s, {per:6.1f} ms per submission, "
        f"{report.failed} timeouts/errors, mean score {report.mean:.2f}"
    )
    flag = "ok" if projected <= 60 else "SLOW"
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    print(
        f"  10,000 submissions: {projected:7.1f} s {'measured' if n == 10_000 else 'projected'}"
        f" [{flag} <= 60 s] (load average {load})"
    )


def bench_class20(copies: int, workers: int, runs: int) -> None:
    """The example class x ``copies`` through ``dhsym grade --quiet`` (a fresh process)."""
    from dhsym.checking import Assignment, read_submissions
    from dhsym.checking.platforms.selfcheck import read_answer

    with tempfile.TemporaryDirectory(prefix="bench-class20-") as tmp_name:
        tmp = Path(tmp_name)
        folder = tmp / "class"
        for k in range(copies):
            for student in sorted((HW / "submissions").iterdir()):
                if student.is_dir():
                    shutil.copytree(student, folder / f"{student.name}_{k:02d}")
        n = sum(1 for _ in folder.iterdir())
        a = Assignment.load(HW / "assignment.yaml")
        subs = read_submissions(folder, a)
        qs = {q.id: q.key for q in a.questions}
        try:  # each key prepared once, as a grading worker does
            from dhsym.checking import PreparedKeys

            keys = PreparedKeys()

            def read(key: Key, text: str | bytes) -> object:
                return read_answer(key, text, keys=keys)

        except ImportError:  # a dhsym that memoises prepared keys per process
            read = read_answer

        def read_all() -> None:
            for sub in subs:
                for qid, text in sub.answers:
                    read(qs[qid], text)

        read_all()  # warm: the keys' names and sympy's caches
        base = median_ms(read_all, 3) / len(subs)
        # the dhsym this script imported (PYTHONPATH), not necessarily the one beside it
        env = {**os.environ, "PYTHONPATH": str(Path(dhsym.__file__).resolve().parents[1])}
        cmd = [sys.executable, "-m", "dhsym", "grade", str(HW / "assignment.yaml"), str(folder)]
        walls, cpus = [], []
        for r in range(runs):
            out = tmp / f"report{r}"
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            subprocess.run(
                [*cmd, "-o", str(out), "--quiet", "--workers", str(workers)],
                check=True,
                env=env,
                capture_output=True,
            )
            walls.append(time.perf_counter() - t0)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    wall, cpu = statistics.median(walls) / n * 1000, statistics.median(cpus) / n * 1000
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    print(f"\nExample class x {copies}: {n} submissions x 5 questions, `dhsym grade --quiet`,")
    print(f"  {workers} workers, median of {runs} fresh processes (load average {load})")
    print(f"  baseline: read the answers only (checking readers)  {base:7.2f} ms per submission")
    flag = "ok" if wall <= 20 else "SLOW"
    print(
        f"  dhsym grade, wall {wall:7.1f} ms per submission ({wall / base:5.1f}x baseline)"
        f" [{flag} <= 20 ms]"
    )
    print(f"  dhsym grade, cpu (all processes) {cpu:7.1f} ms per submission ({cpu / base:5.1f}x)")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="a small class (300 submissions)")
    p.add_argument("--students", type=int, default=None)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument(
        "--class20", action="store_true", help="only the example class x 20 via dhsym grade"
    )
    p.add_argument("--runs", type=int, default=3, help="runs of dhsym grade (--class20)")
    args = p.parse_args()
    if args.class20:
        bench_class20(20, args.workers, args.runs)
        return
    bench_single(20 if args.quick else 50)
    bench_class(args.students or (300 if args.quick else 10_000), args.workers)


if __name__ == "__main__":
    main()
