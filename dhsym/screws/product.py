r"""A robot as a product of exponentials (PoE), exact: from a DH table, its fk and Jacobians.

Lynch and Park, *Modern Robotics*, chapter 4: with the joints at zero the tool is at
its *home configuration* ``M``; joint ``i`` moves about (along) its *screw axis*
``S_i``, written in the space frame at home, and

.. math::

    T(\theta) = e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_n]\theta_n} M
              = M e^{[\mathcal{B}_1]\theta_1} \cdots e^{[\mathcal{B}_n]\theta_n},
    \qquad \mathcal{B}_i = [\mathrm{Ad}_{M^{-1}}]\,\mathcal{S}_i .

**From a DH table.** The space frame is the frame of the DH ``fk`` (the world frame when
the table has a base transform, else frame 0) and the tool frame is its end (the tool
frame after a tool transform, else frame n); ``M`` is that pose at ``q = 0``. Joint ``i``
turns about (slides along) the ``z`` axis of one DH frame: frame ``i − 1`` in the standard
convention, frame ``i`` in the modified (Craig) one. At home that frame's ``z`` column
is ``ω_i`` and its origin a point ``q_i`` on the axis, so ``S_i = (ω_i, −ω_i × q_i)``:
a point ``p`` of the turning body moves with :math:`\dot p = \omega \times (p - q) =
\omega \times p + v`, hence :math:`v = -\omega \times q` (the velocity of the body point
at the space origin). A prismatic joint gives ``S_i = (0, z)``. A table entry that is
``−q`` or ``2 q`` scales the axis by the rate.

**Jacobians** (§5.1): the space Jacobian's column ``i`` is
:math:`[\mathrm{Ad}_{e^{[\mathcal{S}_1]\theta_1}\cdots
e^{[\mathcal{S}_{i-1}]\theta_{i-1}}}]\mathcal{S}_i`,
the body Jacobian's :math:`[\mathrm{Ad}_{e^{-[\mathcal{B}_n]\theta_n}\cdots
e^{-[\mathcal{B}_{i+1}]\theta_{i+1}}}]\mathcal{B}_i`, and :math:`J_s = [\mathrm{Ad}_{T}]J_b`.
Rows are ``[ω; v]``. dhsym's DH :meth:`~dhsym.kinematics.chain.KinematicChain.jacobian`
has rows ``[v; ω]`` with ``v`` the velocity of the *tool origin*; so, with ``p`` the tool
position, :math:`J_b = \begin{bmatrix}0 & I\\ I & 0\end{bmatrix} J_{\text{tool}}` and
:math:`J_s = \begin{bmatrix}0 & I\\ I & [p]\end{bmatrix} J_{\text{base}}`
(:func:`space_from_geometric`, :func:`body_from_geometric`).

Examples
--------
>>> import dhsym
>>> poe = from_chain(dhsym.load("planar2r"))
>>> poe.screw_matrix("space")
Matrix([
[0, 0],
[0, 0],
[1, 1],
[0, 0],
[0, -a1],
[0, 0]])
>>> print(poe.notation.text(poe.home))
Matrix([
[1, 0, 0, a1 + a2],
[0, 1, 0,       0],
[0, 0, 1,       0],
[0, 0, 0,       1]])
>>> print(poe.fk_space().text())
Matrix([
[C12, -S12, 0, a1*C1 + a2*C12],
[S12,  C12, 0, a1*S1 + a2*S12],
[  0,    0, 1,              0],
[  0,    0, 0,              1]])
>>> poe.formula_text("space")
'T(theta) = e^([S1]*theta1) e^([S2]*theta2) M'
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, TypeAlias

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.jacobian import (
    LectureMatrix,
    axis_frame,
    compact,
    joint_rows,
    resolve_frame,
)
from dhsym.kinematics.pose import Pose
from dhsym.kinematics.transforms import rigid_inverse
from dhsym.model.kinds import JointType
from dhsym.notation.printers import Notation

from .algebra import Exponential, ScrewAxis, adjoint, is_zero, matrix_exp, skew

if TYPE_CHECKING:
    import numpy as np

    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "AxisStep",
    "ProductOfExponentials",
    "ScrewJacobian",
    "body_from_geometric",
    "from_chain",
    "prove_same_fk",
    "space_from_geometric",
]

Matrix: TypeAlias = sp.ImmutableMatrix


@dataclass(frozen=True)
class AxisStep:
    """How the screw axis of one joint is read off the DH frames at home.

    ``frame`` is the DH frame whose ``z`` is the joint's axis, ``omega`` its direction
    and ``point`` its origin (a point on the axis) at home, in the space frame; ``v`` is
    ``−ω × q`` (revolute) or the direction (prismatic); ``rate`` the factor of the
    variable in the table entry (1, or −1 for an entry ``−q``).
    """

    joint: int
    variable: sp.Symbol
    kind: JointType
    frame: int | str
    rate: sp.Expr
    omega: Matrix
    point: Matrix
    v: Matrix

    def text(self, notation: Notation) -> str:
        """The step as a sentence in plain text."""

        def t(vector: Matrix) -> str:
            return "(" + ", ".join(notation.text(x) for x in vector) + ")"

        if self.kind is JointType.REVOLUTE:
            w = "omega" + str(self.joint)
            return (
                f"Joint {self.joint} (R, {self.variable}) turns about z of frame {self.frame}: "
                f"at home {w} = {t(self.omega)}, a point on the axis q{self.joint} = "
                f"{t(self.point)} (the frame's origin), so v{self.joint} = -{w} x "
                f"q{self.joint} = {t(self.v)}."
            )
        return (
            f"Joint {self.joint} (P, {self.variable}) slides along z of frame {self.frame}: "
            f"omega{self.joint} = 0 and v{self.joint} = {t(self.v)}."
        )


@dataclass(frozen=True)
class ScrewJacobian(LectureMatrix):
    """An exact 6×n Jacobian with rows ``[ω; v]``: ``frame`` is ``"space"`` or ``"body"``
    (printed as :class:`~dhsym.kinematics.jacobian.LectureMatrix` prints, ``J_s``, ``J_b``)."""

    matrix: Matrix
    frame: str
    notation: Notation = field(repr=False)

    def symbol_latex(self) -> str:
        """``J_{s}`` or ``J_{b}``, in LaTeX."""
        return f"J_{{{self.frame[0]}}}"


def _vector(M: sp.MatrixBase) -> Matrix:
    return Matrix(M.applyfunc(compact))


@dataclass(frozen=True)
class ProductOfExponentials:
    r"""A robot in PoE form: the space screw axes ``S_i`` and the home configuration ``M``.

    ``variables`` are the joint variables (``θ_i`` or ``d_i``), one per axis;
    ``values`` numbers for the symbolic lengths; ``steps`` how the axes were found
    (empty when the axes were given); ``frames`` the names of the space and tool frames.
    """

    name: str
    variables: tuple[sp.Symbol, ...]
    space: tuple[ScrewAxis, ...]
    home: Matrix
    notation: Notation = field(compare=False, repr=False)
    steps: tuple[AxisStep, ...] = field(default=(), compare=False, repr=False)
    values: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()
    frames: tuple[int | str, int | str] = ("s", "b")

    def __post_init__(self) -> None:
        if len(self.variables) != len(self.space):
            raise DHError(
                f"{len(self.space)} screw axes need as many joint variables, "
                f"got {len(self.variables)}"
            )
        if sp.Matrix(self.home).shape != (4, 4):
            raise DHError("the home configuration M must be a 4×4 transform")
        object.__setattr__(self, "home", Matrix(self.home))

    @property
    def n(self) -> int:
        """The number of joints."""
        return len(self.space)

    @cached_property
    def body(self) -> tuple[ScrewAxis, ...]:
        r"""The body screw axes :math:`\mathcal{B}_i = [\mathrm{Ad}_{M^{-1}}]\mathcal{S}_i`."""
        Ad = adjoint(rigid_inverse(self.home))
        return tuple(ScrewAxis.from_vector(_vector(Ad * s.vector)) for s in self.space)

    def axes(self, frame: str = "space") -> tuple[ScrewAxis, ...]:
        """The screw axes in the ``"space"`` or the ``"body"`` frame."""
        return self.body if _frame(frame) == "body" else self.space

    def screw_matrix(self, frame: str = "space") -> Matrix:
        """The axes as the columns of a 6×n matrix (rows ``[ω; v]``)."""
        return Matrix.hstack(*[s.vector for s in self.axes(frame)])

    def exponentials(self, frame: str = "space") -> tuple[Exponential, ...]:
        """The factors ``e^{[S_i]θ_i}`` (space) or ``e^{[B_i]θ_i}`` (body), in order."""
        letter = "B" if _frame(frame) == "body" else "S"
        return tuple(
            Exponential(s, q, i, letter, self.notation)
            for i, (s, q) in enumerate(zip(self.axes(frame), self.variables), start=1)
        )

    def product_latex(self, frame: str = "space") -> str:
        r"""The product in LaTeX: ``e^{[\mathcal{S}_1]\theta_1} \cdots M`` (space) or
        ``M e^{[\mathcal{B}_1]\theta_1} \cdots`` (body)."""
        factors = " ".join(e.latex() for e in self.exponentials(frame))
        return f"M {factors}" if _frame(frame) == "body" else f"{factors} M"

    def product_text(self, frame: str = "space") -> str:
        """The product in plain text."""
        factors = " ".join(e.text() for e in self.exponentials(frame))
        return f"M {factors}" if _frame(frame) == "body" else f"{factors} M"

    def formula_latex(self, frame: str = "space") -> str:
        r"""``T(\theta)`` equated to the product (:meth:`product_latex`), in LaTeX."""
        return rf"T(\theta) = {self.product_latex(frame)}"

    def formula_text(self, frame: str = "space") -> str:
        """``T(theta)`` equated to the product, in plain text."""
        return f"T(theta) = {self.product_text(frame)}"

    # -- forward kinematics -------------------------------------------------------------
    def _pose(self, M: sp.MatrixBase) -> Pose:
        frm, to = self.frames
        return Pose(_vector(M), frm, to, self.notation)

    def product(self, frame: str = "space") -> Matrix:
        r"""The plain product :math:`e^{[\mathcal{S}_1]\theta_1}\cdots M` (space) or
        :math:`M e^{[\mathcal{B}_1]\theta_1}\cdots` (body), each entry expanded."""
        body = _frame(frame) == "body"
        out = sp.Matrix(self.home) if body else sp.eye(4)
        for e in self.exponentials(frame):
            out = (out * e.matrix).applyfunc(sp.expand)
        return Matrix(out if body else (out * self.home).applyfunc(sp.expand))

    def fk_space(self) -> Pose:
        r"""The tool pose :math:`e^{[\mathcal{S}_1]\theta_1}\cdots e^{[\mathcal{S}_n]\theta_n}M`,
        exact, each entry in compact form."""
        return self._pose(self.product("space"))

    def fk_body(self) -> Pose:
        r"""The tool pose :math:`M e^{[\mathcal{B}_1]\theta_1}\cdots e^{[\mathcal{B}_n]\theta_n}`,
        exact, each entry in compact form."""
        return self._pose(self.product("body"))

    # -- Jacobians ------------------------------------------------------------------------
    def jacobian_space(self) -> ScrewJacobian:
        r"""The space Jacobian :math:`J_s`: column ``i`` is ``S_i`` carried by
        :math:`[\mathrm{Ad}_{e^{[\mathcal{S}_1]\theta_1}\cdots
        e^{[\mathcal{S}_{i-1}]\theta_{i-1}}}]`."""
        T = sp.eye(4)
        cols = []
        for e in self.exponentials("space"):
            cols.append(_vector(adjoint(T) * e.screw.vector))
            T = (T * e.matrix).applyfunc(sp.expand)
        return ScrewJacobian(Matrix.hstack(*cols), "space", self.notation)

    def jacobian_body(self) -> ScrewJacobian:
        r"""The body Jacobian :math:`J_b`: column ``i`` is ``B_i`` carried by
        :math:`[\mathrm{Ad}_{e^{-[\mathcal{B}_n]\theta_n}\cdots
        e^{-[\mathcal{B}_{i+1}]\theta_{i+1}}}]`."""
        T = sp.eye(4)
        cols: list[Matrix] = []
        for e in reversed(self.exponentials("body")):
            cols.append(_vector(adjoint(T) * e.screw.vector))
            T = (T * matrix_exp(e.screw, -e.variable)).applyfunc(sp.expand)
        return ScrewJacobian(Matrix.hstack(*reversed(cols)), "body", self.notation)

    def jacobian_determinant(self, frame: str = "space") -> sp.Expr:
        """``det J_s`` (or ``det J_b``; equal, as ``det Ad_T = 1``), factored: its zeros are the
        singular configurations. Only for six joints (a square Jacobian)."""
        from dhsym.kinematics.singularities import factored_det

        if self.n != 6:
            raise DHError(
                f"the determinant needs a square 6×6 Jacobian; this robot has {self.n} joints"
            )
        J = self.jacobian_body() if _frame(frame) == "body" else self.jacobian_space()
        return factored_det(sp.Matrix(J.matrix))

    # -- numbers ---------------------------------------------------------------------------
    def function(
        self, what: str, values: Mapping[Any, object] | None = None
    ) -> Callable[[object], np.ndarray]:
        """A compiled ``q -> array`` of ``"fk_space"``, ``"fk_body"``, ``"jacobian_space"``
        or ``"jacobian_body"`` (one configuration ``(n,)`` or a batch ``(N, n)``), with the
        description's ``values`` and ``values`` given."""
        from dhsym.kinematics.numeric import compile_matrix
        from dhsym.model.table import symbol_values

        exact = {
            "fk_space": lambda: self.fk_space().matrix,
            "fk_body": lambda: self.fk_body().matrix,
            "jacobian_space": lambda: self.jacobian_space().matrix,
            "jacobian_body": lambda: self.jacobian_body().matrix,
        }
        if what not in exact:
            raise DHError(f"unknown function {what!r}: expected one of {', '.join(exact)}")
        vals = dict(self.values)
        vals.update(symbol_values(values))
        return compile_matrix(exact[what](), self.variables, vals)


