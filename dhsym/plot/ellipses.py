r"""The manipulability ellipse: where the tool can move fast, drawn on the arm.

For a unit ball of joint rates ``‖q̇‖ = 1`` the tool's linear velocity ``v = J_v q̇`` fills
the ellipsoid ``vᵀ (J_v J_vᵀ)⁻¹ v = 1`` (Yoshikawa; Spong, Hutchinson and Vidyasagar,
*Robot Modeling and Control*, §4.12): its semi-axes point along the left singular
vectors of ``J_v`` and are as long as its singular values; their product is the
manipulability ``w = sqrt(det(J_v J_vᵀ))``. It flattens as the arm nears a singularity
and collapses to a segment there (the planar 2R stretched out: ``S2 = 0``).

:func:`velocity_ellipse` computes it (numbers from the compiled Jacobian);
:func:`plot_manipulability` draws the arm at one or more configurations with the ellipse
at the tool point (in the plane for a planar arm, an ellipsoid in 3D otherwise).

Examples
--------
>>> import dhsym
>>> e = velocity_ellipse(dhsym.load("planar2r"), [0.0, 1.5707963267948966])
>>> e.axes.round(6), round(e.w, 6)
(array([1.397196, 0.572575]), 0.8)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from dhsym.errors import DHError

from .draw import equal_axes
from .figures import is_planar, joint_values, plot_robot

__all__ = ["VelocityEllipse", "plot_manipulability", "velocity_ellipse"]


@dataclass(frozen=True, eq=False)
class VelocityEllipse:
    """The velocity ellipse (ellipsoid) of the tool at one configuration.

    ``centre`` is the tool point, ``directions`` the unit semi-axes (columns), ``axes``
    their lengths (the singular values of ``J_v``, largest first) and ``w`` the
    manipulability ``sqrt(det(J_v J_vᵀ))`` over the ``dim`` rows used.
    """

    centre: np.ndarray
    directions: np.ndarray
    axes: np.ndarray
    w: float
    dim: int


def velocity_ellipse(
    robot: Any, q: object, *, deg: bool = False, dim: int | None = None
) -> VelocityEllipse:
    """The ellipse of ``robot`` at ``q``: ``dim`` is 2 (the x, y rows: a planar arm) or 3.

    Without ``dim`` a planar arm (every z axis vertical) gets 2, any other arm 3.
    """
    qv = joint_values(robot, q, deg=deg)
    if dim is None:
        dim = 2 if is_planar(robot, qv) else 3
    if dim not in (2, 3):
        raise DHError(f"the velocity ellipse is drawn in 2 or 3 dimensions, not {dim}")
    J = robot.jacob0(qv)[:dim]
    U, sv, _ = np.linalg.svd(J)
    axes = np.zeros(dim)
    axes[: len(sv)] = sv[:dim]
    centre = np.asarray(robot.fk(qv), dtype=float)[:3, 3]
    w = float(np.prod(axes))  # = sqrt(det(J Jᵀ)), without the round-off of the square root
    return VelocityEllipse(centre, U[:, :dim], axes, w, dim)


def _ellipse_points(e: VelocityEllipse, scale: float, n: int = 60) -> np.ndarray:
    """Points of the ellipse (``(n, 2)``) or of a wireframe of the ellipsoid (``(n, n, 3)``)."""
    M = e.directions * (e.axes * scale)
    if e.dim == 2:
        t = np.linspace(0.0, 2 * np.pi, n)
        ring: np.ndarray = e.centre[:2] + (M @ np.vstack([np.cos(t), np.sin(t)])).T
        return ring
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, n), np.linspace(0, np.pi, n // 2))
    ball = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)], axis=-1)
    surface: np.ndarray = e.centre + ball @ M.T
    return surface


def plot_manipulability(
    robot: Any,
    q: object,
    *,
    ax: Any = None,
    deg: bool = False,
    scale: float | None = None,
    title: str | None = None,
) -> Any:
    """Draw the arm at ``q`` (or at each row of a ``(k, n)`` array) with its velocity ellipse.

    Every ellipse uses one ``scale`` (drawn length per unit of speed; default: the longest
    semi-axis is a quarter of the arm's reach) so that they compare; each is labelled with
    its manipulability ``w``. Returns the matplotlib ``Figure``.

    Parameters
    ----------
    robot
        A :class:`~dhsym.kinematics.chain.KinematicChain`.
    q
        One configuration ``(n,)`` or several ``(k, n)`` (degrees for revolute joints
        with ``deg=True``).
    ax
        Draw into this Axes (2D for a planar arm, else 3D) instead of a new figure.
    scale
        Drawn length of a unit velocity.
    title
        The title (default: the robot's name and the manipulability measure).
    """
    from matplotlib.figure import Figure

    qs = np.atleast_2d(np.asarray(q, dtype=float))
    ellipses = [velocity_ellipse(robot, row, deg=deg) for row in qs]
    dim = ellipses[0].dim
    if ax is None:
        fig = Figure(figsize=(6.4, 6.0), layout="constrained")
        ax = fig.add_subplot(projection="3d" if dim == 3 else None)
    elif (getattr(ax, "name", "") == "3d") != (dim == 3):
        raise DHError(f"{robot.name} needs a {'3D' if dim == 3 else '2D'} axes for its ellipse")
    reach = max(float(np.linalg.norm(e.centre)) for e in ellipses) or 1.0
    biggest = max(float(e.axes.max()) for e in ellipses)
    if scale is None:
        scale = 0.25 * reach / biggest if biggest > 0 else 1.0
    colours = ["tab:red", "tab:purple", "tab:green", "tab:orange", "tab:brown", "tab:cyan"]
    points = []
    for k, (row, e) in enumerate(zip(qs, ellipses, strict=True)):
        plot_robot(robot, row, ax=ax, deg=deg, frames=k == len(qs) - 1, labels=False, title="")
        pts = _ellipse_points(e, scale)
        colour = colours[k % len(colours)]
        label = f"w = {e.w:.3g}"
        if dim == 2:
            ax.plot(*pts.T, color=colour, lw=2, label=label, gid=f"ellipse:{k}", zorder=9)
        else:
            ax.plot_wireframe(
                *np.moveaxis(pts, -1, 0),
                color=colour,
                lw=0.5,
                alpha=0.6,
                label=label,
                gid=f"ellipse:{k}",
            )
        points.append(pts.reshape(-1, dim))
        points.append(np.asarray(robot.fk(joint_values(robot, row, deg=deg)))[None, :dim, 3])
    points.append(np.zeros((1, dim)))
    allp = np.vstack(points)
    pad = np.vstack([allp, allp.min(0) - 0.05 * reach, allp.max(0) + 0.05 * reach])
    equal_axes(ax, np.pad(pad, ((0, 0), (0, 3 - dim))), dim, None)
    ax.legend(loc="upper left", fontsize=8)
    default = (
        f"{robot.name}: velocity ellipse of the tool\n"
        f"semi-axes = singular values of J_v (drawn × {scale:.3g}), w = sqrt(det(J_v J_vᵀ))"
    )
    ax.set_title(default if title is None else title, fontsize=10)
    return ax.figure
