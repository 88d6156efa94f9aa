"""Core benchmark: dhsym against plain sympy and numpy, measured in the same process.

Prints ratios (baseline time / dhsym time) and ``count_ops`` of each result:

* planar nR (2 … 20): dhsym compact arm matrix vs plain product + ``trigsimp``
  and vs plain product + ``fu``;
* PUMA 560 (standard and modified): cold (first derivation in this process),
  warm (new Robot, sympy's cache warm) vs plain product + ``trigsimp``;
* tables as people type them: the PUMA 560 with twists 1.5708 and 1.5707963267948966
  vs the exact built-in, and ``convert`` of a 10-joint arm with float twists vs pi/2;
* single-configuration ``fk`` (one q, the pure-float path) vs roboticstoolbox-style numpy
  (a product of per-link 4x4 numpy matrices) and vs the previous implementation;
* batch ``fk`` of PUMA 560 configurations vs a plain numpy product of (N, 4, 4) stacks and
  vs the previous implementation;
* ``import dhsym`` vs ``import sympy`` in fresh interpreters.

Timings of small operations are medians of repeated runs (``timeit``); the load average
of the machine is printed at the start and the end.

Usage::

    python benchmarks/bench_core.py            # everything (fu on 8R alone takes ~2 minutes)
    python benchmarks/bench_core.py --quick    # skips the slow baselines above 6R
    python benchmarks/bench_core.py --only fk,typed   # some sections only
"""

from __future__ import annotations

import argparse
import gc
import math
import os
import statistics
import subprocess
import sys
import time
import timeit
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import numpy as np
import sympy as sp
from sympy.core.cache import clear_cache
from sympy.simplify.fu import fu

import dhsym
from dhsym.geometry.conversion import check_conversion, convert
from dhsym.kinematics.transforms import chain_word, plain_product
from dhsym.model.tablefile import dump_table, read_table_text


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


def median_time(fn: Callable[[], object], number: int, repeat: int = 15) -> float:
    """Median over ``repeat`` runs of the mean time of one call (``number`` calls per run)."""
    return statistics.median(timeit.repeat(fn, number=number, repeat=repeat)) / number


# --- tables as people type them ------------------------------------------------------------


def _puma_typed(twist: str) -> str:
    text = (Path(dhsym.__file__).parent / "model" / "robots" / "puma560.yaml").read_text()
    return text.replace("alpha: pi/2", f"alpha: {twist}").replace(
        "alpha: -pi/2", f"alpha: -{twist}"
    )


def _arm10(twist: str, snap: bool = True) -> str:
    rows = []
    for k in range(1, 11):
        alpha = twist if k % 2 else (f"-{twist}" if k % 3 else 0)
        rows.append(f"  - {{type: R, theta: theta{k}, d: d{k}, a: a{k}, alpha: {alpha}}}")
    values = ", ".join(f"a{k}: 0.{k}1, d{k}: 0.0{k}" for k in range(1, 11))
    head = "" if snap else "snap_angles: false\n"
    return f"{head}joints:\n" + "\n".join(rows) + f"\nvalues: {{{values}}}\n"


def typed_tables(rounds: int = 9) -> None:
    print(
        f"\n## Tables as typed from a toolbox printout (median of {rounds} interleaved rounds, "
        "table reading included, sympy's cache emptied before each)"
    )

    def derive(text: str) -> dhsym.Pose:
        return dhsym.Robot(read_table_text(text)).arm_matrix()

    variants = {
        "PUMA 560, alpha = pi/2 (built-in)": _puma_typed("pi/2"),
        "alpha = 1.5708 (toolbox printout)": _puma_typed("1.5708"),
        "alpha = 1.5707963267948966 (Python float)": _puma_typed("1.5707963267948966"),
        "alpha = 1.5708, snap_angles: false": "snap_angles: false\n" + _puma_typed("1.5708"),
    }
    _interleaved(
        variants,
        derive,
        rounds,
        lambda P: (
            f"ops {P.count_ops()}" + (", has cos(3927/2500)" if "cos(3927" in str(P.matrix) else "")
        ),
    )

    print(
        f"\n## dhsym convert of a 10-joint arm (convert, fk check at 20 q, YAML), median of "
        f"{rounds} interleaved rounds"
    )

    def run(text: str) -> str:
        table = read_table_text(text)
        new = convert(table, "modified")
        check_conversion(table, new)
        return dump_table(new)

    variants = {
        "alpha = pi/2": _arm10("pi/2"),
        "alpha = 1.5707963267948966": _arm10("1.5707963267948966"),
        "alpha = 1.5707963267948966, kept": _arm10("1.5707963267948966", snap=False),
        "alpha = 1.2 (near no multiple)": _arm10("1.2"),
    }
    _interleaved(variants, run, rounds, lambda out: "")


