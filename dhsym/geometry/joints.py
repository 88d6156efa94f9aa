"""Joint types, multi-DOF joints as 1-DOF joints, and the mobility of mechanisms.

The table of pairs of Ghosal (IISc), Lecture 5 "Elements of robot – Joints, Links": a
joint with m constraints leaves 6 − m degrees of freedom. Serial robots use 1-DOF R and
P joints (one DH row each); a cylindrical (C), Hooke (U/T), spherical (S) or planar (E)
joint is written as intersecting or coincident 1-DOF joints ("a spherical joint can be
represented by 3 intersecting rotary joints") and then gets a DH table like any other
robot. A screw (H) couples θ and d, so it has no DH row of its own.

The Grübler–Kutzbach count for a mechanism with N links (the ground
included) and J joints of f_i freedoms is ``M = λ(N − 1 − J) + Σ f_i`` with
λ = 6 in space and 3 in the plane; idle freedoms (a leg spinning about its
own axis) are subtracted.

Examples
--------
>>> PAIRS["S"].dof, PAIRS["S"].constraints, pair("hooke").symbol
(3, 3, 'U')
>>> four_bar().mobility, stewart_platform().mobility
(1, 6)
>>> print(four_bar().equation)
M = 3(N - 1 - J) + Σf = 3(4 - 1 - 4) + 4 = 1
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from types import MappingProxyType

import sympy as sp

from dhsym.errors import GeometryError

from .axes import JointAxis, is_zero_vector, simplify_vector, unit, vector

__all__ = [
    "PAIRS",
    "Joint",
    "Mechanism",
    "PairType",
    "decompose",
    "four_bar",
    "joint_axes",
    "mobility",
    "pair",
    "planar_five_bar",
    "serial_6r",
    "stewart_platform",
]


@dataclass(frozen=True)
class PairType:
    """One row of the table of pairs (Ghosal, Lecture 5): symbol, name, DOF, constraints."""

    symbol: str
    name: str
    dof: int
    equivalent: str  # the 1-DOF joints it is written as ('' for H)
    aliases: tuple[str, ...] = ()

    @property
    def constraints(self) -> int:
        """Constraints imposed in space, m = 6 − DOF."""
        return 6 - self.dof


PAIRS = MappingProxyType(
    {
        "H": PairType("H", "screw", 1, "", ("screw", "helical")),
        "R": PairType("R", "revolute", 1, "R", ("revolute", "rotary", "hinge")),
        "P": PairType("P", "prismatic", 1, "P", ("prismatic", "sliding")),
        "C": PairType("C", "cylindrical", 2, "RP", ("cylindrical", "cylindric")),
        "S": PairType("S", "spherical", 3, "RRR", ("spherical", "ball", "ball and socket")),
        "E": PairType("E", "planar pair", 3, "PPR", ("planar", "planar pair")),
        "U": PairType("U", "Hooke (universal)", 2, "RR", ("T", "hooke", "hook", "universal")),
    }
)


def pair(kind: str) -> PairType:
    """The pair type for a symbol or name (``'T'`` and ``'hooke'`` are ``U``).

    >>> pair("T").name, pair("ball").symbol
    ('Hooke (universal)', 'S')
    """
    key = str(kind).strip()
    if key.upper() in PAIRS:
        return PAIRS[key.upper()]
    for p in PAIRS.values():
        if key.lower() in (a.lower() for a in p.aliases):
            return p
    raise GeometryError(f"unknown joint type {kind!r}: expected one of H, R, P, C, S, E, U (T)")


def _perpendicular(u: sp.ImmutableMatrix) -> sp.ImmutableMatrix:
    for e in ((1, 0, 0), (0, 1, 0)):
        v = vector(e)
        w = simplify_vector(v - v.dot(u) * u)
        if not is_zero_vector(w):
            return unit(w)
    raise AssertionError("unreachable")


@dataclass(frozen=True)
class Joint:
    """A joint of a serial robot at its home pose, possibly multi-DOF.

    ``direction`` is the axis (R, P, H, C), the first axis (U, S) or the plane
    normal (E); ``second`` is the second axis (U, S) or the first in-plane
    sliding direction (E), perpendicular to ``direction`` (default: world x or
    y made perpendicular). ``euler=True`` writes S as R(u) R(v) R(u) (a wrist
    like the PUMA's) instead of three mutually perpendicular axes.
    """

    kind: str
    point: object
    direction: object
    second: object | None = None
    name: str = ""
    euler: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", pair(self.kind).symbol)

    def axes(self) -> tuple[JointAxis, ...]:
        """The equivalent 1-DOF joint axes, in order (Ghosal, Lecture 5).

        >>> [(a.joint, tuple(a.direction)) for a in Joint("S", (0, 0, 0), (0, 0, 1)).axes()]
        [('R', (0, 0, 1)), ('R', (1, 0, 0)), ('R', (0, 1, 0))]
        """
        kind, label = self.kind, self.name or self.kind
        if kind == "H":
            raise GeometryError(
                f"joint {label}: a screw pair (H) couples rotation and translation "
                "(d = pitch · θ / 2π); one DH row holds one variable, so describe "
                "it as R with the coupling noted, or as a C joint"
            )
        first = JointAxis(self.point, self.direction, "R")
        u = first.direction
        v = _perpendicular(u) if self.second is None else unit(vector(self.second, field="second"))
        if kind in ("U", "S", "E") and simplify_vector(sp.ImmutableMatrix([u.dot(v)]))[0] != 0:
            raise GeometryError(
                f"joint {label}: the second direction {tuple(v)} must be "
                f"perpendicular to the first {tuple(u)}"
            )
        w = sp.ImmutableMatrix(u.cross(v))
        p = first.point
        layout = {
            "R": [("R", u)],
            "P": [("P", u)],
            "C": [("R", u), ("P", u)],
            "U": [("R", u), ("R", v)],
            "S": [("R", u), ("R", v), ("R", u if self.euler else w)],
            "E": [("P", v), ("P", w), ("R", u)],
        }[kind]
        many = len(layout) > 1
        return tuple(
            JointAxis(p, d, j, f"{label}.{k}" if many else label)
            for k, (j, d) in enumerate(layout, start=1)
        )


def decompose(joints: Sequence[Joint]) -> tuple[JointAxis, ...]:
    """All joints as 1-DOF axes, in order (C → R P, U → R R, S → R R R, E → P P R).

    >>> [a.name for a in decompose([Joint("R", (0, 0, 0), (0, 0, 1), name="1"),
    ...                             Joint("C", (1, 0, 0), (0, 0, 1), name="2")])]
    ['1', '2.1', '2.2']
    """
    return tuple(ax for j in joints for ax in j.axes())


def joint_axes(joints: Sequence[Joint | JointAxis]) -> tuple[JointAxis, ...]:
    """Like :func:`decompose`, also accepting plain :class:`~dhsym.geometry.axes.JointAxis` items.

    >>> len(joint_axes([JointAxis((0, 0, 0), (0, 0, 1)), Joint("U", (0, 0, 0), (1, 0, 0))]))
    3
    """
    return tuple(ax for j in joints for ax in ((j,) if isinstance(j, JointAxis) else j.axes()))


# --- mobility ---------------------------------------------------------------------------------

_PLANAR_DOF = MappingProxyType({"R": 1, "P": 1})


@dataclass(frozen=True)
class Mechanism:
    """Links (the first is the ground) and joints ``(kind, link, link)``; spatial or planar.

    ``idle`` counts freedoms that move no link of interest (each S–S or S–P–S
    leg spinning about its own axis).
    """

    name: str
    links: tuple[str, ...]
    joints: tuple[tuple[str, str, str], ...]
    space: str = "spatial"
    idle: int = 0

    def __post_init__(self) -> None:
        if self.space not in ("spatial", "planar"):
            raise GeometryError(f"space must be 'spatial' or 'planar', got {self.space!r}")
        known = set(self.links)
        if len(known) != len(self.links):
            raise GeometryError(f"{self.name}: link names repeat")
        for k, (kind, a, b) in enumerate(self.joints, start=1):
            for link in (a, b):
                if link not in known:
                    raise GeometryError(
                        f"{self.name}: joint {k} ({kind}) names an unknown link {link!r}", row=k
                    )
            if a == b:
                raise GeometryError(f"{self.name}: joint {k} connects link {a!r} to itself", row=k)
            self._dof(kind, k)

    def _dof(self, kind: str, k: int) -> int:
        p = pair(kind)
        if self.space == "planar":
            if p.symbol not in _PLANAR_DOF:
                raise GeometryError(
                    f"{self.name}: joint {k} ({p.name}) is not a planar pair; "
                    "planar mechanisms use R and P",
                    row=k,
                )
            return _PLANAR_DOF[p.symbol]
        return p.dof

    @property
    def lam(self) -> int:
        """λ: 6 in space, 3 in the plane."""
        return 6 if self.space == "spatial" else 3

    @property
    def freedoms(self) -> int:
        """Σ f_i over the joints."""
        return sum(self._dof(kind, k) for k, (kind, _, _) in enumerate(self.joints, start=1))

    @property
    def loops(self) -> int:
        """Independent loops J − N + 1 (0 for a serial chain)."""
        return len(self.joints) - len(self.links) + 1

    @property
    def mobility(self) -> int:
        """Grübler–Kutzbach: λ(N − 1 − J) + Σ f_i − idle."""
        return mobility(len(self.links), [k for k, _, _ in self.joints], self.space, self.idle)

    @property
    def equation(self) -> str:
        """The count written out, as in a lecture."""
        N, J, lam = len(self.links), len(self.joints), self.lam
        idle = f" - {self.idle}" if self.idle else ""
        head = f"M = {lam}(N - 1 - J) + Σf" + (" - idle" if self.idle else "")
        return f"{head} = {lam}({N} - 1 - {J}) + {self.freedoms}{idle} = {self.mobility}"


def mobility(links: int, joints: Sequence[str | int], space: str = "spatial", idle: int = 0) -> int:
    """Grübler–Kutzbach mobility from the number of links (ground included) and the joints.

    ``joints`` are pair symbols (``'R'``, ``'S'``, …) or freedoms (ints).

    >>> mobility(7, "RRRRRR"), mobility(4, "RRRR", "planar"), mobility(5, "RRRRR", "planar")
    (6, 1, 2)
    """
    lam = {"spatial": 6, "planar": 3}.get(space)
    if lam is None:
        raise GeometryError(f"space must be 'spatial' or 'planar', got {space!r}")
    total = 0
    for k, j in enumerate(joints, start=1):
        if isinstance(j, int):
            f = j
        elif space == "planar":
            sym = pair(j).symbol
            if sym not in _PLANAR_DOF:
                raise GeometryError(f"joint {k} ({j}) is not a planar pair; use R or P", row=k)
            f = _PLANAR_DOF[sym]
        else:
            f = pair(j).dof
        total += f
    return lam * (links - 1 - len(joints)) + total - idle


def four_bar() -> Mechanism:
    """The planar four-bar linkage (Ghosal, Lecture 5): ground, crank, coupler, rocker; M = 1."""
    links = ("ground", "crank", "coupler", "rocker")
    joints = (
        ("R", "ground", "crank"),
        ("R", "crank", "coupler"),
        ("R", "coupler", "rocker"),
        ("R", "rocker", "ground"),
    )
    return Mechanism("four-bar linkage", links, joints, "planar")


def planar_five_bar() -> Mechanism:
    """The planar five-bar linkage: 5 links, 5 R → M = 2 (two inputs).

    >>> planar_five_bar().mobility
    2
    """
    links = ("ground", "l1", "l2", "l3", "l4")
    ring = (*links, "ground")
    return Mechanism(
        "planar five-bar linkage",
        links,
        tuple(("R", ring[k], ring[k + 1]) for k in range(5)),
        "planar",
    )


def serial_6r() -> Mechanism:
    """A 6R serial arm (PUMA-like): 7 links, 6 R → M = 6.

    >>> serial_6r().mobility, serial_6r().loops
    (6, 0)
    """
    links = ("base", *(f"link{k}" for k in range(1, 7)))
    return Mechanism("6R serial arm", links, tuple(("R", links[k], links[k + 1]) for k in range(6)))


def stewart_platform() -> Mechanism:
    """The 6-SPS Stewart platform: 14 links, 18 joints; Grübler gives 12, minus 6 idle spins = 6."""
    legs = [(f"cyl{k}", f"rod{k}") for k in range(1, 7)]
    links = ("base", "platform", *(x for leg in legs for x in leg))
    joints = tuple(
        j for c, r in legs for j in (("S", "base", c), ("P", c, r), ("S", r, "platform"))
    )
    return Mechanism("6-SPS Stewart platform", links, joints, idle=6)
