"""Drawing primitives for :mod:`dhsym.plot.figures`: triads, links, joint glyphs, equal axes.

Everything here draws a :class:`~dhsym.plot.figures.Skeleton` (plain numbers) into a
matplotlib Axes, 3D or a 2D top view; matplotlib itself is imported only inside
the functions that need it. Each triad line carries the gid ``frame:<label>:<axis>``,
which :func:`plotted_frames` reads back.

Examples
--------
>>> import numpy as np
>>> u, v = _basis(np.array([0.0, 0.0, 1.0]))
>>> (u @ v, u @ [0, 0, 1.0]) == (0.0, 0.0)
True
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from dhsym.model.table import JointType

if TYPE_CHECKING:
    from matplotlib.artist import Artist

    from .figures import JointGlyph, Skeleton

__all__ = ["AXIS_COLORS", "SEGMENT_COLORS", "TOL", "draw", "equal_axes", "plotted_frames"]

AXIS_COLORS = ("tab:red", "tab:green", "tab:blue")
SEGMENT_COLORS = {"a": "#d95f02", "d": "#7570b3"}
#: Lengths below this are zero (segments not drawn, no extent).
TOL = 1e-9


def draw(
    ax: Any, sk: Skeleton, dim: int, *, frames: bool, labels: bool, alpha: float = 1.0
) -> np.ndarray:
    """Draw joints, link segments, frame triads, labels and the legend of ``sk`` into ``ax``.

    ``dim`` is 3, or 2 for a top view. Returns the points drawn (rows of 3), for
    :func:`equal_axes`.
    """
    L, pts = sk.scale, [sk.poses[:, :3, 3]]
    P = lambda v: v[:dim]  # noqa: E731 - project to the drawing plane
    for g in sk.joints:
        pts.append(_joint_glyph(ax, g, L, dim, alpha))
    for s in sk.segments:
        if np.linalg.norm(P(s.end - s.start)) < TOL:
            continue  # perpendicular to the page in a top view
        ax.plot(
            *np.column_stack([P(s.start), P(s.end)]),
            color=SEGMENT_COLORS[s.kind],
            lw=4,
            solid_capstyle="round",
            zorder=2,
            alpha=alpha,
        )
        if labels:
            ax.text(
                *P((s.start + s.end) / 2),
                s.label,
                color=SEGMENT_COLORS[s.kind],
                fontsize=9,
                ha="left",
                va="bottom",
                zorder=7,
                bbox={"fc": "white", "ec": "none", "alpha": 0.75, "pad": 1},
            )
    base = sk.poses[0, :3, 3]
    ax.plot(*P(base)[:, None], marker="s", ms=10, color="0.25", zorder=1)
    groups: dict[tuple[float, ...], list[int]] = {}
    for k in range(len(sk.labels)):
        groups.setdefault(tuple(np.round(P(sk.poses[k, :3, 3]), 9)), []).append(k)
    for members in groups.values():
        for rank, k in enumerate(members):
            T, length = sk.poses[k], L * (1.0 - 0.18 * rank)
            if frames:
                pts.append(_triad(ax, T, length, sk.labels[k], dim))
    if labels:
        # origins closer than half a triad share one label (the UR5's {4} {5} {6} {tool}
        # sit within 0.1 m): no two labels are drawn within half a triad of each other
        for members in _label_groups(np.array([P(T[:3, 3]) for T in sk.poses]), 0.5 * L):
            T = sk.poses[members[0]]
            text = " ".join("{" + sk.labels[k] + "}" for k in members)
            ax.text(
                *P(T[:3, 3]),
                text,
                fontsize=10,
                fontweight="bold",
                ha="right",
                va="top",
                zorder=8,
                bbox={"fc": "white", "ec": "0.6", "alpha": 0.85, "pad": 1.5},
                gid="frame label",
            )
    ax.legend(handles=_legend(sk, dim), loc="upper left", fontsize=8, framealpha=0.8)
    return np.vstack([p.reshape(-1, 3) for p in pts])


def _label_groups(points: np.ndarray, gap: float) -> list[list[int]]:
    """The indices of ``points`` in groups: two points closer than ``gap`` are in one group
    (and so, in a chain of such steps, are all between); groups in order of their first
    member.

    >>> _label_groups(np.array([[0, 0], [0.05, 0], [1, 0], [1.08, 0], [3, 0]]), 0.1)
    [[0, 1], [2, 3], [4]]
    """
    parent = list(range(len(points)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(len(points)):
        for j in range(i):
            if np.linalg.norm(points[i] - points[j]) < gap:
                parent[max(root(i), root(j))] = min(root(i), root(j))
    groups: dict[int, list[int]] = {}
    for i in range(len(points)):
        groups.setdefault(root(i), []).append(i)
    return sorted(groups.values())


def _legend(sk: Skeleton, dim: int) -> list[Artist]:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    kinds = {s.kind for s in sk.segments if np.linalg.norm((s.end - s.start)[:dim]) > TOL}
    joints = {g.joint for g in sk.joints}
    handles: list[Artist] = [
        Line2D([], [], color=c, lw=2, label=f"{n} axis")
        for c, n in zip(AXIS_COLORS, "xyz", strict=True)
    ]
    handles += [
        Line2D([], [], color=SEGMENT_COLORS[k], lw=4, label=text)
        for k, text in (("a", "$a$: along x"), ("d", "$d$: along z"))
        if k in kinds
    ]
    if dim == 3 and joints:
        handles.append(Line2D([], [], color="0.4", ls="--", lw=1, label="joint axis"))
    handles += [
        Patch(fc=fc, ec="0.3", label=f"{j.name.lower()} joint")
        for j, fc in ((JointType.REVOLUTE, "lightsteelblue"), (JointType.PRISMATIC, "khaki"))
        if j in joints
    ]
    return handles


def _triad(ax: Any, T: np.ndarray, length: float, label: str, dim: int) -> np.ndarray:
    o = T[:3, 3]
    tips = [o + length * T[:3, j] for j in range(3)]
    for j, (color, tip) in enumerate(zip(AXIS_COLORS, tips, strict=True)):
        gid = f"frame:{label}:{'xyz'[j]}"
        if dim == 3:
            ax.plot(*np.column_stack([o, tip]), color=color, lw=2, gid=gid, zorder=4)
        elif j < 2:
            ax.plot(*np.column_stack([o[:2], tip[:2]]), color=color, lw=2, gid=gid, zorder=4)
        else:  # z out of the page (dot) or into it (cross)
            out = T[2, 2] > 0
            ax.plot(
                *o[:2, None], marker="o", ms=9, mfc="white", mec=color, mew=1.5, gid=gid, zorder=5
            )
            ax.plot(
                *o[:2, None],
                marker="." if out else "x",
                ms=6 if out else 5,
                color=color,
                mew=1.5,
                zorder=6,
            )
    return np.array([o, *tips])


def _basis(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    helper = np.array([1.0, 0, 0]) if abs(axis[0]) < 0.9 else np.array([0, 1.0, 0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    return u, np.cross(axis, u)


def _joint_glyph(ax: Any, g: JointGlyph, L: float, dim: int, alpha: float) -> np.ndarray:
    from matplotlib.patches import Circle, Polygon

    u, v = _basis(g.axis)
    if dim == 2:
        if g.joint is JointType.REVOLUTE:
            ax.add_patch(
                Circle(
                    (g.point[0], g.point[1]),
                    0.16 * L,
                    fc="lightsteelblue",
                    ec="0.3",
                    zorder=3,
                    alpha=alpha,
                )
            )
        else:
            c, a2 = g.point[:2], g.axis[:2]
            if np.linalg.norm(a2) < 0.5:  # slides out of the page: a square
                d, n = np.array([0.14 * L, 0.0]), np.array([0.0, 0.14 * L])
                corners = [c - d - n, c + d - n, c + d + n, c - d + n]
            else:  # a sleeve along the sliding direction
                u2 = a2 / np.linalg.norm(a2)
                d, n = 0.45 * L * u2, 0.12 * L * np.array([-u2[1], u2[0]])
                corners = [c - n, c - n + d, c + n + d, c + n]
            ax.add_patch(Polygon(corners, fc="khaki", ec="0.3", zorder=3, alpha=alpha))
        return np.array([g.point - 0.2 * L, g.point + 0.2 * L])
    ends = [g.point - 1.1 * L * g.axis, g.point + 1.1 * L * g.axis]
    ax.plot(*np.column_stack(ends), color="0.4", ls="--", lw=1, zorder=1)
    if g.joint is JointType.REVOLUTE:
        r, h = 0.13 * L, 0.22 * L
        t, s = np.meshgrid(np.linspace(0, 2 * np.pi, 24), [-h, h])
        surf = (
            g.point[:, None, None]
            + g.axis[:, None, None] * s
            + r * (u[:, None, None] * np.cos(t) + v[:, None, None] * np.sin(t))
        )
        ax.plot_surface(*surf, color="lightsteelblue", alpha=0.7 * alpha, linewidth=0, shade=True)
    else:
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        w, lo, hi = 0.11 * L, -0.15 * L, 0.45 * L
        box = [
            g.point + a * g.axis + w * (su * u + sv * v)
            for a in (lo, hi)
            for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))
        ]
        faces = [[box[0], box[1], box[2], box[3]], [box[4], box[5], box[6], box[7]]] + [
            [box[j], box[(j + 1) % 4], box[4 + (j + 1) % 4], box[4 + j]] for j in range(4)
        ]
        ax.add_collection3d(
            Poly3DCollection(faces, fc="khaki", ec="0.3", alpha=0.8 * alpha, lw=0.5)
        )
    return np.array(ends)


def equal_axes(ax: Any, points: np.ndarray, dim: int, limits: tuple[Any, float] | None) -> None:
    """Equal scales on every axis: a cube around ``points``, or ``(centre, half_width)``."""
    if limits is None:
        lo, hi = points[:, :dim].min(axis=0), points[:, :dim].max(axis=0)
        centre, half = (lo + hi) / 2, max(float((hi - lo).max()) / 2 * 1.12, 1e-3)
    else:
        centre, half = np.asarray(limits[0], float)[:dim], float(limits[1])
    for setter, c in zip(
        (ax.set_xlim, ax.set_ylim, getattr(ax, "set_zlim", None)), centre, strict=False
    ):
        setter(c - half, c + half)
    if dim == 3:
        ax.set_box_aspect((1, 1, 1))
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
    else:
        ax.set_aspect("equal", adjustable="box")
        ax.grid(True, alpha=0.3)
        ax.set_xlabel("x")
        ax.set_ylabel("y")


def plotted_frames(fig: Any) -> dict[str, np.ndarray]:
    """Read the triads back from a figure: label → rows (origin, tip of x, tip of y[, z]).

    Rows have 3 coordinates in a 3D axes and 2 in a 2D one (there z is a marker).
    """
    found: dict[str, dict[str, np.ndarray]] = {}
    for ax in fig.axes:
        for line in ax.get_lines():
            gid = line.get_gid() or ""
            if not gid.startswith("frame:"):
                continue
            _, label, axis = gid.split(":")
            data = line.get_data_3d() if hasattr(line, "get_data_3d") else line.get_data()
            found.setdefault(label, {})[axis] = np.column_stack(data).astype(float)
    out = {}
    for label, axes in found.items():
        rows = [axes["x"][0], axes["x"][-1], axes["y"][-1]]
        if axes["x"].shape[1] == 3:
            rows.append(axes["z"][-1])
        out[label] = np.array(rows)
    return out