def _interleaved(
    variants: Mapping[str, str], fn: Callable[[str], object], rounds: int, describe: Callable
) -> None:
    """Time ``fn`` on each variant once per round (so load changes hit all alike); medians."""
    times: dict[str, list[float]] = {label: [] for label in variants}
    for _ in range(rounds):
        for label, text in variants.items():
            clear_cache()  # each variant starts from sympy's empty cache: no order effects
            gc.collect()  # and the garbage of the previous variant is not charged to it
            times[label].append(timed(lambda text=text: fn(text))[0])
    first = statistics.median(next(iter(times.values())))
    for label, text in variants.items():
        t = statistics.median(times[label])
        extra = describe(fn(text))
        print(
            f"{label:44s} {t:.3f} s"
            + (f", {extra}" if extra else "")
            + (f", ratio to the first {t / first:.2f}" if t is not first else ""),
            flush=True,
        )


# --- numbers: single configurations and batches ----------------------------------------------


def _dh_params(table: dhsym.DHTable) -> list[tuple[float, float, float, float, float]]:
    vals = table.value_map
    out = []
    for row in table.rows:
        off, d, a, al = (float(v.subs(vals)) for v in (row.offset, row.d, row.a, row.alpha))
        out.append((off, d, a, math.cos(al), math.sin(al)))
    return out


