"""Inverse kinematics benchmark: the compiled closed form against a numeric solver.

Both run in this process on the same machine, one after the other. The reference is
dhsym's own Levenberg–Marquardt solver (:func:`dhsym.ik.levenberg_marquardt.numeric_ik`) on
the compiled ``fk`` and Jacobian, started from random configurations. It finds one
solution per run (or none), so it is measured twice:

* per converged solution: random starts, total time divided by the runs that converged;
* for every solution of a pose: random starts until it has found as many distinct
  solutions as the closed form returns for that pose (a stopping rule that favours LM:
  on its own it could not know how many there are), or a budget of starts is spent;
  the time per pose, and how many it found (each compared with the closed form's). It
  is never started near the analytic solutions.

The closed form is measured

* one pose per call (``robot.ik(T)``: every branch, each checked by ``fk``, singular
  factors evaluated; the program for floats, in C through ctypes when a compiler is
  there), per pose: the best of 200 passes over blocks of 20 poses (:func:`per_pose`,
  EAIK's ``IK`` timed the same way when installed); and the same poses rounded to 6 and
  to 4 decimals (best of 50 passes);
* batched, ``solver.raw`` (every branch, unchecked) and ``robot.ik`` (checked, the
  default), in poses per second; the same run's batch ``fk`` is the yardstick (IK time
  in units of one ``fk`` of one configuration: less dependent on the machine's load).

Every timing is the best of a few repeats; ``os.getloadavg()`` is printed before and
after, since the figures move with the load.

Usage::

    python benchmarks/bench_inverse.py           # PUMA 560 (both), Stanford, Example 4, 2R, SCARA
    python benchmarks/bench_inverse.py --quick   # PUMA 560 only, fewer poses
    python benchmarks/bench_inverse.py --ur      # UR5 beside the PUMA 560, in one run
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable

import numpy as np

import dhsym
from dhsym.ik import inverse, numeric_ik
from dhsym.ik.closed_form_solver import ClosedFormSolver


def best(fn: Callable[[], object], repeat: int) -> float:
    """Best wall time of ``repeat`` runs."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def per_pose(fn: Callable[[np.ndarray], object], poses: list[np.ndarray], rounds: int) -> float:
    """Seconds per pose: the best of ``rounds`` passes over blocks of 20 poses (a block
    short enough to fall between the other work of a shared machine), the same for
    dhsym and its peer so that their ratio is fair."""
    blocks = [poses[k : k + 20] for k in range(0, len(poses), 20)]
    fastest = float("inf")
    for _ in range(rounds):
        for block in blocks:
            t0 = time.perf_counter_ns()
            for T in block:
                fn(T)
            fastest = min(fastest, (time.perf_counter_ns() - t0) / len(block))
    return fastest * 1e-9


def random_q(robot: dhsym.Robot, count: int, rng: np.random.Generator) -> np.ndarray:
    q = rng.uniform(-np.pi, np.pi, (count, len(robot.variables)))
    for k, row in enumerate(r for r in robot.table.rows if r.variable is not None):
        if row.joint.value == "P":
            lo, hi = (float(v) for v in row.limits) if row.limits else (0.1, 0.8)
            q[:, k] = rng.uniform(max(lo, 0.05), hi, count)
    return q


def load() -> str:
    return (
        "load average "
        + ", ".join(f"{x:.2f}" for x in os.getloadavg())
        + f" ({os.cpu_count()} cores)"
    )


