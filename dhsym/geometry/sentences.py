"""The lecture's sentences for :func:`dhsym.geometry.frames.assign_frames`: one template per step.

Each template states a rule of the DH algorithm as the lectures teach it: Ghosal (IISc),
Lecture 5, for the modified (Craig) convention, and Asokan (IIT Madras), Introduction to
Robotics, Lecture 2.6 "DH algorithm", for the standard (Schilling/Spong) one; :func:`say`
fills it in for link ``k`` with the numbers of the case at hand and returns a
:class:`~dhsym.geometry.chains.Step`.

Examples
--------
>>> print(say("tool transform", "no tool transform", 2).text)
Frame 2 → tool: frame 2 is the tool frame; no tool transform.
>>> import textwrap
>>> v = sp.ImmutableMatrix
>>> s = say("base", "given base", 0, z=v([0, 0, 1]), o=v([0, 0, 0]), x=v([1, 0, 0]))
>>> print(textwrap.fill(s.markdown, 90))
Frame 0 is the given base frame: $z_{0}$ = $(0, 0, 1)$ along the axis of joint 1, $O_{0}$
= $(0, 0, 0)$, $x_{0}$ = $(1, 0, 0)$.
"""

from __future__ import annotations

from types import MappingProxyType

import sympy as sp

from .chains import Step, name, step, vec

__all__ = ["SENTENCES", "say"]

# {…p}, {…k}, {…n} are the names with index k − 1, k, k + 1 (z, x, y, O, a, d, b, th, al).

