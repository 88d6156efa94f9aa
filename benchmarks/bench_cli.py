"""Start-up time of the command line, as a ratio to ``python -c "import sympy"`` in the same run.

Each command runs as a fresh process, as a student's shell runs it. The runs are
interleaved (one of each command per round, the reference included), so a machine
shared with other work slows them alike; the report gives the median of each
command, its ratio to the reference's median, and the load average before and after.

    python benchmarks/bench_cli.py [--runs 9] [--python PATH]

``--python`` takes the interpreter of another environment (for instance a fresh venv
with only the wheel installed: there is no editable-install finder to import).
"""

from __future__ import annotations

import argparse
import os
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


def wall_time(python: str, args: list[str], cwd: str) -> float:
    """Seconds from start to exit of ``python args`` (output discarded; must succeed)."""
    start = time.perf_counter()
    subprocess.run(
        [python, *args], cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True
    )
    return time.perf_counter() - start


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
            wall_time(args.python, argv, cwd)
        load_before = os.getloadavg()
        times: dict[str, list[float]] = {name: [] for name in cmds}
        for _ in range(args.runs):
            for name, argv in cmds.items():
                times[name].append(wall_time(args.python, argv, cwd))
        load_after = os.getloadavg()

    ref_name = next(iter(cmds))
    ref = statistics.median(times[ref_name])
    print(f"python: {args.python}")
    print(
        f"cores: {os.cpu_count()}, load average (1 min) before {load_before[0]:.2f}, "
        f"after {load_after[0]:.2f}; median of {args.runs} interleaved runs"
    )
    print(f"{'command':40s} {'median':>8s} {'min':>8s} {'ratio':>6s}")
    for name, ts in times.items():
        med = statistics.median(ts)
        print(f"{name:40s} {med:7.3f}s {min(ts):7.3f}s {med / ref:6.2f}")
    print(f"ratio = median / median of {ref_name} (same run)")


if __name__ == "__main__":
    main()
