"""Animate the arm along a joint-space path (IRob2305 Lecture 5: "We can animate a path").

The file type follows the writers that exist: a ``.gif`` with matplotlib's
``PillowWriter`` (Pillow comes with matplotlib), an ``.mp4`` with
``FFMpegWriter`` when ``ffmpeg`` is installed; otherwise, or for any other
name, a folder of numbered PNG frames (a "frame strip").

Examples
--------
>>> joint_path([0, 0], [90, 45], 4)
array([[ 0.,  0.],
       [30., 15.],
       [60., 30.],
       [90., 45.]])
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from dhsym.errors import DHError

__all__ = ["animate_path", "joint_path"]


def joint_path(q0: object, q1: object, steps: int) -> np.ndarray:
    """``steps`` configurations from ``q0`` to ``q1`` (both included), straight in joint space."""
    a, b = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
    if a.shape != b.shape or a.ndim != 1:
        raise DHError(
            f"q0 and q1 must be two joint vectors of one length, got {a.shape}, {b.shape}"
        )
    if steps < 2:
        raise DHError(f"a path needs at least 2 steps, got {steps}")
    path: np.ndarray = a + np.linspace(0.0, 1.0, steps)[:, None] * (b - a)
    return path


def _writer(suffix: str, fps: int) -> Any:
    from matplotlib import animation

    if suffix == ".gif" and animation.writers.is_available("pillow"):
        return animation.PillowWriter(fps=fps)
    if suffix == ".mp4" and animation.writers.is_available("ffmpeg"):
        return animation.FFMpegWriter(fps=fps)
    return None


def animate_path(
    robot: Any,
    qs: object,
    path: str | Path,
    *,
    fps: int = 10,
    deg: bool = False,
    view: str = "3d",
    dpi: int = 80,
    **plot_kw: Any,
) -> Path:
    """Draw ``robot`` at each configuration of ``qs`` ``(N, n)`` and save the frames.

    Returns what was written: ``path`` itself (GIF/MP4), or a folder
    ``path`` without its suffix holding ``frame_000.png`` … when no writer
    for that suffix exists. The view stays fixed over the whole path.
    ``plot_kw`` go to :func:`~dhsym.plot.figures.plot_robot`.
    """
    from matplotlib.figure import Figure

    from .figures import joint_values, plot_robot, view_limits

    Q = np.atleast_2d(np.asarray(qs, dtype=float))
    if Q.shape[0] < 1:
        raise DHError("the path has no configurations")
    Q = np.stack([joint_values(robot, q, deg=deg) for q in Q])
    limits = view_limits(robot, Q, dim=3 if view == "3d" else 2)
    fig = Figure(figsize=(5.6, 5.2), layout="constrained")
    ax = fig.add_subplot(projection="3d" if view == "3d" else None)
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)

    def draw(q: np.ndarray) -> None:
        ax.clear()
        plot_robot(robot, q, ax=ax, limits=limits, **plot_kw)

    writer = _writer(out.suffix.lower(), fps)
    if writer is None:
        folder = out.with_suffix("") if out.suffix else out
        folder.mkdir(parents=True, exist_ok=True)
        for k, q in enumerate(Q):
            draw(q)
            fig.savefig(folder / f"frame_{k:03d}.png", dpi=dpi)
        return folder
    with writer.saving(fig, str(out), dpi):
        for q in Q:
            draw(q)
            writer.grab_frame()
    return out