def _frame(frame: str) -> str:
    key = str(frame).strip().lower()
    if key not in ("space", "body"):
        raise DHError(f"frame must be 'space' or 'body', got {frame!r}")
    return key


def _at_home(chain: KinematicChain, M: sp.MatrixBase) -> Matrix:
    return Matrix(sp.Matrix(M).xreplace({q: 0 for q in chain.variables}).applyfunc(sp.expand))


def from_chain(chain: KinematicChain) -> ProductOfExponentials:
    """The PoE description of a DH chain: space axes and ``M`` at ``q = 0``, with the steps.

    The space frame is the frame of ``chain.fk`` (world or frame 0), the tool frame its
    end (tool or frame n); see the module's text for the rule.

    >>> import dhsym
    >>> poe = from_chain(dhsym.load("stanford"))
    >>> print(poe.steps[2].text(poe.notation))
    Joint 3 (P, d3) slides along z of frame 2: omega3 = 0 and v3 = (0, 0, 1).
    >>> print(from_chain(dhsym.load("planar2r")).steps[1].text(poe.notation))
    Joint 2 (R, theta2) turns about z of frame 1: at home omega2 = (0, 0, 1), a point on the
    axis q2 = (a1, 0, 0) (the frame's origin), so v2 = -omega2 x q2 = (0, -a1, 0).
    """
    k = resolve_frame(chain, "base")
    e = resolve_frame(chain, "tool")
    axes, steps, variables = [], [], []
    for row, var, joint, rate in joint_rows(chain):
        a = axis_frame(chain, row)
        home = _at_home(chain, chain.transform(k, a).matrix)
        z, origin = home[:3, 2], home[:3, 3]
        if joint is JointType.REVOLUTE:
            omega = Matrix(rate * z)
            v = _vector(-omega.cross(origin))
        else:
            omega, v = Matrix.zeros(3, 1), Matrix(rate * z)
        screw = ScrewAxis(omega, v)
        if not is_zero(rate**2 - 1):
            raise DHError(
                f"joint {row}: the entry is {rate}·{var}; a screw axis needs a rate of ±1",
                row=row,
            )
        axes.append(screw)
        variables.append(var)
        label = a if a not in (-1, chain.n + 1) else ("W" if a == -1 else "tool")
        steps.append(AxisStep(len(axes), var, joint, label, rate, z, origin, v))
    frames = (
        "W" if k == -1 else k,
        "tool" if e == chain.n + 1 else e,
    )
    return ProductOfExponentials(
        chain.name,
        tuple(variables),
        tuple(axes),
        _at_home(chain, chain.transform(k, e).matrix),
        chain.notation,
        tuple(steps),
        chain.table.values,
        frames,
    )


