"""Pictures of a robot with its DH frames (matplotlib, imported only when drawing).

The geometry is computed first, as plain numbers (:func:`skeleton`): every frame
``{0} … {n}`` (plus ``{W}`` and ``{tool}`` when the table has base and tool
transforms) from the compiled ``^0T_k`` of
:meth:`~dhsym.kinematics.chain.KinematicChain.fk_function`, and each row's ``d`` and ``a``
segments where its convention puts them:

* standard: from ``O_{i-1}`` along ``z_{i-1}`` by ``d_i``, then along ``x_i`` by ``a_i``;
* modified: from ``O_{i-1}`` along ``x_{i-1}`` by ``a_{i-1}``, then along ``z_i`` by ``d_i``.

:func:`plot_robot` then draws it: x red, y green, z blue; joint axes dashed,
revolute joints as cylinders (discs in 2D), prismatic joints as boxes.
:func:`plotted_frames` reads the triads back from a figure (for tests).

Examples
--------
>>> import dhsym
>>> frame_origins(dhsym.load("planar2r"), [90, 0], deg=True).round(6) + 0.0
array([[0. , 0. , 0. ],
       [0. , 1. , 0. ],
       [0. , 1.8, 0. ]])
>>> [(s.kind, s.label) for s in skeleton(dhsym.load("planar2r")).segments]
[('a', '$a_{1} = 1$'), ('a', '$a_{2} = 0.8$')]
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError, GeometryError
from dhsym.model.table import Convention, JointType

from .draw import TOL as _TOL
from .draw import draw, equal_axes, plotted_frames

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "JointGlyph",
    "Segment",
    "Skeleton",
    "frame_origins",
    "is_planar",
    "joint_values",
    "plot_robot",
    "plot_workspace",
    "plotted_frames",
    "skeleton",
    "view_limits",
    "workspace_points",
]


@dataclass(frozen=True, eq=False)
class Segment:
    """One constant-direction piece of a link: ``kind`` 'a' (along x) or 'd' (along z)."""

    kind: str
    start: np.ndarray
    end: np.ndarray
    label: str


@dataclass(frozen=True, eq=False)
class JointGlyph:
    """Where joint ``index`` is drawn: a point on its axis and the axis direction."""

    index: int
    joint: JointType
    point: np.ndarray
    axis: np.ndarray


@dataclass(frozen=True, eq=False)
class Skeleton:
    """Everything a picture shows, in the plot's coordinates (world if there is a base)."""

    labels: tuple[str, ...]
    poses: np.ndarray
    segments: tuple[Segment, ...]
    joints: tuple[JointGlyph, ...]
    scale: float


def joint_values(robot: Any, q: object = None, *, deg: bool = False) -> np.ndarray:
    """The configuration as floats in radians (``None``: all joint variables zero).

    >>> import dhsym
    >>> joint_values(dhsym.load("example1_rrp"), [90, 0, 0.1], deg=True).round(4)
    array([1.5708, 0.    , 0.1   ])
    """
    n = len(robot.variables)
    arr = np.zeros(n) if q is None else np.array(q, dtype=float).reshape(-1)
    if arr.shape != (n,) or not np.all(np.isfinite(arr)):
        raise DHError(f"{robot.name} needs {n} finite joint values, got {arr.tolist()}")
    if deg:
        rows = [robot.table.rows[i - 1] for i in robot.table.joint_rows]
        arr[[r.joint is JointType.REVOLUTE for r in rows]] *= math.pi / 180.0
    return arr


def _frame_range(robot: Any) -> tuple[int, list[int], list[str]]:
    first = -1 if robot.table.base else 0
    ks = list(range(first, robot.n + 1)) + ([robot.n + 1] if robot.table.tool else [])
    names = {-1: "W", robot.n + 1: "tool"}
    return first, ks, [names.get(k, str(k)) for k in ks]


_LONG_CHAIN = 12  # frames; beyond, ^0T_k is built up link by link (numbers, not closed forms)


def _poses(robot: Any, qv: np.ndarray) -> tuple[np.ndarray, list[str]]:
    first, ks, labels = _frame_range(robot)
    if len(ks) <= _LONG_CHAIN:
        return np.stack([robot.fk_function(first, k)(qv) for k in ks]), labels
    from dhsym.kinematics.numeric import compile_word
    from dhsym.kinematics.transforms import chain_word

    words = [chain_word(robot.table, a, b) for a, b in zip(ks, ks[1:])]
    ends = np.cumsum([0] + [len(w) for w in words])  # where each frame's prefix ends
    prefixes = compile_word(
        [e for w in words for e in w], robot.variables, robot.table.value_map, prefixes=True
    )
    return prefixes(qv)[ends], labels


