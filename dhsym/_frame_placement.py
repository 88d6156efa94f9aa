"""Placing the DH frames along the joint axes at the home pose (seeds 000 and 004).

:func:`place_standard` follows seed 004 (``z_k`` along joint *k + 1*, the last
frame at the tool point, what it cannot hold left to the tool transform);
:func:`place_modified` follows seed 000 (``z_i`` along joint *i*, with the
first-link and last-link rules). Between two consecutive axes the x axis runs
along their common normal: through the previous origin for parallel axes, along
``±z × z`` closest to the previous x for intersecting ones. Each returns the
frames, the points ``b_k`` (standard only) and the steps that explain them.
Used by :func:`dhsym.frames.assign_frames`.

Examples
--------
>>> axes = (JointAxis((0, 0, 0), (0, 0, 1), name="1"), JointAxis((1, 0, 0), (0, 0, 1), name="2"))
>>> frames, points_b, steps = place_standard(axes, None, None, {})
>>> [tuple(f.origin) for f in frames], [tuple(b) for b in points_b]
([(0, 0, 0), (1, 0, 0), (1, 0, 0)], [(0, 0, 0), (1, 0, 0)])
>>> [s.rule for s in steps]
['numbering', 'base', 'parallel', 'last link']
>>> frames, points_b, steps = place_modified(axes, None, None, {})
>>> [tuple(f.origin) for f in frames], points_b, [s.rule for s in steps]
([(0, 0, 0), (0, 0, 0), (1, 0, 0)], [], ['numbering', 'first link', 'parallel', 'last link'])
"""

from __future__ import annotations

import sympy as sp

from ._frame_sentences import say
from .axes import (
    CommonNormal,
    Frame,
    JointAxis,
    Relation,
    Tool,
    common_normal,
    is_zero_vector,
    sign_of,
    simplify_vector,
    unit,
)
from .chains import Step

__all__ = ["Built", "place_modified", "place_standard"]

Vector = sp.ImmutableMatrix
_EX, _EY = Vector([1, 0, 0]), Vector([0, 1, 0])


def _reference(axis: JointAxis) -> tuple[Vector, Vector]:
    """The point of the axis nearest the world origin, and world x (or y) made perpendicular."""
    u = axis.direction
    v = simplify_vector(_EX - _EX.dot(u) * u)
    if is_zero_vector(v):
        v = simplify_vector(_EY - _EY.dot(u) * u)
    return axis.foot((0, 0, 0)), unit(v)


def _closest(candidate: Vector, ref: Vector, vals: dict) -> tuple[Vector, str]:
    s = sign_of(candidate.dot(ref), vals, what="a direction")
    return (Vector(-candidate), "−") if s < 0 else (candidate, "+")


def _at_home(axis: JointAxis) -> str:
    return " at home (its joint variable)" if axis.joint == "P" else ""


_Link = tuple[CommonNormal, Vector, str, Vector, Vector]
Built = tuple[list[Frame], list[Vector], list[Step]]


def _link(L1: JointAxis, L2: JointAxis, start: Vector, prev_x: Vector, vals: dict) -> _Link:
    """x along the common normal of L1 and L2; returns (normal, x, sign, foot on L1, on L2).

    Parallel lines: the normal through ``start``; intersecting: the sign of
    ``±L1 × L2`` closest to ``prev_x``; coincident: ``prev_x`` at ``start``.
    """
    cn = common_normal(L1, L2, through=start, values=vals)
    if cn.relation is Relation.INTERSECTING:
        x, sgn = _closest(unit(Vector(L1.direction.cross(L2.direction))), prev_x, vals)
        return cn, x, sgn, cn.foot1, cn.foot1
    if cn.relation is Relation.COINCIDENT:
        return cn, prev_x, "", start, start
    return cn, cn.direction, "", cn.foot1, cn.foot2


def place_standard(
    axes: tuple[JointAxis, ...], base: Frame | None, tool: Tool | None, vals: dict
) -> Built:
    n = len(axes)
    log = [say("numbering", "standard numbering", n=str(n))]
    if base is None:
        origin, x = _reference(axes[0])
        base = Frame(0, origin, x, axes[0].direction)
        log.append(say("base", "standard base", 0, z=base.z, o=base.origin, x=x))
    else:
        log.append(say("base", "given base", 0, z=base.z, o=base.origin, x=base.x))
    frames, bs = [base], []
    for k in range(1, n):
        prev = frames[-1]
        cn, x, sgn, b, origin = _link(axes[k - 1], axes[k], prev.origin, prev.x, vals)
        frames.append(Frame(k, origin, x, axes[k].direction))
        bs.append(b)
        log.append(
            say(
                cn.relation.value,
                f"standard {cn.relation.value}",
                k,
                foot=b,
                o=origin,
                x=x,
                len=cn.length,
                sgn=sgn,
                start=prev.origin,
                home=_at_home(axes[k - 1]),
            )
        )
    last, b, text = _standard_last(axes[-1], frames[-1], tool, vals, n)
    return [*frames, last], [*bs, b], [*log, text]


def _standard_last(
    Ln: JointAxis, prev: Frame, tool: Tool | None, vals: dict, n: int
) -> tuple[Frame, Vector, Step]:
    if tool is None:
        return Frame(n, prev.origin, prev.x, prev.z), prev.origin, say("last link", "no tool", n)
    p, t = tool.point, tool.frame
    foot = Ln.foot(p)
    gap = simplify_vector(p - foot)
    if is_zero_vector(gap, vals):  # the tool point is on the last axis: x_n only ⊥ z_{n−1}
        x = simplify_vector(t.x - t.x.dot(prev.z) * prev.z)
        x = prev.x if is_zero_vector(x) else unit(x)
    else:
        x = unit(gap, vals)
    z = simplify_vector(t.z - t.z.dot(x) * x)
    frame = Frame(n, p, x, prev.z if is_zero_vector(z) else unit(z))
    dh = is_zero_vector(simplify_vector(frame.matrix - t.matrix))
    args = dict(p=p, a=tool.approach, s=tool.sliding, nv=t.x, b=foot, x=frame.x, z=frame.z)
    keys = ("tool", "tool is DH" if dh else "tool is not DH")
    return frame, foot, say("tool", keys, n, **args)


def place_modified(
    axes: tuple[JointAxis, ...], base: Frame | None, tool: Tool | None, vals: dict
) -> Built:
    n = len(axes)
    log = [say("numbering", "modified numbering", n=str(n))]
    start, prev_x = (base.origin, base.x) if base is not None else _reference(axes[0])
    frames: list[Frame] = []
    for i in range(1, n):
        cn, x, sgn, origin, start = _link(axes[i - 1], axes[i], start, prev_x, vals)
        frames.append(Frame(i, origin, x, axes[i - 1].direction))
        log.append(
            say(
                cn.relation.value,
                f"modified {cn.relation.value}",
                i,
                o=origin,
                x=x,
                len=cn.length,
                sgn=sgn,
                home=_at_home(axes[i - 1]),
            )
        )
        prev_x = x
    frames.append(Frame(n, start, prev_x, axes[-1].direction))
    kind = "revolute" if axes[-1].joint == "R" else "prismatic"
    log.append(say("last link", "last link", n, o=start, kind=kind))
    if base is None:
        base = Frame(0, frames[0].origin, frames[0].x, frames[0].z)
        log.insert(1, say("first link", f"first link {axes[0].joint}", 0))
    else:
        log.insert(1, say("base", "given base", 0, z=base.z, o=base.origin, x=base.x))
    return [base, *frames], [], log