def distance(robot: dhsym.Robot, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Largest joint difference (angles modulo 2π) between ``a`` ``(n,)`` and rows of ``b``."""
    revolute = np.array([r.joint.value == "R" for r in robot.table.rows if r.variable is not None])
    d = b - a
    d[..., revolute] = np.remainder(d[..., revolute] + np.pi, 2 * np.pi) - np.pi
    return np.abs(d).max(axis=-1)  # type: ignore[no-any-return]


def lm_all_branches(
    robot: dhsym.Robot, T: np.ndarray, K: int, budget: int, rng: np.random.Generator
) -> tuple[list[np.ndarray], int]:
    """LM from random starts until K distinct solutions or ``budget`` starts; the solutions
    and the number of starts."""
    found: list[np.ndarray] = []
    starts = 0
    while len(found) < K and starts < budget:
        starts += 1
        sol = numeric_ik(robot, T, random_q(robot, 1, rng)[0])
        if sol.converged and (not found or distance(robot, sol.q[0], np.array(found)).min() > 1e-6):
            found.append(sol.q[0])
    return found, starts


def bench(
    name: str, lm_poses: int, lm_all_poses: int, budget: int, single: int, batch: int
) -> None:
    robot = dhsym.load(name)
    rng = np.random.default_rng(0)
    t0 = time.perf_counter()
    ik = inverse(robot)
    t_derive = time.perf_counter() - t0
    t0 = time.perf_counter()
    solver = ClosedFormSolver(ik, robot.table.value_map)
    T0 = robot.fk(random_q(robot, 2, rng))
    solver.solve(T0[0]), solver.solve(T0), solver.raw(T0)  # compile the three programs
    t_compile = time.perf_counter() - t0
    K = ik.count
    print(f"\n## {robot.name}: {ik.structure}")
    print(f"derive {t_derive:.2f} s, compile {t_compile:.2f} s, {K} branches; {load()}")

    # numeric reference 1: one solution per run from a random start
    T_lm = robot.fk(random_q(robot, lm_poses, rng))
    starts = random_q(robot, lm_poses, rng)
    numeric_ik(robot, T_lm[0], starts[0])  # compile the Jacobian outside the timing
    t0 = time.perf_counter()
    converged = sum(numeric_ik(robot, T, s).converged for T, s in zip(T_lm, starts))
    t_lm = (time.perf_counter() - t0) / max(converged, 1)
    print(
        f"LM (numeric), one solution: {t_lm * 1e6:10.1f} µs per converged solution "
        f"({converged}/{lm_poses} runs converged)"
    )

    # numeric reference 2: every solution of a pose, from random starts
    T_all = robot.fk(random_q(robot, lm_all_poses, rng))
    closed = [robot.ik(T).q for T in T_all]  # how many to look for (outside the timing)
    t0 = time.perf_counter()
    results = [lm_all_branches(robot, T, len(c), budget, rng) for T, c in zip(T_all, closed)]
    t_lm_all = (time.perf_counter() - t0) / lm_all_poses
    want = sum(len(c) for c in closed)
    got = sum(len(found) for found, _ in results)
    complete = sum(len(found) == len(c) for (found, _), c in zip(results, closed))
    matched = sum(
        distance(robot, q, c).min() < 1e-6 for (found, _), c in zip(results, closed) for q in found
    )
    starts_per_pose = sum(n for _, n in results) / lm_all_poses
    print(
        f"LM (numeric), every solution: {t_lm_all * 1e3:8.1f} ms per pose (random starts until "
        f"as many distinct as the closed form has, or {budget} starts; found {got}/{want}, "
        f"all for {complete}/{lm_all_poses} poses, {starts_per_pose:.0f} starts per pose; "
        f"{matched}/{got} equal a closed-form solution)"
    )

    # closed form, one pose per call
    T1 = list(robot.fk(random_q(robot, single, rng)))
    t_one = per_pose(robot.ik, T1, 200)
    n_one = np.mean([len(robot.ik(T)) for T in T1])
    print(
        f"closed form, one pose per call: {t_one * 1e6:8.1f} µs (all {K} branches, each checked "
        f"by fk, singular factors; {n_one:.2f} solutions per pose)"
    )
    for decimals in (6, 4):  # poses as they come: typed with 6 or 4 decimals
        typed = [np.round(T, decimals) for T in T1]
        t_typed = per_pose(robot.ik, typed, 50)
        n_typed = np.mean([len(robot.ik(T)) for T in typed])
        print(
            f"closed form, one pose per call, rounded to {decimals} decimals: "
            f"{t_typed * 1e6:8.1f} µs ({n_typed:.2f} solutions per pose; the best block of "
            "20 poses: a block with a branch refined in Python costs more)"
        )

    # closed form, batched; batch fk in the same run as a yardstick of this machine's speed
    qB = random_q(robot, batch, rng)
    t_fk = best(lambda: robot.fk(qB), 3) / batch
    TB = robot.fk(qB)
    t_b_raw = best(lambda: solver.raw(TB), 3) / batch
    t_b_chk = best(lambda: robot.ik(TB), 3) / batch
    print(
        f"closed form, batch of {batch:,}: {1 / t_b_raw:12,.0f} poses/s unchecked, "
        f"{1 / t_b_chk:12,.0f} poses/s checked (default); batch fk {1 / t_fk:12,.0f} "
        f"configurations/s (IK unchecked = {t_b_raw / t_fk:.1f} fk, "
        f"checked = {t_b_chk / t_fk:.1f} fk)"
    )
    eaik_peer(robot, T1, TB[: min(batch, 20_000)], t_one, t_b_chk)
    print(
        f"ratios: LM per converged solution / closed form per pose (all branches): "
        f"{t_lm / t_one:8.0f}x one pose per call, {t_lm / t_b_chk:8.0f}x batched checked; "
        f"LM every solution / closed form: {t_lm_all / t_one:8.0f}x one pose per call, "
        f"{t_lm_all / t_b_chk:8.0f}x batched checked"
    )
    print(load())


def eaik_peer(
    robot: dhsym.Robot, T1: list[np.ndarray], TB: np.ndarray, t_one: float, t_batch: float
) -> None:
    """EAIK (C++ subproblem decomposition, ``pip install eaik``), when installed: an
    optional peer on the same poses, standard DH tables without base or tool only."""
    try:
        from eaik.IK_DH import DhRobot
    except ImportError:
        print("EAIK: not installed (pip install eaik), no comparison")
        return
    table = robot.table
    if robot.convention.value != "standard" or table.base or table.tool:
        print("EAIK: takes standard DH tables without base or tool; not this one")
        return
    if any(r.offset != 0 for r in table.rows):
        print("EAIK: takes no joint offsets; not this one")
        return
    vals = table.value_map
    col = {
        k: np.array([float(getattr(r, k).xreplace(vals)) for r in table.rows])
        for k in "a d alpha".split()
    }
    bot = DhRobot(col["alpha"], col["a"], col["d"])
    if not bot.hasKnownDecomposition():
        print("EAIK: no known decomposition for this arm")
        return
    t_e1 = per_pose(bot.IK, T1, 200)
    t_check = best(lambda: [robot.fk_function()(np.asarray(bot.IK(T).Q)) for T in T1], 3) / len(T1)
    t_eb = best(lambda: bot.IK_batched(list(TB)), 3) / len(TB)
    print(
        f"EAIK {bot.getKinematicFamily()}: one pose {t_e1 * 1e6:8.1f} µs (all solutions, "
        f"unchecked; {t_check * 1e6:.1f} µs with dhsym's fk check of each), batched "
        f"{1 / t_eb:12,.0f} poses/s; dhsym / EAIK: {t_one / t_e1:.1f}x one pose, "
        f"{t_batch / t_eb:.1f}x batched (dhsym checked)"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="PUMA 560 only, fewer poses")
    parser.add_argument("--ur", action="store_true", help="UR5 and PUMA 560 only (same run)")
    args = parser.parse_args()
    print(load())
    if args.ur:  # three parallel axes against the spherical wrist, in one run
        for name in ("puma560", "ur5"):
            bench(name, lm_poses=20, lm_all_poses=3, budget=100, single=300, batch=100_000)
        return
    if args.quick:
        bench("puma560", lm_poses=50, lm_all_poses=5, budget=100, single=300, batch=100_000)
        return
    for name in (
        "puma560",
        "puma560_modified",
        "ur5",
        "stanford",
        "example4_6dof",
        "planar2r",
        "scara",
    ):
        bench(name, lm_poses=100, lm_all_poses=10, budget=200, single=500, batch=200_000)


if __name__ == "__main__":
    main()
