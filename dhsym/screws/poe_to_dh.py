"""From a product of exponentials back to a DH table, through the frame assignment.

Each space screw axis is a line: a revolute axis ``(ω, v)`` with ``‖ω‖ = 1`` passes through
``q = ω × v`` (its point nearest the origin) along ``ω``; a prismatic axis ``(0, v)`` has
only a direction, and is placed through the point of the axis before it (or the origin).
The home configuration ``M`` gives the tool: its position, approach ``z`` and sliding
``y``. These lines go to :func:`dhsym.geometry.frames.assign_frames`, which places the DH
frames at home with its sentences; the variables are zero at home (constant offsets in the
table), so the table's ``fk`` at ``q`` is the PoE's ``T(q)``.

Examples
--------
>>> import dhsym
>>> from dhsym.screws.product import from_chain
>>> fa = to_dh(from_chain(dhsym.load("planar2r")))
>>> [(r.theta, r.a) for r in fa.table.rows]
[(theta1, a1), (theta2, a2)]
"""

from __future__ import annotations

import sympy as sp

from dhsym.geometry.axes import JointAxis, Tool
from dhsym.geometry.frames import FrameAssignment, assign_frames
from dhsym.model.kinds import Convention

from .product import ProductOfExponentials

__all__ = ["joint_axes", "to_dh"]


def joint_axes(poe: ProductOfExponentials) -> tuple[JointAxis, ...]:
    """The joint axes of ``poe`` at home, as lines (:class:`~dhsym.geometry.axes.JointAxis`).

    >>> import dhsym
    >>> from dhsym.screws.product import from_chain
    >>> [a.point.T for a in joint_axes(from_chain(dhsym.load("planar2r")))]
    [Matrix([[0, 0, 0]]), Matrix([[a1, 0, 0]])]
    """
    out: list[JointAxis] = []
    last = sp.ImmutableMatrix([0, 0, 0])
    for k, s in enumerate(poe.space, start=1):
        if s.is_revolute:
            last = s.point()
            out.append(JointAxis(last, s.omega, "R", str(k)))
        else:
            out.append(JointAxis(last, s.v, "P", str(k)))
    return tuple(out)


def to_dh(
    poe: ProductOfExponentials,
    convention: Convention | str = Convention.STANDARD,
    *,
    name: str | None = None,
) -> FrameAssignment:
    """A DH table for ``poe`` (both conventions), with the frame-assignment sentences.

    The result's ``table`` has the world → frame 0 step as its base transform and what the
    last DH frame cannot hold of ``M`` as its tool transform; its joint variables are zero
    at home, in the order of the screw axes. :meth:`FrameAssignment.verify` has checked
    it against the axes' screw motions.
    """
    M = poe.home
    tool = Tool(M[:3, 3], M[:3, 2], M[:3, 1])
    return assign_frames(
        joint_axes(poe),
        convention=convention,
        tool=tool,
        values=dict(poe.values),
        name=poe.name if name is None else name,
    )
