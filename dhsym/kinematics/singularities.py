r"""Singular configurations: the Jacobian determinant factored the way the lectures write it.

For a six-joint arm with a spherical wrist, take the Jacobian at the wrist centre: the
wrist joints then move the centre not at all, so

.. math::

    J_c = \begin{bmatrix} J_{11} & 0 \\ J_{21} & J_{22} \end{bmatrix},
    \qquad \det J = \det J_{11} \cdot \det J_{22}

(moving the reference point multiplies ``J`` by ``[[I, −S(r)], [0, I]]``, of
determinant 1). ``J11`` is the 3×3 arm block, ``J22 = [z_a4 z_a5 z_a6]`` the wrist
axes. Determinants are expanded along the line with most zeros and every minor is
factored before it is used (sum-angle folds, then ``factor``), in the frame that gives
the shortest result; a rotation does not change a determinant. A six-joint arm
without a spherical wrist (the UR arms: axes 2, 3, 4 parallel, 5 and 6 meeting in the
*wrist point*) has the whole ``J`` factored the same way, at the wrist point and in the
middle frame where it has the most zeros, within a bound on the work
(:data:`MAX_TERMS`); a wrist factor there is one whose zeros make the axes beside its
joint parallel (``θ5 = 0``: axes 4 and 6, with 2 and 3). Other arms use the
square part of ``J`` (the position rows for a positioning arm, the non-zero rows
otherwise) or, when it is not square, the manipulability ``w = sqrt(det(J Jᵀ))`` by the
Cauchy–Binet sum of squared minors.

Each factor is named from the structure, not the robot's name: a factor of the wrist
block is the *wrist* singularity, a factor that divides the wrist centre's radial
reach (its distance from the axis of joint 1, measured in the arm's plane) is the
*shoulder* singularity, one in the last arm joint alone is the *elbow* singularity
(the arm stretched out or folded back: the workspace boundary).

Examples
--------
>>> import dhsym
>>> s = singularities(dhsym.load("puma560"))
>>> print(s.text())
det J = a2*S5*(a2*C2 + a3*C23 - d4*S23)*(a3*S3 + d4*C3)
>>> [(f.kind, f.text()) for f in s.factors if f.kind != "constant"]
[('elbow', 'a3*S3 + d4*C3'), ('shoulder', 'a2*C2 + a3*C23 - d4*S23'), ('wrist', 'S5')]
>>> s.factors[-1].solutions
((theta5, 0), (theta5, pi))
>>> print(singularities(dhsym.load("planar2r")).text())
det J_v = a1*a2*S2
>>> print(singularities(dhsym.load("ur5")).text())
det J = a2*a3*S3*S5*(a2*C2 + a3*C23 + d5*S234)
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from enum import Enum
from typing import TYPE_CHECKING, Any, TypeAlias

import sympy as sp

from dhsym.model.table import JointType

from .decoupling import ArmGeometry, Decoupling, StructureError, arm_geometry, decouple
from .jacobian import axis_frame, geometric_jacobian
from .simplification import fold_sum_angles, prove_equal, trig_coefficients

if TYPE_CHECKING:
    import numpy as np

    from dhsym.notation.printers import Notation

    from .chain import KinematicChain

__all__ = [
    "Block",
    "SingularFactor",
    "Singularities",
    "SingularityKind",
    "factored_det",
    "singularities",
    "singularities_data",
    "stored_singularities",
]

Matrix: TypeAlias = sp.ImmutableMatrix
_MAX_MINORS = 5  # Cauchy–Binet beyond this takes seconds: one redundant joint at most


# --- determinants, factored as they are built -----------------------------------------------


def _factor(expr: sp.Expr, max_terms: int | None = None) -> sp.Expr:
    """Factor a sum after folding sum angles; products are kept as they are. A sum that
    expands to more than ``max_terms`` terms is a :class:`StructureError` (the bound)."""
    if expr == 0 or not expr.is_Add:
        return expr
    expanded = sp.expand(expr)
    if max_terms is not None and len(sp.Add.make_args(expanded)) > max_terms:
        raise StructureError(
            f"a minor of the determinant expands to {len(sp.Add.make_args(expanded))} terms, "
            f"more than the {max_terms} factored here"
        )
    folded = fold_sum_angles(expanded)
    return sp.factor(folded) if folded != 0 else sp.Integer(0)


def factored_det(M: sp.MatrixBase, *, max_terms: int | None = None) -> sp.Expr:
    """Determinant by expansion along the line with most zeros, each minor factored.

    ``max_terms`` bounds the work: a minor whose expanded sum has more terms raises
    :class:`~dhsym.kinematics.decoupling.StructureError` (None: no bound).

    >>> t2, t3, a2, a3 = sp.symbols("theta2 theta3 a2 a3", real=True)
    >>> factored_det(sp.Matrix([[1, 0, 0], [0, -a2 * sp.sin(t2), -a3 * sp.sin(t2 + t3)],
    ...                         [0, a2 * sp.cos(t2), a3 * sp.cos(t2 + t3)]]))
    a2*a3*sin(theta3)
    >>> factored_det(sp.Matrix([[a2, a3], [a3, a2]]), max_terms=1)
    Traceback (most recent call last):
    ...
    dhsym.kinematics.decoupling.StructureError: a minor of the determinant expands to 2 terms, ...
    """
    n = M.rows
    if n == 0:
        return sp.Integer(1)
    if n == 1:
        return _factor(M[0, 0], max_terms)
    lines = [(sum(1 for x in M.row(i) if x == 0), 0, i) for i in range(n)]
    lines += [(sum(1 for x in M.col(j) if x == 0), 1, j) for j in range(n)]
    _, along_column, k = max(lines)
    terms = []
    for m in range(n):
        i, j = (m, k) if along_column else (k, m)
        if M[i, j] == 0:
            continue
        sub = sp.Matrix(M).minor_submatrix(i, j)
        terms.append((-1) ** (i + j) * M[i, j] * factored_det(sub, max_terms=max_terms))
    return _factor(sp.Add(*terms), max_terms)


def _best_det(matrices: Sequence[sp.MatrixBase]) -> sp.Expr:
    """The shortest factored determinant among equal-determinant ``matrices``."""
    return min((factored_det(M) for M in matrices), key=sp.count_ops)


# --- naming --------------------------------------------------------------------------------


@dataclass(frozen=True)
class SingularFactor:
    """One factor of the determinant, with the configurations where it vanishes.

    ``kind`` is a :class:`SingularityKind` value (``"wrist"``, ``"elbow"``, ``"shoulder"``,
    ``"boundary"`` or ``"constant"``) and ``name`` its title;
    ``solutions`` lists ``(variable, value)`` pairs when the factor has one variable.
    """

    expr: sp.Expr
    power: int
    kind: str
    name: str
    description: str
    variables: tuple[sp.Symbol, ...]
    solutions: tuple[tuple[sp.Symbol, sp.Expr], ...]
    notation: Notation | None = field(compare=False, repr=False, default=None)

    def text(self) -> str:
        """The factor in plain text, compact notation."""
        return self.notation.text(self.expr) if self.notation else sp.sstr(self.expr)

    def latex(self) -> str:
        """The factor in LaTeX, compact notation."""
        return self.notation.latex(self.expr) if self.notation else sp.latex(self.expr)


def _zeros(expr: sp.Expr, x: sp.Symbol, joint: JointType) -> tuple[sp.Expr, ...]:
    """The values of ``x`` where ``expr`` (in ``x`` alone) vanishes, when they are simple."""
    if joint is JointType.PRISMATIC:
        poly = sp.Poly(sp.expand(expr), x)
        if poly.degree() >= 1 and len(set(sp.roots(poly).keys())) >= 1:
            return tuple(sorted(set(sp.roots(poly)), key=sp.default_sort_key))
        return ()
    abc = trig_coefficients(expr, x)
    if abc is None or abc[2] != 0:
        return ()
    A, B, _ = abc
    return (sp.atan2(-A, B), sp.atan2(A, -B))


def _divides(factor: sp.Expr, expr: sp.Expr) -> bool:
    """True when ``factor`` divides ``expr`` as a polynomial in sines and cosines."""
    f = sp.expand(sp.expand_trig(factor))
    e = sp.expand(sp.expand_trig(expr))
    if not f.free_symbols:
        return False
    _, rem = sp.div(e, f)
    return bool(sp.expand(rem) == 0)


class SingularityKind(str, Enum):
    """The one list of singularity names, applied by structure (see the module text).

    Every output that names a singular factor (derivations, handouts, feedback, notebooks)
    takes its name from here: a factor of the wrist block is the *wrist* singularity, one
    dividing the wrist centre's radial reach the *shoulder*, one in the last arm joint alone
    the *elbow*, any other factor of the arm block the *boundary* (the arm at the edge of its
    workspace); a factor without joint variables is a *constant*.

    >>> SingularityKind.SHOULDER.phrase, SingularityKind("boundary").phrase
    ('shoulder singularity', 'boundary singularity')
    >>> [k.value for k in SingularityKind]
    ['constant', 'elbow', 'shoulder', 'boundary', 'wrist']
    """

    CONSTANT = "constant"
    ELBOW = "elbow"
    SHOULDER = "shoulder"
    BOUNDARY = "boundary"
    WRIST = "wrist"

    @property
    def phrase(self) -> str:
        """The name a student reads: ``"<kind> singularity"`` (``"constant factor"``)."""
        if self is SingularityKind.CONSTANT:
            return "constant factor"
        return f"{self.value} singularity"


def _describe(
    kind: SingularityKind,
    robot: KinematicChain,
    joint: int | None,
    point: str,
    offset: sp.Expr | None,
) -> tuple[str, str]:
    if kind is SingularityKind.WRIST:
        where = "the first and last wrist axes line up, so two wrist joints turn about one axis"
    elif kind is SingularityKind.ELBOW:
        where = (
            f"joint {joint} stretches the arm out or folds it back: the boundary of the workspace"
        )
    elif kind is SingularityKind.SHOULDER:
        where = (
            f"the {point} lies on the axis of joint 1"
            if offset is None or offset == 0
            else f"the {point} lies on the line parallel to the axis of joint 1 "
            "at the shoulder offset"
        )
    elif kind is SingularityKind.BOUNDARY:
        where = "the arm joints lose a direction of motion: the arm is at the edge of its workspace"
    else:
        where = "a length of the table; the arm is singular everywhere if it is 0"
    return kind.phrase, where


# --- the result -----------------------------------------------------------------------------


@dataclass(frozen=True)
class Block:
    """One matrix whose determinant is a factor of the measure (``J11``, ``J22``, …)."""

    name: str
    matrix: Matrix
    frame: int | str
    determinant: sp.Expr


@dataclass(frozen=True)
class Singularities:
    """The factored determinant (or manipulability) and its named factors.

    ``measure`` names what is factored: ``"det J"`` (square), ``"det J_v"`` (a
    positioning arm), ``"det J_w"`` (a wrist alone) or ``"det(J J^T)"`` (the square of
    the manipulability ``w``). ``rows`` are the rows of the 6×n Jacobian it uses.
    """

    measure: str
    determinant: sp.Expr
    factors: tuple[SingularFactor, ...]
    blocks: tuple[Block, ...]
    rows: tuple[int, ...]
    method: str
    robot: KinematicChain = field(compare=False, repr=False)

    def text(self) -> str:
        """``det J = …`` in plain text."""
        return f"{self.measure} = {self.robot.notation.text(self.determinant)}"

    def latex(self) -> str:
        """The measure and its factored value in LaTeX."""
        head = {
            "det J": r"\det J",
            "det J_v": r"\det J_v",
            "det J_w": r"\det J_\omega",
            "det(J J^T)": r"\det(J J^{T})",
        }[self.measure]
        return f"{head} = {self.robot.notation.latex(self.determinant)}"

    @property
    def whole(self) -> bool:
        """True for the whole 6×6 ``J`` of an arm without a spherical wrist (one block, at
        the wrist point in a middle frame; see :func:`reference_point`)."""
        return self.measure == "det J" and len(self.blocks) == 1 and len(self.rows) == 6

    def verify(self) -> bool:
        """Exact proof that the factored form equals the determinant of ``J`` in frame 0.

        For the block form each block is proven against its own determinant in frame
        0 and the block triangle is checked (the wrist joints do not move the centre).
        The whole ``J`` of an arm without a spherical wrist is proven against the
        determinant of its own matrix (at the wrist point, in a middle frame) and then
        compared, exactly, with ``det J`` in frame 0 at the tool point at rational points
        (:func:`_equal_at_rational_points`).
        """
        robot = self.robot
        if self.whole:
            (block,) = self.blocks
            J0 = geometric_jacobian(robot, 0).matrix
            return (
                prove_equal(Matrix([block.determinant]), Matrix([block.matrix.det("berkowitz")]))
                and prove_equal(Matrix([self.determinant]), Matrix([block.determinant]))
                and _equal_at_rational_points(J0, self.determinant, robot)
            )
        if self.measure == "det J" and len(self.blocks) == 2:
            dec = decouple(robot, 3)
            J = geometric_jacobian(robot, 0, dec.centre).matrix
            if any(x != 0 for x in J[:3, 3:]):
                return False
            pieces = [J[:3, :3], J[3:, 3:]]
        elif self.blocks and self.blocks[0].name == "J22":
            J = geometric_jacobian(robot, 0, decouple(robot, 3).centre).matrix
            pieces = [J[3:, :]]
        else:
            J = geometric_jacobian(robot, 0).matrix
            pieces = [J.extract(list(self.rows), list(range(J.cols)))]
        if self.measure == "det(J J^T)":
            M = pieces[0] if pieces[0].rows <= pieces[0].cols else pieces[0].T
            return prove_equal(
                Matrix([self.determinant]), Matrix([(M * M.T).det(method="berkowitz")])
            )
        for block, M in zip(self.blocks, pieces):
            if not prove_equal(Matrix([block.determinant]), Matrix([M.det(method="berkowitz")])):
                return False
        product = sp.Mul(*(b.determinant for b in self.blocks))
        return prove_equal(Matrix([self.determinant]), Matrix([product]))

    def function(
        self, values: Mapping[Any, object] | None = None
    ) -> Callable[[object], np.ndarray]:
        """The compiled measure: ``(n,)`` → scalar, ``(N, n)`` → ``(N,)``."""
        return _compile(self.determinant, self.robot, values)

    def factor_functions(
        self, values: Mapping[Any, object] | None = None
    ) -> tuple[Callable[[object], np.ndarray], ...]:
        """One compiled function per non-constant factor (same order as ``factors``)."""
        return tuple(
            _compile(f.expr, self.robot, values) for f in self.factors if f.kind != "constant"
        )


def _equal_at_rational_points(
    J: sp.MatrixBase, det: sp.Expr, robot: KinematicChain, points: int = 3, seed: int = 0
) -> bool:
    """Whether ``det J = det`` at ``points`` random points where every sine and cosine is a
    rational number, compared exactly: each joint angle's ``(cos, sin)`` is the rational
    point ``((1 − t²)/(1 + t²), 2t/(1 + t²))`` of the unit circle, the lengths and the
    prismatic joints random rationals (seeded: the same points every run).

    >>> import dhsym
    >>> r = dhsym.load("planar2r")
    >>> J = sp.Matrix(r.jacobian().matrix[:2, :])
    >>> t2 = r.variables[1]
    >>> a1, a2 = sp.symbols("a1 a2", real=True)
    >>> _equal_at_rational_points(J, a1 * a2 * sp.sin(t2), r)
    True
    >>> _equal_at_rational_points(J, a1 * a2 * sp.cos(t2), r)
    False
    """
    import random

    rng = random.Random(seed)
    joints = {r.variable: r.joint for r in robot.table.rows if r.variable is not None}
    entries = [sp.expand_trig(e) for e in J] + [sp.expand_trig(det)]
    symbols = set().union(*(e.free_symbols for e in entries))
    for _ in range(points):
        at: dict[sp.Expr, sp.Expr] = {}
        for v, joint in joints.items():
            t = sp.Rational(rng.randint(-30, 30), rng.randint(1, 30))
            if joint is JointType.PRISMATIC:
                at[v] = t
            else:
                at[sp.cos(v)] = (1 - t**2) / (1 + t**2)
                at[sp.sin(v)] = 2 * t / (1 + t**2)
        for x in symbols - set(joints):
            at[x] = sp.Rational(rng.randint(1, 60), rng.randint(1, 30))
        values = [e.xreplace(at) for e in entries]
        if any(v.free_symbols for v in values):
            return False  # an angle that is not a sum of joint angles: not evaluated exactly
        M = sp.Matrix(J.rows, J.cols, values[:-1])
        if sp.simplify(M.det(method="bareiss") - values[-1]) != 0:
            return False
    return True


def _compile(
    expr: sp.Expr, robot: KinematicChain, values: Mapping[Any, object] | None
) -> Callable[[object], np.ndarray]:
    import numpy as np

    from .numeric import compile_matrix

    inner = compile_matrix(
        sp.Matrix([[expr]]), robot.variables, robot.table.with_values(values or {}).value_map
    )

    def evaluate(q: object) -> np.ndarray:
        out = inner(q)
        return np.asarray(out[..., 0, 0])

    return evaluate


# --- building -------------------------------------------------------------------------------


def _rotation_about_z0(robot: KinematicChain, k: int) -> bool:
    z = robot.transform(0, k).matrix[:3, 2]
    return list(z) == [0, 0, 1]


def _wrist_blocks(robot: KinematicChain, dec: Decoupling) -> tuple[Block, ...]:
    frames = range(0, dec.centre + 1)
    blocks = []
    if dec.arm:
        arm = [geometric_jacobian(robot, k, dec.centre).linear[:, : len(dec.arm)] for k in frames]
        det11 = _best_det(arm)
        blocks.append(Block("J11", Matrix(arm[0]), 0, det11))
    k = axis_frame(robot, dec.wrist[0])
    J22 = geometric_jacobian(robot, k, dec.centre).angular[:, len(dec.arm) :]
    blocks.append(Block("J22", Matrix(J22), k, factored_det(J22)))
    return tuple(blocks)


def _square_rows(J: Matrix, n: int) -> tuple[str, tuple[int, ...]] | None:
    nonzero = [i for i in range(6) if any(x != 0 for x in J.row(i))]
    position = [i for i in nonzero if i < 3]
    if len(position) == n:
        return "det J_v", tuple(position)
    if len(nonzero) == n:
        return "det J", tuple(nonzero)
    return None


def _normal_product(expr: sp.Expr) -> tuple[sp.Expr, list[tuple[sp.Expr, int]]]:
    """``expr`` as ``coefficient · Π baseᵖ`` with no base starting with a minus sign."""
    if expr.is_Add:
        coeff, pairs = sp.factor_list(expr)
    else:
        coeff, rest = expr.as_coeff_Mul()
        pairs = [f.as_base_exp() for f in sp.Mul.make_args(rest)] if rest != 1 else []
    out = []
    for base, power in pairs:
        if base.could_extract_minus_sign():
            base = -base
            coeff = -coeff if power % 2 else coeff
        out.append((base, int(power)))
    return coeff, out


def _name_factors(
    robot: KinematicChain,
    det: sp.Expr,
    wrist_factors: set[sp.Expr],
    geo: ArmGeometry | None,
    point: str,
    wrist_words: Mapping[sp.Expr, str] | None = None,
) -> tuple[sp.Expr, tuple[SingularFactor, ...]]:
    """The determinant with tidy signs, and its factors named (see the module text);
    ``wrist_words`` are the descriptions of wrist factors read from the axes (an arm
    without a spherical wrist), by factor."""
    variables = robot.variables
    joints = {r.variable: r.joint for r in robot.table.rows if r.variable is not None}
    number = {v: i for i, v in enumerate(variables, start=1)}
    coeff, pairs = _normal_product(det)
    wrist = {w if not w.could_extract_minus_sign() else -w for w in wrist_factors}
    out = []
    for base, power in pairs:
        vs = tuple(v for v in variables if v in base.free_symbols)
        if not vs:
            kind = SingularityKind.CONSTANT
        elif base in wrist:
            kind = SingularityKind.WRIST
        elif geo is not None and geo.radial is not None and _divides(base, geo.radial):
            kind = SingularityKind.SHOULDER
        elif len(vs) == 1 and vs[0] != variables[0] and joints[vs[0]] is JointType.REVOLUTE:
            kind = SingularityKind.ELBOW
        else:
            kind = SingularityKind.BOUNDARY
        offset = geo.offset if geo is not None else None
        name, text = _describe(kind, robot, number[vs[0]] if vs else None, point, offset)
        if kind is SingularityKind.WRIST and wrist_words and base in wrist_words:
            text = wrist_words[base]
        sols = _zeros(base, vs[0], joints[vs[0]]) if len(vs) == 1 else ()
        out.append(
            SingularFactor(
                base,
                power,
                kind.value,
                name,
                text,
                vs,
                tuple((vs[0], z) for z in sols),
                robot.notation,
            )
        )
    order = [k.value for k in SingularityKind]
    tidy = coeff * sp.Mul(*(b**p for b, p in pairs))
    return tidy, tuple(sorted(out, key=lambda f: order.index(f.kind)))


def _structure(robot: KinematicChain) -> tuple[Decoupling | None, ArmGeometry | None]:
    joints = len(robot.variables)
    for size in (3, 1, 0):
        if size >= joints and not (size == 3 and joints == 3):
            continue
        try:
            dec = decouple(robot, size)
            geo = arm_geometry(robot, dec) if dec.arm else None
        except StructureError:
            continue
        if size == 3 and joints not in (3, 6):
            continue
        return dec, geo
    return None, None


def _tool_geometry(robot: KinematicChain, fallback: ArmGeometry | None) -> ArmGeometry | None:
    """The arm geometry read up to the tool point (every joint an arm joint), so that a
    positioning arm's shoulder is named as the same arm's shoulder with a wrist is."""
    try:
        dec = decouple(robot, 0)
        return arm_geometry(robot, dec) if dec.arm else fallback
    except StructureError:
        return fallback


#: The bound on the whole 6×6 determinant of an arm without a spherical wrist: no minor's
#: expanded sum of more terms is factored (the UR arms' largest has 3 at the frame chosen, the
#: Kinova Jaco's 60, and its determinant does not factor); a table beyond it is refused in
#: seconds, not factored for minutes.
MAX_TERMS = 40


def reference_point(robot: KinematicChain) -> tuple[int | str, str]:
    """Where the whole Jacobian of a six-joint arm without a spherical wrist is taken: the
    frame whose origin is the point where the axes of the last two joints meet (the *wrist
    point*: those joints do not move it, so their columns of ``J_v`` vanish), else the
    tool point.

    >>> import dhsym
    >>> reference_point(dhsym.load("ur5")), reference_point(dhsym.load("planar4r"))
    ((5, 'wrist point'), ('tool', 'tool point'))
    """
    try:
        return decouple(robot, 2).centre, "wrist point"
    except StructureError:
        return "tool", "tool point"


def _vanishes(expr: sp.Expr) -> bool:
    """Exact proof that ``expr`` is 0 (a polynomial in sines and cosines)."""
    return expr == 0 or prove_equal(Matrix([expr]), Matrix([0]))


def _parallel(robot: KinematicChain, ref: int, frame: int, at: Mapping[sp.Symbol, sp.Expr]) -> bool:
    """Whether the z axis of ``frame`` is parallel to that of ``ref`` with ``at`` put in."""
    z = robot.transform(ref, frame).matrix[:3, 2]
    return _vanishes(z[0].subs(at)) and _vanishes(z[1].subs(at))


def _parallel_axes(robot: KinematicChain, det: sp.Expr) -> dict[sp.Expr, str]:
    """The factors of ``det`` in one revolute joint ``j`` (not the first or the last) at
    whose zeros the axes of joints ``j − 1`` and ``j + 1``, not parallel otherwise, become
    parallel: the wrist singularities of an arm without a spherical wrist, each with its
    description (which axes are then parallel), read from the axes, not from a name.

    >>> import dhsym
    >>> r = dhsym.load("ur5")
    >>> t3, t5 = sp.symbols("theta3 theta5", real=True)
    >>> import textwrap
    >>> print(textwrap.fill(_parallel_axes(r, sp.sin(t3) * sp.sin(t5))[sp.sin(t5)], 80))
    the axes of joints 4 and 6 are parallel: joints 2, 3, 4 and 6 turn about
    parallel axes, which move the tool in three directions only
    >>> list(_parallel_axes(r, sp.sin(t3) * sp.sin(t5)))  # θ3 = 0 makes no axes parallel
    [sin(theta5)]
    """
    rows = [i for i, r in enumerate(robot.table.rows, start=1) if r.variable is not None]
    variables = list(robot.variables)
    revolute = [robot.table.rows[r - 1].joint is JointType.REVOLUTE for r in rows]
    frames = [axis_frame(robot, r) for r in rows]
    out: dict[sp.Expr, str] = {}
    for base, _ in _normal_product(det)[1]:
        vs = [v for v in variables if v in base.free_symbols]
        if len(vs) != 1:
            continue
        j = variables.index(vs[0])
        if not 0 < j < len(rows) - 1 or not (revolute[j - 1] and revolute[j + 1]):
            continue
        zeros = _zeros(base, vs[0], JointType.REVOLUTE) if revolute[j] else ()
        if not zeros:
            continue
        ref, at = frames[j + 1], {vs[0]: zeros[0]}
        if _parallel(robot, ref, frames[j - 1], {}) or not _parallel(robot, ref, frames[j - 1], at):
            continue
        together = [
            k
            for k in range(len(rows))
            if revolute[k] and (k == j + 1 or _parallel(robot, ref, frames[k], at))
        ]
        names = [str(k + 1) for k in together]
        text = f"the axes of joints {j} and {j + 2} are parallel"
        if len(together) > 2:
            listed = ", ".join(names[:-1]) + f" and {names[-1]}"
            text += (
                f": joints {listed} turn about parallel axes, which move the tool in three "
                "directions only"
            )
        out[base] = text
    return out


def _whole(robot: KinematicChain) -> Singularities:
    """A six-joint arm without a spherical wrist (the UR arms): the whole ``J`` at the wrist
    point (:func:`reference_point`) in the middle frame where it has the most zeros, its
    determinant expanded along its sparsest lines, bounded by :data:`MAX_TERMS`."""
    point, where = reference_point(robot)
    middle = sorted(range(1, robot.n), key=lambda k: abs(2 * k - robot.n))[:3]
    mats = {k: geometric_jacobian(robot, k, point).matrix for k in middle}
    frame = max(middle, key=lambda k: sum(1 for x in mats[k] if x == 0))
    try:
        det = factored_det(mats[frame], max_terms=MAX_TERMS)
    except StructureError as err:
        raise StructureError(
            f"{robot.name or 'this arm'} has no spherical wrist and its 6×6 determinant (J at "
            f"the {where}, in frame {frame}) is not factored here: {err} (use the numeric "
            "measure)"
        ) from None
    try:
        geo: ArmGeometry | None = arm_geometry(robot, decouple(robot, 2))
    except StructureError:
        geo = _tool_geometry(robot, None)
    words = _parallel_axes(robot, det)
    block = Block("J", Matrix(mats[frame]), frame, det)
    det, named = _name_factors(robot, det, set(words), geo, where, words)
    method = (
        f"the whole J at the {where}, in frame {frame} (of the middle frames, the one where J "
        "has the most zeros): moving the point or turning the frame does not change det J"
    )
    return Singularities("det J", det, named, (block,), tuple(range(6)), method, robot)


def singularities(robot: KinematicChain) -> Singularities:
    """The factored Jacobian determinant of ``robot`` and its named singular factors.

    Derived once per table: kept in the disk cache (:mod:`dhsym.cache`; verified when read,
    :func:`stored_singularities`).

    >>> import dhsym
    >>> print(singularities(dhsym.load("stanford")).text())
    det J = d3**2*S2*S5
    >>> [f.kind for f in singularities(dhsym.load("stanford")).factors]
    ['shoulder', 'shoulder', 'wrist']
    >>> print(singularities(dhsym.load("planar4r")).measure)
    det(J J^T)
    """
    from dhsym.cache.keys import entry_name
    from dhsym.cache.store import derived_once

    def read(data: bytes) -> Singularities | None:
        found = stored_singularities(data, robot)
        return found if isinstance(found, Singularities) else None

    return derived_once(
        lambda: entry_name(robot.table, "singularities"),
        lambda: _derive(robot),
        singularities_data,
        read,
        StructureError,
    )


def singularities_data(result: Singularities) -> bytes | None:
    """``result`` as the data the disk cache keeps (:mod:`dhsym.cache.codec`: text and
    expressions, no code); ``None`` when an expression cannot be written."""
    from dhsym.cache.codec import CodecError, write_exprs

    items: list[Any] = [result.determinant]
    for f in result.factors:
        items += [f.expr, sp.Tuple(*f.variables)]
        items += [sp.Tuple(*(v for v, _ in f.solutions)), sp.Tuple(*(z for _, z in f.solutions))]
    for b in result.blocks:
        items += [b.matrix, b.determinant]
    try:
        exprs = write_exprs(items)
    except CodecError:
        return None
    meta = {
        "measure": result.measure,
        "rows": list(result.rows),
        "method": result.method,
        "factors": [[f.power, f.kind, f.name, f.description] for f in result.factors],
        "blocks": [[b.name, b.frame] for b in result.blocks],
    }
    return json.dumps({"singularities": meta, "exprs": exprs}).encode()


def stored_singularities(
    data: bytes, robot: KinematicChain
) -> Singularities | StructureError | None:
    """The :class:`Singularities` of :func:`singularities_data` for ``robot`` (printed in
    its notation), or the :class:`StructureError` kept for a table that has none; ``None``
    when the data is not what this version writes."""
    from dhsym.cache.codec import CodecError, read_exprs

    try:
        doc = json.loads(data)
        if isinstance(doc, dict) and isinstance(doc.get("refused"), str):
            return StructureError(doc["refused"])
        meta = doc["singularities"]
        items = read_exprs(doc["exprs"])
        det, k = items[0], 1
        factors = []
        for power, kind, name, description in meta["factors"]:
            expr, vs, sv, sz = items[k : k + 4]
            k += 4
            solutions = tuple(zip(sv.args, sz.args))
            factors.append(
                SingularFactor(
                    expr,
                    int(power),
                    str(kind),
                    str(name),
                    str(description),
                    tuple(vs.args),
                    solutions,
                    robot.notation,
                )
            )
        blocks = []
        for name, frame in meta["blocks"]:
            blocks.append(Block(str(name), items[k], frame, items[k + 1]))
            k += 2
        if k != len(items):
            return None
        rows = tuple(int(r) for r in meta["rows"])
        return Singularities(
            str(meta["measure"]),
            det,
            tuple(factors),
            tuple(blocks),
            rows,
            str(meta["method"]),
            robot,
        )
    except (CodecError, ValueError, KeyError, TypeError, IndexError, AttributeError):
        return None


def _derive(robot: KinematicChain) -> Singularities:
    n = len(robot.variables)
    if n > 6:
        raise StructureError(
            f"{robot.name or 'this arm'} has {n} joints: a redundant arm's manipulability is "
            "not factored here; evaluate sqrt(det(J Jᵀ)) from robot.jacob0(q) instead"
        )
    dec, geo = _structure(robot)
    if dec is not None and len(dec.wrist) == 3:
        blocks = _wrist_blocks(robot, dec)
        det = sp.Mul(*(b.determinant for b in blocks))
        wrist_factors = {b for b, _ in _normal_product(blocks[-1].determinant)[1]}
        if dec.arm:
            measure, rows = "det J", tuple(range(6))
            method = "J at the wrist centre is block lower triangular: det J = det J11 · det J22"
        else:
            measure, rows = "det J_w", (3, 4, 5)
            method = "a wrist alone: the determinant of its three axes"
        det, named = _name_factors(robot, det, wrist_factors, geo, "wrist centre")
        return Singularities(measure, det, named, blocks, rows, method, robot)
    J0 = geometric_jacobian(robot).matrix
    square = _square_rows(J0, n)
    frames = [k for k in range(0, robot.n + 1) if _rotation_about_z0(robot, k)]
    if square is not None:
        measure, rows = square
        if len(rows) == 6 and n == 6:
            return _whole(robot)
        if len(rows) > 4:
            raise StructureError(
                f"{robot.name or 'this arm'} has no spherical wrist: the {len(rows)}×{len(rows)} "
                "determinant is not factored here (use the numeric measure)"
            )
        mats = [
            geometric_jacobian(robot, k).matrix.extract(list(rows), list(range(n))) for k in frames
        ]
        det = _best_det(mats)
        method = "the position rows of J" if measure == "det J_v" else "the non-zero rows of J"
        block = Block("J", Matrix(mats[0]), 0, det)
        if measure == "det J_v":  # the reach that matters is the tool point's own
            geo = _tool_geometry(robot, geo)
        det, named = _name_factors(robot, det, set(), geo, "tool point")
        return Singularities(measure, det, named, (block,), rows, method, robot)
    rows = tuple(i for i in range(6) if any(x != 0 for x in J0.row(i)))
    M = J0.extract(list(rows), list(range(n)))
    wide = M if M.rows <= M.cols else M.T
    count = math.comb(wide.cols, wide.rows)
    if count > _MAX_MINORS:
        raise StructureError(
            f"{robot.name or 'this arm'}: det(J Jᵀ) is a sum of {count} squared minors, more "
            f"than the {_MAX_MINORS} factored here; evaluate sqrt(det(J Jᵀ)) from "
            "robot.jacob0(q) instead"
        )
    minors = [
        factored_det(wide.extract(list(range(wide.rows)), list(cols)))
        for cols in itertools.combinations(range(wide.cols), wide.rows)
    ]
    det = sp.Add(*[m**2 for m in minors])
    block = Block("J", Matrix(M), 0, det)
    return Singularities(
        "det(J J^T)",
        det,
        (),
        (block,),
        rows,
        "Cauchy–Binet: det(J Jᵀ) is the sum of the squared maximal minors",
        robot,
    )
