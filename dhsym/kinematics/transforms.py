"""Elementary 4×4 transforms, link matrices as words of elementaries, plain products.

A link matrix is the product of four elementary transforms (Mohan, Lecture 9,
Transformations 1–4):

* standard:  ``A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)``
* modified:  ``^{i-1}T_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)``

Everything here is exact; this module multiplies plainly (the reference that
:mod:`dhsym.kinematics.simplification` is checked against).

Examples
--------
>>> from dhsym.model.table import DHRow, Convention
>>> row = DHRow.revolute("theta1", a="a1")
>>> link_word(row, Convention.STANDARD)
(Rz(theta1), Tz(0), Tx(a1), Rx(0))
>>> link_matrix(row, Convention.STANDARD)
Matrix([
[cos(theta1), -sin(theta1), 0, a1*cos(theta1)],
[sin(theta1),  cos(theta1), 0, a1*sin(theta1)],
[          0,            0, 1,              0],
[          0,            0, 0,              1]])
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TypeAlias

import sympy as sp

from dhsym.model.table import Convention, DHRow, DHTable, Elementary

from .constants import as_basic, to_float

__all__ = [
    "Rx",
    "Ry",
    "Rz",
    "Tx",
    "Ty",
    "Tz",
    "chain_word",
    "cos_sin",
    "elementary_matrix",
    "link_matrix",
    "link_word",
    "plain_product",
    "rigid_inverse",
]

Matrix: TypeAlias = sp.ImmutableMatrix


def cos_sin(angle: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """``cos`` and ``sin`` of an angle: exact, except for a number that is not a multiple of π.

    A twist written as a decimal that stands for no multiple of π/12 (1.2 rad,
    see :mod:`dhsym.model.angles`) is a measured number: its cosine and sine are
    floats, so products fold into numbers instead of ``cos(6/5)`` terms.

    >>> cos_sin(sp.pi / 3), cos_sin(sp.Symbol("t"))
    ((1/2, sqrt(3)/2), (cos(t), sin(t)))
    >>> cos_sin(sp.Rational(6, 5))
    (0.362357754476674, 0.932039085967226)
    """
    angle = as_basic(angle)  # a Python number becomes sympy's; text is refused
    c, s = sp.cos(angle), sp.sin(angle)
    if angle.free_symbols or not (c.has(sp.cos, sp.sin) or s.has(sp.cos, sp.sin)):
        return c, s
    if (angle / sp.pi).is_rational:  # an exact angle such as pi/7 stays exact
        return c, s
    return sp.Float(to_float(c)), sp.Float(to_float(s))


def Rx(angle: sp.Expr) -> Matrix:
    """Rotation about x by ``angle`` as a 4×4 homogeneous matrix.

    >>> Rx(sp.pi / 2)
    Matrix([
    [1, 0,  0, 0],
    [0, 0, -1, 0],
    [0, 1,  0, 0],
    [0, 0,  0, 1]])
    """
    c, s = cos_sin(angle)
    return Matrix([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def Ry(angle: sp.Expr) -> Matrix:
    """Rotation about y by ``angle`` (4×4)."""
    c, s = cos_sin(angle)
    return Matrix([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]])


def Rz(angle: sp.Expr) -> Matrix:
    """Rotation about z by ``angle`` (4×4).

    >>> Rz(sp.Symbol("t"))[:2, :2]
    Matrix([
    [cos(t), -sin(t)],
    [sin(t),  cos(t)]])
    """
    c, s = cos_sin(angle)
    return Matrix([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def _translation(x: sp.Expr = 0, y: sp.Expr = 0, z: sp.Expr = 0) -> Matrix:
    x, y, z = as_basic(x), as_basic(y), as_basic(z)  # never text: Matrix would sympify it
    return Matrix([[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]])


def Tx(distance: sp.Expr) -> Matrix:
    """Translation along x (4×4).

    >>> Tx(3)[0, 3]
    3
    """
    return _translation(x=distance)


def Ty(distance: sp.Expr) -> Matrix:
    """Translation along y (4×4)."""
    return _translation(y=distance)


def Tz(distance: sp.Expr) -> Matrix:
    """Translation along z (4×4)."""
    return _translation(z=distance)


_BUILDERS = {
    ("R", "x"): Rx,
    ("R", "y"): Ry,
    ("R", "z"): Rz,
    ("T", "x"): Tx,
    ("T", "y"): Ty,
    ("T", "z"): Tz,
}


def elementary_matrix(e: Elementary) -> Matrix:
    """The 4×4 matrix of one elementary transform.

    >>> elementary_matrix(Elementary("T", "z", 5))[2, 3]
    5
    """
    return _BUILDERS[(e.kind, e.axis)](e.value)


def link_word(row: DHRow, convention: Convention) -> tuple[Elementary, ...]:
    """The four elementary transforms of a link matrix, in multiplication order.

    >>> from dhsym.model.table import DHRow, Convention
    >>> link_word(DHRow.revolute("theta2", d="d2", a="a1", alpha="alpha1"), Convention.MODIFIED)
    (Rx(alpha1), Tx(a1), Rz(theta2), Tz(d2))
    """
    if Convention(convention) is Convention.STANDARD:
        return (
            Elementary("R", "z", row.theta),
            Elementary("T", "z", row.d),
            Elementary("T", "x", row.a),
            Elementary("R", "x", row.alpha),
        )
    return (
        Elementary("R", "x", row.alpha),
        Elementary("T", "x", row.a),
        Elementary("R", "z", row.theta),
        Elementary("T", "z", row.d),
    )


def plain_product(word: Sequence[Elementary]) -> Matrix:
    """Multiply the elementary matrices of ``word`` left to right, with no simplification.

    >>> plain_product([Elementary("R", "z", 0), Elementary("T", "x", 2)])[0, 3]
    2
    """
    out = sp.eye(4)
    for e in word:
        out = out * elementary_matrix(e)
    return Matrix(out)


def link_matrix(row: DHRow, convention: Convention) -> Matrix:
    """The link matrix of one row, as the plain product of its four factors."""
    return plain_product(link_word(row, convention))


def inverse_word(word: Sequence[Elementary]) -> tuple[Elementary, ...]:
    """The word of the inverse transform: the factors reversed, each inverted.

    >>> inverse_word((Elementary("R", "z", sp.Symbol("q")), Elementary("T", "x", 2)))
    (Tx(-2), Rz(-q))
    """
    return tuple(e.inverse() for e in reversed(word))


def chain_word(table: DHTable, i: int, j: int) -> tuple[Elementary, ...]:
    """The elementary word of ``^iT_j`` between DH frames ``i`` and ``j`` (0 … n).

    For ``j < i`` the word is the exact inverse: the factors of ``^jT_i``
    reversed, each inverted (a rigid inverse, never a generic matrix inverse).
    Frame ``-1`` is the world frame before ``table.base``; frame ``n + 1`` is the
    tool frame after ``table.tool``.

    >>> from dhsym.model.table import DHRow, DHTable
    >>> t = DHTable.from_rows([DHRow.revolute("q1", a="a1"), DHRow.revolute("q2", a="a2")])
    >>> chain_word(t, 2, 1)
    (Rx(0), Tx(-a2), Tz(0), Rz(-q2))
    """
    n = table.n
    if not (-1 <= i <= n + 1 and -1 <= j <= n + 1):
        raise IndexError(f"frames are numbered -1 (world) … {n + 1} (tool); got {i}, {j}")
    if j < i:
        return inverse_word(chain_word(table, j, i))
    word: list[Elementary] = []
    if i == -1 and j >= 0:
        word.extend(table.base)
    for k in range(max(i, 0) + 1, min(j, n) + 1):
        word.extend(link_word(table.rows[k - 1], table.convention))
    if j == n + 1 and i <= n:
        word.extend(table.tool)
    return tuple(word)


def rigid_inverse(T: sp.MatrixBase) -> Matrix:
    """Inverse of a homogeneous transform as ``[Rᵀ, −Rᵀp; 0 0 0 1]``.

    >>> T = Rz(sp.Symbol("t")) * Tx(1)
    >>> sp.simplify(rigid_inverse(T) * T) == sp.eye(4)
    True
    """
    R = T[:3, :3].T
    p = -R * T[:3, 3]
    out = sp.eye(4)
    out[:3, :3] = R
    out[:3, 3] = p
    return Matrix(out)
