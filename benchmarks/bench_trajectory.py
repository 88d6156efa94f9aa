"""Sampling a trajectory: 10⁶ samples of a 6-joint quintic (q, q̇, q̈), target ≤ 0.1 s.

Run ``python benchmarks/bench_trajectory.py``. Times ``Profile.sample`` (the exact
coefficients converted to floats once, then one product of the powers of ``t`` with the
coefficient matrix) against a plain numpy reference in the same run: ``np.polyval`` of
the same coefficients and of their derivatives, joint by joint. Prints the best of
``--repeat`` runs of each (wall and CPU time), their ratios (wall and CPU), and the
largest difference between the two.
The first sample of the profile (the float conversion) is timed apart: it is paid once.

The same for a 6-joint LSPB whose joints have different blend times (three segments
each, no breaks shared: the segment of every sample found per joint) against numpy's
``np.select`` of the three polynomials per joint.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from dhsym.trajectory import lspb, quintic  # noqa: E402


def best(f, repeat: int) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """The best wall time and the best CPU time (all threads of this process) of ``f``."""
    walls, cpus = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        f()
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    return min(walls), min(cpus)


def _report(name: str, ours: float, ours_cpu: float, ref: float, ref_cpu: float) -> None:
    """The reference's wall time and both ratios, wall and CPU."""
    print(f"  {name:<22} {1000 * ref:8.1f} ms  (reference, same run)")
    print(
        f"  ratio dhsym / reference: wall {ours / ref:.2f}, CPU {ours_cpu / ref_cpu:.2f} "
        f"(CPU: dhsym {1000 * ours_cpu:.1f} ms, reference {1000 * ref_cpu:.1f} ms; a loaded "
        "machine stretches the wall time, not the CPU time)"
    )


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--samples", type=int, default=1_000_000)
    p.add_argument("--repeat", type=int, default=5)
    args = p.parse_args()
    q0 = [0.1, -0.4, 0.3, 0.0, 1.2, -0.7]
    qf = [1.0, 0.5, -0.8, 0.9, -0.3, 0.6]
    profile = quintic(q0, qf, 2, v0=[0.1] * 6, vf=[-0.2] * 6)
    t = np.linspace(0.0, 2.0, args.samples)
    t0 = time.perf_counter()
    profile.sample(t[:2])  # the float conversion, once per profile
    first = time.perf_counter() - t0
    coeffs = [np.array([float(c) for c in s[0].coefficients[::-1]]) for s in profile.joints]
    derivs = [(c, np.polyder(c), np.polyder(c, 2)) for c in coeffs]

    def reference() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        q = np.empty((t.size, 6))
        qd = np.empty((t.size, 6))
        qdd = np.empty((t.size, 6))
        for j, (c, d1, d2) in enumerate(derivs):
            q[:, j] = np.polyval(c, t)
            qd[:, j] = np.polyval(d1, t)
            qdd[:, j] = np.polyval(d2, t)
        return q, qd, qdd

    ours, ours_cpu = best(lambda: profile.sample(t), args.repeat)
    ref, ref_cpu = best(reference, args.repeat)
    diff = max(np.abs(a - b).max() for a, b in zip(profile.sample(t), reference()))
    print(f"sample: {args.samples} samples × 6 joints (q, q̇, q̈), best of {args.repeat}")
    verdict = "ok" if ours <= 0.1 else "FAIL"
    print(f"  dhsym Profile.sample   {1000 * ours:8.1f} ms  [{verdict}: ≤ 100 ms]")
    _report("numpy polyval per joint", ours, ours_cpu, ref, ref_cpu)
    print(f"  first call (floats made once) {1000 * first:.1f} ms; largest difference {diff:.1e}")

    ratios = [1.1, 1.3, 1.5, 1.2, 1.7, 1.4]  # of the least speed: each joint its own blend time
    blends = lspb(q0, qf, 2, v=[r * abs(b - a) / 2 for r, a, b in zip(ratios, q0, qf)])
    assert len({s[0].end for s in blends.joints}) == 6
    blends.sample(t[:2])
    pieces = [
        [(float(s.start), [float(c) for c in s.coefficients[::-1]]) for s in segs]
        for segs in blends.joints
    ]

    def lspb_reference() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        out = [np.empty((t.size, 6)) for _ in range(3)]
        for j, segs in enumerate(pieces):
            which = [t <= segs[1][0], t <= segs[2][0], np.ones(t.size, dtype=bool)]
            for k in range(3):
                parts = []
                for start, c in segs:
                    tau = t - start
                    parts.append(np.polyval(np.polyder(c, k) if k else c, tau))
                out[k][:, j] = np.select(which, parts)
        return out[0], out[1], out[2]

    ours_l, ours_l_cpu = best(lambda: blends.sample(t), args.repeat)
    ref_l, ref_l_cpu = best(lspb_reference, args.repeat)
    diff_l = max(np.abs(a - b).max() for a, b in zip(blends.sample(t), lspb_reference()))
    print(f"lspb: {args.samples} samples × 6 joints, blend times differing per joint")
    print(f"  dhsym Profile.sample   {1000 * ours_l:8.1f} ms")
    _report("numpy select per joint", ours_l, ours_l_cpu, ref_l, ref_l_cpu)
    print(f"  largest difference {diff_l:.1e}")
    print(f"  load average {os.getloadavg()[0]:.2f} (uptime's first figure)")
    diff = max(diff, diff_l)
    return 0 if diff < 1e-9 else 1


if __name__ == "__main__":
    sys.exit(main())
