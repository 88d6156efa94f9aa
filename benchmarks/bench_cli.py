"""Start-up time of the command line, as a ratio to ``python -c "import sympy"`` in the same run.

Each command runs as a fresh process, as a student's shell runs it. The runs are
interleaved (one of each command per round, the reference included), so a machine
shared with other work slows them alike; the report gives, for each command, the median
wall time and the median CPU time (user + system of the process: less disturbed by other
work on a shared machine), each also as a ratio to the reference's, and the load average
before and after.

    python benchmarks/bench_cli.py [--runs 9] [--python PATH]

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


# Bytecode is written and read as after a normal install (pip compiles at install time).
_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def run_timed(python: str, args: list[str], cwd: str) -> tuple[float, float]:
    """Wall and CPU seconds (user + system) of ``python args`` (output discarded; must succeed)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(
        [python, *args],
        cwd=cwd,
        env=_ENV,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        check=True,
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=9, help="rounds (median of these)")
    parser.add_argument("--python", default=sys.executable, help="interpreter to run")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as cwd:  # an empty folder, as a new user's
        answer = Path(cwd) / "answer.txt"
        answer.write_text(RIGHT)
        cmds = commands(answer)
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
        load_after = os.getloadavg()

    ref_name = next(iter(cmds))
    ref_wall, ref_cpu = statistics.median(wall[ref_name]), statistics.median(cpu[ref_name])
    print(f"python: {args.python}")
    print(
        f"cores: {os.cpu_count()}, load average (1 min) before {load_before[0]:.2f}, "
        f"after {load_after[0]:.2f}; medians of {args.runs} interleaved runs"
    )
    print(f"{'command':40s} {'wall':>8s} {'ratio':>6s} {'cpu':>8s} {'ratio':>6s}")
    for name in cmds:
        w, c = statistics.median(wall[name]), statistics.median(cpu[name])
        print(f"{name:40s} {w:7.3f}s {w / ref_wall:6.2f} {c:7.3f}s {c / ref_cpu:6.2f}")
    print(f"ratio = median / median of {ref_name} (same run)")


if __name__ == "__main__":
    main()
