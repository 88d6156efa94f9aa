"""Speed of the exported C for the PUMA 560 (spherical wrist) and the UR5 (three parallel
axes): fk and IK (all branches, each checked by its fk) per call, against EAIK in the same
run.

Measured three ways in one run: in C (a program compiled with gcc -std=gnu99 -O2 that calls
fk on 1,000 configurations in [-3.1, 3.1]^6 a thousand times, and IK on their 1,000 poses,
exact and typed with 6 and with 4 decimals, ten times; best of 15 runs, thread CPU time
(clock_gettime(CLOCK_THREAD_CPUTIME_ID): not counting time the process waits for a core)
and wall time), through ctypes (dhsym.export.shared_library, timeit) and dhsym's own
NumPy/float path (robot.fk, robot.ik) as the reference; robot.ik of one pose rounded to 6
and to 4 decimals (the same pose 2,000 times, and 200 poses once each, best of 5 passes:
these include the few poses whose branches robot.ik refines in Python); EAIK's ``IK`` (its
C++ through its Python binding, all solutions, unchecked) on 200 poses when installed and
the table suits it; roboticstoolbox is not compared. Then the PUMA 560's inverse dynamics:
its operation count, the exported ``rne`` in a C loop (best of 15 runs of 100,000 calls,
wall and thread CPU time), through ctypes (``compiled(robot).rne``), the exported NumPy
module and ``robot.rne`` on one state (the reference, NumPy). The ratio column is dhsym's
own time over this row's (fk to robot.fk, IK to robot.ik, rne to robot.rne), per robot, in
the same run; the load average is printed first and last.

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
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <time.h>
#include "arm.h"
#define NP 1000
static double Q[NP][6], POSES[3][NP][16];
static double seconds(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
int main(void)
{
    double S[ARM_MAX_IK_SOLUTIONS][6], R[ARM_MAX_IK_SOLUTIONS], sink = 0.0;
    static const char *kind[3] = {"exact", "rounded6", "rounded4"};
    long i, z, r, found;
    int j, k;
    srand(1);
    for (i = 0; i < NP; ++i) { /* 1000 configurations in [-3.1, 3.1]^6 and their poses */
        for (j = 0; j < 6; ++j) {
            Q[i][j] = (2.0 * rand() / RAND_MAX - 1.0) * 3.1;
        }
        arm_fk(Q[i], POSES[0][i]);
        for (j = 0; j < 16; ++j) { /* the pose typed with 6 and with 4 decimals */
            POSES[1][i][j] = rint(POSES[0][i][j] * 1e6) / 1e6;
            POSES[2][i][j] = rint(POSES[0][i][j] * 1e4) / 1e4;
        }
    }
    { /* fk: best of 15 runs of 1000 x 1000 calls, wall and thread CPU */
        double wall = 1e30, cpu = 1e30;
        for (r = 0; r < 15; ++r) {
            const double w0 = seconds(CLOCK_MONOTONIC), c0 = seconds(CLOCK_THREAD_CPUTIME_ID);
            for (z = 0; z < 1000; ++z) {
                for (i = 0; i < NP; ++i) {
                    double T[16];
                    arm_fk(Q[i], T);
                    sink += T[3];
                }
            }
            cpu = fmin(cpu, (seconds(CLOCK_THREAD_CPUTIME_ID) - c0) / (1000.0 * NP) * 1e9);
            wall = fmin(wall, (seconds(CLOCK_MONOTONIC) - w0) / (1000.0 * NP) * 1e9);
        }
        printf("fk_wall %.2f\nfk_cpu %.2f\n", wall, cpu);
    }
    for (k = 0; k < 3; ++k) { /* ik: best of 15 runs of 10 x 1000 poses */
        double wall = 1e30, cpu = 1e30;
        for (r = 0; r < 15; ++r) {
            const double w0 = seconds(CLOCK_MONOTONIC), c0 = seconds(CLOCK_THREAD_CPUTIME_ID);
            found = 0;
            for (z = 0; z < 10; ++z) {
                for (i = 0; i < NP; ++i) {
                    found += arm_ik(POSES[k][i], 0.0, S, R);
                    sink += S[0][0];
                }
            }
            cpu = fmin(cpu, (seconds(CLOCK_THREAD_CPUTIME_ID) - c0) / (10.0 * NP) * 1e9);
            wall = fmin(wall, (seconds(CLOCK_MONOTONIC) - w0) / (10.0 * NP) * 1e9);
        }
        printf("ik_%s_wall %.2f\nik_%s_cpu %.2f\nik_%s_solutions %.3f\n", kind[k], wall, kind[k],
               cpu, kind[k], (double)found / (10.0 * NP));
    }
    printf("sink %g\n", sink);
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


def per_pose(fn, poses: list[np.ndarray], repeat: int = 5) -> float:
    """Nanoseconds per pose: the best of ``repeat`` passes over ``poses``, one call each."""

    def run() -> None:
        for pose in poses:
            fn(pose)

    return min(timeit.repeat(run, number=1, repeat=repeat)) / len(poses) * 1e9


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

    rng = np.random.default_rng(1)
    poses = list(robot.fk(rng.uniform(-3.1, 3.1, size=(200, robot.n))))
    rounded = {d: [np.round(pose, d) for pose in poses] for d in (6, 4)}
    rows = [
        ("fk, C loop (thread CPU)", c["fk_cpu"]),
        ("fk, C loop (wall)", c["fk_wall"]),
        ("fk, ctypes (compiled)", per_call(fast.fk, q, 20000)),
        ("fk, dhsym robot.fk", per_call(robot.fk, q, 20000)),
        ("ik all branches, C loop (thread CPU)", c["ik_exact_cpu"]),
        ("ik all branches, C loop (wall)", c["ik_exact_wall"]),
        ("ik 6 decimals, C loop (thread CPU)", c["ik_rounded6_cpu"]),
        ("ik 4 decimals, C loop (thread CPU)", c["ik_rounded4_cpu"]),
        ("ik, ctypes (compiled)", per_pose(fast.ik, poses)),
        ("ik, dhsym robot.ik", per_pose(robot.ik, poses[:50])),
        ("ik 6 decimals, robot.ik", per_call(robot.ik, np.round(T, 6), 2000)),
        ("ik 4 decimals, robot.ik", per_call(robot.ik, np.round(T, 4), 2000)),
        ("ik 6 decimals, robot.ik, 200 poses", per_pose(robot.ik, rounded[6])),
        ("ik 4 decimals, robot.ik, 200 poses", per_pose(robot.ik, rounded[4])),
        ("ik, robot.ik NumPy path", per_call(numpy_path, T, 2000)),
    ]
    eaik = eaik_call(robot)
    if eaik is not None:
        rows.append(("ik, EAIK bot.IK (C++ via Python)", per_pose(eaik, poses)))
    family = robot.inverse().family
    print(
        f"{robot.name} ({family}), IK solutions per pose: "
        f"{c['ik_exact_solutions']:.2f} exact, {c['ik_rounded6_solutions']:.2f} with 6 decimals, "
        f"{c['ik_rounded4_solutions']:.2f} with 4 (1000 poses of configurations in [-3.1, 3.1]^6; "
        f"backend {fast.backend})"
    )
    ref = {"fk": rows[3][1], "ik": rows[9][1]}
    exact_one, typed_one = rows[9][1], rows[10][1]
    for label, ns in rows:
        kind = label.split(",")[0].split()[0]
        print(f"  {label:38s} {ns:12.1f} ns   dhsym/this = {ref[kind] / ns:8.1f}x")
    print(
        f"  goals (issue 30, thread CPU): fk {c['fk_cpu']:.0f} ns (<= 100), all IK branches "
        f"{c['ik_exact_cpu'] / 1000:.2f} us exact, {c['ik_rounded6_cpu'] / 1000:.2f} us with 6 "
        f"decimals (<= 2); robot.ik {exact_one / 1000:.1f} us exact (<= 10), "
        f"{typed_one / 1000:.1f} us with 6 decimals (<= 15)"
    )
    if eaik is not None:
        e = rows[-1][1]
        print(
            f"  per pose: exported C IK (thread CPU) / EAIK: {c['ik_exact_cpu'] / e:.2f}; "
            f"ctypes (compiled) / EAIK: {rows[8][1] / e:.2f} (above 1: EAIK is faster; EAIK's "
            "figure includes its Python call and checks nothing)"
        )


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
