"""Inverse kinematics benchmark: the compiled closed form against a numeric solver.

Both run in this process on the same poses. The reference is dhsym's own
Levenberg–Marquardt solver (:func:`dhsym.kinematics.inverse.numeric_ik`) on the compiled ``fk``
and Jacobian, started from random configurations; it finds one solution per run, so
its cost for all branches is at least K times its cost per solution.

Printed per robot:

* derivation and compilation time (once per robot);
* LM: time per converged solution, convergence rate;
* closed form, one pose per call: every branch, checked (fk of each branch compared with
  the pose, singular factors evaluated) and unchecked;
* closed form, batched: poses per second, unchecked and checked, and the same run's batch
  ``fk`` throughput as a yardstick (IK time in units of one ``fk``: independent of load);
* ratios LM time per solution / closed-form time per pose (all branches).

Usage::

    python benchmarks/bench_inverse.py           # PUMA 560 (both), Stanford, Example 4, 2R, SCARA
    python benchmarks/bench_inverse.py --quick   # PUMA 560 only, smaller batches
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable

import numpy as np

import dhsym
from dhsym.kinematics.inverse import inverse, numeric_ik


def best(fn: Callable[[], object], repeat: int) -> float:
    """Best wall time of ``repeat`` runs."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def random_q(robot: dhsym.Robot, count: int, rng: np.random.Generator) -> np.ndarray:
    q = rng.uniform(-np.pi, np.pi, (count, len(robot.variables)))
    for k, row in enumerate(r for r in robot.table.rows if r.variable is not None):
        if row.joint.value == "P":
            lo, hi = (float(v) for v in row.limits) if row.limits else (0.1, 0.8)
            q[:, k] = rng.uniform(max(lo, 0.05), hi, count)
    return q


def bench(name: str, lm_poses: int, single: int, batch: int) -> None:
    robot = dhsym.load(name)
    rng = np.random.default_rng(0)
    t0 = time.perf_counter()
    ik = inverse(robot)
    t_derive = time.perf_counter() - t0
    t0 = time.perf_counter()
    solver = ik.solver()
    solver.solve(robot.fk(random_q(robot, 1, rng)))  # first call: compile fk, singular factors
    t_compile = time.perf_counter() - t0
    K = ik.count
    print(f"\n## {robot.name}: {ik.structure}")
    print(f"derive {t_derive:.2f} s, compile {t_compile:.2f} s, {K} branches")

    # numeric reference: LM from a random start, one solution per run
    q_lm = random_q(robot, lm_poses, rng)
    T_lm = robot.fk(q_lm)
    starts = random_q(robot, lm_poses, rng)
    numeric_ik(robot, T_lm[0], starts[0])  # compile the Jacobian outside the timing
    t0 = time.perf_counter()
    converged = sum(numeric_ik(robot, T, s).converged for T, s in zip(T_lm, starts))
    t_lm = (time.perf_counter() - t0) / max(converged, 1)
    print(
        f"LM (numeric): {t_lm * 1e6:10.1f} µs per converged solution "
        f"({converged}/{lm_poses} converged); all {K} branches would need ≥ {K}× that"
    )

    # closed form, one pose per call
    T1 = robot.fk(random_q(robot, single, rng))
    t_checked = best(lambda: [solver.solve(T) for T in T1], 3) / single
    t_raw = best(lambda: [solver.raw(T[None]) for T in T1], 3) / single
    print(
        f"closed form, one pose per call: {t_checked * 1e6:8.1f} µs checked, "
        f"{t_raw * 1e6:8.1f} µs unchecked (all {K} branches)"
    )

    # closed form, batched; batch fk in the same run as a yardstick of this machine's speed
    qB = random_q(robot, batch, rng)
    t_fk = best(lambda: robot.fk(qB), 3) / batch
    TB = robot.fk(qB)
    t_b_raw = best(lambda: solver.raw(TB), 3) / batch
    t_b_chk = best(lambda: solver.solve(TB), 1) / batch
    print(
        f"closed form, batch of {batch}: {1 / t_b_raw:12,.0f} poses/s unchecked, "
        f"{1 / t_b_chk:12,.0f} poses/s checked; batch fk {1 / t_fk:12,.0f} configurations/s "
        f"(IK unchecked = {t_b_raw / t_fk:.1f} fk, checked = {t_b_chk / t_fk:.1f} fk)"
    )
    print(
        f"ratio LM per solution / closed form per pose (all branches): "
        f"{t_lm / t_checked:7.0f}x one checked pose per call, "
        f"{t_lm / t_raw:7.0f}x one unchecked pose per call, "
        f"{t_lm / t_b_raw:8.0f}x batched unchecked, {t_lm / t_b_chk:8.0f}x batched checked"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="PUMA 560 only, smaller batches")
    args = parser.parse_args()
    if args.quick:
        bench("puma560", lm_poses=50, single=200, batch=100_000)
        return
    for name in ("puma560", "puma560_modified", "stanford", "example4_6dof", "planar2r", "scara"):
        bench(name, lm_poses=200, single=500, batch=200_000)


if __name__ == "__main__":
    main()