_SENTENCES = {
    "standard numbering": (
        "Step 1 of the DH algorithm: number the joints 1 … {n} from the base to the tool; frame"
        " k has its z axis along the axis of joint k + 1."
    ),
    "modified numbering": (
        "Number the joints 1 … {n} from the base to the tool: frame i has its z axis along the "
        "axis of joint i and is attached to link i."
    ),
    "standard base": (
        "Frame 0 (base): {zk} = {z} along the axis of joint 1; we place {Ok} = {o}, the point "
        "of that axis nearest the world origin, and take {xk} = {x}, the world x axis made "
        "perpendicular to {zk} (any perpendicular would do)."
    ),
    "given base": (
        "Frame 0 is the given base frame: {zk} = {z} along the axis of joint 1, {Ok} = {o}, "
        "{xk} = {x}."
    ),
    "standard skew": (
        "{zp} and {zk} are skew: the common normal is unique (Dimentberg); it meets {zp} at "
        "{bk} = {foot} and {zk} at {Ok} = {o}, the origin of frame {k}; {xk} = {x} points along"
        " it away from {zp}, and {ak} = {len}."
    ),
    "modified skew": (
        "{zk} and {zn} are skew: the common normal is unique (Dimentberg); its foot on {zk} is "
        "{Ok} = {o}, {xk} = {x} points along it towards {zn}, and {ak} = {len}."
    ),
    "standard intersecting": (
        "{zp} and {zk} intersect at {o}: {Ok} is the intersection and {ak} = 0; {xk} = ±({zp} ×"
        " {zk})/‖{zp} × {zk}‖, and we take the sign {sgn} so that {xk} = {x} stays closest to "
        "{xp}."
    ),
    "modified intersecting": (
        "{zk} and {zn} intersect at {o}: {Ok} is the intersection and {ak} = 0; {xk} = ±({zk} ×"
        " {zn})/‖{zk} × {zn}‖, normal to their plane, with the sign {sgn} so that {xk} = {x} "
        "stays closest to {xp}."
    ),
    "standard parallel": (
        "{zp} and {zk} are parallel: the common normal is not unique; we choose the one through"
        " {Op} = {start}, so that {dk} = 0{home}; it meets {zk} at {Ok} = {o}, {xk} = {x} "
        "points away from {zp}, and {ak} = {len}."
    ),
    "modified parallel": (
        "{zk} and {zn} are parallel: the common normal is not unique; we choose the one through"
        " {Ok} = {o}, where {xp} meets {zk}, so that {dk} = 0{home}; {xk} = {x} points away "
        "from {zk}, and {ak} = {len}."
    ),
    "standard coincident": (
        "{zp} and {zk} lie on one line: joints {k} and {n1} form a cylindrical pair (C = R + "
        "P); every perpendicular is a common normal, so we keep {Ok} = {Op} and {xk} = {xp} "
        "({ak} = 0)."
    ),
    "modified coincident": (
        "{zk} and {zn} lie on one line: joints {k} and {n1} form a cylindrical pair (C = R + "
        "P); every perpendicular is a common normal, so we keep {Ok} = {o} and {xk} = {xp} "
        "({ak} = 0)."
    ),
    "no tool": (
        "Last frame: no tool was given, so frame {k} is frame {m} at the home pose ({ak} = 0, "
        "{alk} = 0, {dk} = 0); give a tool (point, approach, sliding) to place it at the tool "
        "tip."
    ),
    "tool": (
        "Last frame: {Ok} at the tool point {p}, {zk} along the approach vector a = {a}, {yk} "
        "along the sliding vector s = {s}, {xk} = s × a = {nv}. "
    ),
    "tool is DH": (
        "{xk} is perpendicular to {zp} and meets it at {bk} = {b}, so this is a DH frame and no"
        " tool transform is needed."
    ),
    "tool is not DH": (
        "It breaks a DH rule ({xk} must be perpendicular to {zp} and meet it), so frame {k} is "
        "the DH frame nearest to it: {Ok} = {p}, {xk} = {x}, {zk} = {z}; the constant rest is "
        "the tool transform."
    ),
    "last link": (
        "Last link (modified convention): there is no {zn}; joint {k} is {kind}, so {Ok} = {o} "
        "is where {xp} meets {zk} and {xk} = {xp} at the home pose: {dk} = 0 and {thk} = 0 at "
        "home."
    ),
    "first link R": (
        "First link (modified convention): {zk} is not fixed by any joint; joint 1 is revolute,"
        " so frame 0 is chosen coincident with frame 1 at home: {alk} = 0, {ak} = 0, {dn} = 0, "
        "{thn} = 0."
    ),
    "first link P": (
        "First link (modified convention): {zk} is not fixed by any joint; joint 1 is "
        "prismatic, so frame 0 is chosen parallel to frame 1 (and at its home position): {alk} "
        "= 0, {ak} = 0, {thn} = 0, {dn} = 0 at home."
    ),
    "standard row": (
        "Row {k} (standard convention): {thk} = angle from {xp} to {xk} about {zp} = {th} at "
        "home; {dk} = distance from {Op} to {bk} = {b} along {zp} = {d} at home; {ak} = "
        "distance from {bk} to {Ok} along {xk} = {a}; {alk} = angle from {zp} to {zk} about "
        "{xk} = {al}. The joint variable {v} is {zero} at the home pose."
    ),
    "modified row": (
        "Row {k} (modified convention): {alp} = angle from {zp} to {zk} about {xp} = {al}; {ap}"
        " = distance from {zp} to {zk} along {xp} = {a}; {dk} = distance from {xp} to {xk} "
        "along {zk} = {d} at home; {thk} = angle from {xp} to {xk} about {zk} = {th} at home. "
        "The joint variable {v} is {zero} at the home pose."
    ),
    "base transform": ("World → frame 0: {w} (the base transform)."),
    "no base transform": ("World → frame 0: frame 0 is the world frame; no base transform."),
    "tool transform": ("Frame {k} → tool: {w} (the tool transform)."),
    "no tool transform": ("Frame {k} → tool: frame {k} is the tool frame; no tool transform."),
    "verified": (
        "Check: at the home pose and at 5 random configurations every frame moves rigidly with "
        "its link (each origin stays on its joint axis, each z along it) and the tool pose "
        "agrees with the geometry (largest difference {e})."
    ),
}
SENTENCES = MappingProxyType(_SENTENCES)


def say(rule: str, key: str | tuple[str, ...], k: int = 0, **args: object) -> Step:
    """The sentence(s) ``SENTENCES[key]`` about link ``k`` (vectors are printed as tuples)."""
    names: dict[str, object] = {"k": str(k), "m": str(k - 1), "n1": str(k + 1)}
    for base in ("z", "x", "y", "O", "a", "d", "b", "theta", "alpha"):
        short = {"theta": "th", "alpha": "al"}.get(base, base)
        for suffix, i in (("p", k - 1), ("k", k), ("n", k + 1)):
            names[short + suffix] = name(base, i)
    marked = {key_: vec(v) if isinstance(v, sp.MatrixBase) else v for key_, v in args.items()}
    template = "".join(SENTENCES[x] for x in ((key,) if isinstance(key, str) else key))
    return step(rule, template, **{**names, **marked})
