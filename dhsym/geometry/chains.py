"""Frames for a task: named frames, known transforms, composition, inversion and loops.

The pick-and-place task of Issac (IIT Bombay), Robotics, Lecture 19: the part frame {2}
is known in the global frame {1}, the gripper {3} in the part frame, the inclined plane
{4} in {1}, the part's final place {5} in {4}, and the grip does not change, so
``^5T_6 = ^2T_3``. Then ``^1T_3 = ^1T_2 ^2T_3`` and ``^1T_6 = ^1T_4 ^4T_5 ^5T_6``: each
a path in the graph of known transforms, walked forwards (a known transform) or
backwards (its rigid inverse). Approach and depart frames are the gripper frame moved
along its own z axis.

A :class:`FrameChain` is a value: :meth:`FrameChain.known` returns a new chain.
Adding a transform between frames that are already connected closes a loop;
the loop must close (the product around it is the identity) or
:class:`~dhsym.errors.ChainError` names it.

Examples
--------
>>> from dhsym.kinematics.transforms import Rz, Tx
>>> c = FrameChain().known("world", "table", Tx(2)).known("table", "part", Rz(sp.pi / 2))
>>> d = c.derive("part", "world")
>>> print(d.text)
Tpart_world = (Ttable_part)^-1 (Tworld_table)^-1
>>> d.pose.position.T
Matrix([[0, 2, 0]])
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeAlias

import sympy as sp

from dhsym.errors import ChainError
from dhsym.kinematics.numeric import to_float
from dhsym.kinematics.pose import Pose
from dhsym.kinematics.transforms import Tz, rigid_inverse
from dhsym.model.entries import as_expr
from dhsym.model.table import Elementary
from dhsym.notation.printers import Notation, format_angle

from .axes import measured

__all__ = [
    "ChainDerivation",
    "FrameChain",
    "KnownTransform",
    "Step",
    "angle",
    "name",
    "step",
    "vec",
    "word",
]

Matrix: TypeAlias = sp.ImmutableMatrix


# --- steps: sentences with math, printed as plain text or Markdown -------------------------


@dataclass(frozen=True)
class _Angle:
    value: sp.Expr


@dataclass(frozen=True)
class _Vec:
    value: Matrix


@dataclass(frozen=True)
class _Word:
    value: tuple[Elementary, ...]


@dataclass(frozen=True)
class _Name:
    base: str
    index: object


_GREEK_TEXT = {"theta": "θ", "alpha": "α"}
_NOTATION = Notation(compact=False)  # decimals as written (0.4, not 2/5)


def name(base: str, index: object) -> _Name:
    """Mark an indexed name for a :class:`Step`: ``name("theta", 1)`` is θ1 / ``\\theta_{1}``."""
    return _Name(base, index)


def angle(value: sp.Expr) -> _Angle:
    """Mark an angle for a :class:`Step` (printed in degrees when exact)."""
    return _Angle(as_expr(value))


def vec(value: sp.MatrixBase) -> _Vec:
    """Mark a vector for a :class:`Step` (printed as a tuple)."""
    return _Vec(Matrix(value))


def word(value: Sequence[Elementary]) -> _Word:
    """Mark a word of elementary transforms for a :class:`Step`."""
    return _Word(tuple(value))


def _fmt(value: object, md: bool) -> str:
    if isinstance(value, str):
        return value
    if isinstance(value, _Angle):
        shown = measured(value.value)
        nice = (shown / sp.pi).is_rational is True or shown == 0
        if shown != value.value:  # a measured angle: its radians as a decimal
            text = _NOTATION.latex(shown) if md else _NOTATION.text(shown)
        else:
            text = format_angle(shown, degrees=nice, latex=md)
        return f"${text}$" if md else text
    if isinstance(value, _Vec):
        parts = [
            _NOTATION.latex(c) if md else _NOTATION.text(c) for c in map(measured, value.value)
        ]
        return f"$({', '.join(parts)})$" if md else f"({', '.join(parts)})"
    if isinstance(value, _Name):
        if md:
            return f"${sp.latex(sp.Symbol(f'{value.base}_{value.index}'))}$"
        return f"{_GREEK_TEXT.get(value.base, value.base)}{value.index}"
    if isinstance(value, _Word):
        if md:
            return (
                "$"
                + r"\,".join(
                    f"{e.kind}_{{{e.axis}}}({_NOTATION.latex(measured(e.value))})"
                    for e in value.value
                )
                + "$"
            )
        return " ".join(
            f"{e.kind}{e.axis}({_NOTATION.text(measured(e.value))})" for e in value.value
        )
    if isinstance(value, sp.Expr):
        value = measured(value)
    return f"${_NOTATION.latex(value)}$" if md else _NOTATION.text(value)


@dataclass(frozen=True)
class Step:
    r"""One sentence of a derivation: a template with named math arguments.

    >>> s = step("parallel", "{z} is parallel to {w}", z=sp.Symbol("z1"), w=sp.Symbol("z2"))
    >>> s.text, s.markdown
    ('z1 is parallel to z2', '$z_{1}$ is parallel to $z_{2}$')
    >>> print(step("angle", "{t} = {v}", t=name("theta", 3), v=angle(-sp.pi / 2)).markdown)
    $\theta_{3}$ = $-90^{\circ}$

    """

    rule: str
    template: str
    args: tuple[tuple[str, object], ...] = ()

    @property
    def text(self) -> str:
        """The sentence in plain text."""
        return self.template.format(**{k: _fmt(v, False) for k, v in self.args})

    @property
    def markdown(self) -> str:
        """The sentence in Markdown with ``$…$`` math."""
        return self.template.format(**{k: _fmt(v, True) for k, v in self.args})

    def __str__(self) -> str:
        return self.text


def step(rule: str, template: str, **args: object) -> Step:
    """Build a :class:`Step` (arguments: strings, sympy objects, :func:`vec`, :func:`angle`)."""
    return Step(rule, template, tuple(args.items()))


# --- frame chains -----------------------------------------------------------------------------


@dataclass(frozen=True)
class KnownTransform:
    """``^{frm}T_{to}``: the pose of frame ``to`` in frame ``frm`` (exact 4×4)."""

    frm: str
    to: str
    matrix: Matrix
    note: str = ""


@dataclass(frozen=True)
class ChainDerivation:
    """An unknown transform found along a path of known ones, with its steps."""

    frm: str
    to: str
    path: tuple[str, ...]
    factors: tuple[tuple[str, str, bool], ...]  # (from, to, inverted) of each known factor
    pose: Pose
    steps: tuple[Step, ...]

    @property
    def equation_latex(self) -> str:
        """``{}^{1}T_{6} = {}^{1}T_{4}\\,{}^{4}T_{5}\\,{}^{5}T_{6}``."""
        parts = [_label(a, b, inv, True) for a, b, inv in self.factors]
        return f"{self.pose.label_latex} = " + r"\,".join(parts)

    @property
    def text(self) -> str:
        """``T1_6 = T1_4 T4_5 T5_6`` (inverses as ``(T…)^-1``)."""
        parts = [_label(a, b, inv, False) for a, b, inv in self.factors]
        return f"{self.pose.label_text} = " + " ".join(parts)

    def _repr_markdown_(self) -> str:
        lines = [f"- {s.markdown}" for s in self.steps]
        eq = f"$${self.equation_latex} = {self.pose.latex()}$$"
        return "\n".join([*lines, "", eq])


def _label(a: str, b: str, inverted: bool, latex: bool) -> str:
    p = Pose(Matrix(sp.eye(4)), a, b)
    if latex:
        return f"\\left({p.label_latex}\\right)^{{-1}}" if inverted else p.label_latex
    return f"({p.label_text})^-1" if inverted else p.label_text


def _nonzero(x: sp.Expr, tol: float = 1e-9) -> bool:
    x = sp.simplify(x)
    return x != 0 and (bool(x.free_symbols) or abs(to_float(x)) > tol)


def _as_matrix(matrix: object, frm: str, to: str) -> Matrix:
    from .axes import exact_matrix

    try:
        M = exact_matrix(matrix)
    except (TypeError, ValueError) as err:
        raise ChainError(f"T[{frm}←{to}]: expected a 4×4 matrix ({err})") from None
    if M.shape != (4, 4) or any(sp.simplify(M[3, j] - (1 if j == 3 else 0)) != 0 for j in range(4)):
        raise ChainError(f"T[{frm}←{to}]: expected a 4×4 homogeneous matrix with last row 0 0 0 1")
    R = M[:3, :3]
    if any(_nonzero(x) for x in R.T * R - sp.eye(3)):
        raise ChainError(f"T[{frm}←{to}]: the 3×3 part is not a rotation (RᵀR ≠ I)")
    return Matrix(M)


class FrameChain:
    """Named frames and the transforms known between them (an immutable value).

    >>> from dhsym.kinematics.transforms import Rx, Tz
    >>> c = FrameChain().known(1, 2, Tz(1)).known(2, 3, Rx(sp.pi))
    >>> c.same_as(5, 6, 2, 3).derive(5, 6).pose.matrix == c[2, 3].matrix
    True
    >>> c.approach(3, 1, "above")[1, "above"].position.T  # z3 points down: above is up
    Matrix([[0, 0, 2]])
    >>> c.solve(3, 1)[1].text
    'T3_1 = (T2_3)^-1 (T1_2)^-1'

    Parameters
    ----------
    known
        :class:`KnownTransform` values.
    notation
        Printing of the results (default: plain sympy with C/S abbreviations off).
    tol
        A loop closes when the difference is exactly zero, or (for numeric
        entries, e.g. measured poses given as floats) at most ``tol``.
    """

    def __init__(
        self,
        known: Sequence[KnownTransform] = (),
        *,
        notation: Notation | None = None,
        tol: float = 1e-9,
    ) -> None:
        self._known: tuple[KnownTransform, ...] = ()
        self.notation = notation or Notation(compact=False)
        self.tol = tol
        for k in known:
            self._known = self._add(k)._known

    @property
    def transforms(self) -> tuple[KnownTransform, ...]:
        """The known transforms in the order they were added."""
        return self._known

    @property
    def frames(self) -> tuple[str, ...]:
        """All frame names, in order of appearance."""
        seen: dict[str, None] = {}
        for k in self._known:
            seen.setdefault(k.frm)
            seen.setdefault(k.to)
        return tuple(seen)

    def __repr__(self) -> str:
        pairs = ", ".join(f"T[{k.frm}←{k.to}]" for k in self._known)
        return f"FrameChain({pairs})"

    def known(self, frm: object, to: object, matrix: object, note: str = "") -> FrameChain:
        """A new chain that also knows ``^{frm}T_{to}`` (the pose of ``to`` in ``frm``)."""
        a, b = str(frm), str(to)
        if a == b:
            raise ChainError(f"T[{a}←{b}]: a frame's transform to itself is the identity")
        return self._add(KnownTransform(a, b, _as_matrix(matrix, a, b), note))

    def same_as(
        self, frm: object, to: object, like_frm: object, like_to: object, note: str = ""
    ) -> FrameChain:
        """A new chain with ``^{frm}T_{to} = ^{like_frm}T_{like_to}`` (e.g. the grip is kept)."""
        M = self.derive(like_frm, like_to).pose.matrix
        why = note or f"same as T[{like_frm}←{like_to}]"
        return self.known(frm, to, M, why)

    def moved_along_z(self, frame: object, distance: object, name: object) -> FrameChain:
        """A new frame ``name`` = ``frame`` translated by ``distance`` along its own z axis."""
        from .axes import exact_number

        h = exact_number(distance)
        return self.known(frame, name, Tz(h), f"{name}: {frame} moved by {h} along its z axis")

    def approach(self, frame: object, distance: object, name: object | None = None) -> FrameChain:
        """The approach (or depart) frame: ``frame`` backed off by ``distance`` along −z.

        The gripper's approach vector a = z points into the work (Asokan, Lecture 2.6), so
        the frame a distance h before it is ``T · Tz(−h)`` (Issac, Lecture 19: a
        translation along z with nothing else changing).
        """
        from .axes import exact_number

        return self.moved_along_z(frame, -exact_number(distance), name or f"{frame}_approach")

    def depart(self, frame: object, distance: object, name: object | None = None) -> FrameChain:
        """The depart (lift-off) frame: like :meth:`approach`, named ``{frame}_depart``."""
        return self.approach(frame, distance, name or f"{frame}_depart")

    def _add(self, k: KnownTransform) -> FrameChain:
        out = FrameChain(notation=self.notation, tol=self.tol)
        if k.frm in self.frames and k.to in self.frames and self._path(k.frm, k.to) is not None:
            existing = self.derive(k.frm, k.to)
            diff = [sp.simplify(x) for x in existing.pose.matrix - k.matrix]
            off = [x for x in diff if x != 0 and (x.free_symbols or abs(to_float(x)) > self.tol)]
            if off:
                loop = " → ".join((*existing.path, k.frm))
                size = (
                    ""
                    if any(x.free_symbols for x in off)
                    else (f" (difference up to {max(abs(to_float(x)) for x in off):.3g})")
                )
                raise ChainError(
                    f"the loop {loop} does not close: T[{k.frm}←{k.to}] given differs from "
                    f"{existing.text.split(' = ', 1)[1]}{size}"
                )
        out._known = (*self._known, k)
        return out

    def _edges(self) -> dict[str, list[tuple[str, KnownTransform, bool]]]:
        adj: dict[str, list[tuple[str, KnownTransform, bool]]] = {}
        for k in self._known:
            adj.setdefault(k.frm, []).append((k.to, k, False))
            adj.setdefault(k.to, []).append((k.frm, k, True))
        return adj

    def _path(self, frm: str, to: str) -> list[tuple[str, KnownTransform, bool]] | None:
        adj = self._edges()
        prev: dict[str, tuple[str, KnownTransform, bool] | None] = {frm: None}
        queue = deque([frm])
        while queue:
            f = queue.popleft()
            if f == to:
                break
            for nxt, k, inv in adj.get(f, []):
                if nxt not in prev:
                    prev[nxt] = (f, k, inv)
                    queue.append(nxt)
        if to not in prev:
            return None
        out = []
        node = to
        while (step := prev[node]) is not None:
            f, k, inv = step
            out.append((node, k, inv))
            node = f
        return out[::-1]

    def derive(self, frm: object, to: object) -> ChainDerivation:
        """``^{frm}T_{to}`` from the known transforms along the shortest path, with steps."""
        a, b = str(frm), str(to)
        for name in (a, b):
            if name not in self.frames:
                raise ChainError(
                    f"unknown frame {name!r}: known frames are "
                    + (", ".join(self.frames) or "none")
                )
        path = self._path(a, b) if a != b else []
        if path is None:
            reach = ", ".join(sorted(self._reachable(a))) or "no other frame"
            raise ChainError(
                f"no chain of known transforms from frame {a!r} to {b!r}: {a!r} reaches only "
                f"{reach}; a transform linking these to {b!r} is missing"
            )
        M = sp.eye(4)
        factors, steps, nodes = [], [], [a]
        for node, k, inv in path:
            factor = rigid_inverse(k.matrix) if inv else k.matrix
            M = M * factor
            pair = (k.frm, k.to, inv)
            factors.append(pair)
            nodes.append(node)
            what = f"the inverse of T[{k.frm}←{k.to}]" if inv else f"T[{k.frm}←{k.to}]"
            steps.append(
                step("factor", "{what}" + (f" ({k.note})" if k.note else "") + ".", what=what)
            )
        M = sp.ImmutableMatrix(sp.simplify(M))
        pose = Pose(M, a, b, self.notation)
        d = ChainDerivation(a, b, tuple(nodes), tuple(factors), pose, ())
        head = step(
            "path", "T[{a}←{b}] along the path {p}: {eq}.", a=a, b=b, p=" → ".join(nodes), eq=d.text
        )
        return ChainDerivation(a, b, tuple(nodes), tuple(factors), pose, (head, *steps))

    def __getitem__(self, key: tuple[object, object] | str) -> Pose:
        """``chain["world", "table"]`` (or ``chain["world←table"]``) is ``^{world}T_{table}``."""
        frm: object
        to: object
        if isinstance(key, str):
            if "←" not in key:
                raise ChainError(f"write T[from←to], e.g. chain['world←table']; got {key!r}")
            frm, to = (part.strip() for part in key.split("←", 1))
        else:
            frm, to = key
        return self.derive(frm, to).pose

    def solve(self, frm: object, to: object) -> tuple[FrameChain, ChainDerivation]:
        """Solve the loop for the unknown ``^{frm}T_{to}``; return the chain that knows it too."""
        d = self.derive(frm, to)
        return self.known(frm, to, d.pose.matrix, f"solved: {d.text}"), d

    def _reachable(self, frm: str) -> set[str]:
        adj = self._edges()
        seen, todo = {frm}, [frm]
        while todo:
            for nxt, _, _ in adj.get(todo.pop(), []):
                if nxt not in seen:
                    seen.add(nxt)
                    todo.append(nxt)
        return seen - {frm}
