r"""The manipulator Jacobian in lecture form: geometric and analytic, exact and compiled.

Column *i* of the geometric Jacobian (Spong, Hutchinson and Vidyasagar, *Robot
Modeling and Control*, §4.6) is, for a revolute and a prismatic joint,

.. math::

    J_i = \begin{bmatrix} z_{i-1} \times (o_n - o_{i-1}) \\ z_{i-1} \end{bmatrix},
    \qquad
    J_i = \begin{bmatrix} z_{i-1} \\ 0 \end{bmatrix},

where ``z_{i-1}`` is the joint's axis and ``o_{i-1}`` a point on it. In the standard
convention joint *i* turns about ``z_{i-1}`` of frame *i−1*; in the modified
(Craig) convention it turns about ``z_i`` of frame *i*, so there the axis frame is *i*.

Compact entries come from the compact transforms, never from a global simplify:
the lever ``o_n − o_a`` is the position column of the compact ``^aT_n``, so
``z_a × (o_n − o_a) = {}^kR_a\,(e_z × {}^a p_n) = {}^kR_a\,(-p_y, p_x, 0)`` is one
rotation times a vector; each entry then only gets the targeted sum-angle folds of
:mod:`dhsym.kinematics.simplification`. :meth:`Jacobian.verify` proves the linear part equal to
the derivative of the plain forward kinematics and the angular part equal to
``vee(Ṙ Rᵀ)``, exactly.

Examples
--------
>>> import dhsym
>>> J = geometric_jacobian(dhsym.load("planar2r"))
>>> print(J.text())
Matrix([
[-a1*S1 - a2*S12, -a2*S12],
[ a1*C1 + a2*C12,  a2*C12],
[              0,       0],
[              0,       0],
[              0,       0],
[              1,       1]])
>>> J.verify()
True
>>> jacobian_function(dhsym.load("planar2r"))([0.0, 0.0])[:2]
array([[0. , 0. ],
       [1.8, 0.8]])
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, TypeAlias

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.parsing import REAL
from dhsym.model.table import Convention, JointType
from dhsym.notation.printers import Notation

from .simplification import fold_sum_angles, prove_equal, tidy_signs
from .transforms import Rx, Ry, Rz

if TYPE_CHECKING:
    import numpy as np

    from .chain import KinematicChain

__all__ = [
    "EULER_SETS",
    "AnalyticJacobian",
    "Jacobian",
    "JacobianColumn",
    "LectureMatrix",
    "analytic_jacobian",
    "analytic_jacobian_function",
    "axis_frame",
    "compact",
    "euler_angles",
    "geometric_jacobian",
    "jacobian_function",
    "joint_column",
    "joint_rows",
    "numeric_jacobian",
    "rate_matrix",
    "resolve_frame",
]

Matrix: TypeAlias = sp.ImmutableMatrix

#: Euler-angle sets for the analytic Jacobian: name → rotation axes in order.
#: ``zyz``: R = Rz(φ) Ry(θ) Rz(ψ); ``rpy``: R = Rz(φ) Ry(θ) Rx(ψ) (roll ψ, pitch θ, yaw φ).
EULER_SETS: Mapping[str, tuple[str, str, str]] = {
    "zyz": ("z", "y", "z"),
    "rpy": ("z", "y", "x"),
}


# --- small exact helpers ----------------------------------------------------------------


def compact(expr: sp.Expr) -> sp.Expr:
    """The shortest of a few cheap exact rewrites of ``expr`` (no global simplify).

    Candidates: the sum-angle folds of ``expr`` as it is and of its expansion, each with
    common factors pulled out; the one with the fewest operations wins.

    >>> t1, t2, a = sp.symbols("theta1 theta2 a", real=True)
    >>> compact(-a * sp.cos(t1) * sp.sin(t2) - a * sp.sin(t1) * sp.cos(t2))
    -a*sin(theta1 + theta2)
    """
    if not isinstance(expr, sp.Expr) or expr.is_Atom:
        return expr
    candidates = []
    for start in (expr, sp.expand(expr)):
        folded = tidy_signs(fold_sum_angles(start))
        candidates += [folded, sp.factor_terms(folded, sign=False)]
    return min(candidates, key=sp.count_ops)


def resolve_frame(robot: KinematicChain, frame: int | str) -> int:
    """A frame number for ``frame``: ``"base"`` and ``"tool"`` are the ends of ``fk``.

    ``"base"`` is the world frame when the table has a base transform, else frame 0;
    ``"tool"`` is the tool frame when it has a tool transform, else frame n.

    >>> import dhsym
    >>> r = dhsym.load("puma560")
    >>> resolve_frame(r, "base"), resolve_frame(r, "tool"), resolve_frame(r, 3)
    (0, 6, 3)
    """
    n = robot.n
    if frame == "base":
        return -1 if robot.table.base else 0
    if frame == "tool":
        return n + 1 if robot.table.tool else n
    if isinstance(frame, int) and not isinstance(frame, bool) and -1 <= frame <= n + 1:
        return frame
    raise DHError(f"frame must be 'base', 'tool' or a frame number -1 … {n + 1}; got {frame!r}")


def axis_frame(robot: KinematicChain, row: int) -> int:
    """The frame whose z axis is the axis of the joint in ``row`` (1-based).

    Standard convention: frame ``row − 1``; modified (Craig): frame ``row``.

    >>> import dhsym
    >>> axis_frame(dhsym.load("puma560"), 4), axis_frame(dhsym.load("puma560_modified"), 4)
    (3, 4)
    """
    return row - 1 if robot.convention is Convention.STANDARD else row


#: ``(row, variable, joint type, rate)`` of one joint: see :func:`joint_rows`
JointRow: TypeAlias = tuple[int, sp.Symbol, JointType, sp.Expr]


def joint_rows(robot: KinematicChain) -> list[JointRow]:
    """``(row, variable, joint type, rate)`` for every row with a joint variable, in order:
    the row's number (from 1), its variable, revolute or prismatic, and the rate
    ``∂ entry / ∂ variable`` of its variable entry (1, or −1 for an entry ``−q``); an entry
    that is not linear in its variable is a :class:`~dhsym.errors.DHError` naming the row
    and field. The Jacobians (geometric, analytic) and the screw axes of
    :func:`dhsym.screws.product.from_chain` read the joints through it.

    >>> import dhsym
    >>> joint_rows(dhsym.load("stanford"))[2]
    (3, d3, <JointType.PRISMATIC: 'P'>, 1)
    """
    out = []
    for i, row in enumerate(robot.table.rows, start=1):
        if row.variable is None or row.variable_field is None:
            continue
        rate = sp.diff(getattr(row, row.variable_field), row.variable)
        if rate.free_symbols or rate == 0:
            raise DHError(
                f"the {row.variable_field} entry must be linear in {row.variable}",
                row=i,
                field=row.variable_field,
            )
        out.append((i, row.variable, row.joint, rate))
    return out


def joint_column(
    turn: sp.MatrixBase, lever: sp.MatrixBase, joint: JointType, rate: sp.Expr
) -> tuple[Matrix, Matrix]:
    """``(linear, angular)`` of one joint's Jacobian column, before any tidying: the joint
    turns (slides) about ``z_a`` of its axis frame *a* at ``rate · q̇`` (the rate of
    :func:`joint_rows`: an entry ``k q + c`` moves the axis at ``k q̇``).

    ``turn`` is ``^kR_a`` (frame *a* written in the Jacobian's frame *k*) and ``lever``
    the point seen from frame *a*, ``^a p``; a revolute column is
    ``k ^kR_a (e_z × ^a p)`` and ``k ^kR_a e_z``, a prismatic one ``k ^kR_a e_z`` and 0.
    The geometric Jacobian and the dynamics' link Jacobians
    (:func:`dhsym.dynamics.lagrange_euler.link_jacobians`) take their columns here.

    >>> x, y = sp.symbols("x y", real=True)
    >>> joint_column(sp.eye(3), Matrix([x, y, 0]), JointType.REVOLUTE, sp.Integer(-1))
    (Matrix([
    [ y],
    [-x],
    [ 0]]), Matrix([
    [ 0],
    [ 0],
    [-1]]))
    """
    axis = Matrix(turn[:, 2])
    if joint is JointType.REVOLUTE:
        linear = Matrix(turn * Matrix([-lever[1], lever[0], 0]))
        return Matrix(rate * linear), Matrix(rate * axis)
    return Matrix(rate * axis), Matrix.zeros(3, 1)


def _label(robot: KinematicChain, frame: int) -> int | str:
    if frame == -1:
        return "W"
    if frame == robot.n + 1:
        return "tool"
    return frame


# --- the geometric Jacobian --------------------------------------------------------------


@dataclass(frozen=True)
class JacobianColumn:
    """One column ``J_i``: the joint's axis, the lever to the point and the two parts.

    ``axis`` is ``z`` of ``axis_frame`` and ``lever`` is ``o_point − o_axis_frame``, both
    in the Jacobian's frame; ``linear`` is ``axis × lever`` (revolute) or ``axis``
    (prismatic) and ``angular`` is ``axis`` or 0, each times ``rate`` (1 unless the
    table entry is a multiple of the variable).
    """

    variable: sp.Symbol
    joint: JointType
    row: int
    axis_frame: int | str
    rate: sp.Expr
    axis: Matrix
    lever: Matrix
    linear: Matrix
    angular: Matrix


class _Printable(Protocol):
    """What :class:`LectureMatrix` prints: an exact matrix, its notation and its symbol."""

    @property
    def matrix(self) -> Matrix: ...

    @property
    def notation(self) -> Notation: ...

    def symbol_latex(self) -> str: ...


class LectureMatrix:
    """The printing hooks of an exact matrix shown in lecture notation (a mixin): plain
    text and LaTeX through the robot's :class:`~dhsym.notation.printers.Notation`, sympy's
    ``_sympystr`` and ``_latex``, and Jupyter's ``_repr_latex_`` as ``symbol = matrix``.
    The class gives ``matrix``, ``notation`` and :meth:`symbol_latex` (the geometric
    :class:`Jacobian`, the screws room's ``ScrewJacobian``)."""

    def text(self: _Printable) -> str:
        """The matrix in plain text, compact notation."""
        return self.notation.text(self.matrix)

    def latex(self: _Printable) -> str:
        """The matrix in LaTeX, compact notation."""
        return self.notation.latex(self.matrix)

    def _sympystr(self: _Printable, printer: object) -> str:
        return self.notation.text(self.matrix)

    def _latex(self: _Printable, printer: object) -> str:
        return self.notation.latex(self.matrix)

    def _repr_latex_(self: _Printable) -> str:
        return f"$${self.symbol_latex()} = {self.notation.latex(self.matrix)}$$"


@dataclass(frozen=True)
class Jacobian(LectureMatrix):
    """The 6×n geometric Jacobian ``[J_v; J_ω]`` of a robot, exact and compact.

    ``frame`` is the frame the vectors are written in; ``point`` the frame whose origin
    is the reference point (the end effector by default).
    """

    matrix: Matrix
    columns: tuple[JacobianColumn, ...]
    frame: int | str
    point: int | str
    robot: KinematicChain = field(compare=False, repr=False)

    @property
    def linear(self) -> Matrix:
        """``J_v``, the top three rows."""
        return self.matrix[:3, :]

    @property
    def angular(self) -> Matrix:
        """``J_ω``, the bottom three rows."""
        return self.matrix[3:, :]

    @property
    def variables(self) -> tuple[sp.Symbol, ...]:
        """The joint variables, one per column."""
        return tuple(c.variable for c in self.columns)

    @property
    def notation(self) -> Notation:
        """The robot's lecture notation."""
        return self.robot.notation

    def __getitem__(self, key: object) -> object:
        return self.matrix[key]

    def symbol_latex(self) -> str:
        """``{}^{0}J``: the Jacobian's symbol with its frame, in LaTeX."""
        return f"{{}}^{{{self.frame}}}J"

    def verify(self) -> bool:
        """Exact proof against the plain forward kinematics.

        ``J_v`` (rotated to the base frame) must equal ``∂p/∂q`` of the plain product and
        each column of ``J_ω`` must equal ``vee(∂R/∂q_i · Rᵀ)``; both are reduced modulo
        ``sin² + cos² = 1`` by :func:`~dhsym.kinematics.simplification.prove_equal`.
        """
        robot = self.robot
        base = resolve_frame(robot, "base")
        point = resolve_frame(robot, self.point) if isinstance(self.point, str) else self.point
        frame = resolve_frame(robot, self.frame) if isinstance(self.frame, str) else self.frame
        pose = robot.plain_transform(base, point)
        turn = robot.plain_transform(base, frame)[:3, :3]
        position, rotation = pose[:3, 3], pose[:3, :3]
        if not prove_equal(turn * self.linear, position.jacobian(list(self.variables))):
            return False
        for col, var in zip((turn * self.angular).T.tolist(), self.variables):
            W = rotation.diff(var) * rotation.T
            if not prove_equal(Matrix(col), Matrix([W[2, 1], W[0, 2], W[1, 0]])):
                return False
        return True


def geometric_jacobian(
    robot: KinematicChain, frame: int | str = "base", point: int | str = "tool"
) -> Jacobian:
    """The geometric Jacobian of ``robot`` in compact form.

    Parameters
    ----------
    robot
        The robot.
    frame
        Where the vectors are written: ``"base"`` (the frame of ``fk``), ``"tool"`` (the
        end-effector frame) or a frame number.
    point
        Whose origin's velocity the linear part gives: ``"tool"`` (the end effector) or
        a frame number (e.g. the wrist centre).

    >>> import dhsym
    >>> J = geometric_jacobian(dhsym.load("stanford"))
    >>> J.columns[2].joint.value, J.linear[:, 2].T
    ('P', Matrix([[sin(theta2)*cos(theta1), sin(theta1)*sin(theta2), cos(theta2)]]))
    >>> tool = geometric_jacobian(dhsym.load("planar2r"), frame="tool")
    >>> print(tool.notation.text(tool.linear))
    Matrix([
    [     a1*S2,  0],
    [a1*C2 + a2, a2],
    [         0,  0]])
    """
    k = resolve_frame(robot, frame)
    e = resolve_frame(robot, point)
    columns = []
    for row, var, joint, rate in joint_rows(robot):
        a = axis_frame(robot, row)
        turn = robot.transform(k, a).matrix[:3, :3]
        axis = turn[:, 2]
        lever_a = robot.transform(a, e).matrix[:3, 3]
        lever = (turn * lever_a).applyfunc(compact)
        linear, angular = joint_column(turn, lever_a, joint, rate)
        columns.append(
            JacobianColumn(
                var,
                joint,
                row,
                _label(robot, a),
                rate,
                Matrix(axis),
                Matrix(lever),
                Matrix(linear.applyfunc(compact)),
                Matrix(angular.applyfunc(compact)),
            )
        )
    matrix = Matrix.hstack(*[Matrix.vstack(c.linear, c.angular) for c in columns])
    return Jacobian(Matrix(matrix), tuple(columns), _label(robot, k), _label(robot, e), robot)


# --- the analytic Jacobian ----------------------------------------------------------------

_ROT = {"x": Rx, "y": Ry, "z": Rz}
_UNIT = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}


def _euler_axes(euler: str) -> tuple[str, str, str]:
    key = euler.strip().lower()
    if key not in EULER_SETS:
        raise DHError(f"unknown Euler set {euler!r}: use one of {', '.join(EULER_SETS)}")
    return EULER_SETS[key]


def euler_symbols(euler: str = "zyz") -> tuple[sp.Symbol, sp.Symbol, sp.Symbol]:
    """The angle symbols ``(φ, θ, ψ)`` of an Euler set, in rotation order.

    >>> euler_symbols("rpy")
    (phi, theta, psi)
    """
    _euler_axes(euler)
    angles: tuple[sp.Symbol, sp.Symbol, sp.Symbol] = sp.symbols("phi theta psi", **REAL)
    return angles


def rate_matrix(euler: str = "zyz") -> Matrix:
    """``B(φ, θ, ψ)`` with ``ω = B · (φ̇, θ̇, ψ̇)`` for ``R = R_{a1}(φ) R_{a2}(θ) R_{a3}(ψ)``.

    Column k is the k-th rotation axis carried by the rotations before it.

    >>> rate_matrix("zyz")
    Matrix([
    [0, -sin(phi), sin(theta)*cos(phi)],
    [0,  cos(phi), sin(phi)*sin(theta)],
    [1,         0,          cos(theta)]])
    """
    axes = _euler_axes(euler)
    angles = euler_symbols(euler)
    R = sp.eye(3)
    cols = []
    for ax, ang in zip(axes, angles):
        cols.append(R * sp.Matrix(_UNIT[ax]))
        R = R * _ROT[ax](ang)[:3, :3]
    return Matrix(sp.Matrix.hstack(*cols).applyfunc(compact))


@dataclass(frozen=True)
class AnalyticJacobian:
    """``J_A = diag(I, B⁻¹) J``: velocity of the position and of the Euler angles.

    ``matrix`` contains the joint variables and the Euler angles ``angles`` of the
    current orientation; ``rate`` is ``B`` (``ω = B φ̇``) and ``rate_inverse`` is ``B⁻¹``,
    defined where ``det B ≠ 0`` (``sin θ ≠ 0`` for ZYZ, ``cos θ ≠ 0`` for RPY).
    """

    matrix: Matrix
    euler: str
    angles: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    rate: Matrix
    rate_inverse: Matrix
    geometric: Jacobian


def analytic_jacobian(
    robot: KinematicChain, euler: str = "zyz", frame: int | str = "base"
) -> AnalyticJacobian:
    """The analytic Jacobian for the Euler set ``euler`` (``"zyz"`` or ``"rpy"``).

    >>> import dhsym
    >>> A = analytic_jacobian(dhsym.load("planar2r"))
    >>> A.rate_inverse
    Matrix([
    [-cos(phi)/tan(theta), -sin(phi)/tan(theta), 1],
    [           -sin(phi),             cos(phi), 0],
    [ cos(phi)/sin(theta),  sin(phi)/sin(theta), 0]])
    """
    J = geometric_jacobian(robot, frame=frame)
    B = rate_matrix(euler)
    inv = Matrix(B.inv().applyfunc(sp.trigsimp))
    top = J.linear
    bottom = (inv * J.angular).applyfunc(compact)
    return AnalyticJacobian(
        Matrix(Matrix.vstack(top, Matrix(bottom))), euler, euler_symbols(euler), B, inv, J
    )


# --- numbers -----------------------------------------------------------------------------


def _values(robot: KinematicChain, values: Mapping[Any, object] | None) -> dict[sp.Symbol, sp.Expr]:
    # none given: the table's own (a copy of the table, validated again, has the same map;
    # the general 6R asks once per pose)
    if not values:
        return robot.table.value_map
    return robot.table.with_values(values).value_map


def jacobian_function(
    robot: KinematicChain,
    frame: int | str = "base",
    point: int | str = "tool",
    values: Mapping[Any, object] | None = None,
) -> Callable[[object], np.ndarray]:
    """The compiled geometric Jacobian: ``(n,)`` → ``(6, n)``, ``(N, n)`` → ``(N, 6, n)``."""
    from .numeric import compile_matrix

    J = geometric_jacobian(robot, frame, point)
    return compile_matrix(J.matrix, robot.variables, _values(robot, values))


def numeric_jacobian(
    robot: KinematicChain, q: object, values: Mapping[Any, object] | None = None
) -> np.ndarray:
    """The geometric Jacobian at ``q`` from numeric frames, nothing compiled:
    ``(n,)`` → ``(6, n)``, ``(N, n)`` → ``(N, 6, n)``.

    The frames ``^bT_i`` (``b`` the base of ``fk``) are the partial products of the
    chain's elementary transforms, multiplied as numbers
    (:func:`~dhsym.kinematics.numeric.word_product`); with ``z`` and ``p`` the axis and
    origin of the joint's axis frame and ``p_e`` the tool's origin, a revolute column is
    ``[z × (p_e − p); z]`` and a prismatic one ``[z; 0]`` (times the joint's rate, as in
    :func:`geometric_jacobian`). The same numbers as :meth:`~dhsym.kinematics.chain.
    KinematicChain.jacob0` without compiling the Jacobian: for a few one-off evaluations
    (the compiled one pays for itself over many).

    >>> import dhsym, numpy as np
    >>> r = dhsym.load("stanford")
    >>> q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
    >>> numeric_jacobian(r, q).shape, np.allclose(numeric_jacobian(r, q), r.jacob0(q))
    ((6, 6), True)
    >>> numeric_jacobian(dhsym.load("planar2r"), [[0.0, 0.0]])[:, :2]
    array([[[0. , 0. ],
            [1.8, 0.8]]])
    """
    import numpy as np

    from dhsym.model.table import Elementary

    from .numeric import word_product
    from .transforms import chain_word

    Q = np.asarray(q, dtype=float)
    single = Q.ndim == 1
    Q = Q.reshape(-1, robot.n)
    N = Q.shape[0]
    vals = _values(robot, values)
    base, tool = resolve_frame(robot, "base"), resolve_frame(robot, "tool")
    word = [
        Elementary(e.kind, e.axis, e.value.xreplace(vals))
        for e in chain_word(robot.table, base, tool)
    ]
    env = {v: Q[:, i] for i, v in enumerate(robot.variables)}
    frames = word_product(word, env, N, prefixes=True)  # (N, len(word) + 1, 4, 4)
    end = frames[:, -1, :3, 3]
    J = np.zeros((N, 6, robot.n))
    for col, (row, _, joint, rate) in enumerate(joint_rows(robot)):
        # frame a's product is a prefix of the word from the base to the tool
        F = frames[:, len(chain_word(robot.table, base, axis_frame(robot, row)))]
        z, p = F[:, :3, 2], F[:, :3, 3]
        if joint is JointType.REVOLUTE:
            J[:, :3, col], J[:, 3:, col] = np.cross(z, end - p), z
        else:
            J[:, :3, col] = z
        J[:, :, col] *= float(rate)
    return J[0] if single else J


def euler_angles(R: object, euler: str = "zyz") -> np.ndarray:
    """Euler angles ``(φ, θ, ψ)`` of rotation matrices ``(..., 3, 3)`` (or 4×4 poses).

    ZYZ takes ``θ ∈ [0, π]``; RPY takes ``θ ∈ [−π/2, π/2]``.

    >>> import numpy as np
    >>> from dhsym.kinematics.transforms import Rz, Ry
    >>> R = np.array((Rz(0.3) * Ry(0.5) * Rz(-0.2))[:3, :3], dtype=float)
    >>> np.round(euler_angles(R, "zyz"), 12)
    array([ 0.3,  0.5, -0.2])
    """
    import numpy as np

    axes = _euler_axes(euler)
    M = np.asarray(R, dtype=float)[..., :3, :3]
    if axes == ("z", "y", "z"):
        phi = np.arctan2(M[..., 1, 2], M[..., 0, 2])
        theta = np.arctan2(np.hypot(M[..., 0, 2], M[..., 1, 2]), M[..., 2, 2])
        psi = np.arctan2(M[..., 2, 1], -M[..., 2, 0])
    else:
        phi = np.arctan2(M[..., 1, 0], M[..., 0, 0])
        theta = np.arctan2(-M[..., 2, 0], np.hypot(M[..., 0, 0], M[..., 1, 0]))
        psi = np.arctan2(M[..., 2, 1], M[..., 2, 2])
    return np.stack([phi, theta, psi], axis=-1)


def analytic_jacobian_function(
    robot: KinematicChain,
    euler: str = "zyz",
    values: Mapping[Any, object] | None = None,
) -> Callable[[object], np.ndarray]:
    """The compiled analytic Jacobian in the base frame (angles read from ``fk``)."""
    import numpy as np

    from .numeric import compile_exprs

    geometric = jacobian_function(robot, values=values)
    B = rate_matrix(euler)
    inverse = compile_exprs(list(B.inv().applyfunc(sp.trigsimp)), euler_symbols(euler))
    fk = robot.fk_function(values=values)

    def evaluate(q: object) -> np.ndarray:
        arr = np.asarray(q, dtype=float)
        J = geometric(arr)
        ang = euler_angles(fk(arr), euler)
        cells = inverse(ang[..., 0], ang[..., 1], ang[..., 2])
        shape = ang.shape[:-1]
        Binv = np.stack([np.broadcast_to(np.asarray(c, float), shape) for c in cells], -1)
        out: np.ndarray = J.copy()
        out[..., 3:, :] = Binv.reshape(*shape, 3, 3) @ J[..., 3:, :]
        return out

    return evaluate
