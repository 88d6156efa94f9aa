"""Joint axes as exact lines, and the line geometry the DH algorithm needs.

A joint axis is a line in space (a point and a unit direction) with a joint
type: ``R`` (the link turns about the line) or ``P`` (the link slides along
it; only the direction matters, Issac, Lecture 19). Two consecutive axes are *skew*
(one common normal), *intersecting* (a = 0), *parallel* (infinitely many common
normals, Ghosal, Lecture 5) or *coincident*. :func:`common_normal` finds the common
normal with its feet, exactly (Dimentberg's link length, Issac, Lecture 19).

Numbers are exact sympy values. Floats are read as the simplest exact number
within 1e-12 (a fraction with denominator at most 1000, or such a fraction times
√2, √3 or √6, or a fraction with denominator at most 10⁶; otherwise the float's
exact decimal), so ``0.7071067811865476``
becomes ``sqrt(2)/2``. Directions are numbers; points may hold symbols
(lengths such as ``a2``): then a zero or sign test that sympy cannot decide
uses the numeric ``values`` given, or raises :class:`~dhsym.errors.GeometryError`.

Examples
--------
>>> z1 = JointAxis((0, 0, 0), (0, 0, 2), "R", "1")
>>> z1.direction.T
Matrix([[0, 0, 1]])
>>> JointAxis((0, 0, 0), (1, 1, 0)).direction.T
Matrix([[sqrt(2)/2, sqrt(2)/2, 0]])
>>> cn = common_normal(z1, JointAxis((1, 0, 5), (0, 1, 0)))
>>> cn.relation.value, cn.foot1.T, cn.foot2.T, cn.length
('skew', Matrix([[0, 0, 5]]), Matrix([[1, 0, 5]]), 1)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import Enum
from fractions import Fraction
from functools import cached_property
from typing import Any, TypeAlias

import numpy as np
import sympy as sp

from dhsym.errors import GeometryError
from dhsym.kinematics.numeric import to_float
from dhsym.model.table import JointType, as_expr

__all__ = [
    "CommonNormal",
    "Frame",
    "JointAxis",
    "MEASURED_DIGITS",
    "Relation",
    "exact_matrix",
    "Tool",
    "classify",
    "common_normal",
    "cross",
    "dot",
    "entries",
    "exact_number",
    "measured",
    "is_zero_vector",
    "norm",
    "sign_of",
    "simplify_vector",
    "unit",
    "unit_direction",
    "vector",
]

Vector: TypeAlias = sp.ImmutableMatrix
Values = Mapping[sp.Symbol, sp.Expr]
_SURDS = (sp.Integer(1), sp.sqrt(2), sp.sqrt(3), sp.sqrt(6))


def exact_matrix(matrix: Any) -> sp.Matrix:  # sympy, numpy or rows; TypeError else
    """A sympy matrix for ``matrix``: a sympy matrix as it is, else rows of values each read
    by :func:`exact_number` (text through the whitelist parser, never sympified).

    >>> exact_matrix([[0.5, "a2"], [0, 1]])
    Matrix([
    [1/2, a2],
    [  0,  1]])
    """
    if isinstance(matrix, sp.MatrixBase):
        return sp.Matrix(matrix)
    return sp.Matrix([[exact_number(v) for v in row] for row in matrix])


def exact_number(value: object, *, field: str | None = None) -> sp.Expr:
    """An exact sympy number or expression for ``value`` (floats: simplest exact form).

    >>> exact_number(0.15005000000000002), exact_number(-0.8660254037844386)
    (3001/20000, -sqrt(3)/2)
    >>> exact_number("a2 + 1")
    a2 + 1
    """
    if hasattr(value, "dtype") and hasattr(value, "item"):  # numpy scalar
        value = value.item()
    if isinstance(value, float):
        return _from_float(value, field)
    try:
        return as_expr(value, field=field)
    except Exception as err:  # noqa: BLE001 - re-raised as a geometry error
        raise GeometryError(str(err), field=field) from None


#: significant digits of a measured entry (a URDF's decimals carry 4 to 9)
MEASURED_DIGITS = 12
#: largest numerator and denominator of the numbers of an exact form kept as it is
#: (``sqrt(2)/2``, ``3*pi/4``, ``1/3``)
_SMALL = 1000


def measured(value: sp.Expr) -> sp.Expr:
    """An entry as a textbook prints it: an exact form kept where the numbers given make
    one (a decimal as written, ``pi/2``, ``sqrt(2)/20``, ``atan2(1, 3)``), and a measured
    number (a fraction of 20 digits, the root of a large integer, the ``atan2`` of two
    such: what the frame geometry makes of a URDF's decimals) as its decimal to
    :data:`MEASURED_DIGITS` significant digits. An angle given by its tangent keeps it,
    the tangent as a decimal (``atan(0.0145842538689)``): its cosine and sine stay exact
    (the kernel takes a decimal angle in radians as measured, with float cosines, and an
    exact proof such as PoE = DH would meet floats). Joint variables stay as they are;
    only the constant part changes, by less than 5e-13 of itself.

    >>> from dhsym.model.entries import exact_decimal
    >>> exact_decimal(measured(sp.Rational(15726572319968823, 132156387503562500)))
    '0.118999714029'
    >>> exact_decimal(measured(sp.sqrt(134560049) / 100000))
    '0.116000021121'
    >>> th2 = sp.Symbol("theta2", real=True)
    >>> measured(th2 + sp.atan2(sp.Rational(4840101082143211, 331871697081907052), 1))
    theta2 + atan(145842538689/10000000000000)
    >>> measured(sp.Rational(-306, 10000)), measured(sp.pi / 2), measured(sp.sqrt(2) / 20)
    (-153/5000, pi/2, sqrt(2)/20)
    """
    if value.is_Rational or value.is_Symbol:  # most entries: no sum to split
        const, rest = (value, sp.Integer(0)) if value.is_Rational else (sp.Integer(0), value)
    else:
        const, rest = value.as_independent(*value.free_symbols, as_Add=True)
    if const == 0 or not const.is_number or _exact_form(const):
        return value
    if const.has(sp.atan):  # sympy writes atan2(y, x) of numbers as atan(y/x) (± pi)
        return rest + const.replace(sp.atan, lambda t: sp.atan(measured(t)))
    return rest + sp.Rational(f"{to_float(const):.{MEASURED_DIGITS}g}")


def _exact_form(value: sp.Expr) -> bool:
    """Whether a constant is kept: a decimal of at most :data:`MEASURED_DIGITS` significant
    digits, or an expression of small numbers (roots, π, ``atan2(1, 3)``)."""
    if value.is_Rational:
        return bool(value.q <= _SMALL) or value == sp.Rational(
            f"{float(value):.{MEASURED_DIGITS}g}"
        )
    if value.has(sp.Float):
        return False
    return all(abs(r.p) <= _SMALL and r.q <= _SMALL for r in value.atoms(sp.Rational))


def _from_float(f: float, field: str | None) -> sp.Expr:
    if f != f or f in (float("inf"), float("-inf")):
        raise GeometryError(f"non-finite number {f!r}", field=field)
    if abs(f) < 1e-14:
        return sp.Integer(0)
    candidates = [(surd, 1000) for surd in _SURDS] + [(_SURDS[0], 10**6)]
    for surd, largest in candidates:
        s = float(surd)
        frac = Fraction(f / s).limit_denominator(largest)
        if abs(float(frac) * s - f) <= 1e-12 * max(1.0, abs(f)):
            return sp.Rational(frac.numerator, frac.denominator) * surd
    return sp.Rational(repr(f))


def vector(values: object, *, field: str = "vector") -> Vector:
    """A 3×1 exact column vector from three numbers (a list, tuple, numpy or sympy matrix).

    >>> vector([1, 0.5, "d3"]).T
    Matrix([[1, 1/2, d3]])
    """
    if isinstance(values, sp.MatrixBase):
        items = list(entries(values))
        if values.shape == (3, 1) and all(c.is_Rational for c in items):
            return Vector(values)  # exact already: nothing to read (frames of a long chain)
    else:
        try:
            items = list(values)  # type: ignore[call-overload]  # anything: refused just below
        except TypeError:
            raise GeometryError(f"{field} must be three numbers, got {values!r}") from None
    if len(items) != 3:
        raise GeometryError(f"{field} must have three components, got {len(items)}")
    return Vector([exact_number(v, field=field) for v in items])


def sign_of(expr: sp.Expr, values: Values | None = None, *, what: str = "a length") -> int:
    """The sign (-1, 0, 1) of an exact expression; symbols are decided at ``values``.

    >>> a2 = sp.Symbol("a2", real=True)
    >>> sign_of(sp.sqrt(2) - 1), sign_of(a2 - 1, {a2: sp.Rational(1, 2)}), sign_of(a2**2 + 1)
    (1, -1, 1)
    """
    if expr.is_Rational:
        return int(sp.sign(expr))
    expr = sp.radsimp(sp.expand(expr)) if not expr.free_symbols else sp.expand(expr)
    for test, result in ((expr.is_zero, 0), (expr.is_positive, 1), (expr.is_negative, -1)):
        if test:
            return result
    if expr.free_symbols:
        known = {k: v for k, v in (values or {}).items() if k in expr.free_symbols}
        missing = expr.free_symbols - set(known)
        if missing:
            names = ", ".join(sorted(str(s) for s in missing))
            raise GeometryError(
                f"cannot decide the sign of {what} {expr}: give values for {names} "
                "(values={...}) or declare the symbols positive"
            )
        return sign_of(expr.subs(known), None, what=what)
    if sp.simplify(expr) == 0:
        return 0
    v = sp.N(expr, 50)
    return 0 if abs(v) < sp.Float("1e-40") else (1 if v > 0 else -1)


def entries(v: sp.MatrixBase) -> tuple[sp.Expr, ...]:
    """The entries of an exact vector or matrix, row by row.

    An immutable matrix holds them as its third argument (``args``: rows, columns, the
    flat entries): read there, without the per-entry indexing of iterating a sympy matrix
    (which dominates a long chain's frame assignment).

    >>> entries(vector([1, 0, "a2"]))
    (1, 0, a2)
    """
    if isinstance(v, sp.ImmutableDenseMatrix):
        return tuple(v.args[2])
    return tuple(v)


def _rational(u: sp.MatrixBase) -> bool:
    return all(c.is_Rational for c in entries(u))


def dot(u: sp.MatrixBase, v: sp.MatrixBase) -> sp.Expr:
    """``u · v`` of two exact 3-vectors.

    Rational vectors (most robot files) are multiplied entry by entry: the same exact
    number as sympy's ``Matrix.dot``, which first converts each 3-vector to a domain
    matrix and costs far more (a 100-joint chain calls this thousands of times); others
    go through ``Matrix.dot``, so their form is sympy's.

    >>> dot(vector([1, 2, 3]), vector([0.5, 0, 1])), dot(vector(["a2", 0, 0]), vector([2, 0, 0]))
    (7/2, 2*a2)
    """
    if _rational(u) and _rational(v):
        return sp.Add(*(a * b for a, b in zip(entries(u), entries(v), strict=True)))
    return u.dot(v)


def cross(u: sp.MatrixBase, v: sp.MatrixBase) -> Vector:
    """``u × v`` of two exact 3-vectors (rational ones entry by entry, as :func:`dot`).

    >>> cross(vector([1, 0, 0]), vector([0, 1, 0])).T
    Matrix([[0, 0, 1]])
    """
    if _rational(u) and _rational(v):
        (a, b, c), (x, y, z) = entries(u), entries(v)
        return Vector([b * z - c * y, c * x - a * z, a * y - b * x])
    return Vector(u.cross(v))


def is_zero_vector(v: Vector, values: Values | None = None) -> bool:
    """True when every component of ``v`` is zero (symbols decided at ``values``).

    >>> is_zero_vector(vector([0, sp.sqrt(2) - sp.sqrt(8) / 2, 0]))
    True
    """
    return all(sign_of(c, values) == 0 for c in entries(v))


def norm(v: Vector, values: Values | None = None) -> sp.Expr:
    """Exact Euclidean norm; ``sqrt(x**2)`` becomes ``±x`` by the sign of ``x`` at ``values``.

    >>> a2 = sp.Symbol("a2", real=True)
    >>> norm(vector([0, "a2", 0]), {a2: 1}), norm(vector([3, 4, 0]))
    (a2, 5)
    """
    n2 = sp.factor(sp.expand(dot(v, v)))
    r = sp.sqrt(n2)
    if r.has(sp.Abs):
        r = r.replace(sp.Abs, lambda x: sign_of(x, values) * x)
    return sp.radsimp(r) if not r.free_symbols else r


def unit(v: Vector, values: Values | None = None) -> Vector:
    """``v / |v|`` exactly (radicals rationalised).

    >>> unit(vector([1, 0, 1])).T
    Matrix([[sqrt(2)/2, 0, sqrt(2)/2]])
    """
    n = norm(v, values)
    return Vector([c / n if (c / n).is_Rational else sp.radsimp(sp.simplify(c / n)) for c in v])


#: Largest component of the primitive integer vector of a direction normalised exactly
#: (``(1, 1, 0)`` → ``sqrt(2)/2``); larger ones, and sums of roots of integers above
#: :data:`_SMALL_NUMBER`, are normalised in floating point (:func:`unit_direction`).
_SMALL_DIRECTION = 100
_SMALL_NUMBER = 10**12


def unit_direction(d: Vector) -> Vector:
    """The unit vector along a direction of numbers, exact where that stays cheap.

    A direction that is already exactly unit is kept; a small-integer direction (the
    components in the ratio of integers up to 100: ``(0.6, 0, 0.8)``, ``(1, 1, 0)``) and
    one of small radicals (``(sqrt(3)/2, 1/2, 0)``) is normalised exactly. Any other (a
    measured direction such as ``(0.3, 1e-17, 0.95)``) is normalised in floating point
    and read as the nearest *rational* unit vector (stereographic coordinates within
    1e-12), so it is exactly unit, its arithmetic stays rational, and no huge number is
    ever factorised.

    >>> unit_direction(vector([0.6, 0, 0.8])).T, unit_direction(vector([1, 1, 0])).T
    (Matrix([[3/5, 0, 4/5]]), Matrix([[sqrt(2)/2, sqrt(2)/2, 0]]))
    >>> u = unit_direction(vector([3, sp.Rational("1e-40"), 7]))
    >>> u.dot(u), [round(float(c), 12) for c in u]
    (1, [0.393919298579, 0.0, 0.919145030018])
    """
    n2 = sp.expand(dot(d, d))
    if n2 == 1:
        return Vector(d)
    if all(c.is_Rational for c in d):
        scale = sp.ilcm(*(c.q for c in d))
        ints = [int(c * scale) for c in d]
        g = sp.igcd(*ints)
        primitive = [i // g for i in ints]
        if max(abs(i) for i in primitive) <= _SMALL_DIRECTION:
            return unit(Vector(primitive))
        return _rational_unit(d)
    atoms = [a for a in (*d.atoms(sp.Rational), *n2.atoms(sp.Rational))]
    if all(abs(a.p) <= _SMALL_NUMBER and a.q <= _SMALL_NUMBER for a in atoms):
        return unit(d)
    return _rational_unit(d)


def _rational_unit(d: Vector) -> Vector:
    """The rational unit vector nearest (within about 1e-12) the float normalisation of ``d``:
    inverse stereographic projection ``(2s, 2t, 1 − s² − t²)/(1 + s² + t²)`` of rational
    ``s, t`` (from the pole opposite the largest component, so nothing divides by ~0)."""
    big = max(abs(to_float(c)) for c in d)
    f = np.array([to_float(c) / big for c in d])  # scaled first: 1e300 would overflow
    f = f / np.linalg.norm(f)
    k = int(np.argmax(np.abs(f)))
    sign = 1 if f[k] > 0 else -1
    i, j = [m for m in range(3) if m != k]
    s, t = (
        sp.Rational(Fraction(f[m] / (1 + sign * f[k])).limit_denominator(_SMALL_NUMBER))
        for m in (i, j)
    )
    r = 1 + s**2 + t**2
    out = [sp.Integer(0)] * 3
    out[i], out[j], out[k] = 2 * s / r, 2 * t / r, sign * (1 - s**2 - t**2) / r
    return Vector(out)


def simplify_vector(v: sp.MatrixBase) -> Vector:
    """Entry-wise ``simplify`` + ``radsimp`` (small exact vectors only).

    >>> simplify_vector(sp.Matrix([1 / sp.sqrt(2), sp.sin(1) ** 2 + sp.cos(1) ** 2, 0])).T
    Matrix([[sqrt(2)/2, 1, 0]])
    """
    return Vector([c if c.is_Rational else sp.radsimp(sp.simplify(c)) for c in entries(v)])


@dataclass(frozen=True)
class JointAxis:
    """A joint axis: a line through ``point`` along unit ``direction``, joint ``'R'`` or ``'P'``.

    ``direction`` is normalised exactly; a zero direction raises
    :class:`~dhsym.errors.GeometryError` naming the joint.

    >>> JointAxis((0, 0, 0), (0, 0, 0), "R", "2")
    Traceback (most recent call last):
    ...
    dhsym.errors.GeometryError: joint 2: the direction of the axis has zero length
    """

    point: Vector
    direction: Vector
    joint: str = "R"
    name: str = ""

    def __post_init__(self) -> None:
        label = f"joint {self.name}" if self.name else "joint axis"
        try:
            kind = JointType.parse(self.joint)
        except Exception:  # noqa: BLE001
            raise GeometryError(
                f"{label}: unknown joint type {self.joint!r}: expected R or P"
            ) from None
        if kind is JointType.FIXED:
            raise GeometryError(f"{label}: a joint axis is R or P, not fixed")
        object.__setattr__(self, "joint", kind.value)
        object.__setattr__(self, "name", str(self.name))
        point = vector(self.point, field="point")
        d = vector(self.direction, field="direction")
        if d.free_symbols:
            raise GeometryError(f"{label}: the direction must be numbers, got {tuple(d)}")
        if is_zero_vector(d):
            raise GeometryError(f"{label}: the direction of the axis has zero length")
        object.__setattr__(self, "point", point)
        object.__setattr__(self, "direction", unit_direction(d))

    @property
    def label(self) -> str:
        """``joint NAME`` for messages.

        >>> JointAxis((0, 0, 0), (0, 0, 1), "P", "3").label
        'joint 3'
        """
        return f"joint {self.name}" if self.name else "joint axis"

    def at(self, t: object) -> Vector:
        """The point ``point + t·direction``.

        >>> JointAxis((1, 0, 0), (0, 0, 2)).at(3).T
        Matrix([[1, 0, 3]])
        """
        return Vector(self.point + exact_number(t) * self.direction)

    def contains(self, p: object, values: Values | None = None) -> bool:
        """True when point ``p`` lies on the line.

        >>> JointAxis((1, 0, 0), (0, 0, 1)).contains((1, 0, 7))
        True
        """
        w = vector(p) - self.point
        return is_zero_vector(cross(w, self.direction), values)

    def foot(self, p: object) -> Vector:
        """The foot of the perpendicular from ``p`` onto the line (the closest point).

        >>> JointAxis((1, 0, 0), (0, 0, 1)).foot((5, 5, 2)).T
        Matrix([[1, 0, 2]])
        """
        w = vector(p) - self.point
        return simplify_vector(self.point + dot(w, self.direction) * self.direction)

    def motion(self, q: float, values: Values | None = None) -> np.ndarray:
        """The 4×4 rigid motion (numbers) of turning by ``q`` about (R) or sliding ``q`` along (P).

        >>> JointAxis((1, 0, 0), (0, 0, 1)).motion(np.pi)[:3, 3].round(12) + 0.0
        array([2., 0., 0.])
        """
        one: np.ndarray = self.motions(np.array([q], dtype=float), values)[0]
        return one

    def motions(self, q: np.ndarray, values: Values | None = None) -> np.ndarray:
        """The motions of :meth:`motion` for ``N`` values of ``q`` at once: ``(N, 4, 4)``
        (the line read as floats once: Rodrigues' formula, Lynch and Park,
        *Modern Robotics*, 3.2.3.3).

        >>> JointAxis((0, 0, 0), (0, 0, 1), "P").motions(np.array([1.0, 2.0]))[:, 2, 3]
        array([1., 2.])
        """
        subs = dict(values or {})
        p = np.array([to_float(c.xreplace(subs)) for c in self.point])
        u = np.array([to_float(c) for c in self.direction])
        q = np.asarray(q, dtype=float).reshape(-1)
        M = np.tile(np.eye(4), (q.size, 1, 1))
        if self.joint == "P":
            M[:, :3, 3] = q[:, None] * u
            return M
        K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
        R = np.eye(3) + np.sin(q)[:, None, None] * K + (1 - np.cos(q))[:, None, None] * (K @ K)
        M[:, :3, :3], M[:, :3, 3] = R, p - R @ p
        return M


class Relation(str, Enum):
    """How two lines lie: the DH special cases (Ghosal, Lecture 5)."""

    SKEW = "skew"
    INTERSECTING = "intersecting"
    PARALLEL = "parallel"
    COINCIDENT = "coincident"


@dataclass(frozen=True)
class CommonNormal:
    """The common normal of two lines: feet on each line, unit direction, length.

    ``direction`` points from ``foot1`` to ``foot2``; it is ``None`` when the
    lines intersect or coincide (length 0). For parallel lines the normal is
    not unique: this one passes through the ``through`` point on line 1.
    """

    relation: Relation
    foot1: Vector
    foot2: Vector
    direction: Vector | None
    length: sp.Expr


def classify(l1: JointAxis, l2: JointAxis, values: Values | None = None) -> Relation:
    """Skew, intersecting, parallel or coincident.

    >>> z = JointAxis((0, 0, 0), (0, 0, 1))
    >>> [classify(z, JointAxis(p, d)).value for p, d in
    ...  [((1, 0, 0), (0, 0, -1)), ((0, 0, 3), (0, 0, 1)), ((0, 0, 3), (1, 0, 0))]]
    ['parallel', 'coincident', 'intersecting']
    """
    return common_normal(l1, l2, values=values).relation


def common_normal(
    l1: JointAxis,
    l2: JointAxis,
    *,
    through: object | None = None,
    values: Values | None = None,
) -> CommonNormal:
    """The common normal of two lines with its feet (exact).

    Parameters
    ----------
    l1, l2
        The lines.
    through
        For parallel lines: the point of ``l1`` the chosen normal passes
        through (default: ``l1.point``); ignored otherwise.
    values
        Numbers for symbols in the points, used only to decide zero and sign.

    >>> z0 = JointAxis((0, 0, 0), (0, 0, 1))
    >>> cn = common_normal(z0, JointAxis(("a1", 0, 3), (0, 0, 1)), through=(0, 0, 1),
    ...                    values={sp.Symbol("a1", real=True): 1})
    >>> cn.relation.value, cn.foot2.T, cn.direction.T, cn.length
    ('parallel', Matrix([[a1, 0, 1]]), Matrix([[1, 0, 0]]), a1)
    """
    u1, u2 = l1.direction, l2.direction
    w = Vector(l2.point - l1.point)
    c = cross(u1, u2)
    if is_zero_vector(c):
        start = l1.point if through is None else vector(through, field="through")
        w = Vector(l2.point - start)
        perp = simplify_vector(w - dot(w, u1) * u1)
        if is_zero_vector(perp, values):
            return CommonNormal(Relation.COINCIDENT, start, start, None, sp.Integer(0))
        length = norm(perp, values)
        direction = simplify_vector(perp / length)
        return CommonNormal(
            Relation.PARALLEL, start, simplify_vector(start + perp), direction, length
        )
    cc = dot(c, c)
    t1 = dot(cross(w, u2), c) / cc
    t2 = dot(cross(w, u1), c) / cc
    foot1 = simplify_vector(l1.point + t1 * u1)
    foot2 = simplify_vector(l2.point + t2 * u2)
    gap = simplify_vector(foot2 - foot1)
    if is_zero_vector(gap, values):
        return CommonNormal(Relation.INTERSECTING, foot1, foot1, None, sp.Integer(0))
    length = norm(gap, values)
    return CommonNormal(Relation.SKEW, foot1, foot2, simplify_vector(gap / length), length)


@dataclass(frozen=True)
class Frame:
    """A frame at the home pose: origin and unit x, z axes (y = z × x), exact.

    >>> Frame(0, vector([0, 0, 1]), vector([1, 0, 0]), vector([0, 0, 1])).y.T
    Matrix([[0, 1, 0]])
    """

    index: int | str
    origin: Vector
    x: Vector
    z: Vector

    def __post_init__(self) -> None:
        for key in ("origin", "x", "z"):
            object.__setattr__(self, key, vector(getattr(self, key), field=f"frame {key}"))
        checks = (dot(self.x, self.x) - 1, dot(self.z, self.z) - 1, dot(self.x, self.z))
        if any(sign_of(c) != 0 for c in checks):
            raise GeometryError(f"frame {self.index}: x and z must be orthogonal unit vectors")

    @property
    def y(self) -> Vector:
        """``z × x`` (right-handed)."""
        return cross(self.z, self.x)

    @cached_property
    def matrix(self) -> sp.ImmutableMatrix:
        """The 4×4 pose of the frame in world coordinates (built once per frame: the frame
        assignment and its checks read it for every frame of a chain)."""
        columns = [entries(v) for v in (self.x, self.y, self.z, self.origin)]
        top = [columns[j][i] for i in range(3) for j in range(4)]
        return sp.ImmutableMatrix(4, 4, [*top, 0, 0, 0, 1])

    @classmethod
    def from_matrix(cls, T: Any, index: int | str = "") -> Frame:  # sympy, numpy or lists
        """Read a 4×4 pose (sympy, numpy or nested lists); checks that it is rigid.

        >>> Frame.from_matrix([[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]).x.T
        Matrix([[0, 1, 0]])
        """
        rows = T.tolist() if hasattr(T, "tolist") else list(T)
        M = sp.Matrix([[exact_number(v) for v in row] for row in rows])
        if M.shape != (4, 4):
            raise GeometryError(f"frame {index}: expected a 4×4 matrix, got {M.shape}")
        R = M[:3, :3]
        if not is_zero_vector(Vector(list(R.T * R - sp.eye(3)))) or sign_of(R.det() - 1) != 0:
            raise GeometryError(f"frame {index}: the 3×3 part is not a rotation")
        return cls(index, Vector(M[:3, 3]), Vector(M[:3, 0]), Vector(M[:3, 2]))


@dataclass(frozen=True)
class Tool:
    """Tool point with approach ``a`` (z_n) and sliding ``s`` (y_n) vectors (Asokan, Lecture 2.6).

    >>> Tool((0, 0, 1), (0, 0, 1), (1, 0, 1))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dhsym.errors.GeometryError: tool: the approach vector a = ... got a·s = sqrt(2)/2 (unit vectors)
    """

    point: Vector
    approach: Vector
    sliding: Vector

    def __post_init__(self) -> None:
        raw = {
            k: vector(getattr(self, k), field=f"tool {k}") for k in ("point", "approach", "sliding")
        }
        for k in ("approach", "sliding"):
            if raw[k].free_symbols or is_zero_vector(raw[k]):
                raise GeometryError(
                    f"tool: the {k} vector must be non-zero numbers, got {tuple(raw[k])}"
                )
        a, s = unit(raw["approach"]), unit(raw["sliding"])
        dot = sp.radsimp(sp.simplify(a.dot(s)))
        if dot != 0:
            raise GeometryError(
                f"tool: the approach vector a = {tuple(raw['approach'])} and the sliding vector "
                f"s = {tuple(raw['sliding'])} must be orthogonal; got a·s = {dot} (unit vectors)"
            )
        object.__setattr__(self, "point", raw["point"])
        object.__setattr__(self, "approach", a)
        object.__setattr__(self, "sliding", s)

    @property
    def frame(self) -> Frame:
        """The tool frame: x = n = s × a, y = s, z = a.

        >>> Tool((0, 0, 1), (0, 0, -1), (0, 1, 0)).frame.x.T
        Matrix([[-1, 0, 0]])
        """
        return Frame("tool", self.point, cross(self.sliding, self.approach), self.approach)