def prove_same_fk(poe: ProductOfExponentials, chain: KinematicChain) -> bool:
    """Exact proof that both PoE forms of ``poe`` equal the plain DH product of ``chain``.

    Nothing is simplified: the three products — the elementary matrices of the DH word
    from the space frame to the tool frame, :math:`e^{[\\mathcal{S}_1]\\theta_1}\\cdots M`
    and :math:`M e^{[\\mathcal{B}_1]\\theta_1}\\cdots` — are multiplied factor by factor in
    one polynomial ring of the sines and cosines (joint angles and constant angles) and
    the square roots, each step reduced modulo ``sin² + cos² = 1`` and ``(√b)² = b``, and
    their entries compared (:func:`~dhsym.kinematics.trig_ring.prove_products_equal`).

    >>> import dhsym
    >>> r = dhsym.load("planar2r")
    >>> prove_same_fk(from_chain(r), r)
    True
    """
    from dhsym.kinematics.transforms import chain_word, elementary_matrix
    from dhsym.kinematics.trig_ring import prove_products_equal

    if tuple(poe.variables) != tuple(chain.variables):
        raise DHError("the PoE description and the chain have different joint variables")
    word = chain_word(chain.table, resolve_frame(chain, "base"), resolve_frame(chain, "tool"))
    dh = [elementary_matrix(e) for e in word]
    space = [*(e.matrix for e in poe.exponentials("space")), poe.home]
    body = [poe.home, *(e.matrix for e in poe.exponentials("body"))]
    return prove_products_equal([dh, space, body], poe.variables)


