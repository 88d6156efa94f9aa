"""Core benchmark: dhsym against plain sympy and numpy, measured in the same process.

Prints ratios (baseline time / dhsym time) and ``count_ops`` of each result:

* planar nR (2 … 20): dhsym compact arm matrix vs plain product + ``trigsimp``
  and vs plain product + ``fu``;
* PUMA 560 (standard and modified): cold (first derivation in this process),
  warm (new Robot, sympy's cache warm) vs plain product + ``trigsimp``;
* batch ``fk`` of PUMA 560 configurations vs a plain numpy product of (N, 4, 4) stacks;
* ``import dhsym`` vs ``import sympy`` in fresh interpreters.

Usage::

    python benchmarks/bench_core.py            # everything (fu on 8R alone takes ~2 minutes)
    python benchmarks/bench_core.py --quick    # skips the slow baselines above 6R
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from collections.abc import Callable

import numpy as np
import sympy as sp
from sympy.simplify.fu import fu

import dhsym
from dhsym.kinematics.transforms import chain_word, plain_product


def timed(fn: Callable[[], object], repeat: int = 1) -> tuple[float, object]:
    """Best wall time of ``repeat`` runs, and the last result."""
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def ops(M: sp.MatrixBase) -> int:
    return int(sum(sp.count_ops(e) for e in M))


def planar(ns: list[int], fu_max: int, trig_max: int) -> None:
    print("\n## Planar nR: arm matrix in closed form")
    print(
        f"{'n':>3} {'dhsym s':>9} {'ops':>5} | {'trigsimp s':>10} {'ops':>5} {'ratio':>7} |"
        f" {'fu s':>8} {'ops':>5} {'ratio':>7}"
    )
    for n in ns:
        table = dhsym.planar_chain(n)
        t_d, T = timed(lambda table=table: dhsym.Robot(table).arm_matrix().matrix)
        plain = plain_product(chain_word(table, 0, n))
        row = f"{n:>3} {t_d:9.4f} {ops(T):5d} |"
        if n <= trig_max:
            t_t, Tt = timed(lambda plain=plain: sp.trigsimp(plain))
            row += f" {t_t:10.3f} {ops(Tt):5d} {t_t / t_d:6.0f}x |"
        else:
            row += f" {'skipped':>10} {'':5} {'':7} |"
        if n <= fu_max:
            t_f, Tf = timed(lambda plain=plain: plain.applyfunc(fu))
            row += f" {t_f:8.3f} {ops(Tf):5d} {t_f / t_d:6.0f}x"
        else:
            row += f" {'skipped':>8}"
        print(row, flush=True)


def puma() -> None:
    print("\n## PUMA 560 arm matrix (6R), derivation with simplification")
    for name in ("puma560", "puma560_modified"):
        table = dhsym.builtin_table(name)
        t_cold, T = timed(lambda table=table: dhsym.Robot(table).arm_matrix().matrix)
        t_warm, T = timed(lambda table=table: dhsym.Robot(table).arm_matrix().matrix, repeat=5)
        plain = plain_product(chain_word(table, 0, 6))
        t_trig, Tt = timed(lambda plain=plain: sp.trigsimp(plain))
        print(
            f"{name:17s} dhsym cold {t_cold:.3f} s, warm {t_warm:.3f} s, ops {ops(T)} | "
            f"trigsimp {t_trig:.2f} s, ops {ops(Tt)} | ratio cold {t_trig / t_cold:.0f}x, "
            f"warm {t_trig / t_warm:.0f}x",
            flush=True,
        )


def numpy_baseline(table: dhsym.DHTable, Q: np.ndarray) -> np.ndarray:
    """Plain numpy: build each link's (N,4,4) stack from its DH row and multiply."""
    vals = table.value_map
    N = Q.shape[0]
    out = np.broadcast_to(np.eye(4), (N, 4, 4)).copy()
    for k, row in enumerate(table.rows):
        th = Q[:, k] + float(row.offset.subs(vals))
        d, a, al = (float(v.subs(vals)) for v in (row.d, row.a, row.alpha))
        ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
        A = np.zeros((N, 4, 4))
        A[:, 0, 0], A[:, 0, 1], A[:, 0, 2], A[:, 0, 3] = ct, -st * ca, st * sa, a * ct
        A[:, 1, 0], A[:, 1, 1], A[:, 1, 2], A[:, 1, 3] = st, ct * ca, -ct * sa, a * st
        A[:, 2, 1], A[:, 2, 2], A[:, 2, 3] = sa, ca, d
        A[:, 3, 3] = 1.0
        out = out @ A
    return out


def batch_fk(N: int) -> None:
    print(f"\n## Batch fk, PUMA 560, N = {N:,} configurations (one core)")
    robot = dhsym.load("puma560")
    table = robot.table
    rng = np.random.default_rng(0)
    Q = rng.uniform(-np.pi, np.pi, size=(N, 6))
    f = robot.fk_function()
    f(Q[:10])  # compile once
    t_d, T = timed(lambda: f(Q), repeat=3)
    t_n, Tn = timed(lambda: numpy_baseline(table, Q), repeat=3)
    err = float(np.max(np.abs(T - Tn)))
    print(
        f"dhsym {t_d:.3f} s ({N / t_d / 1e6:.1f} M configs/s) | numpy 4x4 stacks {t_n:.3f} s "
        f"({N / t_n / 1e6:.1f} M/s) | ratio {t_n / t_d:.1f}x | max |diff| {err:.1e}"
    )


def import_time(runs: int = 5) -> None:
    print("\n## Import time (fresh interpreter, median of", runs, "runs)")

    def run(stmt: str) -> float:
        code = f"import time; t=time.perf_counter(); {stmt}; print(time.perf_counter()-t)"
        times = []
        for _ in range(runs):
            out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
            times.append(float(out.stdout.strip()))
        return statistics.median(times)

    t_sympy = run("import sympy")
    t_dhsym = run("import dhsym")
    print(
        f"import sympy {t_sympy:.3f} s | import dhsym {t_dhsym:.3f} s "
        f"(ratio {t_dhsym / t_sympy:.2f})"
    )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="skip slow baselines above 6R")
    p.add_argument("--n", type=int, default=1_000_000, help="configurations for batch fk")
    args = p.parse_args()
    print(
        f"dhsym {dhsym.__version__}, sympy {sp.__version__}, numpy {np.__version__}, "
        f"python {sys.version.split()[0]}"
    )
    import_time()
    puma()
    planar([2, 3, 4, 6, 8, 12, 20], fu_max=6 if args.quick else 8, trig_max=6 if args.quick else 8)
    batch_fk(args.n)


if __name__ == "__main__":
    main()
