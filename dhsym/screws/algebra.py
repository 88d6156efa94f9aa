r"""Screws, twists and the exponential coordinates of rigid motions, exact.

The algebra of Lynch and Park, *Modern Robotics*, chapter 3, with vectors ordered
``[ω; v]`` (angular part first, as the book writes them):

* a **screw axis** :math:`\mathcal{S} = (\omega, v)`: for a revolute joint ``ω`` is the unit
  direction of the axis and :math:`v = -\omega \times q` for a point ``q`` on it (plus
  ``h ω`` for a screw of pitch ``h``); for a prismatic joint ``ω = 0`` and ``v`` is the
  unit direction of motion;
* its matrix :math:`[\mathcal{S}] = \begin{bmatrix}[\omega] & v \\ 0 & 0\end{bmatrix}`
  in se(3), ``[ω]`` the skew-symmetric matrix of ``ω``;
* the matrix exponential :math:`e^{[\mathcal{S}]\theta}` in closed form (Rodrigues' formula,
  Proposition 3.25): :math:`R = I + \sin\theta\,[\omega] + (1 - \cos\theta)[\omega]^2`,
  :math:`p = (I\theta + (1 - \cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2)\,v`;
  ``R = I``, ``p = vθ`` when ``ω = 0`` (no matrix exponential of sympy is used);
* the matrix logarithm (Algorithm of §3.3.3.2) with its special cases ``R = I`` (a
  translation, or ``θ = 0``) and ``tr R = −1`` (``θ = π``);
* the adjoint :math:`[\mathrm{Ad}_T] = \begin{bmatrix}R & 0 \\ [p]R & R\end{bmatrix}`,
  which carries a twist from one frame to another.

Everything is exact: entries are sympy numbers or expressions, and
:class:`Exponential` prints the factor the way the lecture writes it,
:math:`e^{[\mathcal{S}_1]\theta_1}`, through sympy's printing hooks.

Examples
--------
>>> import sympy as sp
>>> t = sp.Symbol("theta1", real=True)
>>> S = ScrewAxis.revolute((0, 0, 1), (1, 0, 0))
>>> S.vector.T
Matrix([[0, 0, 1, 0, -1, 0]])
>>> matrix_exp(S, t)
Matrix([
[cos(theta1), -sin(theta1), 0, 1 - cos(theta1)],
[sin(theta1),  cos(theta1), 0,    -sin(theta1)],
[          0,            0, 1,               0],
[          0,            0, 0,               1]])
>>> log = matrix_log(matrix_exp(S, sp.pi / 2))
>>> log.screw.vector.T, log.theta
(Matrix([[0, 0, 1, 0, -1, 0]]), pi/2)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeAlias

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.constants import as_basic
from dhsym.model.entries import as_expr
from dhsym.notation.printers import Notation

__all__ = [
    "Exponential",
    "MatrixLog",
    "ScrewAxis",
    "adjoint",
    "bracket",
    "is_zero",
    "matrix_exp",
    "matrix_log",
    "skew",
    "unskew",
]

Matrix: TypeAlias = sp.ImmutableMatrix


def is_zero(expr: sp.Expr) -> bool:
    """Whether an exact expression is zero (numbers at once, else after ``simplify``).

    >>> t = sp.Symbol("t", real=True)
    >>> is_zero(sp.cos(t) ** 2 + sp.sin(t) ** 2 - 1), is_zero(sp.sqrt(2) - 1)
    (True, False)
    """
    expr = as_basic(expr)  # a sympy object or a Python number: text is refused
    if expr == 0:
        return True
    if not expr.free_symbols:
        return bool(sp.radsimp(sp.nsimplify(expr) if expr.has(sp.Float) else expr).equals(0))
    return bool(sp.simplify(expr) == 0)


def _column(values: object, what: str) -> Matrix:
    """A 3×1 exact column from a sympy matrix or a sequence (text read by the whitelist)."""
    if isinstance(values, sp.MatrixBase):
        items = list(values)
    elif isinstance(values, Sequence) and not isinstance(values, str):
        items = list(values)
    else:
        raise DHError(f"{what} must be three numbers, got {values!r}")
    if len(items) != 3:
        raise DHError(f"{what} must be three numbers, got {len(items)}")
    return Matrix([as_expr(x, field=what) for x in items])


def skew(w: object) -> Matrix:
    r"""The skew-symmetric matrix :math:`[\omega]` of a 3-vector, ``[ω] x = ω × x``.

    >>> skew((1, 2, 3))
    Matrix([
    [ 0, -3,  2],
    [ 3,  0, -1],
    [-2,  1,  0]])
    """
    x, y, z = _column(w, "omega")
    return Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def unskew(W: sp.MatrixBase) -> Matrix:
    """The vector of a skew-symmetric 3×3 matrix (the inverse of :func:`skew`).

    >>> unskew(skew((1, 2, 3))).T
    Matrix([[1, 2, 3]])
    """
    return Matrix([W[2, 1], W[0, 2], W[1, 0]])


@dataclass(frozen=True)
class ScrewAxis:
    r"""A screw axis (or a twist) :math:`\mathcal{S} = (\omega, v)`, exact, rows ``[ω; v]``.

    ``omega`` and ``v`` are 3×1 exact columns. A *screw axis* has ``‖ω‖ = 1`` or
    (prismatic) ``ω = 0`` and ``‖v‖ = 1``; :meth:`check` says which rule fails. A
    general twist (a velocity) is the same value without the rule.

    >>> ScrewAxis.prismatic((0, 1, 0)).vector.T
    Matrix([[0, 0, 0, 0, 1, 0]])
    >>> ScrewAxis.revolute((0, 0, 2), (0, 0, 0))
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: a revolute screw axis needs a unit omega: |omega|^2 = 4
    """

    omega: Matrix
    v: Matrix

    def __post_init__(self) -> None:
        object.__setattr__(self, "omega", _column(self.omega, "omega"))
        object.__setattr__(self, "v", _column(self.v, "v"))

    @classmethod
    def revolute(cls, omega: object, point: object, pitch: object = 0) -> ScrewAxis:
        r"""The axis of a revolute joint (or a screw of ``pitch`` h) about the unit ``omega``
        through ``point``: :math:`v = -\omega \times q + h\,\omega`.

        >>> ScrewAxis.revolute((0, 0, 1), (0, "L1", 0)).v.T
        Matrix([[L1, 0, 0]])
        """
        w = _column(omega, "omega")
        q = _column(point, "point")
        h = as_expr(pitch, field="pitch")
        screw = cls(w, Matrix(-w.cross(q) + h * w))
        screw.check(revolute=True)
        return screw

    @classmethod
    def prismatic(cls, direction: object) -> ScrewAxis:
        """The axis of a prismatic joint sliding along the unit ``direction``: ``ω = 0``, ``v``."""
        screw = cls(Matrix.zeros(3, 1), _column(direction, "v"))
        screw.check(revolute=False)
        return screw

    @classmethod
    def from_vector(cls, vector: object) -> ScrewAxis:
        """A twist from the six numbers ``[ω; v]``.

        >>> ScrewAxis.from_vector([0, 0, 1, 0, -2, 0]).v.T
        Matrix([[0, -2, 0]])
        """
        items = list(vector) if isinstance(vector, (sp.MatrixBase, Sequence)) else []
        if len(items) != 6 or isinstance(vector, str):
            raise DHError(f"a twist is six numbers [omega; v], got {vector!r}")
        return cls(Matrix(items[:3]), Matrix(items[3:]))

    @property
    def vector(self) -> Matrix:
        """The 6×1 column ``[ω; v]``."""
        return Matrix.vstack(self.omega, self.v)

    @property
    def is_revolute(self) -> bool:
        """True when ``ω ≠ 0`` (a rotation about the axis), False for a pure translation."""
        return not all(is_zero(w) for w in self.omega)

    def check(self, *, revolute: bool | None = None) -> None:
        """Raise :class:`~dhsym.errors.DHError` unless this is a screw axis: ``‖ω‖ = 1`` (and,
        ``revolute=True``, ``ω·v = 0``: no pitch) or ``ω = 0`` with ``‖v‖ = 1``.

        >>> ScrewAxis((0, 0, 1), (0, 0, 1)).check(revolute=True)
        Traceback (most recent call last):
        ...
        dhsym.errors.DHError: a revolute joint's axis needs omega·v = 0 (no pitch): omega·v = 1
        """
        kind = self.is_revolute if revolute is None else revolute
        if kind:
            n2 = sp.expand(self.omega.dot(self.omega))
            if not is_zero(n2 - 1):
                raise DHError(f"a revolute screw axis needs a unit omega: |omega|^2 = {n2}")
            if revolute:
                wv = sp.expand(self.omega.dot(self.v))
                if not is_zero(wv):
                    raise DHError(
                        f"a revolute joint's axis needs omega·v = 0 (no pitch): omega·v = {wv}"
                    )
            return
        if not all(is_zero(w) for w in self.omega):
            raise DHError(f"a prismatic screw axis has omega = 0, got {tuple(self.omega)}")
        n2 = sp.expand(self.v.dot(self.v))
        if not is_zero(n2 - 1):
            raise DHError(f"a prismatic screw axis needs a unit v: |v|^2 = {n2}")

    def point(self) -> Matrix:
        r"""The point of a revolute axis nearest the origin, :math:`q = \omega \times v`
        (for a unit ``ω`` with ``ω·v = 0``).

        >>> ScrewAxis.revolute((0, 0, 1), (3, 4, 5)).point().T
        Matrix([[3, 4, 0]])
        """
        return Matrix(self.omega.cross(self.v).applyfunc(sp.expand))

    def bracket(self) -> Matrix:
        """``[S]``, the 4×4 matrix in se(3) (:func:`bracket`)."""
        return bracket(self)

    def scaled(self, k: sp.Expr) -> ScrewAxis:
        """The twist ``k S``."""
        return ScrewAxis(Matrix(k * self.omega), Matrix(k * self.v))

    def _sympystr(self, printer: object) -> str:
        return f"ScrewAxis({list(self.vector)})"


def _screw(S: ScrewAxis | object) -> ScrewAxis:
    return S if isinstance(S, ScrewAxis) else ScrewAxis.from_vector(S)


def bracket(S: ScrewAxis | object) -> Matrix:
    r"""The 4×4 matrix :math:`[\mathcal{S}] = \begin{bmatrix}[\omega] & v\\0 & 0\end{bmatrix}`.

    >>> bracket([0, 0, 1, 0, -1, 0])
    Matrix([
    [0, -1, 0,  0],
    [1,  0, 0, -1],
    [0,  0, 0,  0],
    [0,  0, 0,  0]])
    """
    s = _screw(S)
    out = sp.zeros(4, 4)
    out[:3, :3] = skew(s.omega)
    out[:3, 3] = s.v
    return Matrix(out)


def matrix_exp(S: ScrewAxis | object, theta: object) -> Matrix:
    r"""The rigid motion :math:`e^{[\mathcal{S}]\theta}` in closed form (Rodrigues' formula).

    For ``‖ω‖ = 1``: :math:`R = I + \sin\theta[\omega] + (1-\cos\theta)[\omega]^2` and
    :math:`p = (I\theta + (1-\cos\theta)[\omega] + (\theta-\sin\theta)[\omega]^2)v`; for
    ``ω = 0``: ``R = I``, ``p = vθ``. A twist whose ``ω`` is not a unit vector is written
    as the unit axis ``S/‖ω‖`` turned by ``‖ω‖θ`` (Lynch and Park, §3.3.3).

    >>> d = sp.Symbol("d3", real=True)
    >>> matrix_exp(ScrewAxis.prismatic((0, 0, 1)), d)[:3, 3].T
    Matrix([[0, 0, d3]])
    >>> matrix_exp([0, 0, 2, 0, 0, 0], sp.pi / 4)[:2, :2]
    Matrix([
    [0, -1],
    [1,  0]])
    """
    s = _screw(S)
    th = as_expr(theta, field="theta")
    if not s.is_revolute:
        out = sp.eye(4)
        out[:3, 3] = (s.v * th).applyfunc(sp.expand)
        return Matrix(out)
    n2 = sp.expand(s.omega.dot(s.omega))
    if not is_zero(n2 - 1):
        n = sp.sqrt(n2)
        s, th = ScrewAxis(Matrix(s.omega / n), Matrix(s.v / n)), n * th
    W = skew(s.omega)
    W2 = W * W
    c, sn = sp.cos(th), sp.sin(th)
    R = sp.eye(3) + sn * W + (1 - c) * W2
    p = (sp.eye(3) * th + (1 - c) * W + (th - sn) * W2) * s.v
    out = sp.eye(4)
    out[:3, :3] = R.applyfunc(sp.expand)
    out[:3, 3] = p.applyfunc(sp.expand)
    return Matrix(out)


def adjoint(T: sp.MatrixBase) -> Matrix:
    r"""The 6×6 adjoint :math:`[\mathrm{Ad}_T] = \begin{bmatrix}R & 0\\ [p]R & R\end{bmatrix}`
    of a transform: :math:`\mathcal{V}_a = [\mathrm{Ad}_{T_{ab}}]\mathcal{V}_b` (rows ``[ω; v]``).

    >>> from dhsym.kinematics.transforms import Tx
    >>> (adjoint(Tx(2)) * sp.Matrix([0, 0, 1, 0, 0, 0])).T
    Matrix([[0, 0, 1, 0, -2, 0]])
    """
    R = sp.Matrix(T[:3, :3])
    out = sp.zeros(6, 6)
    out[:3, :3] = R
    out[3:, 3:] = R
    out[3:, :3] = (skew(T[:3, 3]) * R).applyfunc(sp.expand)
    return Matrix(out)


@dataclass(frozen=True)
class MatrixLog:
    r"""The exponential coordinates :math:`\mathcal{S}\theta` of a transform: ``screw`` (a
    unit screw axis) and ``theta``; ``T = matrix_exp(screw, theta)``. For the identity,
    ``θ = 0`` and the screw is the zero twist (any axis would do)."""

    screw: ScrewAxis
    theta: sp.Expr

    @property
    def twist(self) -> Matrix:
        """The 6×1 exponential coordinates ``S θ``."""
        return Matrix(self.screw.vector * self.theta)


def _tidy(expr: sp.Expr) -> sp.Expr:
    expr = sp.radsimp(sp.simplify(expr))
    return sp.Integer(0) if is_zero(expr) else expr


def matrix_log(T: sp.MatrixBase) -> MatrixLog:
    r"""The matrix logarithm of a rigid transform: ``S`` and ``θ`` with ``e^{[S]θ} = T``.

    Lynch and Park, §3.3.3.2: ``R = I`` gives ``ω = 0``, ``v = p/‖p‖``, ``θ = ‖p‖`` (or
    ``θ = 0``); ``tr R = −1`` gives ``θ = π`` and ``ω`` from a column of ``R + I``;
    otherwise ``θ = arccos((tr R − 1)/2)``, :math:`[\omega] = (R - R^T)/(2\sin\theta)`.
    Then :math:`v = G^{-1}(\theta)p`,
    :math:`G^{-1} = I/\theta - [\omega]/2 + (1/\theta - \cot(\theta/2)/2)[\omega]^2`.

    >>> from dhsym.kinematics.transforms import Rx, Tz
    >>> L = matrix_log(Rx(sp.pi))
    >>> L.screw.vector.T, L.theta
    (Matrix([[1, 0, 0, 0, 0, 0]]), pi)
    >>> L = matrix_log(Tz(3))
    >>> L.screw.vector.T, L.theta
    (Matrix([[0, 0, 0, 0, 0, 1]]), 3)
    """
    T = sp.Matrix(T)
    if T.shape != (4, 4):
        raise DHError(f"the matrix logarithm takes a 4×4 transform, got {T.shape}")
    R, p = T[:3, :3], T[:3, 3]
    zero = Matrix.zeros(3, 1)
    if all(is_zero(e) for e in (R - sp.eye(3))):
        dist2 = sp.expand(p.dot(p))
        if is_zero(dist2):
            return MatrixLog(ScrewAxis(zero, zero), sp.Integer(0))
        dist = _tidy(sp.sqrt(dist2))
        return MatrixLog(ScrewAxis(zero, Matrix(p / dist).applyfunc(_tidy)), dist)
    trace = sp.expand(R.trace())
    if is_zero(trace + 1):
        theta: sp.Expr = sp.pi
        for k in (2, 1, 0):  # the column of R + I with a non-zero diagonal entry
            if not is_zero(1 + R[k, k]):
                w = (R[:, k] + sp.eye(3)[:, k]) / sp.sqrt(2 * (1 + R[k, k]))
                break
        omega = Matrix(w).applyfunc(_tidy)
    else:
        theta = _tidy(sp.acos((trace - 1) / 2))
        omega = Matrix(unskew((R - R.T) / (2 * sp.sin(theta)))).applyfunc(_tidy)
    W = skew(omega)
    G_inv = sp.eye(3) / theta - W / 2 + (1 / theta - sp.cot(theta / 2) / 2) * W * W
    v = Matrix(G_inv * p).applyfunc(_tidy)
    return MatrixLog(ScrewAxis(omega, v), theta)


@dataclass(frozen=True, repr=False)
class Exponential:
    r"""One factor :math:`e^{[\mathcal{S}_i]\theta_i}` of a product of exponentials, as the
    lecture prints it; ``matrix`` is its closed form (:func:`matrix_exp`).

    ``letter`` is ``S`` (a space axis) or ``B`` (a body axis).

    >>> t = sp.Symbol("theta1", real=True)
    >>> E = Exponential.of(ScrewAxis.revolute((0, 0, 1), (0, 0, 0)), t, 1)
    >>> sp.latex(E), str(E)
    ('e^{[\\mathcal{S}_{1}]\\theta_{1}}', 'e^([S1]*theta1)')
    >>> print(E.notation.text(E.matrix))
    Matrix([
    [C1, -S1, 0, 0],
    [S1,  C1, 0, 0],
    [ 0,   0, 1, 0],
    [ 0,   0, 0, 1]])
    """

    screw: ScrewAxis
    variable: sp.Symbol
    index: int
    letter: str = "S"
    notation: Notation = Notation()

    @classmethod
    def of(
        cls,
        screw: ScrewAxis,
        variable: sp.Symbol,
        index: int,
        letter: str = "S",
        notation: Notation | None = None,
    ) -> Exponential:
        """The factor of joint ``index``; the notation labels ``variable`` by default."""
        if notation is None:
            notation = Notation.from_variables([variable], [str(index)])
        return cls(screw, variable, index, letter, notation)

    @property
    def matrix(self) -> Matrix:
        """The closed form :math:`e^{[\\mathcal{S}]\\theta}`."""
        return matrix_exp(self.screw, self.variable)

    def latex(self) -> str:
        """``e^{[\\mathcal{S}_1]\\theta_1}``."""
        return rf"e^{{[\mathcal{{{self.letter}}}_{{{self.index}}}]{sp.latex(self.variable)}}}"

    def text(self) -> str:
        """``e^([S1]*theta1)``."""
        return f"e^([{self.letter}{self.index}]*{self.variable})"

    def _latex(self, printer: object) -> str:
        return self.latex()

    def _sympystr(self, printer: object) -> str:
        return self.text()

    def __str__(self) -> str:
        return self.text()

    def __repr__(self) -> str:
        return self.text()

    def _repr_latex_(self) -> str:
        return f"$${self.latex()} = {self.notation.latex(self.matrix)}$$"