_SWAP = sp.ImmutableMatrix(sp.BlockMatrix([[sp.zeros(3), sp.eye(3)], [sp.eye(3), sp.zeros(3)]]))


def body_from_geometric(J_tool: sp.MatrixBase) -> Matrix:
    r"""``J_b`` from dhsym's geometric Jacobian in the tool frame (rows ``[v; ω]``, the
    velocity of the tool origin): the halves swapped,
    :math:`J_b = \begin{bmatrix}0 & I\\ I & 0\end{bmatrix} J_{\text{tool}}`.

    >>> body_from_geometric(sp.Matrix([1, 2, 3, 4, 5, 6])).T
    Matrix([[4, 5, 6, 1, 2, 3]])
    """
    return Matrix(_SWAP * sp.Matrix(J_tool))


def space_from_geometric(J_base: sp.MatrixBase, T: sp.MatrixBase) -> Matrix:
    r"""``J_s`` from dhsym's geometric Jacobian in the base frame and the tool pose ``T``:
    the space twist's ``v`` is the velocity of the body point at the space origin,
    :math:`v_s = \dot p - \omega \times p = \dot p + [p]\,\omega`, so
    :math:`J_s = \begin{bmatrix}0 & I\\ I & [p]\end{bmatrix} J_{\text{base}}`.

    >>> from dhsym.kinematics.transforms import Tx
    >>> space_from_geometric(sp.Matrix([0, 1, 0, 0, 0, 1]), Tx(1)).T
    Matrix([[0, 0, 1, 0, 0, 0]])
    """
    J = sp.Matrix(J_base)
    top = J[3:, :]
    bottom = J[:3, :] + skew(sp.Matrix(T)[:3, 3]) * J[3:, :]
    return Matrix(sp.Matrix.vstack(top, bottom).applyfunc(compact))
