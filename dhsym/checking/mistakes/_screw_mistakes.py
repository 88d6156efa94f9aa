r"""Mistakes in a product of exponentials (Lynch and Park, *Modern Robotics*), each recognised
by recomputing the key under it with the screws room (:mod:`dhsym.screws`).

- ``omega_cross_q``: ``v = ω × q`` written for ``v = −ω × q`` (every revolute axis's ``v``
  of the wrong sign; the Jacobians and ``T(θ)`` built from those axes);
- ``body_for_space`` / ``space_for_body``: the body axes ``B_i`` (or ``J_b``) given where the
  space axes (``J_s``) are asked, and the reverse; in ``T(θ)`` the body axes in the space
  form ``e^{[B_1]θ_1}⋯M``, or the space axes in the body form ``M e^{[S_1]θ_1}⋯``;
- ``wrong_home``: the home configuration ``M`` read at the wrong configuration: the pose of
  another link's frame, or at the zeros of the DH table's entries instead of the joint
  variables' (a table with offsets); the body axes, ``J_b`` and ``T(θ)`` built on that ``M``;
- ``rows_swapped``: the rows ``[v; ω]`` of other texts for Lynch and Park's ``[ω; v]``;
- ``reverse_order``: the exponentials of ``T(θ)`` multiplied from the last joint;
- ``transposed``: ``M`` or ``T(θ)`` (or its rotation) transposed.

Every variant is an exact matrix derived once, when the key is prepared
(:func:`screw_variants`), and recognised at the diagnosis samples like the dynamics mistakes
(:class:`~dhsym.checking.mistakes._dynamics_mistakes.DynamicsMistake`).  The public names
are re-exported by :mod:`dhsym.checking.mistakes.registry`.

Examples
--------
>>> import dhsym
>>> found = screw_variants(dhsym.load("planar2r"), "S")
>>> for kind, m, _ in found:  # the second axis under each mistake
...     print(kind, m.T.tolist()[1])
omega_cross_q [0, 0, 1, 0, a1, 0]
body_for_space [0, 0, 1, 0, a2, 0]
rows_swapped [0, -a1, 0, 0, 0, 1]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.jacobian import resolve_frame
from dhsym.kinematics.transforms import rigid_inverse
from dhsym.screws.algebra import ScrewAxis, adjoint, matrix_exp
from dhsym.screws.product import ProductOfExponentials

from ._dynamics_mistakes import DynamicsMistake

if TYPE_CHECKING:
    from dhsym.robot import Robot

__all__ = ["SCREW_MISTAKES", "ScrewMistake", "screw_variants"]

Matrix: TypeAlias = sp.ImmutableMatrix
Variants: TypeAlias = list[tuple[str, Matrix, str]]

_TITLES = {
    "omega_cross_q": "v = ω × q for v = −ω × q",
    "body_for_space": "body frame for space frame",
    "space_for_body": "space frame for body frame",
    "wrong_home": "home configuration M read wrongly",
    "rows_swapped": "rows [v; ω] for [ω; v]",
    "reverse_order": "product in reverse order",
    "transposed": "matrix transposed",
}
_BOOK = "Lynch and Park, Modern Robotics"
_SIGN = (
    "The v of {which} has the wrong sign: v = omega x q is the velocity of the "
    "space origin turning the wrong way; a point p of the turning link moves with "
    "omega x (p - q), so at the origin v = -omega x q ({book})."
)
_ROWS = (
    "The rows are [v; omega]; {book} write screw axes and twists with omega first, "
    "[omega; v] (other texts put v first: say which order you use)."
)


@dataclass(frozen=True)
class ScrewMistake(DynamicsMistake):
    """One catalogued PoE mistake; its variants come from the prepared key (derived once by
    :func:`screw_variants`, carried by the case like the dynamics variants)."""

    @property
    def title(self) -> str:  # type: ignore[override]  # per instance, like kind
        return _TITLES[self.which]


SCREW_MISTAKES: tuple[ScrewMistake, ...] = tuple(
    ScrewMistake(k)
    for k in (
        "body_for_space",
        "space_for_body",
        "omega_cross_q",
        "wrong_home",
        "rows_swapped",
        "reverse_order",
        "transposed",
    )
)


def _flipped(axes: tuple[ScrewAxis, ...], only: int | None = None) -> tuple[ScrewAxis, ...]:
    """The axes with ``v`` of every revolute axis (or of axis ``only``, 0-based) negated:
    ``ω × q`` for ``−ω × q``."""
    return tuple(
        ScrewAxis(s.omega, -s.v) if s.is_revolute and only in (None, k) else s
        for k, s in enumerate(axes)
    )


def _one_by_one(
    axes: tuple[ScrewAxis, ...], letter: str
) -> list[tuple[tuple[ScrewAxis, ...], str]]:
    """The axes with every revolute ``v`` flipped, then with each one flipped alone (a
    student who slipped in one axis) when there is more than one, each with the detail
    that says which (details tell the variants apart)."""
    alone = [k for k, s in enumerate(axes) if s.is_revolute and any(x != 0 for x in s.v)]
    every = _SIGN.format(which=f"the revolute axes {letter}_i", book=_BOOK)
    out = [(_flipped(axes), every)]
    if len(alone) > 1:
        for k in alone:
            which = f"the axis {letter}_{k + 1}"
            out.append((_flipped(axes, k), _SIGN.format(which=which, book=_BOOK)))
    return out


def _columns(axes: tuple[ScrewAxis, ...]) -> Matrix:
    return Matrix.hstack(*(s.vector for s in axes))


def _exps(axes: tuple[ScrewAxis, ...], variables: tuple[sp.Symbol, ...]) -> sp.Matrix:
    """``e^{[A_1]q_1} ⋯ e^{[A_n]q_n}``, not expanded (its numbers are all a diagnosis needs)."""
    out = sp.eye(4)
    for s, q in zip(axes, variables, strict=True):
        out = out * matrix_exp(s, q)
    return out


def _regarded(M: Matrix, wrong: sp.Matrix) -> Matrix:
    """``[Ad_(M'^-1 M)]``: carries the body twists of home ``M`` to those of home ``M'``."""
    return adjoint(sp.Matrix(rigid_inverse(Matrix(wrong)) * M).applyfunc(sp.expand))


#: ``(ω, v) → (ω, −v)``
_FLIP = Matrix(sp.diag(1, 1, 1, -1, -1, -1))


def _flipped_jacobian(poe: ProductOfExponentials, part: str, J: Matrix) -> Matrix:
    """``J_s`` (``part`` ``Js``) or ``J_b`` built on the axes with ``ω × q`` for ``−ω × q``.

    With revolute joints only this is ``J`` with its ``v`` rows negated: each flipped axis
    is its axis reflected through the origin, :math:`e^{[S_i']θ} = P e^{[S_i]θ} P` with
    ``P = diag(−1, −1, −1, 1)``, which keeps ``ω`` and negates ``v`` of every twist (the
    same for the body axes).  A prismatic joint's axis is not flipped, so then the
    Jacobian is derived again from the flipped axes.
    """
    if all(s.is_revolute for s in poe.space):
        return Matrix(_FLIP * J)
    if part == "Js":
        return _with_space(poe, _flipped(poe.space)).jacobian_space().matrix
    return _from_body(poe, _flipped(poe.body)).jacobian_body().matrix


def _swapped(X: Matrix) -> Matrix:
    return Matrix.vstack(X[3:, :], X[:3, :])


def _with_space(poe: ProductOfExponentials, space: tuple[ScrewAxis, ...]) -> ProductOfExponentials:
    return ProductOfExponentials(poe.name, poe.variables, space, poe.home, poe.notation)


def _from_body(poe: ProductOfExponentials, body: tuple[ScrewAxis, ...]) -> ProductOfExponentials:
    """The PoE whose body axes are ``body`` (its space axes ``[Ad_M] B_i``)."""
    Ad = adjoint(poe.home)
    space = tuple(ScrewAxis.from_vector(Ad * b.vector) for b in body)
    return _with_space(poe, space)


def _homes(robot: Robot) -> list[tuple[sp.Matrix, str]]:
    """The wrong home configurations: the pose at home of every other frame of the chain,
    and the tool's pose where the table's entries (not the joint variables) are zero."""
    k, e = resolve_frame(robot, "base"), resolve_frame(robot, "tool")
    home = {q: 0 for q in robot.variables}
    out = []
    last = robot.n + 1 if robot.table.tool else robot.n
    for j in range(max(k, 0), last + 1):
        if j in (k, e):
            continue
        what = "the tool" if j == robot.n + 1 else f"frame {j}"
        out.append(
            (
                sp.Matrix(robot.transform(k, j).matrix).xreplace(home),
                f"M is the pose of {what} at home, not of the end-effector frame ({_end(robot)}): "
                "M is the pose of the last frame, the one T(theta) is the pose of, with every "
                "joint variable zero.",
            )
        )
    zeros: dict[sp.Symbol, sp.Expr] = {}
    for row in robot.table.rows:
        if row.variable is None:
            continue
        entry = row.theta if row.variable in row.theta.free_symbols else row.d
        rate, offset = sp.diff(entry, row.variable), entry.xreplace({row.variable: 0})
        if rate != 0 and offset != 0:
            zeros[row.variable] = -offset / rate
    if zeros:
        at = {**home, **zeros}
        shown = ", ".join(f"{q} = {sp.sstr(v)}" for q, v in zeros.items())
        out.append(
            (
                sp.Matrix(robot.transform(k, e).matrix).xreplace(at),
                f"M is read where the table's entries are zero ({shown}), not at home: the home "
                "configuration is the pose with every joint variable zero, offsets kept.",
            )
        )
    return out


def _end(robot: Robot) -> str:
    e = resolve_frame(robot, "tool")
    return "the tool" if e == robot.n + 1 else f"frame {e}"


def screw_variants(robot: Robot, part: str) -> tuple[tuple[str, Matrix, str], ...]:
    """The whole key of ``part`` (``S``, ``B``, ``Mhome``, ``Js``, ``Jb`` or ``T``) under each
    catalogued mistake: ``(kind, matrix, detail)``, exact (see the module text).

    >>> import dhsym
    >>> print(*sorted({k for k, _, _ in screw_variants(dhsym.load("planar2r"), "T")}))
    body_for_space omega_cross_q reverse_order space_for_body transposed wrong_home
    """
    poe = robot.poe()
    S, B, M, q = poe.space, poe.body, poe.home, poe.variables
    revolute = any(s.is_revolute for s in S)
    out: Variants = []
    if part in ("S", "B"):
        own, other = (S, B) if part == "S" else (B, S)
        if revolute:
            flips = _one_by_one(own, part)
            out += [("omega_cross_q", _columns(axes), detail) for axes, detail in flips]
        kind = "body_for_space" if part == "S" else "space_for_body"
        given, asked = ("body", "space") if part == "S" else ("space", "body")
        out.append(
            (
                kind,
                _columns(other),
                f"These are the {given} axes ({given[0].upper()}_i); the {asked} axes are asked"
                + (
                    ": S_i is joint i's axis in the space frame at home, B_i = [Ad_(M^-1)] S_i "
                    "the same axis seen from the end-effector frame."
                ),
            )
        )
        out.append(("rows_swapped", _swapped(_columns(own)), _ROWS.format(book=_BOOK)))
        if part == "B":  # on M': B_i' = [Ad_(M'^-1)] S_i = [Ad_(M'^-1 M)] B_i
            for home, detail in _homes(robot):
                out.append(("wrong_home", Matrix(_regarded(M, home) * _columns(B)), detail))
    elif part in ("Js", "Jb"):
        Js, Jb = robot.jacobian_space().matrix, robot.jacobian_body().matrix
        own, other = (Js, Jb) if part == "Js" else (Jb, Js)
        if revolute:
            which = "the revolute axes " + ("S_i" if part == "Js" else "B_i")
            sign = _SIGN.format(which=which, book=_BOOK)
            out.append(("omega_cross_q", _flipped_jacobian(poe, part, own), sign))
        given, asked = ("J_b", "J_s") if part == "Js" else ("J_s", "J_b")
        out.append(
            (
                "body_for_space" if part == "Js" else "space_for_body",
                other,
                f"This is {given}; {asked} is asked: J_s = [Ad_T] J_b, J_s has the twists in the "
                "space frame, J_b in the end-effector frame.",
            )
        )
        out.append(("rows_swapped", _swapped(own), _ROWS.format(book=_BOOK)))
        if part == "Jb":  # on M': J_b' = [Ad_(M'^-1 M)] J_b, as T' = T M^-1 M'
            for home, detail in _homes(robot):
                out.append(("wrong_home", Matrix(_regarded(M, home) * Jb), detail))
    elif part == "Mhome":
        for home, detail in _homes(robot):
            out.append(("wrong_home", Matrix(home), detail))
        out += _transposed(M, "M")
    else:  # T(theta)
        P = _exps(S, q)
        if revolute:
            for axes, detail in _one_by_one(S, "S"):
                out.append(("omega_cross_q", Matrix(_exps(axes, q) * M), detail))
            for axes, detail in _one_by_one(B, "B"):
                out.append(("omega_cross_q", Matrix(M * _exps(axes, q)), detail))
        out.append(
            (
                "body_for_space",
                Matrix(_exps(B, q) * M),
                "The body axes are used in the space form e^([S1]theta1) ... e^([Sn]thetan) M: "
                "with B_i, M comes first, T = M e^([B1]theta1) ... e^([Bn]thetan).",
            )
        )
        out.append(
            (
                "space_for_body",
                Matrix(M * _exps(S, q)),
                "M is put first with the space axes: with S_i, M comes last, "
                "T = e^([S1]theta1) ... e^([Sn]thetan) M (M first belongs to the body axes B_i).",
            )
        )
        out.append(
            (
                "reverse_order",
                Matrix(_exps(S[::-1], q[::-1]) * M),
                "The exponentials are multiplied from the last joint: "
                "T = e^([S1]theta1) e^([S2]theta2) ... e^([Sn]thetan) M, joint 1 on the left.",
            )
        )
        for home, detail in _homes(robot):
            out.append(("wrong_home", Matrix(P * home), detail))
        out += _transposed(Matrix(P * M), "T(theta)")
    return tuple(out)


def _transposed(X: Matrix, name: str) -> Variants:
    rot = sp.Matrix(X)
    rot[:3, :3] = X[:3, :3].T
    return [
        (
            "transposed",
            Matrix(X.T),
            f"Rows and columns of {name} are exchanged: its columns are the axes x, y, z of the "
            "end-effector frame and its position, in the space frame.",
        ),
        (
            "transposed",
            Matrix(rot),
            f"The rotation of {name} is transposed (that is the inverse rotation, R^T = R^-1).",
        ),
    ]
