"""The 3D view's page: its size, its first frame and its redraw rate, in headless Chromium.

Run ``python benchmarks/bench_view.py [--robot puma560] [--moves 300]``. It writes the page of
``dhsym view ROBOT`` (with its 4,000-point workspace cloud), opens it from a file in
Debian's Chromium (driven by Playwright, software WebGL: no GPU), and prints

* ``size``: the page's bytes (three.js, the view, the robot and the cloud inlined);
* ``first frame``: milliseconds from the start of the page's navigation to its first drawn
  frame (``performance.now()`` at the first render), the median of ``--repeat`` loads;
* ``redraws``: frames per second while a slider moves, each move waiting for the next
  animation frame (``requestAnimationFrame``), over ``--moves`` moves (a multiple of the
  browser's frame clock: 60, 30, 20 … per second);
* ``work``: the milliseconds of one move when moves follow each other at once, the update
  and the drawing finished (``gl.finish()``): what bounds the rate;
* the reference in the same process: matplotlib redrawing ``robot.plot`` (the static
  picture dhsym drew before) for the same moves, frames per second, and the ratio.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import dhsym  # noqa: E402
from dhsym.view import view_page  # noqa: E402

MOVES = """async (moves) => {
  const input = document.querySelector('input[data-joint="2"]');
  const lo = Number(input.min), hi = Number(input.max);
  const frame = () => new Promise((resolve) => requestAnimationFrame(resolve));
  await frame();
  const t0 = performance.now();
  for (let k = 0; k < moves; k++) {
    input.value = String(lo + ((hi - lo) * k) / moves);
    input.dispatchEvent(new Event("input"));
    await frame();
  }
  return (performance.now() - t0) / moves;
}"""


WORK = """(moves) => {
  const view = window.dhsymView;
  const input = document.querySelector('input[data-joint="2"]');
  const lo = Number(input.min), hi = Number(input.max);
  const gl = view.renderer.getContext();
  const t0 = performance.now();
  for (let k = 0; k < moves; k++) {
    input.value = String(lo + ((hi - lo) * k) / moves);
    input.dispatchEvent(new Event("input"));
    gl.finish();  // the frame drawn, not only queued
  }
  return (performance.now() - t0) / moves;
}"""


def matplotlib_fps(robot: dhsym.Robot, moves: int) -> float:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = robot.plot(np.zeros(len(robot.variables)))
    ax = fig.axes[0]
    t0 = time.perf_counter()
    for k in range(moves):
        q = np.zeros(len(robot.variables))
        q[1] = -2 + 4 * k / moves
        ax.cla()
        robot.plot(q, ax=ax)
        fig.canvas.draw()
    plt.close(fig)
    return moves / (time.perf_counter() - t0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robot", default="puma560")
    parser.add_argument("--moves", type=int, default=300)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    robot = dhsym.load(args.robot)
    html = view_page(robot)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "view.html"
        path.write_text(html, encoding="utf-8")
        with sync_playwright() as p:
            browser = p.chromium.launch(
                executable_path="/usr/bin/chromium",
                args=["--no-sandbox", "--disable-gpu", "--disable-background-networking"],
            )
            firsts = []
            for _ in range(args.repeat):
                page = browser.new_page()
                page.goto(path.as_uri())
                page.wait_for_function("() => window.dhsymView && window.dhsymView.firstFrame")
                firsts.append(page.evaluate("() => window.dhsymView.firstFrame"))
                page.close()
            page = browser.new_page()
            page.goto(path.as_uri())
            page.wait_for_function("() => window.dhsymView && window.dhsymView.firstFrame")
            per_move = page.evaluate(MOVES, args.moves)
            work = page.evaluate(WORK, args.moves)
            browser.close()
    fps = 1000 / per_move
    reference = matplotlib_fps(robot, max(20, args.moves // 10))
    print(f"{robot.name}: the page of dhsym view")
    print(f"  size         {len(html.encode()) / 1e6:.3f} MB")
    print(f"  first frame  {statistics.median(firsts):.0f} ms (median of {args.repeat} loads)")
    print(f"  redraws      {fps:.1f} frames/s while a slider moves ({args.moves} moves)")
    print(f"  work         {work:.1f} ms per move, update and draw finished ({1000 / work:.0f}/s)")
    print(f"  reference    matplotlib robot.plot redrawn: {reference:.1f} frames/s")
    print(f"  ratio        {fps / reference:.1f}x")


if __name__ == "__main__":
    main()
