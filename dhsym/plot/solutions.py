"""Every inverse-kinematics solution of one pose, drawn side by side (matplotlib).

:func:`plot_solutions` takes the solutions of :meth:`~dhsym.robot.Robot.ik`
(an :class:`~dhsym.ik.solution.IKSolution`, or a ``(k, n)`` array with names) and
draws the arm in each, one panel per solution titled with its branch (left/right arm,
elbow up/down, wrist flipped or not), all with one view so that they compare, and the
target pose's frame marked in every panel.

Examples
--------
>>> import dhsym, matplotlib
>>> matplotlib.use("Agg")
>>> r = dhsym.load("planar2r")
>>> fig = plot_solutions(r, r.ik(r.fk([0.3, 0.9])[:3, 3]))
>>> [ax.get_title() for ax in fig.axes]
['elbow down', 'elbow up']
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from dhsym.errors import DHError

from .figures import is_planar, plot_robot, view_limits

__all__ = ["plot_solutions"]


def plot_solutions(
    robot: Any,
    solutions: Any,
    *,
    names: Sequence[str] | None = None,
    columns: int = 4,
    view: str | None = None,
    frames: bool = False,
    title: str | None = None,
) -> Any:
    """Draw each solution in its own panel; returns the matplotlib ``Figure``.

    Parameters
    ----------
    robot
        A :class:`~dhsym.kinematics.chain.KinematicChain`.
    solutions
        What ``robot.ik(T)`` returns for one pose, or a ``(k, n)`` array of joint values.
    names
        Panel titles (default: the branch names of an ``IKSolution``, else ``q1 … qk``).
    columns
        Panels per row.
    view
        ``'3d'`` or ``'2d'`` (default: 2D for a planar arm, else 3D).
    frames
        Draw every DH frame (default: only the base and the tool frame).
    title
        The figure's title (default: the robot's name and the number of solutions).
    """
    from matplotlib.figure import Figure

    q = np.atleast_2d(np.asarray(getattr(solutions, "q", solutions), dtype=float))
    if q.size == 0 or q.shape[1] != len(robot.variables):
        raise DHError(
            f"{robot.name} needs solutions of {len(robot.variables)} joint values, got "
            f"shape {q.shape}"
        )
    k = len(q)
    if names is None:
        names = getattr(solutions, "branches", None) or [f"q{i + 1}" for i in range(k)]
    if len(names) != k:
        raise DHError(f"{k} solutions need {k} names, got {len(names)}")
    if view is None:
        view = "2d" if is_planar(robot) else "3d"
    cols = max(1, min(columns, k))
    rows = math.ceil(k / cols)
    fig = Figure(figsize=(3.4 * cols, 3.3 * rows + 0.5), layout="constrained")
    limits = view_limits(robot, q, dim=3 if view == "3d" else 2)
    for i, (row, name) in enumerate(zip(q, names, strict=True)):
        ax = fig.add_subplot(rows, cols, i + 1, projection="3d" if view == "3d" else None)
        plot_robot(robot, row, ax=ax, frames=frames, labels=False, limits=limits, title="")
        if not frames:
            _tool_frame(robot, row, ax, view, limits[1])
        ax.set_title(name, fontsize=9)
        legend = ax.get_legend()
        if legend is not None:
            legend.remove()
    fig.suptitle(
        f"{robot.name}: {k} solution{'s' * (k != 1)} for one pose" if title is None else title,
        fontsize=12,
    )
    return fig


def _tool_frame(robot: Any, q: np.ndarray, ax: Any, view: str, half: float) -> None:
    """The tool frame's triad (the pose every panel reaches)."""
    T = np.asarray(robot.fk(q), dtype=float)
    dim = 3 if view == "3d" else 2
    length = 0.25 * half
    for axis, colour in zip("xyz"[:dim], ("tab:red", "tab:green", "tab:blue"), strict=False):
        j = "xyz".index(axis)
        ends = np.column_stack([T[:3, 3], T[:3, 3] + length * T[:3, j]])[:dim]
        ax.plot(*ends, color=colour, lw=2, gid=f"tool:{axis}")
