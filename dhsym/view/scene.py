"""What the view shows of a robot, as plain data: the joints' sliders, the base and tool, the
sizes, the frames' names and the closed-form entries of the arm matrix.

A :class:`Scene` is frozen; :meth:`Scene.data` is the JSON object the JavaScript view reads
(``js/src/viewer.js``). Sliders are in the table's units (degrees when its angles are,
otherwise radians; lengths for prismatic joints) and within the joint's limits; the link
radius follows the DH lengths with the rule of :func:`dhsym.robot.Robot.to_urdf`'s pictures
(3 % of the summed lengths, at least 6 mm).

Examples
--------
>>> import dhsym
>>> s = scene(dhsym.load("puma560"))
>>> [(j.name, j.unit, j.minimum, j.maximum) for j in s.joints][:2]
[('θ₁', 'rad', -2.7925, 2.7925), ('θ₂', 'rad', -3.927, 0.7854)]
>>> arm = dhsym.load("stanford")
>>> [(j.name, j.kind, j.unit) for j in scene(arm, workspace=0).joints][2]
('d₃', 'prismatic', '')
>>> s.frame_names[-1], s.entries[0][3]
('tool', 'C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1')
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.constants import to_float
from dhsym.kinematics.transforms import plain_product
from dhsym.model.kinds import JointType
from dhsym.model.table import AngleUnit

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["JointSlider", "Scene", "scene"]

#: Points of the workspace cloud a view samples by default (the batched fk).
WORKSPACE_POINTS = 4000


@dataclass(frozen=True)
class JointSlider:
    """One joint's slider: its name, kind, unit and range in that unit, its value, and
    ``scale`` (the joint value in radians or length units is ``value × scale``)."""

    name: str
    kind: str
    unit: str
    minimum: float
    maximum: float
    step: float
    value: float
    scale: float
    digits: int
    row: int = 0


@dataclass(frozen=True)
class Scene:
    """A robot as the view shows it (see the module)."""

    name: str
    convention: str
    rows: int
    joints: tuple[JointSlider, ...]
    base: tuple[float, ...]
    tool: tuple[float, ...]
    radius: float
    reach: float
    frame_names: tuple[str, ...]
    link_names: tuple[str, ...]
    matrix_name: str
    entries: tuple[tuple[str, ...], ...]
    cloud: tuple[float, ...] = ()
    note: str = ""

    @property
    def q(self) -> np.ndarray:
        """The configuration the sliders start at (radians and length units)."""
        return np.array([j.value * j.scale for j in self.joints])

    def data(self) -> dict[str, Any]:
        """The JSON object of ``js/src/viewer.js``."""
        return {
            "name": self.name,
            "convention": self.convention,
            "rows": self.rows,
            "joints": [
                {
                    "name": j.name,
                    "kind": j.kind,
                    "unit": j.unit,
                    "min": j.minimum,
                    "max": j.maximum,
                    "step": j.step,
                    "value": j.value,
                    "scale": j.scale,
                    "digits": j.digits,
                    "row": j.row,
                }
                for j in self.joints
            ],
            "base": list(self.base),
            "tool": list(self.tool),
            "radius": self.radius,
            "reach": self.reach,
            "frame_names": list(self.frame_names),
            "link_names": list(self.link_names),
            "matrix_name": self.matrix_name,
            "entries": [list(r) for r in self.entries],
            "cloud": list(self.cloud),
            "note": self.note,
        }


def _matrix(word: Sequence[Any], values: Mapping[Any, Any]) -> tuple[float, ...]:
    M = plain_product(word).xreplace(dict(values))
    return tuple(to_float(x) for x in M)


def _reach(robot: KinematicChain) -> float:
    """The summed DH lengths (|a|, |d|, and a prismatic joint's travel) and base and tool
    offsets: the scale of the picture."""
    values = robot.table.value_map
    total = 0.0
    for row in robot.table.rows:
        for entry in (row.a, row.d):
            if row.variable is not None and row.variable in entry.free_symbols:
                lo, hi = row.limits if row.limits is not None else (0, 1)
                total += max(abs(to_float(lo)), abs(to_float(hi)))
            else:
                total += abs(to_float(entry.xreplace(values)))
    for word in (robot.table.base, robot.table.tool):
        if word:
            total += float(np.linalg.norm(np.array(_matrix(word, values))[[3, 7, 11]]))
    return max(total, 0.2)


def _slider(robot: KinematicChain, k: int, q: float | None, reach: float) -> JointSlider:
    """The slider of the joint in row ``k`` (0-based), starting at ``q``."""
    row = robot.table.rows[k]
    name = sp.pretty(row.variable)
    if row.joint is JointType.PRISMATIC:
        lo, hi = (to_float(x) for x in row.limits) if row.limits else (0.0, 0.5 * reach)
        step = (hi - lo) / 1000 or 1e-3
        value = min(max(0.0 if q is None else q, lo), hi)
        return JointSlider(name, "prismatic", "", lo, hi, step, value, 1.0, 4, k)
    degrees = robot.table.angles is AngleUnit.DEG
    scale = math.pi / 180 if degrees else 1.0
    lo, hi = (to_float(x) for x in row.limits) if row.limits else (-math.pi, math.pi)
    lo, hi = round(lo / scale, 10), round(hi / scale, 10)
    value = min(max(0.0 if q is None else q / scale, lo), hi)
    unit, step, digits = ("°", 0.5, 1) if degrees else ("rad", 0.005, 3)
    return JointSlider(name, "revolute", unit, lo, hi, step, value, scale, digits, k)


def _cloud(robot: KinematicChain, joints: Sequence[JointSlider], points: int) -> tuple[float, ...]:
    """Tool positions at ``points`` configurations drawn evenly from the sliders' ranges
    (seeded: the same scene gives the same cloud)."""
    if points <= 0:
        return ()
    rng = np.random.default_rng(0)
    lo = np.array([j.minimum * j.scale for j in joints])
    hi = np.array([j.maximum * j.scale for j in joints])
    Q = lo + (hi - lo) * rng.random((points, len(joints)))
    T = robot.fk(Q)
    return tuple(float(round(x, 6)) for x in T[:, :3, 3].ravel())


def scene(
    robot: KinematicChain,
    q: Sequence[float] | None = None,
    *,
    workspace: int = WORKSPACE_POINTS,
) -> Scene:
    """The scene of ``robot`` at ``q`` (radians and length units; default: zero, within the
    limits), with ``workspace`` sampled tool positions (0: none).

    The table needs values for its lengths; a symbol without one is a
    :class:`~dhsym.errors.DHError` naming it (``table.with_values``).
    """
    missing = [c.name for c in robot.table.constants if c not in robot.table.value_map]
    if missing:
        raise DHError(
            f"{robot.name or 'this table'}: the view needs a value for {', '.join(missing)} "
            "(give values, e.g. dhsym view NAME --values a1=1,a2=0.8)"
        )
    moving = [i - 1 for i in robot.table.joint_rows]
    if q is not None and len(q) != len(moving):
        raise DHError(
            f"q has {len(q)} values; {robot.name or 'the robot'} has {len(moving)} joints"
        )
    reach = _reach(robot)
    joints = tuple(
        _slider(robot, k, None if q is None else float(q[j]), reach) for j, k in enumerate(moving)
    )
    values = robot.table.value_map
    pose = robot.tool_pose()
    text = robot.notation.text
    entries = tuple(tuple(text(pose.matrix[i, j]) for j in range(4)) for i in range(4))
    frames = tuple(str(i) for i in range(robot.n + 1)) + ("tool",)
    links = tuple(robot.link_matrix(i).label_text for i in range(1, robot.n + 1))
    eye = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    return Scene(
        name=robot.name or "robot",
        convention=robot.convention.value,
        rows=robot.n,
        joints=joints,
        base=_matrix(robot.table.base, values) if robot.table.base else eye,
        tool=_matrix(robot.table.tool, values) if robot.table.tool else eye,
        radius=max(0.03 * reach, 0.006),
        reach=reach,
        frame_names=frames,
        link_names=links,
        matrix_name=pose.label_text,
        entries=entries,
        cloud=_cloud(robot, joints, workspace),
    )
