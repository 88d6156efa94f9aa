"""The general 6R solver against multi-start numeric searches, in the same run.

Run ``python benchmarks/bench_general6r.py`` (``--poses N``, ``--starts N``). For the Kinova
Jaco and Mico (roboticstoolbox DH models, ``tests/data/general6r``), two random general
arms (standard and modified DH) and the degenerate PUMA 560 and UR5, it prints:

* the build time (derivation of the fourteen equations, compilation, self-test);
* the time per pose of ``solve`` (every real solution, each checked by fk), its median over
  random poses, and the part spent in the elimination and Newton polish alone;
* the time of a vectorised multi-start Levenberg–Marquardt (``tests/ik/_multistart.py``,
  all starts at once) and of scipy's MINPACK ``least_squares(method="lm")`` from the same
  number of starts (run on a few poses, scaled per pose), and the ratios;
* solutions per pose (solver vs. multi-start) and whether the search found any the solver
  lacks (it must not);
* a calibration: ``numpy.linalg.eig`` of a 24×24 matrix in the same run, since the machine
  may be shared.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from dhsym.ik.general6r import eigenproblem as g  # noqa: E402
from dhsym.model.library import builtin_table  # noqa: E402
from dhsym.model.table import DHRow, DHTable  # noqa: E402
from dhsym.model.tablefile import read_table  # noqa: E402
from dhsym.robot import Robot  # noqa: E402
from tests.ik._multistart import contains, multistart_lm  # noqa: E402

DATA = ROOT / "tests" / "data" / "general6r"


def _random_table(seed: int, convention: str) -> DHTable:
    rng = np.random.default_rng(seed)
    rows = [
        DHRow.revolute(
            f"q{i}",
            d=float(rng.uniform(-0.5, 0.5)),
            a=float(rng.uniform(-0.5, 0.5)),
            alpha=float(rng.uniform(-3.0, 3.0)),
        )
        for i in range(1, 7)
    ]
    return DHTable.from_rows(rows, convention=convention, snap_angles=False, name=f"random {seed}")


def _arms() -> list[tuple[DHTable, bool]]:
    """The arms, and whether solutions are checked by the closed-form ``Robot.fk_function``
    (else by the default, the table's elementary word through ``compile_word``)."""
    jaco = read_table(DATA / "jaco.yaml")
    return [
        (jaco, False),
        (jaco, True),
        (read_table(DATA / "mico.yaml"), False),
        (_random_table(1, "standard"), False),
        (_random_table(2, "modified"), False),
        (builtin_table("puma560"), False),
        (read_table(DATA / "ur5.yaml"), False),
    ]


def _median_us(f, repeat: int = 1) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return 1e6 * statistics.median(times)


def _scipy_multistart(fk, T: np.ndarray, starts: int, seed: int = 0) -> int:
    from scipy.optimize import least_squares

    rng = np.random.default_rng(seed)
    goal = T[:3, :].ravel()
    found = []
    for q0 in rng.uniform(-np.pi, np.pi, (starts, 6)):
        r = least_squares(lambda q: fk(q)[:3, :].ravel() - goal, q0, method="lm", xtol=1e-15)
        if np.abs(r.fun).max() < 1e-10:
            found.append(r.x)
    return len(found)


def _bench(table: DHTable, closed: bool, args: argparse.Namespace) -> str:
    """One line of the table: build, solve, the searches, for one arm."""
    t0 = time.perf_counter()
    fk = Robot(table).fk_function() if closed else None
    solver = g.general_6r(table, fk=fk)
    build = time.perf_counter() - t0
    rng = np.random.default_rng(42)
    poses = [solver.fk(q) for q in rng.uniform(-np.pi, np.pi, (args.poses, 6))]
    for T in poses[:5]:  # warm up
        solver.solve(T)
    arr = solver.arrangement
    solve_t, inner_t, counts = [], [], []
    for T in poses:
        solve_t.append(_median_us(lambda T=T: solver.solve(T), 3))
        Tp = arr.target(T)
        inner_t.append(_median_us(lambda Tp=Tp: g._polish(arr, g._candidates(arr, Tp), Tp), 3))
        counts.append(len(solver.solve(T)))
    lm_t, sp_t, lm_sols, missed = [], [], [], 0

    def single(q: np.ndarray) -> np.ndarray:
        return solver.fk(np.asarray(q)[None])[0]

    for T in poses[: args.searched]:
        t0 = time.perf_counter()
        found = multistart_lm(solver.fk, T, args.starts)
        lm_t.append(1e6 * (time.perf_counter() - t0))
        Q = solver.solve(T)
        lm_sols.append(len(found))
        missed += sum(not contains(Q, f, 1e-5) for f in found)
        t0 = time.perf_counter()
        _scipy_multistart(single, T, max(args.starts // 10, 1))
        sp_t.append(1e6 * (time.perf_counter() - t0) * 10)  # scaled to args.starts starts
    solve_med = statistics.median(solve_t)
    lm_med, sp_med = statistics.median(lm_t), statistics.median(sp_t)
    pencil = "12x12" if arr.project is None else "16x16"
    name = (table.name[:31] + (" [closed fk]" if closed else ""))[:42]
    return (
        f"{name:<42} {build:7.2f} {pencil:>6} {solve_med:9.0f} "
        f"{statistics.median(inner_t):11.0f} {statistics.mean(counts):5.1f} {lm_med:9.0f} "
        f"{lm_med / solve_med:8.0f} {sp_med:10.0f} {sp_med / solve_med:11.0f} "
        f"{statistics.mean(lm_sols):7.1f} {missed:6d}"
    )


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--poses", type=int, default=100, help="random poses per arm for solve")
    p.add_argument("--starts", type=int, default=200, help="starts of the multi-start searches")
    p.add_argument("--searched", type=int, default=3, help="poses per arm for the searches")
    args = p.parse_args()
    M = np.random.default_rng(0).standard_normal((24, 24))
    calib = statistics.median(_median_us(lambda: np.linalg.eig(M)) for _ in range(200))
    print(f"calibration: numpy.linalg.eig of a 24x24 matrix {calib:.0f} us (same run)")
    header = (
        f"{'arm':<42} {'build s':>7} {'pencil':>6} {'solve us':>9} {'elim+polish':>11} "
        f"{'sols':>5} {'LM us':>9} {'LM/solve':>8} {'scipy us':>10} {'scipy/solve':>11} "
        f"{'LM sols':>7} {'missed':>6}"
    )
    print(header)
    for table, closed in _arms():
        print(_bench(table, closed, args), flush=True)
    print(
        "solve: median per pose (all solutions, fk-checked); elim+polish: the same without the "
        "fk check and deduplication; [closed fk]: checked by Robot.fk_function (the closed "
        "form; its compilation is in the build time), else by the elementary word; "
        "sols: mean solutions per pose; LM: vectorised multi-start "
        f"LM, {args.starts} starts; scipy: least_squares(method='lm') per start, timed on "
        f"{max(args.starts // 10, 1)} starts and scaled to {args.starts}; missed: solutions "
        "found by the LM search and absent from solve (must be 0)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
