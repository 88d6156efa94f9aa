"""Speed of the exported C for the PUMA 560 (spherical wrist) and the UR5 (three parallel
axes): fk and IK (all branches) per call.

Measured three ways in one run: in C (a loop of 1,000,000 fk and 200,000 ik calls over
varying inputs, timed with clock_gettime inside the program, gcc -O2), through ctypes
(dhsym.export.shared_library, timeit), and dhsym's own NumPy/float path (robot.fk, robot.ik)
as the reference; EAIK's ``IK`` (Python call into its C++, all solutions, unchecked)
when installed and the table suits it; roboticstoolbox is not compared. Then the PUMA
560's inverse dynamics: its operation count, the exported ``rne`` in a C loop (best of 15
runs of 100,000 calls, wall and thread CPU time, the latter not counting time the process
waits for a core), through ctypes (``compiled(robot).rne``), the exported NumPy module and
``robot.rne`` on one state (the reference, NumPy). The ratio column is dhsym's own time
over this row's (fk to robot.fk, IK to robot.ik, rne to robot.rne), per robot, in the same
run; the load average is printed first and last.

    PYTHONPATH=. python benchmarks/bench_export.py
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import tempfile
import timeit
from pathlib import Path

import numpy as np

import dhsym
from dhsym.export.shared_library import compiled
from dhsym.ik.choices import IKCache, solve

_MAIN = r"""
#include <stdio.h>
#include <math.h>
#include <time.h>
#include "arm.h"
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
int main(void)
{
    double q[6] = {0.3, -0.5, 0.4, 0.2, 0.7, -1.1}, T[16], sink = 0.0, t0;
    double S[ARM_MAX_IK_SOLUTIONS][6], R[ARM_MAX_IK_SOLUTIONS], Tr[16];
    long i, n = 1000000, m = 200000;
    int c = 0;
    t0 = now();
    for (i = 0; i < n; ++i) {
        q[0] = 1e-7 * (double)i;
        arm_fk(q, T);
        sink += T[3];
    }
    printf("fk_ns %.2f\n", (now() - t0) / n * 1e9);
    arm_fk(q, T);
    t0 = now();
    for (i = 0; i < m; ++i) {
        T[3] += 1e-12;
        c += arm_ik(T, 0.0, S, R);
        sink += S[0][0];
    }
    printf("ik_ns %.2f\nsolutions %.2f\n", (now() - t0) / m * 1e9, (double)c / m);
    for (i = 0; i < 16; ++i) {
        Tr[i] = rint(T[i] * 1e6) / 1e6; /* the pose typed with 6 decimals */
    }
    c = 0;
    t0 = now();
    for (i = 0; i < m; ++i) {
        Tr[3] += 1e-6;
        c += arm_ik(Tr, 0.0, S, R);
        sink += S[0][0];
    }
    printf("ik_rounded_ns %.2f\nrounded_solutions %.2f\nsink %g\n", (now() - t0) / m * 1e9,
           (double)c / m, sink);
    return 0;
}
"""


def in_c(robot: dhsym.Robot) -> dict[str, float]:
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in dhsym.export(robot, "c", prefix="arm").items():
            (Path(tmp) / name).write_text(text)
        (Path(tmp) / "main.c").write_text(_MAIN)
        subprocess.run(
            ["gcc", "-std=gnu99", "-O2", "main.c", "arm.c", "-o", "bench", "-lm"],
            cwd=tmp,
            check=True,
        )
        out = subprocess.run([str(Path(tmp) / "bench")], capture_output=True, text=True, check=True)
    return {k: float(v) for k, v in (line.split() for line in out.stdout.splitlines())}


def per_call(fn, arg, number: int) -> float:
    best = min(timeit.repeat(lambda: fn(arg), number=number, repeat=5))
    return best / number * 1e9


def bench(name: str) -> None:
    robot = dhsym.load(name)
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T = robot.fk(q)
    c = in_c(robot)
    fast = compiled(robot)
    assert len(fast.ik(T)) == len(robot.ik(T))
    numpy_cache = IKCache(robot)  # no native compiler: robot.ik as without one

    def numpy_path(pose: np.ndarray) -> object:
        return solve(robot, pose, cache=numpy_cache)

    rows = [
        ("fk, C loop", c["fk_ns"]),
        ("fk, ctypes (compiled)", per_call(fast.fk, q, 20000)),
        ("fk, dhsym robot.fk", per_call(robot.fk, q, 20000)),
        ("ik all branches, C loop", c["ik_ns"]),
        ("ik, ctypes (compiled)", per_call(fast.ik, T, 20000)),
        ("ik, dhsym robot.ik", per_call(robot.ik, T, 2000)),
        ("ik 6 decimals, C loop", c["ik_rounded_ns"]),
        ("ik 6 decimals, robot.ik", per_call(robot.ik, np.round(T, 6), 2000)),
        ("ik, robot.ik NumPy path", per_call(numpy_path, T, 2000)),
    ]
    eaik = eaik_call(robot)
    if eaik is not None:
        rows.append(("ik, EAIK bot.IK (C++)", per_call(eaik, T, 20000)))
    family = robot.inverse().family
    print(
        f"{robot.name} ({family}), {c['solutions']:.0f} IK solutions per pose "
        f"(backend {fast.backend})"
    )
    ref = {"fk": rows[2][1], "ik": rows[5][1]}
    for label, ns in rows:
        kind = label.split(",")[0].split()[0]
        print(f"  {label:28s} {ns:12.1f} ns   dhsym/this = {ref[kind] / ns:8.1f}x")
    if eaik is not None:
        ratio = rows[4][1] / rows[-1][1]
        print(f"  ik time, ctypes (compiled) / EAIK: {ratio:.2f} (above 1: EAIK is faster)")


def eaik_call(robot: dhsym.Robot):
    """EAIK's ``IK`` for this arm (``pip install eaik``), or ``None`` (not installed, or a
    table it does not take: standard DH without base, tool or joint offsets only)."""
    if importlib.util.find_spec("eaik") is None:
        return None
    from eaik.IK_DH import DhRobot

    table = robot.table
    if robot.convention.value != "standard" or table.base or table.tool:
        print(f"EAIK: takes standard DH tables without base or tool; not {robot.name}")
        return None
    if any(r.offset != 0 for r in table.rows):
        print(f"EAIK: takes no joint offsets; not {robot.name}")
        return None
    vals = table.value_map
    col = {
        k: np.array([float(getattr(r, k).xreplace(vals)) for r in table.rows])
        for k in ("a", "d", "alpha")
    }
    bot = DhRobot(col["alpha"], col["a"], col["d"])
    if not bot.hasKnownDecomposition():
        print(f"EAIK: no known decomposition for {robot.name}")
        return None
    return bot.IK


_RNE_MAIN = r"""
#include <stdio.h>
#include <math.h>
#include <time.h>
#include "arm.h"
static double seconds(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
int main(void)
{
    double q[6] = {0.3, -0.5, 0.4, 0.2, 0.7, -1.1}, qd[6] = {0.5, -0.2, 0.1, 0.9, -0.4, 0.3};
    double qdd[6] = {1.0, 0.5, -0.7, 0.2, 0.3, -0.1}, tau[6], sink = 0.0;
    double wall = 1e30, cpu = 1e30, w0, c0;
    long i, r, m = 100000;
    for (r = 0; r < 15; ++r) {  /* best of 15 runs of m calls */
        w0 = seconds(CLOCK_MONOTONIC);
        c0 = seconds(CLOCK_THREAD_CPUTIME_ID);
        for (i = 0; i < m; ++i) {
            q[0] = 1e-7 * (double)i;
            arm_rne(q, qd, qdd, tau);
            sink += tau[0];
        }
        c0 = (seconds(CLOCK_THREAD_CPUTIME_ID) - c0) / m * 1e9;
        w0 = (seconds(CLOCK_MONOTONIC) - w0) / m * 1e9;
        if (c0 < cpu) cpu = c0;
        if (w0 < wall) wall = w0;
    }
    printf("rne_ns %.2f\nrne_cpu_ns %.2f\nsink %g\n", wall, cpu, sink);
    return 0;
}
"""


def rne_operations(robot: dhsym.Robot) -> dict[str, int]:
    """Multiplications (``MUL``, ``DIV``), additions (``ADD``, ``SUB``) and squares
    (``POW``, written ``x*x`` by the compiler) of the exported ``rne``, by ``sympy.count_ops``
    on its program, as ``tests/export/test_rne.py`` counts them."""
    import sympy as sp

    from dhsym.export.program import rne_program

    prog = rne_program(robot)
    total = sp.Add(*(sp.count_ops(e, visual=True) for e in prog.expressions()))
    ops = {str(s): int(total.coeff(s)) for s in total.free_symbols}
    return {
        "mul": ops.get("MUL", 0) + ops.get("DIV", 0),
        "add": ops.get("ADD", 0) + ops.get("SUB", 0),
        "pow": ops.get("POW", 0),
    }


def bench_rne(name: str) -> None:
    """The exported inverse dynamics against ``robot.rne`` (NumPy, one state per call)."""
    robot = dhsym.load(name)
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    qd = np.array([0.5, -0.2, 0.1, 0.9, -0.4, 0.3])
    qdd = np.array([1.0, 0.5, -0.7, 0.2, 0.3, -0.1])
    with tempfile.TemporaryDirectory() as tmp:
        for lang in ("c", "python"):
            for fname, text in dhsym.export(robot, lang, what="rne", prefix="arm").items():
                (Path(tmp) / fname).write_text(text)
        (Path(tmp) / "main.c").write_text(_RNE_MAIN)
        subprocess.run(
            ["gcc", "-std=gnu99", "-O2", "main.c", "arm.c", "-o", "bench", "-lm"],
            cwd=tmp,
            check=True,
        )
        out = subprocess.run([str(Path(tmp) / "bench")], capture_output=True, text=True, check=True)
        spec = importlib.util.spec_from_file_location("arm_rne_numpy", Path(tmp) / "arm.py")
        assert spec is not None and spec.loader is not None
        exported = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(exported)
    c = {k: float(v) for k, v in (line.split() for line in out.stdout.splitlines())}
    fast = compiled(robot)
    assert np.allclose(fast.rne(q, qd, qdd), robot.rne(q, qd, qdd), rtol=1e-9, atol=1e-9)
    assert np.allclose(exported.rne(q, qd, qdd), robot.rne(q, qd, qdd), rtol=1e-9, atol=1e-9)
    reference = per_call(lambda x: robot.rne(*x), (q, qd, qdd), 5000)
    rows = [
        ("rne, C loop (wall)", c["rne_ns"]),
        ("rne, C loop (thread CPU)", c["rne_cpu_ns"]),
        ("rne, ctypes (compiled)", per_call(lambda x: fast.rne(*x), (q, qd, qdd), 20000)),
        ("rne, exported NumPy", per_call(lambda x: exported.rne(*x), (q, qd, qdd), 5000)),
        ("rne, dhsym robot.rne", reference),
    ]
    ops = rne_operations(robot)
    print(
        f"{robot.name} inverse dynamics (recursive Newton-Euler, friction, motor inertia): "
        f"{ops['mul']} mul + {ops['add']} add = {ops['mul'] + ops['add']} operations "
        f"(and {ops['pow']} squares)"
    )
    for label, ns in rows:
        print(f"  {label:28s} {ns:12.1f} ns   robot.rne/this = {reference / ns:8.1f}x")


def main() -> None:
    print("load average (1, 5, 15 min): {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))
    if importlib.util.find_spec("roboticstoolbox") is not None:
        print("roboticstoolbox is installed but not wired into this benchmark")
    for name in ("puma560", "ur5"):
        bench(name)
    bench_rne("puma560")
    print("load average (1, 5, 15 min): {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))


if __name__ == "__main__":
    main()
