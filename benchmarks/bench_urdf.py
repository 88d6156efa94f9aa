"""Reading a 7-joint URDF (the Franka Panda) as a DH table, against parsing its XML alone.

Run ``python benchmarks/bench_urdf.py``. In one process it times, as the median of
``--repeat`` runs each (after one warm-up):

* ``xml``: the standard library's ``xml.etree.ElementTree.fromstring`` on the file text
  (the reference: the least any URDF reader does);
* ``safe``: dhsym's safe XML reader (defusedxml with DTD/entities refused, depth and size
  limits);
* ``model``: the URDF model with exact numbers (``read_urdf``);
* ``table``: the whole import, standard and modified (``import_urdf``: chain, exact home
  geometry, the frame assignment with its sentences and its check at 6 configurations);
* ``fk``: the robot's first ``fk`` (compiling the closed form), then one call;
* ``hostile``: refusing an entity bomb, a 1,000,000-deep document and 60,000 elements;
* ``chain``: plain chains of 30 and 100 revolute joints (``MAX_CHAIN`` is 100), axes
  alternating z and y, every third origin turned by π/2, each imported once (process
  time, after the warm-up import of a 3-joint chain, in the same process);
* ``axis``: two-joint URDFs whose second axis is a measured direction that once ran for
  minutes in sympy's ``factorint`` (``3 1e-40 7``, ``1e300 1e-300 1``, ``0.3 1e-17 0.95``).

It prints each time and its ratio to ``xml``, and the largest difference between ``fk``
and an independent numpy product of the URDF's origins and axes at 100 random q.

``--cli`` times instead what a student's shell runs: ``dhsym convert X.urdf --to
standard`` and ``dhsym show X.urdf``, each a fresh process with an empty cache folder of
its own (cold), for the campaign's hostile files (the three measured axes; plain chains
of 20, 30 and 100 joints) and every file in ``tests/data/urdf``, interleaved with the
reference ``python -c "import sympy"`` (``bench_cli``'s timing and table: median wall and
CPU seconds, each as a ratio to the reference's, ``--runs`` rounds).

Figures measured on the shared 2-core machine, CPU seconds of the whole fresh process
(start-up included; ``dhsym list`` alone is 0.9 s), cold. Before: a script timing each
command once at load average 8–10 (commit 57dedda); after: ``--cli --runs 1`` at load
average 11.7–12.1, reference ``import sympy`` 0.50 s (CPU times swell by a tenth or two
under such load)::

    file                     convert before -> after   show before -> after
    axis 3 1e-40 7           1.09 -> 1.13 (2.3x)       1.12 -> 1.07 (2.2x)
    axis 1e300 1e-300 1      1.11 -> 0.97 (2.0x)       1.14 -> 1.07 (2.2x)
    axis 0.3 1e-17 0.95      1.17 -> 1.27 (2.6x)       1.14 -> 1.27 (2.5x)
    chain of 20 joints       1.66 -> 2.14 (4.3x)       1.13 -> 1.27 (2.6x)
    chain of 30 joints       1.98 -> 2.30 (4.6x)       1.23 -> 1.27 (2.6x)
    chain of 100 joints      5.71 -> 5.23 (10.5x)      2.45 -> 2.36 (4.8x)
    UR5                      1.33 -> 1.16 (2.3x)       1.14 -> 1.19 (2.4x)
    Panda                    2.30 -> 1.77 (3.6x)       1.35 -> 1.37 (2.8x)
    Kinova                   1.51 -> 1.22 (2.5x)       1.12 -> 1.21 (2.4x)
    SO-ARM100                1.50 -> 1.33 (2.7x)       1.33 -> 1.37 (2.8x)

(ratios to ``import sympy`` in the same run). The measured axes were no longer slow at
57dedda (exact rational unit vectors of bounded size; the 16–20 s of ``factorint`` were
gone). In one warm process ``import_urdf`` of the 100-joint chain takes 0.9–1.3 s
(was 1.3–1.7 s) and the check of the chosen table 0.14 s (was 0.55 s; the Panda's 0.03 s,
was 0.83 s: it derived two 7-joint closed forms). What keeps ``convert`` of long chains
over 2 s is the table file's writer (``model.tablefile.dump_table``, outside this room):
``nsimplify`` of each revolute limit in degrees (−180/π for −1 rad), about 14 ms a limit,
2.75 s for the 200 limits of the 100-joint chain, 0.56 s for the 20-joint one.

Issue 32 ("any URDF within the stated limits converts in ≤ 2 s"), ``--cli --runs 1`` at
load average 12–15, before at ce2a4e5 and after (reference ``import sympy`` 0.53–0.56 s
CPU; CPU seconds, ratio to it in the same run)::

    file                     convert before -> after        show before -> after
    chain of 20 joints       1.33 (2.39x) -> 1.09 (2.05x)    1.10 (1.98x) -> 0.95 (1.79x)
    chain of 30 joints       1.17 (2.10x) -> 1.03 (1.93x)    1.23 (2.21x) -> 0.95 (1.78x)
    chain of 100 joints      2.48 (4.46x) -> 1.47 (2.78x)    2.10 (3.77x) -> 1.23 (2.32x)
    Panda                    1.61 (2.90x) -> 1.18 (2.22x)    1.60 (2.88x) -> 1.18 (2.22x)
    SO-ARM100                1.35 (2.43x) -> 1.23 (2.31x)    1.47 (2.64x) -> 1.30 (2.45x)

What the frame assignment of the 100-joint chain spent (cProfile, ``import_urdf`` in one
process): sympy's ``Matrix.dot`` and ``cross`` on 3-vectors (each converted to a domain
matrix first; now entry by entry for rationals, the same exact numbers), iterating sympy
matrices entry by entry (now read from an immutable matrix's ``args``), each frame's 4×4
matrix built again for every check (now once a frame), each URDF origin's transform built
twice and by five 4×4 products (now once, only its rotations multiplied), and the exact
home check converting 400 factors to domain matrices (now each distinct factor once).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from dhsym.errors import FormatError  # noqa: E402
from dhsym.formats.urdf import import_urdf, read_urdf  # noqa: E402
from dhsym.formats.xmlsafe import read_xml  # noqa: E402
from tests.formats.urdf.support import joint, urdf, urdf_pose  # noqa: E402
from tests.formats.urdf.test_to_dh import plain_chain  # noqa: E402

sys.path.insert(0, str(ROOT / "benchmarks"))
from bench_cli import report, run_timed  # noqa: E402

PANDA = ROOT / "tests" / "data" / "urdf" / "panda.urdf"
TIP = "panda_hand"


def median_time(fn: Callable[[], object], repeat: int) -> float:
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def refuse(text: str) -> None:
    try:
        read_xml(text)
    except FormatError:
        return
    raise AssertionError("not refused")


HOSTILE_AXES = {
    "axis-tiny": "3 1e-40 7",
    "axis-huge": "1e300 1e-300 1",
    "axis-skew": "0.3 1e-17 0.95",
}
DATA_TIPS = {
    "ur5_robot": "tool0",
    "panda": "panda_hand",
    "kinova": "j2s6s200_end_effector",
    "so100": "gripper",
}


def two_joints(axis: str) -> str:
    """Joint 1 about z, joint 2 above it about ``axis`` as written (tip link ``c``)."""
    return urdf(
        joint("j1", "a", "b", body='<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>')
        + joint("j2", "b", "c", body=f'<origin xyz="0.2 0 0.1"/><axis xyz="{axis}"/>')
    )


def cli_files(folder: Path) -> dict[str, tuple[Path, str]]:
    """The campaign's hostile URDFs written into ``folder``, then the test data: name ->
    (file, tip link)."""
    files: dict[str, tuple[Path, str]] = {}
    for name, axis in HOSTILE_AXES.items():
        files[name] = (folder / f"{name}.urdf", "c")
        files[name][0].write_text(two_joints(axis))
    for n in (20, 30, 100):
        files[f"chain-{n}"] = (folder / f"chain{n}.urdf", f"l{n}")
        files[f"chain-{n}"][0].write_text(plain_chain(n))
    for stem, tip in DATA_TIPS.items():
        files[stem] = (PANDA.parent / f"{stem}.urdf", tip)
    return files


def cli(runs: int) -> None:
    """Fresh processes, cold: ``dhsym convert`` and ``dhsym show`` of each file."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        cmds = {'python -c "import sympy"': ["-c", "import sympy"]}
        for name, (path, tip) in cli_files(folder).items():
            cmds[f"convert {name}"] = [
                "-m",
                "dhsym",
                "convert",
                str(path),
                "--to",
                "standard",
                "--tip",
                tip,
                "-o",
                "-",
            ]
            cmds[f"show {name}"] = ["-m", "dhsym", "show", str(path), "--tip", tip]
        wall: dict[str, list[float]] = {}
        cpu: dict[str, list[float]] = {}
        load = os.getloadavg()
        for _ in range(runs):
            for name, args in cmds.items():
                w, c = run_timed(sys.executable, args, tmp)
                wall.setdefault(name, []).append(w)
                cpu.setdefault(name, []).append(c)
        report("fresh process, empty cache", list(cmds), wall, cpu)
        print(f"load average {load[0]:.1f} before, {os.getloadavg()[0]:.1f} after")


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--cli", action="store_true", help="fresh-process convert and show instead")
    p.add_argument("--runs", type=int, default=3, help="rounds of --cli")
    args = p.parse_args()
    if args.cli:
        cli(args.runs)
        return 0
    text = PANDA.read_text()
    bomb = (
        '<!DOCTYPE r [<!ENTITY a "aaaaaaaaaa">'
        + "".join(f'<!ENTITY {c} "{("&" + p + ";") * 10}">' for p, c in zip("abcdefgh", "bcdefghi"))
        + ']><robot name="&i;"/>'
    )
    deep = "<robot>" + "<b>" * 1_000_000 + "</b>" * 1_000_000 + "</robot>"
    many = "<robot>" + "<link/>" * 60_000 + "</robot>"
    rows = [
        ("xml", lambda: ET.fromstring(text)),
        ("safe", lambda: read_xml(text)),
        ("model", lambda: read_urdf(text)),
        ("table standard", lambda: import_urdf(text, tip=TIP)),
        ("table modified", lambda: import_urdf(text, tip=TIP, convention="modified")),
        ("refuse bomb", lambda: refuse(bomb)),
        ("refuse deep", lambda: refuse(deep)),
        ("refuse 60k elements", lambda: refuse(many)),
    ]
    reference = median_time(rows[0][1], args.repeat)
    print(f"{PANDA.name}: {len(text)} bytes, 7 moving joints (tip {TIP}), median of {args.repeat}")
    for name, fn in rows:
        t = median_time(fn, args.repeat)
        print(f"  {name:20s} {1000 * t:9.2f} ms   {t / reference:8.0f} x xml")
    robot = import_urdf(text, tip=TIP).chain()
    t0 = time.perf_counter()
    robot.fk(np.zeros(7))
    first = time.perf_counter() - t0
    t = median_time(lambda: robot.fk(np.ones(7)), max(args.repeat, 100))
    print(f"  {'fk first call':20s} {1000 * first:9.2f} ms   (compiles the closed form)")
    print(f"  {'fk one call':20s} {1e6 * t:9.2f} us")
    rng = np.random.default_rng(0)
    worst = max(
        float(np.abs(robot.fk(q) - urdf_pose(PANDA, TIP, q)).max())
        for q in rng.uniform(-math.pi, math.pi, (100, 7))
    )
    print(f"  fk vs numpy product of the URDF at 100 random q: max difference {worst:.1e}")
    import_urdf(plain_chain(3), tip="l3")  # warm-up
    for n in (30, 100):
        t0 = time.process_time()
        import_urdf(plain_chain(n), tip=f"l{n}")
        print(f"  {f'chain of {n} joints':20s} {time.process_time() - t0:9.2f} s (process time)")
    for axis in HOSTILE_AXES.values():
        text = two_joints(axis)
        t0 = time.process_time()
        import_urdf(text, tip="c")
        print(f"  {f'axis {axis}':20s} {time.process_time() - t0:9.2f} s (process time)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
