"""Singularities of arms without a spherical wrist: the whole 6×6 ``det J`` factored.

For the UR3, UR5 and UR10, the CPU time of :func:`dhsym.kinematics.singularities.singularities`
(derived here, the disk cache not used, sympy's cache cleared before each run) against the
same factoring of ``J`` as a student would write it, in the same process: in frame 0 at
the tool point, and in the tool frame at the tool point. Prints seconds, the ratios
(reference / dhsym) and the load average at the start and the end.

Usage::

    python benchmarks/bench_singularities.py
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable

from sympy.core.cache import clear_cache

import dhsym
from dhsym.kinematics.jacobian import geometric_jacobian
from dhsym.kinematics.singularities import _derive, factored_det


def cpu(fn: Callable[[], object]) -> float:
    """CPU seconds of one run, sympy's cache cleared first (a cold derivation)."""
    clear_cache()
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def main() -> None:
    print(f"load average at the start: {os.getloadavg()}")
    print(
        f"{'arm':6} {'dhsym s':>8} | {'frame 0 s':>9} {'ratio':>6} | "
        f"{'tool frame s':>12} {'ratio':>6}"
    )
    for name in ("ur3", "ur5", "ur10"):
        robot = dhsym.load(name)
        ours = cpu(lambda robot=robot: _derive(robot))
        base = cpu(lambda robot=robot: factored_det(geometric_jacobian(robot, 0).matrix))
        tool = cpu(lambda robot=robot: factored_det(geometric_jacobian(robot, "tool").matrix))
        print(
            f"{name:6} {ours:8.2f} | {base:9.2f} {base / ours:5.1f}x | {tool:12.2f} "
            f"{tool / ours:5.1f}x"
        )
    print(f"load average at the end: {os.getloadavg()}")


if __name__ == "__main__":
    main()