def numpy_single(params: Sequence[tuple[float, ...]], q: Sequence[float]) -> np.ndarray:
    """roboticstoolbox-style: one 4x4 numpy matrix per link (DHLink.A), multiplied in turn."""
    T = np.eye(4)
    for (off, d, a, ca, sa), qi in zip(params, q, strict=True):
        ct, st = math.cos(qi + off), math.sin(qi + off)
        T = T @ np.array(
            [
                [ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0.0, sa, ca, d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
    return T


class PreviousFk:
    """``Robot.fk`` as it was before the pure-float path (commit 5a1ec43), for the same-run ratio.

    Every call rebuilt the cache key from ``str()`` of the sympy values, and one
    configuration went through the numpy batch code.
    """

    def __init__(self, robot: dhsym.Robot) -> None:
        self.robot = robot
        self.cache: dict[object, Callable[[np.ndarray], np.ndarray]] = {}

    def fk_function(self, values: Mapping[object, object] | None = None) -> Callable:
        from dhsym.model.entries import as_expr
        from dhsym.model.parsing import symbol

        pose = self.robot.tool_pose()
        vals = dict(self.robot.table.value_map)
        for k, v in (values or {}).items():
            vals[symbol(k) if isinstance(k, str) else k] = as_expr(v, field="values")
        key = (pose.frm, pose.to, tuple(sorted((str(k), str(v)) for k, v in vals.items())))
        if key not in self.cache:
            self.cache[key] = self._compile(pose.matrix, self.robot.variables, vals)
        return self.cache[key]

    def fk(self, q: object) -> np.ndarray:
        return self.fk_function()(np.asarray(q, dtype=float))

    @staticmethod
    def _compile(matrix: sp.MatrixBase, variables: Sequence[sp.Symbol], values: dict) -> Callable:
        M = sp.Matrix(matrix).subs(values)
        fn = sp.lambdify(
            list(variables), [M[i, j] for i in range(3) for j in range(4)], "numpy", cse=True
        )

        def fk(arr: np.ndarray) -> np.ndarray:
            single = arr.ndim <= 1
            Q = arr.reshape(1, -1) if single else arr
            N = Q.shape[0]
            out = np.empty((N, 4, 4))
            flat = out.reshape(N, 16)
            flat[:, 12:15] = 0.0
            flat[:, 15] = 1.0
            for start in range(0, N, 4096):
                block = flat[start : start + 4096]
                for k, v in enumerate(fn(*Q[start : start + 4096].T)):
                    block[:, k] = v
                block[:, :12] += 0.0
            return out[0] if single else out

        return fk


def single_fk() -> None:
    print("\n## Single-configuration fk, PUMA 560 (median over 15 runs of 20,000 calls)")
    robot = dhsym.load("puma560")
    params = _dh_params(robot.table)
    previous = PreviousFk(robot)
    q = [0.1, -0.4, 0.3, 1.2, -0.5, 2.0]
    qa = np.array(q)
    assert np.allclose(robot.fk(q), numpy_single(params, q)) and np.allclose(
        robot.fk(q), previous.fk(q)
    )
    t_list = median_time(lambda: robot.fk(q), 20_000)
    t_arr = median_time(lambda: robot.fk(qa), 20_000)
    t_np = median_time(lambda: numpy_single(params, q), 5_000)
    t_prev = median_time(lambda: previous.fk(q), 2_000)
    print(
        f"dhsym robot.fk(list) {t_list * 1e6:.2f} us, robot.fk(ndarray) {t_arr * 1e6:.2f} us | "
        f"numpy per-link 4x4 {t_np * 1e6:.2f} us (ratio {t_np / t_list:.1f}x) | "
        f"previous dhsym {t_prev * 1e6:.2f} us (ratio {t_prev / t_list:.1f}x)",
        flush=True,
    )


def batch_fk(N: int) -> None:
    print(f"\n## Batch fk, PUMA 560, N = {N:,} configurations (one core, median of 5)")
    robot = dhsym.load("puma560")
    table = robot.table
    rng = np.random.default_rng(0)
    Q = rng.uniform(-np.pi, np.pi, size=(N, 6))
    f = robot.fk_function()
    f(Q[:10])  # compile once
    previous = PreviousFk(robot)
    previous.fk(Q[:10])
    t_d = median_time(lambda: f(Q), 1, repeat=5)
    t_n = median_time(lambda: numpy_baseline(table, Q), 1, repeat=5)
    t_p = median_time(lambda: previous.fk(Q), 1, repeat=5)
    err = float(np.max(np.abs(f(Q) - numpy_baseline(table, Q))))
    print(
        f"dhsym {t_d:.3f} s ({N / t_d / 1e6:.1f} M configs/s) | numpy 4x4 stacks {t_n:.3f} s "
        f"({N / t_n / 1e6:.1f} M/s) | ratio {t_n / t_d:.1f}x | previous dhsym {t_p:.3f} s "
        f"(ratio {t_p / t_d:.2f}x) | max |diff| {err:.1e}"
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


SECTIONS = ("import", "puma", "typed", "planar", "fk", "batch")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="skip slow baselines above 6R")
    p.add_argument("--n", type=int, default=1_000_000, help="configurations for batch fk")
    p.add_argument("--only", default=",".join(SECTIONS), help=f"sections: {','.join(SECTIONS)}")
    args = p.parse_args()
    only = set(args.only.split(","))
    print(
        f"dhsym {dhsym.__version__}, sympy {sp.__version__}, numpy {np.__version__}, "
        f"python {sys.version.split()[0]}; load average {os.getloadavg()[0]:.2f} "
        f"on {os.cpu_count()} cores"
    )
    if "import" in only:
        import_time()
    if "puma" in only:
        puma()
    if "typed" in only:
        typed_tables()
    if "planar" in only:
        big = 6 if args.quick else 8
        planar([2, 3, 4, 6, 8, 12, 20], fu_max=big, trig_max=big)
    if "fk" in only:
        single_fk()
    if "batch" in only:
        batch_fk(args.n)
    print(f"\nload average at the end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