def frame_origins(robot: Any, q: object = None, *, deg: bool = False) -> np.ndarray:
    """Origins of the DH frames 0 … n, shape ``(n + 1, 3)``, in the plot's coordinates.

    Without a base transform these are the columns ``p`` of ``^0T_k``; with one,
    of ``^WT_k`` (the world frame the picture is drawn in).
    """
    poses, labels = _poses(robot, joint_values(robot, q, deg=deg))
    keep = [i for i, lab in enumerate(labels) if lab not in ("W", "tool")]
    return poses[keep, :3, 3]


def _name(kind: str, index: int, value: float) -> str:
    return f"${sp.latex(sp.Symbol(f'{kind}_{index}'))} = {value:.3g}$"


def skeleton(
    robot: Any, q: object = None, *, deg: bool = False, scale: float | None = None
) -> Skeleton:
    """Frames, link segments and joint glyphs of ``robot`` at ``q`` (numbers only)."""
    poses, labels = _poses(robot, joint_values(robot, q, deg=deg))
    at = {lab: i for i, lab in enumerate(labels)}
    modified = robot.convention is Convention.MODIFIED
    segments: list[Segment] = []
    joints: list[JointGlyph] = []
    for i, row in enumerate(robot.table.rows, start=1):
        prev, cur = poses[at[str(i - 1)]], poses[at[str(i)]]
        o0, o1 = prev[:3, 3], cur[:3, 3]
        if modified:
            x = prev[:3, 0]
            a = float(np.dot(o1 - o0, x))
            mid = o0 + a * x
            pieces = [
                ("a", o0, mid, i - 1, a),
                ("d", mid, o1, i, float(np.dot(o1 - mid, cur[:3, 2]))),
            ]
            axis, point = cur[:3, 2], (mid if row.joint is JointType.PRISMATIC else o1)
        else:
            z = prev[:3, 2]
            d = float(np.dot(o1 - o0, z))
            mid = o0 + d * z
            pieces = [("d", o0, mid, i, d), ("a", mid, o1, i, float(np.dot(o1 - mid, cur[:3, 0])))]
            axis, point = z, o0
        for kind, s, e, idx, val in pieces:
            if abs(val) > _TOL:
                segments.append(Segment(kind, s, e, _name(kind, idx, val)))
        if row.joint is not JointType.FIXED:
            joints.append(JointGlyph(i, row.joint, point, axis))
    if scale is None:
        extent = float(np.ptp(poses[:, :3, 3], axis=0).max())
        scale = 0.18 * (extent if extent > _TOL else 1.0)
    return Skeleton(tuple(labels), poses, tuple(segments), tuple(joints), float(scale))


def is_planar(robot: Any, q: object = None, *, deg: bool = False) -> bool:
    """True when every frame's z axis is ±z of the plot frame (a top view shows it all).

    >>> import dhsym
    >>> is_planar(dhsym.load("planar4r")), is_planar(dhsym.load("puma560"))
    (True, False)
    """
    poses, _ = _poses(robot, joint_values(robot, q, deg=deg))
    return bool(np.allclose(np.abs(poses[:, 2, 2]), 1.0, atol=1e-9))


def _title(robot: Any, qv: np.ndarray) -> str:
    rows = [robot.table.rows[i - 1] for i in robot.table.joint_rows]
    parts = [
        f"{math.degrees(v):.4g}°" if r.joint is JointType.REVOLUTE else f"{v:.4g}"
        for r, v in zip(rows, qv, strict=True)
    ]
    conv = "" if robot.convention.value in robot.name.lower() else f" ({robot.convention.value} DH)"
    return f"{robot.name}{conv}\nq = ({', '.join(parts)})"


def plot_robot(
    robot: Any,
    q: object = None,
    *,
    ax: Any = None,
    frames: bool = True,
    labels: bool = True,
    deg: bool = False,
    view: str = "3d",
    scale: float | None = None,
    title: str | None = None,
    limits: tuple[np.ndarray, float] | None = None,
    alpha: float = 1.0,
) -> Figure:
    """Draw ``robot`` at ``q`` with its DH frames; returns the matplotlib ``Figure``.

    Parameters
    ----------
    robot
        A :class:`~dhsym.kinematics.chain.KinematicChain`.
    q
        Joint values (radians and lengths; degrees for revolute joints with
        ``deg=True``). ``None`` draws the zero configuration.
    ax
        Draw into this Axes (3D or 2D) instead of a new figure.
    frames, labels
        Draw the frame triads; write ``{k}`` and the ``a_i``/``d_i`` lengths.
    view
        ``'3d'`` or ``'2d'`` (top view; only when every z axis is vertical).
    scale
        Length of the triad axes (default: 18 % of the arm's extent).
    title
        Figure title (default: name, convention and q). ``''`` for none.
    limits
        ``(centre, half_width)`` of the view cube (animations keep it fixed).
    alpha
        Opacity of links and joints (below 1 for a "ghost" arm drawn over another).
    """
    from matplotlib.figure import Figure

    qv = joint_values(robot, q, deg=deg)
    sk = skeleton(robot, qv, scale=scale)
    if ax is not None:
        view = "3d" if getattr(ax, "name", "") == "3d" else "2d"
    if view not in ("2d", "3d"):
        raise DHError(f"view must be '2d' or '3d', got {view!r}")
    if view == "2d" and not np.allclose(np.abs(sk.poses[:, 2, 2]), 1.0, atol=1e-9):
        raise GeometryError(
            f"{robot.name} is not planar here: its z axes are not all vertical; use view='3d'"
        )
    if ax is None:
        fig = Figure(figsize=(6.4, 6.0) if view == "3d" else (6.0, 5.4), layout="constrained")
        ax = fig.add_subplot(projection="3d" if view == "3d" else None)
    dim = 3 if view == "3d" else 2
    points = draw(ax, sk, dim, frames=frames, labels=labels, alpha=alpha)
    equal_axes(ax, points, dim, limits)
    ax.set_title(_title(robot, qv) if title is None else title, fontsize=11)
    figure: Figure = ax.figure
    return figure


