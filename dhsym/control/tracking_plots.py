"""Pictures of a simulated closed loop: the tracking error and the joint torques against
time (matplotlib, imported only when drawing).

Each function takes one :class:`~dhsym.control.simulation.ClosedLoop` or several by
name (``{"PD": run, "computed torque": run2}``, the laws compared on one motion) and
draws one line per run and joint into a new figure or into ``ax``; the lines are
labelled ``"joint k"``, ``"<name>"`` or ``"<name>, joint k"``, and their data are the
run's own arrays.

Examples
--------
>>> import numpy as np
>>> from dhsym.control.simulation import ClosedLoop
>>> t = np.linspace(0, 1, 5)
>>> z = np.zeros((5, 2))
>>> run = ClosedLoop(t, z, z, z + [[0.1, -0.2]], z, z, z + [[1.0, 2.0]], z)
>>> fig = plot_tracking_error(run)
>>> [line.get_label() for line in fig.axes[0].get_lines()]
['joint 1', 'joint 2']
>>> fig = plot_torques({"PD": run, "PID": run}, joints=[2])
>>> [line.get_label() for line in fig.axes[0].get_lines()]
['PD', 'PID']
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from dhsym.errors import DHError

from .simulation import ClosedLoop

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_torques", "plot_tracking_error"]


def _runs(runs: ClosedLoop | Mapping[str, ClosedLoop]) -> dict[str, ClosedLoop]:
    """The runs by name (one run has the name ``""``)."""
    if isinstance(runs, ClosedLoop):
        return {"": runs}
    named = dict(runs)
    if not named or not all(isinstance(r, ClosedLoop) for r in named.values()):
        raise DHError("plot: give a ClosedLoop (simulate's result) or a mapping name → ClosedLoop")
    return named


def _joints(joints: Sequence[int] | None, n: int) -> list[int]:
    """The joints to draw, 1-based (all by default)."""
    chosen = list(range(1, n + 1)) if joints is None else [int(j) for j in joints]
    bad = [j for j in chosen if not 1 <= j <= n]
    if bad or not chosen:
        raise DHError(f"plot: joints are numbered 1 … {n}, got {list(joints or [])}")
    return chosen


def _label(name: str, joint: int | None, several: bool) -> str:
    if joint is None:
        return name
    if not name:
        return f"joint {joint}"
    return f"{name}, joint {joint}" if several else name


def _axes(ax: Any) -> tuple[Figure, Any]:
    if ax is not None:
        return ax.figure, ax
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 3.6), layout="constrained")
    return fig, fig.add_subplot()


def _draw(
    runs: dict[str, ClosedLoop],
    values: str,
    joints: Sequence[int] | None,
    ax: Any,
) -> tuple[Figure, Any]:
    fig, axes = _axes(ax)
    for name, run in runs.items():
        data = getattr(run, values)
        chosen = _joints(joints, data.shape[1])
        for j in chosen:
            axes.plot(run.t, data[:, j - 1], label=_label(name, j, len(chosen) > 1))
    axes.set_xlabel("t (s)")
    return fig, axes


def plot_tracking_error(
    runs: ClosedLoop | Mapping[str, ClosedLoop],
    *,
    joints: Sequence[int] | None = None,
    largest: bool = False,
    log: bool = False,
    ax: Any = None,
) -> Figure:
    """The tracking error ``e = q_ref − q`` against time; returns the ``Figure``.

    Parameters
    ----------
    runs
        A :class:`~dhsym.control.simulation.ClosedLoop` or several by name.
    joints
        The joints to draw (1-based; all by default): one line per run and joint.
    largest
        Instead, one line per run: the largest ``|e|`` over the joints at each time.
    log
        A logarithmic error axis (for errors from rounding to radians).
    ax
        Draw into this Axes instead of a new figure.
    """
    named = _runs(runs)
    if largest:
        fig, axes = _axes(ax)
        for name, run in named.items():
            axes.plot(run.t, np.abs(run.error).max(axis=1), label=name or "largest |e|")
        axes.set_xlabel("t (s)")
        axes.set_ylabel("largest |e| (rad or m)")
    else:
        fig, axes = _draw(named, "error", joints, ax)
        axes.set_ylabel("e = q_ref − q (rad or m)")
    if log:
        axes.set_yscale("log")
    axes.set_title("tracking error")
    if len(named) > 1 or not largest:
        axes.legend()
    return fig


def plot_torques(
    runs: ClosedLoop | Mapping[str, ClosedLoop],
    *,
    joints: Sequence[int] | None = None,
    ax: Any = None,
) -> Figure:
    """The controller's joint torques (forces for prismatic joints) against time, one
    line per run and joint (``joints`` 1-based, all by default); returns the ``Figure``.
    """
    named = _runs(runs)
    fig, axes = _draw(named, "tau", joints, ax)
    axes.set_ylabel("τ (N m or N)")
    chosen = _joints(joints, next(iter(named.values())).tau.shape[1])
    axes.set_title(f"torque of joint {chosen[0]}" if len(chosen) == 1 else "joint torques")
    axes.legend()
    return fig
