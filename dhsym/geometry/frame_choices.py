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

__all__ = ["FrameChoice", "flip_x", "match_frames", "textbook_frames", "turned"]

_PI = sp.pi


@dataclass(frozen=True)
class FrameChoice:
    """A table with some ``x`` axes turned: the table, the frames turned (0 … n), and
    the rows that still differ from a reference (:func:`match_frames`), each with why."""

    table: DHTable
    flipped: tuple[int, ...]
    mismatches: tuple[str, ...] = ()

    @property
    def sentences(self) -> tuple[str, ...]:
        """What was chosen, in words (for the table file's comments)."""
        if not self.flipped:
            return ("every x axis as the frame-assignment algorithm chose it",)
        frames = ", ".join(f"x{k}" for k in self.flipped)
        return (
            f"{frames} turned by 180° about their z axes (the same arm and the same joint "
            "values): a table without constant offsets of θ, twists and lengths signed as a "
            "textbook prints them",
        )


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
    rows = list(table.rows)
    n = len(rows)
    if not 0 <= k <= n:
        raise DHError(f"frame {k}: the frames are 0 … {n}")
    base, tool = tuple(table.base), tuple(table.tool)
    modified = table.convention is Convention.MODIFIED
    if k == 0:
        base = _merge(base + (Elementary("R", "z", _PI),))
    else:
        r = _shift_theta(rows[k - 1], _PI)
        r = r if modified else _negate(r)
        rows[k - 1] = replace(r, inertia=_turned_inertia(r.inertia))
    if k == n:
        tool = _merge((Elementary("R", "z", -_PI),) + tool)
    else:
        r = _shift_theta(rows[k], -_PI) if k else _shift_theta(rows[0], -_PI)
        rows[k] = _negate(r) if modified else r
    return replace(table, rows=tuple(rows), base=base, tool=tool)


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
    for k in flipped:
        table = flip_x(table, k)
    return table


def textbook_frames(table: DHTable) -> FrameChoice:
    """The senses of the x axes a textbook would print: no constant offset of θ where a
    turned frame removes it, then the fewest negative twists, the fewest negative lengths
    ``a``, the shortest base and tool transforms (in that order). The same arm, the same
    joint values: ``fk(q)`` is unchanged.

    >>> from dhsym.model.library import builtin_table
    >>> textbook_frames(builtin_table("puma560")).flipped  # the lecture's table stays
    ()
    """
    tiny = 1e-12

    def row_cost(k: int, e: Entries) -> Cost:
        return (int(abs(e[0]) > tiny), int(e[3] < -tiny), int(e[2] < -tiny), 0)

    n = table.n
    ends = {
        (0, 0): len(table.base),
        (0, 1): len(flip_x(table, 0).base),
        (n, 0): len(table.tool),
        (n, 1): len(flip_x(table, n).tool),
    }

    def end_cost(k: int, turned: int) -> Cost:
        return (0, 0, 0, ends[k, turned])

    flipped = _choose(table, row_cost, end_cost)
    return FrameChoice(_apply(table, flipped), flipped)


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
