"""Which family of closed forms an arm belongs to, read from its joint axes.

The axes of neighbouring joints keep their relation whatever the joint values: parallel,
meeting in a point, or skew. Three consecutive axes that are parallel or meet in one
point are what the closed forms rest on (Pieper's condition; Spong, Hutchinson and
Vidyasagar, *Robot Modeling and Control*, §5.3): the last three meeting is the
spherical wrist, three parallel in the middle is the arm of the Universal Robots, and
the same at the start of the chain is solved by reading the chain backwards.

The axes are computed in numbers at one random configuration (the relations do not
depend on it), with the table's values and generic numbers for symbolic lengths, so
that either DH convention gives the same classification.

Examples
--------
>>> import dhsym
>>> s = classify(dhsym.load("puma560"))
>>> print(s)
axes 4, 5, 6 meet in a point
>>> s.family
'spherical wrist'
>>> classify(dhsym.load("ur5")).family
'three parallel axes'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dhsym.kinematics.jacobian import axis_frame
from dhsym.kinematics.numeric import word_product
from dhsym.kinematics.transforms import chain_word
from dhsym.model.table import Elementary, JointType

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "DECOUPLED",
    "GENERAL_6R",
    "INVERTED",
    "PARALLEL",
    "SPHERICAL_WRIST",
    "Structure",
    "classify",
]

#: the families, by the name :attr:`Structure.family` gives them
SPHERICAL_WRIST = "spherical wrist"
PARALLEL = "three parallel axes"
INVERTED = "inverted chain"
GENERAL_6R = "general 6R"
DECOUPLED = "decoupled"  # fewer than six joints or a prismatic one: kinematic decoupling

_TOL = 1e-9


@dataclass(frozen=True)
class Structure:
    """The relations of consecutive joint axes, and the family they put the arm in.

    ``parallel`` and ``meeting`` are the triples of consecutive joints (1-based, as in
    the lectures) whose axes are parallel or meet in one point; ``intersecting`` the
    pairs of consecutive axes that meet; ``family`` one of :data:`SPHERICAL_WRIST`,
    :data:`PARALLEL`, :data:`INVERTED`, :data:`GENERAL_6R`, :data:`DECOUPLED`.
    """

    joints: int
    revolute: tuple[bool, ...]
    parallel: tuple[tuple[int, int, int], ...]
    meeting: tuple[tuple[int, int, int], ...]
    intersecting: tuple[tuple[int, int], ...]
    family: str

    @property
    def sentences(self) -> tuple[str, ...]:
        """One sentence per triple: ``"axes 2, 3, 4 parallel"``, ``"axes 4, 5, 6 meet in a
        point"``."""
        out = [f"axes {', '.join(map(str, t))} parallel" for t in self.parallel]
        out += [f"axes {', '.join(map(str, t))} meet in a point" for t in self.meeting]
        return tuple(out)

    def __str__(self) -> str:
        return "; ".join(self.sentences) or "no three consecutive axes parallel or meeting"


def _axes(robot: KinematicChain, values: object = None) -> tuple[np.ndarray, np.ndarray]:
    """Points ``(n, 3)`` and unit directions ``(n, 3)`` of the joint axes at a random pose.

    The frames are numeric products of the chain's elementary transforms
    (:func:`~dhsym.kinematics.numeric.word_product`): nothing is compiled for one point.
    """
    rng = np.random.default_rng(7)
    table = robot.table
    known = table.value_map
    generic = {s: float(rng.uniform(0.3, 1.3)) for s in table.constants if s not in known}
    given = dict(values) if isinstance(values, dict) else {}
    q = rng.uniform(-np.pi, np.pi, len(robot.variables))
    vals = table.with_values({**generic, **given}).value_map
    env = {v: np.array([x]) for v, x in zip(robot.variables, q)}
    memo: dict[object, np.ndarray] = {}
    points, dirs = [], []
    for row in table.joint_rows:
        word = [
            Elementary(e.kind, e.axis, e.value.xreplace(vals))
            for e in chain_word(table, 0, axis_frame(robot, row))
        ]
        M = word_product(word, env, 1, memo=memo)[0]
        points.append(M[:3, 3])
        dirs.append(M[:3, 2])
    return np.array(points), np.array(dirs)


def _parallel(u: np.ndarray, v: np.ndarray) -> bool:
    return bool(np.linalg.norm(np.cross(u, v)) < _TOL)


def _meet(p: np.ndarray, u: np.ndarray, q: np.ndarray, v: np.ndarray) -> np.ndarray | None:
    """The point where two lines meet, or None (parallel or skew)."""
    n = np.cross(u, v)
    if np.linalg.norm(n) < _TOL:
        return None
    if abs(float(np.dot(q - p, n))) / np.linalg.norm(n) > 1e-8:
        return None
    # p + s u = q + t v, solved in the least-squares sense
    A = np.stack([u, -v], axis=1)
    s, _ = np.linalg.lstsq(A, q - p, rcond=None)[0]
    point: np.ndarray = p + s * u
    return point


def classify(robot: KinematicChain, values: object = None) -> Structure:
    """The relations of consecutive joint axes of ``robot`` and its family of closed forms.

    >>> import dhsym
    >>> s = classify(dhsym.load("stanford"))
    >>> s.sentences, s.family
    (('axes 4, 5, 6 meet in a point',), 'decoupled')
    >>> print(classify(dhsym.load("planar4r")))
    axes 1, 2, 3 parallel; axes 2, 3, 4 parallel
    """
    rows = robot.table.rows
    revolute = tuple(rows[r - 1].joint is JointType.REVOLUTE for r in robot.table.joint_rows)
    n = len(revolute)
    P, U = _axes(robot, values)
    pairs = tuple(
        (k + 1, k + 2) for k in range(n - 1) if _meet(P[k], U[k], P[k + 1], U[k + 1]) is not None
    )
    parallel, meeting = [], []
    for k in range(n - 2):
        if not all(revolute[k : k + 3]):
            continue
        if _parallel(U[k], U[k + 1]) and _parallel(U[k + 1], U[k + 2]):
            parallel.append((k + 1, k + 2, k + 3))
            continue
        a = _meet(P[k], U[k], P[k + 1], U[k + 1])
        b = _meet(P[k + 1], U[k + 1], P[k + 2], U[k + 2])
        if a is not None and b is not None and np.linalg.norm(a - b) < 1e-8:
            meeting.append((k + 1, k + 2, k + 3))
    family = DECOUPLED
    if n == 6 and all(revolute):
        if (4, 5, 6) in meeting:
            family = SPHERICAL_WRIST
        elif (2, 3, 4) in parallel and (5, 6) in pairs:
            family = PARALLEL
        elif (1, 2, 3) in meeting or ((3, 4, 5) in parallel and (1, 2) in pairs):
            family = INVERTED
        else:
            family = GENERAL_6R
    return Structure(n, revolute, tuple(parallel), tuple(meeting), pairs, family)
