"""Speed of the exported C for the PUMA 560: fk and IK (all branches) per call.

Measured three ways in one run: in C (a loop of 1,000,000 fk and 200,000 ik calls over
varying inputs, timed with clock_gettime inside the program, gcc -O2), through ctypes
(dhsym.export.compiled, timeit), and dhsym's own NumPy/float path (robot.fk, robot.ik)
as the reference; EAIK and roboticstoolbox only when already installed.

    PYTHONPATH=. python benchmarks/bench_export.py
"""

from __future__ import annotations

import importlib.util
import subprocess
import tempfile
import timeit
from pathlib import Path

import numpy as np

import dhsym
from dhsym.export.compiled import compiled

_MAIN = r"""
#include <stdio.h>
#include <time.h>
#include "puma.h"
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
int main(void)
{
    double q[6] = {0.3, -0.5, 0.4, 0.2, 0.7, -1.1}, T[16], S[8][6], sink = 0.0, t0;
    long i, n = 1000000, m = 200000;
    int c = 0;
    t0 = now();
    for (i = 0; i < n; ++i) {
        q[0] = 1e-7 * (double)i;
        puma_fk(q, T);
        sink += T[3];
    }
    printf("fk_ns %.2f\n", (now() - t0) / n * 1e9);
    puma_fk(q, T);
    t0 = now();
    for (i = 0; i < m; ++i) {
        T[3] += 1e-12;
        c += puma_ik(T, S);
        sink += S[0][0];
    }
    printf("ik_ns %.2f\nsolutions %.2f\nsink %g\n", (now() - t0) / m * 1e9, (double)c / m, sink);
    return 0;
}
"""


def in_c(robot: dhsym.Robot) -> dict[str, float]:
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in dhsym.export(robot, "c", prefix="puma").items():
            (Path(tmp) / name).write_text(text)
        (Path(tmp) / "main.c").write_text(_MAIN)
        subprocess.run(
            ["gcc", "-std=gnu99", "-O2", "main.c", "puma.c", "-o", "bench", "-lm"],
            cwd=tmp,
            check=True,
        )
        out = subprocess.run([str(Path(tmp) / "bench")], capture_output=True, text=True, check=True)
    return {k: float(v) for k, v in (line.split() for line in out.stdout.splitlines())}


def per_call(fn, arg, number: int) -> float:
    best = min(timeit.repeat(lambda: fn(arg), number=number, repeat=5))
    return best / number * 1e9


def main() -> None:
    robot = dhsym.load("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T = robot.fk(q)
    c = in_c(robot)
    fast = compiled(robot)
    rows = [
        ("fk, C loop", c["fk_ns"]),
        ("fk, ctypes (compiled)", per_call(fast.fk, q, 20000)),
        ("fk, dhsym robot.fk", per_call(robot.fk, q, 20000)),
        ("ik all branches, C loop", c["ik_ns"]),
        ("ik, ctypes (compiled)", per_call(fast.ik, T, 20000)),
        ("ik, dhsym robot.ik", per_call(robot.ik, T, 2000)),
    ]
    if importlib.util.find_spec("eaik") is not None:
        print("EAIK is installed but not wired into this benchmark")
    if importlib.util.find_spec("roboticstoolbox") is not None:
        print("roboticstoolbox is installed but not wired into this benchmark")
    print(f"PUMA 560, {c['solutions']:.0f} IK solutions per pose (backend {fast.backend})")
    ref = {"fk": rows[2][1], "ik": rows[5][1]}
    for name, ns in rows:
        kind = name.split(",")[0].split()[0]
        print(f"{name:28s} {ns:12.1f} ns   dhsym/this = {ref[kind] / ns:8.1f}x")


if __name__ == "__main__":
    main()
