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
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
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


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=5)
    args = p.parse_args()
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
    for axis in ("3 1e-40 7", "1e300 1e-300 1", "0.3 1e-17 0.95"):
        text = urdf(
            joint("j1", "a", "b", body='<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>')
            + joint("j2", "b", "c", body=f'<origin xyz="0.2 0 0.1"/><axis xyz="{axis}"/>')
        )
        t0 = time.process_time()
        import_urdf(text, tip="c")
        print(f"  {f'axis {axis}':20s} {time.process_time() - t0:9.2f} s (process time)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
