"""Among the equivalent DH frames of one arm, the table a textbook prints, or the one that
matches a given table.

The frame-assignment algorithm (:mod:`dhsym.geometry.frames`) fixes each ``z`` axis along
its joint's axis but leaves the sense of each ``x`` axis open where the lecture's rule
does not decide it (intersecting axes, and a maker who measured ``a`` the other way).
Turning frame *k* by π about its ``z`` axis (``x_k → −x_k``) gives the same arm, with the
same joint values, and changes the table only by signs and offsets of π:

* standard (``A_k = Rz(θ_k) Tz(d_k) Tx(a_k) Rx(α_k)``): ``θ_k + π``, ``a_k`` and ``α_k``
  negated, ``θ_{k+1} − π``;
* modified (``A_k = Rx(α_{k−1}) Tx(a_{k−1}) Rz(θ_k) Tz(d_k)``): ``θ_k + π``, then
  ``α_k``, ``a_k`` (row *k + 1*) negated and ``θ_{k+1} − π``;
* frame 0 turned adds ``Rz(π)`` to the base transform, frame *n* turned puts ``Rz(−π)``
  before the tool transform; a link's inertia, written in its frame, turns with it.

The other equivalent choices, and what is decided about each:

* **the sense of z.** Every ``z`` but one is a joint's axis, and the joint variable turns
  right-handed about it: reversing ``z_k`` reverses the variable (``θ_k = −q_k``), and
  takes the joint's limits, velocity and torque with it. The table keeps the URDF's joint
  values with their signs (``fk(q)`` is the URDF's pose for every q, and every round trip
  relies on it), and a row reading ``−θ_k`` is no table a textbook prints; so a joint's
  ``z`` is never reversed. A twist of 180° between two joint axes the file gives in
  opposite senses therefore stays, and the table says why (:attr:`FrameChoice.forced`;
  a maker that reverses such an axis, as Kinova's manual does, writes ``q_k = −θ_k``
  beside its table). The one free ``z`` is the last frame's in the standard convention
  (no joint turns about ``z_n``): :func:`reverse_last_z` turns frame *n* by π about
  ``x_n`` when that brings a twist ``|α_n| > 90°`` (a tool pointing back) into
  [−90°, 90°], the tool transform taking the turn.
* **where an origin slides.** Along two parallel joint axes the common normal may slide;
  the frame-assignment algorithm already takes the one through the previous origin, so
  ``d = 0`` on the row (Ghosal, Lecture 5). Sliding it elsewhere only moves the same
  length to the next row (``d_k + d_{k+1}`` is fixed), so no other choice gives more
  zeros.

:func:`textbook_frames` chooses the senses (one pass of dynamic programming along the
chain, every choice weighed at once) that a textbook would print: first no constant
offset of θ, then the fewest negative twists, the fewest negative lengths, the shortest
base and tool transforms. :func:`match_frames` chooses those that make the table equal a
reference table (Universal Robots' own UR5, say) and names the rows no choice can match,
and why.

Examples
--------
>>> from dhsym.model.table import DHRow, DHTable
>>> t = DHTable.from_rows([DHRow.revolute("theta1", d=1, alpha=-sp.pi / 2),
...                        DHRow.revolute("theta2 + pi", a=2)])
>>> choice = textbook_frames(t)
>>> [(r.theta, r.a, r.alpha) for r in choice.table.rows], choice.table.base, choice.table.tool
([(theta1, 0, pi/2), (theta2, 2, 0)], (Rz(pi),), ())
>>> choice.flipped  # the other choice without offsets, (2,), leaves α1 negative
(0, 1)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.numeric import to_float
from dhsym.model.entries import as_expr
from dhsym.model.inertia import LinkInertia
from dhsym.model.kinds import Convention
from dhsym.model.table import DHRow, DHTable, Elementary, JointType

from .axes import Frame

__all__ = [
    "FrameChoice",
    "flip_x",
    "match_frames",
    "reverse_last_z",
    "textbook_frames",
    "turned",
]

_PI = sp.pi


@dataclass(frozen=True)
class FrameChoice:
    """A table with some ``x`` axes turned: the table, the frames turned (0 … n), and
    the rows that still differ from a reference (:func:`match_frames`), each with why.

    ``last_z_reversed`` says that frame *n* (standard convention: a frame with no joint
    on its ``z`` axis) was also turned by π about its ``x`` axis (:func:`reverse_last_z`).
    ``forced`` says, row by row, why a twist of 180° stays (:func:`textbook_frames`)."""

    table: DHTable
    flipped: tuple[int, ...]
    mismatches: tuple[str, ...] = ()
    last_z_reversed: bool = False
    forced: tuple[str, ...] = ()

    @property
    def sentences(self) -> tuple[str, ...]:
        """What was chosen, in words (for the table file's comments)."""
        n = self.table.n
        said: tuple[str, ...]
        if not self.flipped:
            said = ("every x axis as the frame-assignment algorithm chose it",)
        else:
            frames = ", ".join(f"x{k}" for k in self.flipped)
            said = (
                f"{frames} turned by 180° about their z axes (the same arm and the same joint "
                "values): a table without constant offsets of θ, twists and lengths signed as "
                "a textbook prints them",
            )
        if self.last_z_reversed:
            said += (
                f"z{n} reversed (frame {n} turned by 180° about x{n}): no joint turns about "
                f"z{n}, so its sense is free; the twist α{n} avoids 180° and the tool "
                "transform takes the turn",
            )
        return said + self.forced


def _wrap(angle: sp.Expr) -> sp.Expr:
    """An exact constant angle brought into (−π, π]."""
    value = to_float(angle)
    turns = math.floor((value + math.pi) / (2 * math.pi))
    out = sp.expand(angle - 2 * turns * _PI) if turns else angle
    if to_float(out) <= -math.pi + 1e-12:
        out = sp.expand(out + 2 * _PI)
    return out


def _shift_theta(row: DHRow, by: sp.Expr) -> DHRow:
    """The row with ``θ + by``, its constant offset brought into (−π, π]."""
    offset = row.offset if row.variable_field == "theta" else row.theta
    theta = sp.expand(row.theta - offset + _wrap(offset + by))
    return replace(row, theta=theta)


def _negate(row: DHRow) -> DHRow:
    """The row with ``a`` and ``α`` negated (a twist of π stays π)."""
    return replace(row, a=-row.a, alpha=_wrap(-row.alpha))


def _turned_inertia(inertia: LinkInertia | None) -> LinkInertia | None:
    """A link's inertia in its frame turned by π about z: x and y negated."""
    if inertia is None:
        return None
    R = sp.diag(-1, -1, 1)
    r = inertia.r
    return replace(
        inertia, r=(-r[0], -r[1], r[2]), I=sp.ImmutableMatrix(R * sp.Matrix(inertia.I) * R)
    )


def turned(frame: Frame) -> Frame:
    """The frame turned by π about its z axis (``x → −x``): what :func:`flip_x` does to
    frame k of a table, done to the frame itself.

    >>> from dhsym.geometry.axes import vector
    >>> turned(Frame(1, vector([0, 0, 1]), vector([1, 0, 0]), vector([0, 0, 1]))).x.T
    Matrix([[-1, 0, 0]])
    """
    return Frame(frame.index, frame.origin, -frame.x, frame.z)


def flip_x(table: DHTable, k: int) -> DHTable:
    """The same arm with frame ``k`` (0 … n) turned by π about its z axis.

    >>> from dhsym.model.table import DHRow, DHTable
    >>> t = DHTable.from_rows([DHRow.revolute("theta1", a=1), DHRow.revolute("theta2", a=1)])
    >>> [(r.theta, r.a) for r in flip_x(t, 1).rows]
    [(theta1 + pi, -1), (theta2 + pi, 1)]
    """
    return _apply(table, (k,))


Parts = tuple[list[DHRow], tuple[Elementary, ...], tuple[Elementary, ...]]


def _flip_parts(parts: Parts, k: int, modified: bool) -> Parts:
    """Rows, base and tool with frame ``k`` turned by π about its z axis (see the module)."""
    rows, base, tool = parts
    rows = list(rows)
    n = len(rows)
    if not 0 <= k <= n:
        raise DHError(f"frame {k}: the frames are 0 … {n}")
    if k == 0:
        base = _merge(base + (Elementary("R", "z", _PI),))
    else:
        r = _shift_theta(rows[k - 1], _PI)
        r = r if modified else _negate(r)
        rows[k - 1] = replace(r, inertia=_turned_inertia(r.inertia))
    if k == n:
        tool = _merge((Elementary("R", "z", -_PI),) + tool)
    else:
        r = _shift_theta(rows[k], -_PI)
        rows[k] = _negate(r) if modified else r
    return rows, base, tool


def reverse_last_z(table: DHTable) -> DHTable:
    """The same arm with frame *n* of a standard table turned by π about its x axis
    (``z_n → −z_n``): ``α_n + π``, ``Rx(π)`` before the tool transform, link *n*'s
    inertia turned with its frame. In the standard convention no joint turns about
    ``z_n`` (``z_k`` is the axis of joint *k + 1*), so its sense is a free choice; every
    other ``z`` is a joint's axis, whose sense is the sense of its variable.

    >>> from dhsym.model.table import DHRow, DHTable
    >>> t = reverse_last_z(DHTable.from_rows([DHRow.revolute("theta1", a=1, alpha=sp.pi)]))
    >>> t.rows[0].alpha, t.tool
    (0, (Rx(pi),))
    """
    if table.convention is not Convention.STANDARD:
        raise DHError("z_n is the last joint's axis in the modified convention: not reversed")
    rows = list(table.rows)
    last = rows[-1]
    inertia = last.inertia
    if inertia is not None:
        R = sp.diag(1, -1, -1)
        r = inertia.r
        inertia = replace(
            inertia, r=(r[0], -r[1], -r[2]), I=sp.ImmutableMatrix(R * sp.Matrix(inertia.I) * R)
        )
    rows[-1] = replace(last, alpha=_wrap(last.alpha + _PI), inertia=inertia)
    tool = _merge((Elementary("R", "x", -_PI),) + tuple(table.tool))
    return replace(table, rows=tuple(rows), tool=tool)


def _merge(word: Sequence[Elementary]) -> tuple[Elementary, ...]:
    """Neighbouring elementary transforms of one kind and axis added; zero ones left out;
    rotations brought into (−π, π]."""
    out: list[Elementary] = []
    for e in word:
        if out and out[-1].kind == e.kind and out[-1].axis == e.axis:
            e = Elementary(e.kind, e.axis, out.pop().value + e.value)
        if e.kind == "R" and not e.value.free_symbols:
            e = Elementary("R", e.axis, _wrap(e.value))
        if e.value != 0:
            out.append(e)
    return tuple(out)


# --- the choice: dynamic programming along the chain ------------------------------------------

Cost = tuple[int, ...]
#: a row's constants as floats: the offset of θ (θ itself for a prismatic joint), d's
#: constant part, a, α
Entries = tuple[float, float, float, float]


def _number(value: sp.Expr, values: dict[sp.Symbol, sp.Expr]) -> float:
    """The value of an exact entry as a float (0 when it is still a symbol)."""
    e = as_expr(value).xreplace(values)
    return 0.0 if e.free_symbols else to_float(e)


def _entries(r: DHRow, values: dict[sp.Symbol, sp.Expr]) -> Entries:
    offset = r.offset if r.variable_field == "theta" else r.theta
    d = r.offset if r.variable_field == "d" else r.d
    return (
        _number(offset, values),
        _number(d, values),
        _number(r.a, values),
        _number(r.alpha, values),
    )


def _angle(x: float) -> float:
    """An angle in (−π, π]."""
    y = math.remainder(x, 2 * math.pi)
    return math.pi if y <= -math.pi + 1e-12 else y


def _version(e: Entries, before: int, here: int, modified: bool) -> Entries:
    """A row's constants with frame *k − 1* (``before``) and frame *k* (``here``) turned."""
    offset = _angle(e[0] + math.pi * (here - before))
    if (before if modified else here) == 1:
        return (offset, e[1], -e[2], _angle(-e[3]))
    return (offset, e[1], e[2], e[3])


def _choose(
    table: DHTable,
    row_cost: Callable[[int, Entries], Cost],
    end_cost: Callable[[int, int], Cost],
) -> tuple[int, ...]:
    """The frames to turn that make the summed cost least (lexicographic).

    Row *k*'s constants depend only on whether frames *k − 1* and *k* are turned
    (:func:`_version`), the base on frame 0 and the tool on frame *n* (``end_cost(k,
    turned)`` weighs the base for k = 0, the tool for k = n): the four versions of each
    row are weighed in floats and the best chain of choices found in one pass (Viterbi);
    the table is then turned once, exactly.
    """
    n = table.n
    modified = table.convention is Convention.MODIFIED
    values = table.value_map
    rows = [_entries(r, values) for r in table.rows]

    def add(x: Cost, y: Cost) -> Cost:
        return tuple(a + b for a, b in zip(x, y, strict=True))

    best: dict[int, tuple[Cost, tuple[int, ...]]] = {f: (end_cost(0, f), (f,)) for f in (0, 1)}
    for k in range(1, n + 1):
        nxt: dict[int, tuple[Cost, tuple[int, ...]]] = {}
        for here in (0, 1):
            options = []
            for before, (cost, path) in best.items():
                c = add(cost, row_cost(k, _version(rows[k - 1], before, here, modified)))
                if k == n:
                    c = add(c, end_cost(n, here))
                options.append((c, path + (here,)))
            nxt[here] = min(options)
        best = nxt
    _, path = min(best.values())
    return tuple(k for k, on in enumerate(path) if on)


def _apply(table: DHTable, flipped: Sequence[int]) -> DHTable:
    """The table with the frames ``flipped`` turned, built once (not once a frame)."""
    modified = table.convention is Convention.MODIFIED
    parts: Parts = (list(table.rows), tuple(table.base), tuple(table.tool))
    for k in flipped:
        parts = _flip_parts(parts, k, modified)
    rows, base, tool = parts
    return replace(table, rows=tuple(rows), base=base, tool=tool)


def textbook_frames(table: DHTable) -> FrameChoice:
    """The senses of the x axes a textbook would print: no constant offset of θ where a
    turned frame removes it, then the fewest negative twists, the fewest negative lengths
    ``a``, the shortest base and tool transforms (in that order). In the standard
    convention the last ``z`` is reversed first when ``|α_n| > 90°``
    (:func:`reverse_last_z`); a joint's ``z`` never is, and each twist of 180° that
    stays is explained in :attr:`FrameChoice.forced` (see the module's notes). The same
    arm, the same joint values: ``fk(q)`` is unchanged.

    >>> from dhsym.model.library import builtin_table
    >>> textbook_frames(builtin_table("puma560")).flipped  # the lecture's table stays
    ()
    >>> t = DHTable.from_rows([DHRow.revolute("theta1", a=1, alpha=sp.pi / 2),
    ...                        DHRow.revolute("theta2", a=1, alpha=sp.pi),
    ...                        DHRow.revolute("theta3", a=1)])
    >>> print(textbook_frames(t).forced[0][:60])
    α2 = 180° stays: z1 and z2 are the axes of joints 2 and 3, w
    """
    tiny = 1e-12
    n = table.n
    last_z = table.convention is Convention.STANDARD and (
        abs(_number(table.rows[-1].alpha, table.value_map)) > math.pi / 2 + tiny
    )
    if last_z:
        table = reverse_last_z(table)

    def row_cost(k: int, e: Entries) -> Cost:
        return (int(abs(e[0]) > tiny), int(e[3] < -tiny), int(e[2] < -tiny), 0)

    modified = table.convention is Convention.MODIFIED
    plain: Parts = (list(table.rows), tuple(table.base), tuple(table.tool))
    ends = {
        (0, 0): len(table.base),
        (0, 1): len(_flip_parts(plain, 0, modified)[1]),
        (n, 0): len(table.tool),
        (n, 1): len(_flip_parts(plain, n, modified)[2]),
    }

    def end_cost(k: int, turned: int) -> Cost:
        return (0, 0, 0, ends[k, turned])

    flipped = _choose(table, row_cost, end_cost)
    chosen = _apply(table, flipped)
    return FrameChoice(chosen, flipped, last_z_reversed=last_z, forced=_forced(chosen))


def _forced(table: DHTable) -> tuple[str, ...]:
    """Why each twist of 180° stays: the two z axes are joint axes pointing opposite ways.

    A joint's ``z`` points along its axis as the file gives it, and the joint variable
    turns right-handed about it. Reversing that ``z`` would remove the 180° (and, at
    the first joint, a base turned upside down) only by reversing the variable:
    ``θ_k = −q_k``. dhsym does not do that: the table's variables are the file's joint
    values with their signs (``fk(q)``, the limits, velocities and torques mean what the
    URDF says), and a row reading ``−θ_k`` is no table a textbook prints. A maker's
    manual that reverses an axis says so beside its table (``q_k = −θ_k``); here the
    comment says why the twist stays.
    """
    out = []
    standard = table.convention is Convention.STANDARD
    for k, r in enumerate(table.rows, start=1):
        # standard row k: α_k from z_{k−1} (joint k) to z_k (joint k + 1; none for k = n);
        # modified row k: α_{k−1} from z_{k−1} (joint k − 1; none for k = 1) to z_k (joint k)
        if k == (table.n if standard else 1):
            continue
        if abs(abs(_number(r.alpha, table.value_map)) - math.pi) < 1e-9:
            twist, first = (k, k) if standard else (k - 1, k - 1)
            out.append(
                f"α{twist} = 180° stays: z{k - 1} and z{k} are the axes of joints {first} and "
                f"{first + 1}, which the URDF gives in opposite senses; reversing one would "
                "reverse its joint variable (θ = −q), and the table keeps the URDF's joint values"
            )
    return tuple(out)


def match_frames(table: DHTable, reference: DHTable, *, tol: float = 1e-9) -> FrameChoice:
    """The senses of the x axes that make ``table`` equal ``reference`` row by row (θ
    offsets, ``a`` and ``α``; ``d`` no sense changes), and the rows that cannot, each with
    the reason.

    >>> from dhsym.model.table import DHRow, DHTable
    >>> t = DHTable.from_rows([DHRow.revolute("theta1", a=1), DHRow.revolute("theta2", a=2)])
    >>> ref = DHTable.from_rows([DHRow.revolute("theta1", a=-1), DHRow.revolute("theta2", a=-3)])
    >>> m = match_frames(t, ref)
    >>> m.flipped, m.mismatches
    ((0, 1, 2), ('row 2: a = -2 here, -3 in the reference: a length no frame choice changes',))
    """
    if reference.n != table.n or [r.joint for r in reference.rows] != [r.joint for r in table.rows]:
        raise DHError(
            f"the reference has {reference.n} rows ({_kinds(reference)}), this table "
            f"{table.n} ({_kinds(table)}): no frame choice matches them"
        )
    if reference.convention is not table.convention:
        raise DHError(
            f"the reference is a {reference.convention.value} table, this one "
            f"{table.convention.value}: convert one of them first"
        )

    def differs(x: float, y: float, angle: bool) -> bool:
        return abs(_angle(x - y) if angle else x - y) > tol

    want = [_entries(r, reference.value_map) for r in reference.rows]

    def row_cost(k: int, got: Entries) -> Cost:
        ref = want[k - 1]
        unequal = sum(differs(g, w, i in (0, 3)) for i, (g, w) in enumerate(zip(got, ref)))
        signs = sum(g * w < 0 for g, w in zip(got[2:], ref[2:]))  # then the signs of a, α
        return (unequal, signs)

    flipped = _choose(table, row_cost, lambda k, turned: (0, 0))
    chosen = _apply(table, flipped)
    names = ("θ offset", "d", "a", "α")
    why = []
    for k, r in enumerate(chosen.rows, start=1):
        got, ref = _entries(r, chosen.value_map), want[k - 1]
        for i, name in enumerate(names):
            if not differs(got[i], ref[i], i in (0, 3)):
                continue
            if i == 1:
                reason = "an offset along the joint axis no frame choice changes"
            elif i == 2 and abs(abs(got[2]) - abs(ref[2])) > tol:
                reason = "a length no frame choice changes"
            elif i == 3 and abs(abs(got[3]) - abs(ref[3])) > tol:
                reason = "a twist other than its negative: the z axes point another way"
            else:
                reason = "its sign is tied to another row's by the frames between them"
            angle = i in (0, 3)
            why.append(
                f"row {k}: {name} = {_show(got[i], angle)} here, {_show(ref[i], angle)} in "
                f"the reference: {reason}"
            )
    return FrameChoice(chosen, flipped, tuple(why))


def _show(value: float, angle: bool) -> str:
    return f"{math.degrees(value):.6g}°" if angle else f"{value:.6g}"


def _kinds(table: DHTable) -> str:
    return "".join(r.joint.value for r in table.rows if r.joint is not JointType.FIXED) or "-"
