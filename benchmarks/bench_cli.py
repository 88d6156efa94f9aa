"""Start-up time of the command line, and the first answers of the heavier questions cold and
warm, as ratios to ``python -c "import sympy"`` in the same run.

Each command runs as a fresh process, as a student's shell runs it. The runs are
interleaved (one of each command per round, the reference included), so a machine
shared with other work slows them alike; the report gives, for each command, the median
wall time and the median CPU time (user + system of the process: less disturbed by other
work on a shared machine), each also as a ratio to the reference's, and the load average
before and after.

The first answers (``dhsym check … ik@…`` on the PUMA 560, ``ik(T)`` of the PUMA 560, the
UR5 and the Stanford arm, ``puma.rne(q, qd, qdd)``, the Panda's IK with joint 7 given; ``--only
WORD`` keeps those whose name holds the word) run twice each way: *cold*
with ``DHSYM_CACHE`` an empty temporary folder of its own (everything derived, compiled and
written to the disk cache), *warm* with a folder a cold run filled (dhsym.cache: read back
and verified). The startup table runs with an empty cache folder of its own (a command
that reads nothing from it measures the same either way).

    python benchmarks/bench_cli.py [--runs 9] [--cold-runs 1] [--no-first | --first-only]
                                   [--only WORD] [--python PATH]

``--python`` takes the interpreter of another environment (for instance a fresh venv
with only the wheel installed: there is no editable-install finder to import).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

RIGHT = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]"


def commands(answer: Path) -> dict[str, list[str]]:
    """What is timed: the reference first, then the commands (arguments after ``python``)."""
    return {
        'python -c "import sympy"': ["-c", "import sympy"],
        'python -c "import dhsym"': ["-c", "import dhsym"],
        "dhsym --help": ["-m", "dhsym", "--help"],
        "dhsym fk planar2r --q 0,0": ["-m", "dhsym", "fk", "planar2r", "--q", "0,0"],
        "dhsym fk puma560 --q 0,0,0,0,0,0": ["-m", "dhsym", "fk", "puma560", "--q", "0,0,0,0,0,0"],
        "dhsym check (planar2r T0_2, correct)": [
            "-m",
            "dhsym",
            "check",
            "--key",
            "planar2r",
            "--question",
            "T0_2",
            "--answer",
            str(answer),
        ],
        "dhsym derive planar2r": ["-m", "dhsym", "derive", "planar2r"],
    }


Q = "0.3,-0.5,0.4,0.2,0.7,-1.1"
_PUMA = f"import dhsym, numpy as np; r = dhsym.load('puma560'); q = np.array([{Q}]); "
_ARM = "import dhsym, numpy as np; r = dhsym.load('{}'); q = np.array([" + Q + "]); "
_PANDA = "import dhsym, numpy as np; r = dhsym.load('panda'); "
_PANDA += "q = np.array([0.3, -0.5, 0.4, -1.9, 0.7, 1.6, 0.6]); "


def first_answers(answer: Path) -> dict[str, list[str]]:
    """The first answers timed cold and warm (arguments after ``python``)."""
    return {
        'python -c "import sympy"': ["-c", "import sympy"],
        "dhsym check puma560 ik@q": [
            "-m",
            "dhsym",
            "check",
            "--key",
            "puma560",
            "--question",
            f"ik@{Q}",
            "--answer",
            str(answer),
        ],
        "puma.ik(T)": ["-c", _PUMA + "assert len(r.ik(r.fk(q)).q) == 8"],
        "ur5.ik(T)": ["-c", _ARM.format("ur5") + "assert len(r.ik(r.fk(q)).q) == 8"],
        "stanford.ik(T)": ["-c", _ARM.format("stanford") + "assert len(r.ik(r.fk(q)).q) == 8"],
        "puma.rne(q, qd, qdd)": ["-c", _PUMA + "assert r.rne(q, q, q).shape == (6,)"],
        "panda.ik(T, free={7: q7})": [
            "-c",
            _PANDA + "assert len(r.ik(r.fk(q), free={7: 0.6}).q) >= 1",
        ],
    }


# Bytecode is written and read as after a normal install (pip compiles at install time).
_ENV = {
    k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "DHSYM_NO_CACHE")
}


def run_timed(
    python: str, args: list[str], cwd: str, cache: str | None = None
) -> tuple[float, float]:
    """Wall and CPU seconds (user + system) of ``python args`` (output discarded; must
    succeed), with ``DHSYM_CACHE=cache`` (default: an empty folder of its own in ``cwd``)."""
    if cache is None:
        cache = tempfile.mkdtemp(dir=cwd, prefix="cache-")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(
        [python, *args],
        cwd=cwd,
        env={**_ENV, "DHSYM_CACHE": cache},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        check=True,
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def report(
    title: str, names: list[str], wall: dict[str, list[float]], cpu: dict[str, list[float]]
) -> None:
    """One table: median wall and CPU seconds of each command and their ratios to the first."""
    ref = names[0]
    ref_wall, ref_cpu = statistics.median(wall[ref]), statistics.median(cpu[ref])
    print(f"{title:40s} {'wall':>8s} {'ratio':>6s} {'cpu':>8s} {'ratio':>6s}")
    for name in names:
        w, c = statistics.median(wall[name]), statistics.median(cpu[name])
        print(f"{name:40s} {w:7.3f}s {w / ref_wall:6.2f} {c:7.3f}s {c / ref_cpu:6.2f}")
    print(f"ratio = median / median of {ref} (same run)")


def first_answer_rounds(
    python: str, cmds: dict[str, list[str]], cwd: str, runs: int, cold_runs: int
) -> tuple[dict[str, list[float]], dict[str, list[float]]]:
    """Cold (an empty cache folder per run) and warm (the folder a cold run filled) times,
    keyed ``"name, cold"`` and ``"name, warm"``; the reference runs in both rounds."""
    ref, *rest = cmds
    wall: dict[str, list[float]] = {}
    cpu: dict[str, list[float]] = {}

    def record(key: str, w: float, c: float) -> None:
        wall.setdefault(key, []).append(w)
        cpu.setdefault(key, []).append(c)

    filled = {name: tempfile.mkdtemp(dir=cwd, prefix="warm-") for name in rest}
    for k in range(cold_runs):
        record(ref, *run_timed(python, cmds[ref], cwd))
        for name in rest:  # the first cold run fills the warm folder
            cache = filled[name] if k == 0 else None
            record(f"{name}, cold", *run_timed(python, cmds[name], cwd, cache))
    for _ in range(runs):
        record(ref, *run_timed(python, cmds[ref], cwd))
        for name in rest:
            record(f"{name}, warm", *run_timed(python, cmds[name], cwd, filled[name]))
    return wall, cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=9, help="rounds (median of these)")
    parser.add_argument(
        "--cold-runs", type=int, default=1, help="cold rounds of the first answers (slow)"
    )
    parser.add_argument("--no-first", action="store_true", help="the startup table only")
    parser.add_argument(
        "--first-only", action="store_true", help="the first answers only (no startup table)"
    )
    parser.add_argument(
        "--only", default="", help="the first answers whose name holds this word (ik, rne, …)"
    )
    parser.add_argument("--python", default=sys.executable, help="interpreter to run")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as cwd:  # an empty folder, as a new user's
        answer = Path(cwd) / "answer.txt"
        answer.write_text(RIGHT)
        cmds = commands(answer)
        if args.first_only:  # the reference only: the first answers give their own ratios
            cmds = dict(list(cmds.items())[:1])
        for argv in cmds.values():  # warm the file cache and __pycache__
            run_timed(args.python, argv, cwd)
        load_before = os.getloadavg()
        wall: dict[str, list[float]] = {name: [] for name in cmds}
        cpu: dict[str, list[float]] = {name: [] for name in cmds}
        for _ in range(args.runs):
            for name, argv in cmds.items():
                w, c = run_timed(args.python, argv, cwd)
                wall[name].append(w)
                cpu[name].append(c)
        if not args.no_first:
            joints = Path(cwd) / "joints.txt"
            joints.write_text(Q.replace(",", ", "))
            first = first_answers(joints)
            ref, *rest = first
            first = {k: v for k, v in first.items() if k == ref or args.only in k}
            first_wall, first_cpu = first_answer_rounds(
                args.python, first, cwd, args.runs, args.cold_runs
            )
        load_after = os.getloadavg()

    print(f"python: {args.python}")
    print(
        f"cores: {os.cpu_count()}, load average (1 min) before {load_before[0]:.2f}, "
        f"after {load_after[0]:.2f}; medians of {args.runs} interleaved runs"
    )
    report("command", list(cmds), wall, cpu)
    if not args.no_first:
        ref, *rest = first
        names = [ref] + [f"{n}, cold" for n in rest] + [f"{n}, warm" for n in rest]
        print()
        print(
            f"first answers in a fresh process: cold = an empty DHSYM_CACHE "
            f"(median of {args.cold_runs}), warm = the folder a cold run filled "
            f"(median of {args.runs})"
        )
        report("first answer", names, first_wall, first_cpu)


if __name__ == "__main__":
    main()