def view_limits(
    robot: Any, qs: object, *, deg: bool = False, dim: int = 3
) -> tuple[np.ndarray, float]:
    """A fixed ``(centre, half_width)`` view that holds the arm at every configuration."""
    pts = []
    for q in np.atleast_2d(np.asarray(qs, dtype=float)):
        sk = skeleton(robot, joint_values(robot, q, deg=deg))
        o = sk.poses[:, :3, 3]
        pts.append(np.vstack([o - sk.scale, o + sk.scale]))
    allp = np.vstack(pts)[:, :dim]
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    return (lo + hi) / 2, float((hi - lo).max()) / 2 * 1.05


def _ranges(robot: Any) -> tuple[np.ndarray, np.ndarray]:
    lo, hi = [], []
    for i in robot.table.joint_rows:
        row = robot.table.rows[i - 1]
        default = (-math.pi, math.pi) if row.joint is JointType.REVOLUTE else (0.0, 1.0)
        a, b = (float(v) for v in row.limits) if row.limits is not None else default
        lo.append(a)
        hi.append(b)
    return np.array(lo), np.array(hi)


def workspace_points(robot: Any, n: int = 4000, *, seed: int = 0) -> np.ndarray:
    """Tool positions for ``n`` configurations drawn uniformly within the joint limits.

    Limits are the rows' ``limits``; without them ±π (revolute) and [0, 1] (prismatic).

    >>> import dhsym
    >>> r = np.linalg.norm(workspace_points(dhsym.load("planar2r"), 500)[:, :2], axis=1)
    >>> bool(r.max() <= 1.8 and r.min() >= 0.2)
    True
    """
    if n < 1:
        raise DHError(f"the workspace needs at least one sample, got {n}")
    lo, hi = _ranges(robot)
    Q = np.random.default_rng(seed).uniform(lo, hi, size=(n, len(lo)))
    origins: np.ndarray = robot.fk(Q)[:, :3, 3]
    return origins


def plot_workspace(
    robot: Any,
    n: int = 4000,
    *,
    ax: Any = None,
    view: str | None = None,
    seed: int = 0,
    title: str | None = None,
) -> Figure:
    """Scatter the reachable tool positions (see :func:`workspace_points`); returns the Figure.

    Robots whose reachable points all lie in one horizontal plane are drawn in
    2D (top view) unless ``view='3d'``; the arm is
    shown at its zero configuration for scale.
    """
    from matplotlib.figure import Figure

    pts = workspace_points(robot, n, seed=seed)
    if view is None:
        view = "2d" if is_planar(robot) and np.ptp(pts[:, 2]) < 1e-9 else "3d"
    if ax is None:
        fig = Figure(figsize=(6.0, 5.6), layout="constrained")
        ax = fig.add_subplot(projection="3d" if view == "3d" else None)
    dim = 3 if getattr(ax, "name", "") == "3d" else 2
    ax.scatter(
        *pts[:, :dim].T,
        s=3,
        alpha=0.35,
        color="tab:blue",
        label="reachable tool points",
        gid="workspace",
    )
    plot_robot(robot, ax=ax, frames=False, labels=False, title="")
    lo, hi = np.minimum(pts.min(0), 0)[:dim], np.maximum(pts.max(0), 0)[:dim]
    equal_axes(ax, np.vstack([lo, hi]), dim, ((lo + hi) / 2, float((hi - lo).max()) / 2 * 1.08))
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(
        f"Workspace of {robot.name}\n{n} random configurations within the joint limits"
        if title is None
        else title,
        fontsize=11,
    )
    figure: Figure = ax.figure
    return figure
