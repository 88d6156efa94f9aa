r"""Closed-form inverse kinematics, derived as lecture steps, and its compiled solver.

:func:`inverse` reads the structure of a DH table (never its name) and derives the
joint values from a pose ``T = [n s a p; 0 0 0 1]`` step by step, the way the
lectures do (Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, §5.3;
Craig, *Introduction to Robotics*, §4.7):

1. **Kinematic decoupling.** When the last three axes meet in one point (a spherical
   wrist), that point, the *wrist centre* ``c``, depends on the first three joints only:
   ``c = p + R ·ⁿc``. With one last revolute joint (planar 3R, SCARA) a point of its
   axis plays the same part; a positioning arm places its tool point ``p`` itself.
2. **Position.** Joint 1 turns the arm about ``z0``. If the wrist centre keeps a
   constant *shoulder offset* ``e`` from the plane of joints 2 and 3, its radial reach is
   ``r = ±√(x_c² + y_c² − e²)`` (left/right arm) and ``θ1 = atan2(y_c, x_c) − atan2(e, r)``.
   The remaining joints come from the equations of the arm's plane: the sum of squares
   (the law of cosines: elbow up/down, or ``±√`` for a prismatic reach) and then the
   two coordinates together, linear in ``C_j, S_j`` (one ``atan2``). A planar arm gets
   its elbow from ``x² + y²`` first and ``θ1`` last.
3. **Orientation.** ``R_w = (ᵃʳᵐR)ᵀ R`` is the wrist's own rotation
   ``Rz(θ4) Rx(α4) Rz(θ5) Rx(α5) Rz(θ6)``: ``θ5`` from one entry (``±√``: the wrist
   flip), ``θ4`` and ``θ6`` from its row and column by ``atan2``.

Every step is a :class:`Step` — a sentence and exact sympy expressions; ``atan2`` and
the signs ``σ = ±1`` of each branch are explicit. :meth:`InverseKinematics.solver`
compiles the steps once (``lambdify`` with the steps as the common subexpressions) into a
numpy function over a batch of poses and all branches at once.

Results. One pose ``(4, 4)`` gives an :class:`IKSolution`: ``q`` is ``(k, n)`` (k ≤ 8,
only real, checked, distinct solutions) with a name per solution and the singularities
each one is near. A batch ``(N, 4, 4)`` gives an :class:`IKBatch`: ``q`` is padded to
``(N, K, n)`` with NaN, ``valid`` ``(N, K)`` is the mask, ``K = 2^(number of branches)``.
By default a branch is kept only when its ``fk`` reproduces the whole pose to ``1e-9``
(``check="pose"``). An arm with fewer than six joints cannot reach every pose, so a branch
that only matches the coordinates it solves is dropped: a planar 2R has one solution for
a whole pose and two (elbow up and down) for a position ``(3,)``. Near a singularity a
solution is flagged (``singular``) with the kind of the singular factor (from
:mod:`dhsym.singularities`); at ``sin θ5 = 0`` only ``θ4 + θ6`` is defined and ``θ4 = 0``.

Arms without such structure get a :class:`~dhsym._structure.StructureError` naming
what is missing; :func:`numeric_ik` is a separate, clearly numeric Levenberg–Marquardt
solver on the compiled ``fk``.

Examples
--------
>>> import dhsym
>>> ik = inverse(dhsym.load("planar2r"))
>>> for step in ik.steps:
...     print(ik.text(step))
D_2 = (-a1**2 - a2**2 + p_x**2 + p_y**2)/(2*a1*a2)
theta2 = atan2(sigma_2*sqrt(1 - D_2**2), D_2)
theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)
>>> r = dhsym.load("puma560")
>>> q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
>>> sol = r.ik(r.fk(q))
>>> len(sol), bool(np.abs(sol.q - q).max(axis=1).min() < 1e-9)
(8, True)
>>> sol.branches[0]
'right arm, elbow down, wrist not flipped'
"""

from __future__ import annotations

import functools
import itertools
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from ._structure import ArmGeometry, Decoupling, StructureError, arm_geometry, decouple
from .errors import DHError
from .jacobian import _values, axis_frame, compact
from .simplification import compose, trig_coefficients
from .table import Elementary, JointType
from .transforms import chain_word, plain_product

if TYPE_CHECKING:
    from .robot import Robot
    from .singularities import Singularities

__all__ = [
    "Branch",
    "IKBatch",
    "IKSolution",
    "InverseKinematics",
    "NumericSolution",
    "Step",
    "StructureError",
    "inverse",
    "numeric_ik",
    "pose_symbols",
]

Matrix = sp.ImmutableMatrix
_REAL = {"real": True}


def pose_symbols() -> Matrix:
    """The symbolic pose ``[n s a p; 0 0 0 1]`` (normal, sliding, approach, position).

    >>> pose_symbols()[:3, 3].T
    Matrix([[p_x, p_y, p_z]])
    """
    cols = []
    for v in "nsap":
        cols.append([sp.Symbol(f"{v}_{c}", **_REAL) for c in "xyz"])
    M = sp.Matrix(3, 4, lambda i, j: cols[j][i])
    return Matrix(M.col_join(sp.Matrix([[0, 0, 0, 1]])))


# --- plain data ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Branch:
    """A choice of sign ``symbol = ±1`` made by one step.

    ``role`` is ``"arm"`` (left/right), ``"elbow"`` (up/down), ``"reach"`` (the sign of
    a prismatic ``±√``) or ``"wrist"`` (flip); ``joint`` is the joint it decides.
    """

    symbol: sp.Symbol
    role: str
    joint: int
    sentence: str


@dataclass(frozen=True)
class Step:
    """One line of the derivation: ``lhs = rhs``, exact, with the sentence that explains it.

    ``part`` is ``"wrist centre"``, ``"position"`` or ``"orientation"``; ``equation`` is
    the equation this step solves (when it solves one); ``branch`` the sign it
    introduces; ``singular`` the value used instead when the wrist is singular
    (``sin θ5 = 0``: only ``θ4 + θ6`` is determined, so ``θ4`` is set to 0).
    """

    part: str
    text: str
    lhs: sp.Symbol
    rhs: sp.Expr
    equation: sp.Eq | None = None
    branch: Branch | None = None
    singular: sp.Expr | None = None


# --- equations of the position sub-problem ------------------------------------------------


def _reduce(expr: sp.Expr, revolute: Sequence[sp.Symbol]) -> sp.Expr:
    """Expand into sines and cosines of single joint angles; ``sin² = 1 − cos²``."""
    e = sp.expand(sp.expand_trig(expr))
    for x in revolute:
        s, c = sp.sin(x), sp.cos(x)

        def is_power(t: sp.Expr, s: sp.Expr = s) -> bool:
            return t.is_Pow and t.base == s and t.exp.is_Integer and t.exp >= 2

        def lower(t: sp.Pow, s: sp.Expr = s, c: sp.Expr = c) -> sp.Expr:
            k = int(t.exp)
            return (1 - c**2) ** (k // 2) * s ** (k % 2)

        e = sp.expand(e.replace(is_power, lower))
    return e


def _poly_coefficients(e: sp.Expr, d: sp.Symbol) -> list[sp.Expr] | None:
    """Coefficients (highest first) of ``e`` as a polynomial of degree ≤ 2 in ``d``."""
    poly = sp.Poly(e, d)
    if poly.degree() > 2 or poly.degree() < 1:
        return None
    coeffs = poly.all_coeffs()
    if any(d in c.free_symbols for c in coeffs):
        return None
    return coeffs


@dataclass(frozen=True)
class _Equation:
    expr: sp.Expr  # = 0
    shown: sp.Eq
    name: str


# --- the derivation --------------------------------------------------------------------------


class _Builder:
    """Collects steps and branches while the structure is solved."""

    def __init__(self, robot: Robot, dec: Decoupling) -> None:
        self.robot = robot
        self.dec = dec
        self.steps: list[Step] = []
        self.branches: list[Branch] = []
        rows = robot.table.rows
        self.variables = robot.variables
        self.number = {v: i for i, v in enumerate(self.variables, start=1)}
        self.revolute = [r.variable for r in rows if r.joint is JointType.REVOLUTE]
        self.kind = {r.variable: r.joint for r in rows if r.variable is not None}

    def add(self, part: str, text: str, lhs: sp.Symbol, rhs: sp.Expr, **kw: object) -> sp.Symbol:
        self.steps.append(Step(part, text, lhs, rhs, **kw))  # type: ignore[arg-type]
        return lhs

    def branch(self, role: str, var: sp.Symbol, sentence: str) -> Branch:
        j = self.number[var]
        b = Branch(sp.Symbol(f"sigma_{j}", **_REAL), role, j, sentence)
        self.branches.append(b)
        return b

    def tidy(self, e: sp.Expr) -> sp.Expr:
        return compact(sp.factor_terms(e))


def _solve_joint_from_entry(value: sp.Expr, x: sp.Expr, var: sp.Symbol) -> sp.Expr:
    """``var`` from ``x = value`` where ``x`` is a joint's DH argument ``rate·var + offset``."""
    rate = sp.diff(x, var)
    offset = sp.expand(x - rate * var)
    return (value - offset) / rate


def _position(b: _Builder, geo: ArmGeometry, target: Matrix) -> None:
    """Steps for the arm joints from the point ``target`` (symbols of c or p)."""
    robot, dec = b.robot, b.dec
    table = robot.table
    arm_vars = [table.rows[r - 1].variable for r in dec.arm]
    P = geo.prefix_matrix
    u = target
    if P != sp.eye(4):
        Rp, tp = P[:3, :3], P[:3, 3]
        local = (Rp.T * (target - tp)).applyfunc(sp.expand)
        names = [sp.Symbol(f"u_{c}", **_REAL) for c in "xyz"]
        for name, value in zip(names, local):
            b.add(
                "position",
                "The point in the frame before joint 1 (undo the constant "
                "transform that precedes it).",
                name,
                value,
            )
        u = Matrix(names)
    ux, uy, uz = u
    g = geo.point
    q1 = arm_vars[0]
    unknowns = list(arm_vars[1:])
    equations: list[_Equation] = []
    final_theta1: tuple[sp.Expr, sp.Expr] | None = None
    if geo.first.kind == "R":
        if geo.offset_axis is not None:
            e = geo.offset
            radial_axis = 1 - geo.offset_axis
            r = sp.Symbol("r", **_REAL)
            arm = b.branch(
                "arm",
                q1,
                "σ = +1: right arm (the wrist centre in front of the shoulder, "
                "r > 0); σ = −1: left arm",
            )
            sigma = arm.symbol
            reach = sp.sqrt(ux**2 + uy**2 - e**2)
            b.add(
                "position",
                "Joint 1 turns the arm about z0; the point keeps the shoulder offset "
                f"e = {sp.sstr(e)} from the plane of the arm, so its reach in that plane is",
                r,
                sigma * reach,
                equation=sp.Eq(ux**2 + uy**2, r**2 + e**2),
                branch=arm,
            )
            if e == 0 and radial_axis == 0:
                x1 = sp.atan2(sigma * uy, sigma * ux)
            elif e == 0:
                x1 = sp.atan2(-sigma * ux, sigma * uy)
            else:
                gx, gy = (r, e) if radial_axis == 0 else (e, r)
                x1 = sp.atan2(uy, ux) - sp.atan2(gy, gx)
            b.add(
                "position",
                "The angle of the point minus the angle of (r, e) in the arm's frame:",
                q1,
                _solve_joint_from_entry(x1, geo.first.value, q1),
            )
            radial, height = g[radial_axis], g[2]
            kr = sp.Add(
                *[
                    t
                    for t in sp.Add.make_args(sp.expand(radial))
                    if not t.free_symbols & set(unknowns)
                ]
            )
            kz = sp.Add(
                *[
                    t
                    for t in sp.Add.make_args(sp.expand(height))
                    if not t.free_symbols & set(unknowns)
                ]
            )
            r2 = (ux**2 + uy**2 - e**2) if kr == 0 else (r - kr) ** 2
            equations += [
                _Equation(
                    (radial - kr) ** 2 + (height - kz) ** 2 - r2 - (uz - kz) ** 2,
                    sp.Eq((radial - kr) ** 2 + (height - kz) ** 2, r2 + (uz - kz) ** 2),
                    "the sum of squares of the two coordinates in the arm's plane",
                ),
                _Equation(radial - r, sp.Eq(radial, r), "the reach in the arm's plane"),
                _Equation(height - uz, sp.Eq(height, uz), "the height"),
            ]
        else:
            equations += [
                _Equation(
                    g[0] ** 2 + g[1] ** 2 - ux**2 - uy**2,
                    sp.Eq(g[0] ** 2 + g[1] ** 2, ux**2 + uy**2),
                    "the squared distance from the axis of joint 1",
                ),
                _Equation(g[2] - uz, sp.Eq(g[2], uz), "the height"),
            ]
            final_theta1 = (g[0], g[1])
    else:
        unknowns = list(arm_vars)
        full = geo.first.value
        point = Matrix([g[0], g[1], g[2] + full])
        for i, c in enumerate("xyz"):
            equations.append(
                _Equation(point[i] - u[i], sp.Eq(point[i], u[i]), f"the {c} coordinate")
            )
    _solve_equations(b, equations, unknowns)
    if final_theta1 is not None:
        gx, gy = (b.tidy(v) for v in final_theta1)
        x1 = sp.atan2(uy, ux) - sp.atan2(gy, gx)
        b.add(
            "position",
            "Joint 1: the angle of the point minus the angle the other joints "
            "give it in the frame of joint 1:",
            q1,
            _solve_joint_from_entry(x1, geo.first.value, q1),
        )


def _solve_equations(b: _Builder, equations: list[_Equation], unknowns: list[sp.Symbol]) -> None:
    """Solve the position equations one unknown at a time (pairs first, then ±√)."""
    pending = list(unknowns)
    used: set[int] = set()
    while pending:
        reduced = [_reduce(eq.expr, b.revolute) for eq in equations]
        single: dict[sp.Symbol, list[int]] = {}
        for i, e in enumerate(reduced):
            if i in used:
                continue
            present = [v for v in pending if v in e.free_symbols]
            if len(present) == 1:
                single.setdefault(present[0], []).append(i)
        done = _try_pair(b, equations, reduced, single) or _try_single(
            b, equations, reduced, single
        )
        if done is not None:
            var, rows = done
            used.update(rows)
            pending.remove(var)
            continue
        names = ", ".join(str(v) for v in pending)
        raise StructureError(
            f"the position sub-problem has no equation in one unknown left ({names} appear "
            "together): no closed form by decoupling — a redundant arm, or joints 2 and 3 "
            "do not move the point in a plane through the axis of joint 1"
        )


_Solved = tuple[sp.Symbol, tuple[int, ...]] | None  # the joint solved and the equations used


def _try_pair(
    b: _Builder,
    equations: list[_Equation],
    reduced: list[sp.Expr],
    single: dict[sp.Symbol, list[int]],
) -> _Solved:
    """One revolute joint from two equations linear in its cos and sin: a single atan2."""
    for var, idx in single.items():
        if b.kind[var] is not JointType.REVOLUTE or len(idx) < 2:
            continue
        for i, j in itertools.combinations(idx, 2):
            c1, c2 = trig_coefficients(reduced[i], var), trig_coefficients(reduced[j], var)
            if c1 is None or c2 is None:
                continue
            (A1, B1, C1), (A2, B2, C2) = c1, c2
            det = sp.expand(A1 * B2 - A2 * B1)
            if det == 0:
                continue
            R1, R2 = -C1, -C2
            t = b.tidy
            if sp.expand(A2 + B1) == 0 and sp.expand(B2 - A1) == 0:
                value = sp.atan2(t(R2), t(R1)) - sp.atan2(t(A2), t(A1))
            elif sp.expand(A2 - B1) == 0 and sp.expand(B2 + A1) == 0:
                value = sp.atan2(t(-R2), t(R1)) - sp.atan2(t(-A2), t(A1))
            else:
                delta = sp.Symbol(f"Delta_{b.number[var]}", **_REAL)
                b.add(
                    "position",
                    f"The determinant of the two linear equations in cos and sin of {var}:",
                    delta,
                    t(det),
                )
                value = sp.atan2(t(A1 * R2 - A2 * R1) / delta, t(R1 * B2 - R2 * B1) / delta)
            text = (
                f"With the joints before known, {equations[i].name} and {equations[j].name} "
                f"are linear in cos {var} and sin {var}: one atan2."
            )
            b.add("position", text, var, value, equation=sp.Eq(_show(A1, B1, var), b.tidy(R1)))
            return var, (i, j)
    return None


def _show(A: sp.Expr, B: sp.Expr, var: sp.Symbol) -> sp.Expr:
    return compact(A) * sp.cos(var) + compact(B) * sp.sin(var)


def _try_single(
    b: _Builder,
    equations: list[_Equation],
    reduced: list[sp.Expr],
    single: dict[sp.Symbol, list[int]],
) -> _Solved:
    """One joint from one equation: linear prismatic ones first (no branch), then ±√."""
    order = sorted(single.items(), key=lambda kv: b.kind[kv[0]] is JointType.REVOLUTE)
    for two_branch in (False, True):
        for var, idx in order:
            for i in idx:
                if _solve_single(b, equations[i], reduced[i], var, two_branch):
                    return var, (i,)
    return None


def _solve_single(b: _Builder, eq: _Equation, e: sp.Expr, var: sp.Symbol, two: bool) -> bool:
    j = b.number[var]
    if b.kind[var] is JointType.PRISMATIC:
        coeffs = _poly_coefficients(e, var)
        if coeffs is None:
            return False
        if len(coeffs) == 2 and not two:
            A, C = coeffs
            b.add(
                "position",
                f"{eq.name[0].upper() + eq.name[1:]} is linear in {var}:",
                var,
                b.tidy(-C / A),
                equation=eq.shown,
            )
            return True
        if len(coeffs) == 3 and two:
            A, B, C = coeffs
            br = b.branch("reach", var, f"σ = ±1: the sign of the square root for {var}")
            if B == 0:
                value = br.symbol * sp.sqrt(b.tidy(-C / A))
            else:
                value = (-B + br.symbol * sp.sqrt(b.tidy(B**2 - 4 * A * C))) / (2 * A)
            b.add(
                "position",
                f"{eq.name[0].upper() + eq.name[1:]} is quadratic in {var}:",
                var,
                value,
                equation=eq.shown,
                branch=br,
            )
            return True
        return False
    if not two:
        return False
    abc = trig_coefficients(e, var)
    if abc is None:
        return False
    A, B, C = abc
    K = -C
    g = sp.gcd(A, B) if A != 0 and B != 0 else (A if B == 0 else B)
    if g != 0 and not (g.free_symbols & set(b.variables)):
        A, B, K = (sp.cancel(v / g) for v in (A, B, K))
    br = b.branch("elbow", var, "σ = +1 and σ = −1: the two elbow configurations (up/down)")
    s = br.symbol
    text = f"{eq.name[0].upper() + eq.name[1:]} leaves {var} alone (the law of cosines): "
    if B == 0 or A == 0:
        D = sp.Symbol(f"D_{j}", **_REAL)
        b.add(
            "position",
            text + ("cos" if B == 0 else "sin") + f" {var} = D_{j} with",
            D,
            b.tidy(K / (A if B == 0 else B)),
            equation=sp.Eq(_show(A, B, var), b.tidy(K)),
        )
        root = s * sp.sqrt(1 - D**2)
        value = sp.atan2(root, D) if B == 0 else sp.atan2(D, root)
        b.add("position", "Two solutions, one for each sign of the root:", var, value, branch=br)
        return True
    Ks = sp.Symbol(f"K_{j}", **_REAL)
    b.add(
        "position",
        text + f"{sp.sstr(_show(A, B, var))} = K_{j} with",
        Ks,
        b.tidy(K),
        equation=sp.Eq(_show(A, B, var), b.tidy(K)),
    )
    value = sp.atan2(B, A) + sp.atan2(s * sp.sqrt(A**2 + B**2 - Ks**2), Ks)
    b.add("position", "Two solutions, one for each sign of the root:", var, value, branch=br)
    return True


# --- orientation -------------------------------------------------------------------------------


def _rotation_word(word: Sequence[Elementary]) -> list[Elementary]:
    return [e for e in word if e.kind == "R"]


def _x_twist(word: Sequence[Elementary], where: str) -> sp.Expr:
    R = plain_product(word)[:3, :3] if word else sp.eye(3)
    R = sp.Matrix(R).applyfunc(sp.nsimplify)
    if R[0, 0] != 1 or R[0, 1] != 0 or R[0, 2] != 0:
        raise StructureError(f"the wrist's {where} is not a twist about x: not in DH form")
    return sp.atan2(R[2, 1], R[1, 1])


def _orientation(b: _Builder, pose: Matrix) -> None:
    robot, dec = b.robot, b.dec
    table = robot.table
    wvars = [table.rows[r - 1].variable for r in dec.wrist]
    word = chain_word(table, 0, robot.n)
    k = next(i for i, e in enumerate(word) if wvars[0] in e.value.free_symbols)
    arm_R = compose(word[:k])[:3, :3]
    rot = _rotation_word(word[k:])
    pos = [next(i for i, e in enumerate(rot) if v in e.value.free_symbols) for v in wvars]
    if any(rot[p].axis != "z" for p in pos):
        raise StructureError("a wrist joint does not turn about its z axis")
    Q = plain_product(rot[pos[-1] + 1 :])[:3, :3] if rot[pos[-1] + 1 :] else sp.eye(3)
    R = pose[:3, :3]
    M = (sp.Matrix(arm_R).T * R * sp.Matrix(Q).T).applyfunc(sp.expand)
    names = {}

    def m(i: int, j: int) -> sp.Symbol:
        if (i, j) not in names:
            sym = sp.Symbol(f"m_{i + 1}{j + 1}", **_REAL)
            names[(i, j)] = sym
            b.add(
                "orientation",
                f"Entry ({i + 1}, {j + 1}) of the wrist's rotation "
                "(arm rotation transposed times R):",
                sym,
                b.tidy(M[i, j]),
            )
        return names[(i, j)]

    xs = [rot[p].value for p in pos]
    if len(wvars) == 1:
        x = sp.atan2(m(1, 0), m(0, 0))
        b.add(
            "orientation",
            "The wrist's rotation is Rz of the last joint angle:",
            wvars[0],
            _solve_joint_from_entry(x, xs[0], wvars[0]),
        )
        return
    a4 = _x_twist(rot[pos[0] + 1 : pos[1]], "twist between its first two axes")
    a5 = _x_twist(rot[pos[1] + 1 : pos[2]], "twist between its last two axes")
    s4, c4, s5, c5 = sp.sin(a4), sp.cos(a4), sp.sin(a5), sp.cos(a5)
    if s4 == 0 or s5 == 0:
        raise StructureError("two neighbouring wrist axes are parallel: not a spherical wrist")
    j4, j5, j6 = (b.number[v] for v in wvars)
    cx5 = sp.Symbol(f"c_{j5}", **_REAL)
    b.add(
        "orientation",
        f"Entry (3, 3) of Rz(θ{j4}) Rx(α) Rz(θ{j5}) Rx(α') Rz(θ{j6}) depends on θ{j5} alone:",
        cx5,
        b.tidy((c4 * c5 - m(2, 2)) / (s4 * s5)),
    )
    br = b.branch("wrist", wvars[1], "σ = +1: wrist not flipped (sin > 0); σ = −1: flipped")
    sg = br.symbol
    sx5 = sp.Symbol(f"s_{j5}", **_REAL)
    v = sp.expand(-(c4 * s5 * cx5 + s4 * c5))
    qq = sp.expand(s4 * c5 * cx5 + c4 * s5)
    if v == 0:  # twists of ±90°: the third column is (±s cos θ4, ±s sin θ4, c)
        b.add(
            "orientation",
            f"The rest of column 3 has length |sin θ{j5}|; two signs: the wrist flip.",
            sx5,
            sg * sp.sqrt(m(0, 2) ** 2 + m(1, 2) ** 2),
            branch=br,
        )
    else:
        b.add(
            "orientation",
            "Two signs of the root: the wrist flip.",
            sx5,
            sg * sp.sqrt(1 - cx5**2),
            branch=br,
        )
    b.add(
        "orientation",
        f"θ{j5} from its sine and cosine:",
        wvars[1],
        _solve_joint_from_entry(sp.atan2(sx5, cx5), xs[1], wvars[1]),
    )
    if v == 0:
        x4 = sp.atan2(sp.sign(s5) * sg * m(1, 2), sp.sign(s5) * sg * m(0, 2))
    else:
        x4 = sp.atan2(m(1, 2), m(0, 2)) - sp.atan2(v, s5 * sx5)
    if qq == 0:
        x6 = sp.atan2(-sp.sign(s4) * sg * m(2, 1), sp.sign(s4) * sg * m(2, 0))
    else:
        x6 = sp.atan2(qq, s4 * sx5) - sp.atan2(m(2, 1), m(2, 0))
    # near sin θ5 = 0 only θ4 + θ6 is well determined: θ6 then comes from the whole
    # rotation, Rz(θ6) = (Rz(θ4) Rx(α) Rz(θ5) Rx(α'))ᵀ R_w, and at sin θ5 = 0 θ4 is set to 0
    turn4 = rot_z(xs[0])
    turn5 = sp.Matrix([[cx5, -sx5, 0], [sx5, cx5, 0], [0, 0, 1]])
    N = (turn4 * rot_x(a4) * turn5 * rot_x(a5)).T * sp.Matrix(3, 3, lambda i, j: m(i, j))
    x6_singular = sp.atan2(b.tidy(N[1, 0]), b.tidy(N[0, 0]))
    b.add(
        "orientation",
        f"Column 3 of the wrist's rotation gives θ{j4}:",
        wvars[0],
        _solve_joint_from_entry(x4, xs[0], wvars[0]),
        singular=_solve_joint_from_entry(sp.Integer(0), xs[0], wvars[0]),
    )
    b.add(
        "orientation",
        f"Row 3 of the wrist's rotation gives θ{j6}:",
        wvars[2],
        _solve_joint_from_entry(x6, xs[2], wvars[2]),
        singular=_solve_joint_from_entry(x6_singular, xs[2], wvars[2]),
    )


def rot_z(a: sp.Expr) -> sp.Matrix:
    """3×3 rotation about z (exact)."""
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rot_x(a: sp.Expr) -> sp.Matrix:
    """3×3 rotation about x (exact)."""
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])


# --- the derivation object ---------------------------------------------------------------------


def _sizes(joints: int) -> list[int]:
    """Wrist sizes to try, in order, for a chain of ``joints`` joints."""
    if joints == 6:
        return [3]
    if joints in (4, 5):
        return [1]
    if joints == 3:
        return [3, 0, 1]
    return [0] if joints >= 1 else []


def _structure_text(robot: Robot, dec: Decoupling) -> str:
    number = {r: i for i, r in enumerate(robot.table.joint_rows, start=1)}

    def joints(rows: Sequence[int]) -> str:
        js = [number[r] for r in rows]
        return f"{js[0]}–{js[-1]}" if len(js) > 2 else ", ".join(map(str, js))

    if len(dec.wrist) == 3 and dec.arm:
        return (
            f"spherical wrist: joints {joints(dec.arm)} place the wrist centre (origin of "
            f"frame {dec.centre}), joints {joints(dec.wrist)} turn about it"
        )
    if len(dec.wrist) == 3:
        return f"a spherical wrist alone: joints {joints(dec.wrist)} turn about one point"
    if dec.wrist:
        return (
            f"last joint revolute: joints {joints(dec.arm)} place a point of its axis (origin "
            f"of frame {dec.centre}), joint {joints(dec.wrist)} turns the tool about it"
        )
    return (
        f"positioning arm: joints {joints(dec.arm)} place the tool point "
        f"(origin of frame {dec.centre})"
    )


@dataclass(frozen=True)
class InverseKinematics:
    """The derived closed-form inverse kinematics of one robot: steps and a solver.

    ``steps`` are in order; each defines one symbol (an intermediate quantity or a joint
    variable) from the pose symbols ``pose``, earlier symbols and the branch signs
    ``branches``. Every combination of signs is one solution (``2 ** len(branches)``).
    """

    robot: Robot = field(compare=False, repr=False)
    structure: str
    decoupling: Decoupling
    pose: Matrix
    steps: tuple[Step, ...]
    branches: tuple[Branch, ...]

    @property
    def count(self) -> int:
        """Number of branch combinations (solutions of a generic pose)."""
        return 2 ** len(self.branches)

    def text(self, step: Step) -> str:
        """``lhs = rhs`` in plain text, compact notation."""
        nota = self.robot.notation
        return f"{nota.text(step.lhs)} = {nota.text(step.rhs)}"

    def latex(self, step: Step) -> str:
        """``lhs = rhs`` in LaTeX, compact notation."""
        nota = self.robot.notation
        return f"{nota.latex(step.lhs)} = {nota.latex(step.rhs)}"

    def solver(self, values: Mapping[object, object] | None = None) -> Solver:
        """The compiled solver (built once per set of values, then cached on the robot)."""
        vals = _values(self.robot, values)
        key = ("ik-solver", tuple(sorted((str(k), str(v)) for k, v in vals.items())))
        cache = self.robot._extra_cache
        if key not in cache:
            cache[key] = Solver(self, vals)
        return cache[key]  # type: ignore[no-any-return]

    def solve(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float = 1e-9,
        singular_tol: float = 1e-6,
        values: Mapping[object, object] | None = None,
    ) -> IKSolution | IKBatch:
        """All solutions for one pose ``(4, 4)`` or a batch ``(N, 4, 4)`` (see :class:`Solver`)."""
        return self.solver(values).solve(T, check=check, tol=tol, singular_tol=singular_tol)


def inverse(robot: Robot | str) -> InverseKinematics:
    """Derive the closed-form inverse kinematics of ``robot`` from the structure of its table.

    Raises
    ------
    StructureError
        When no decoupling gives a closed form; the message names what is missing for
        each structure tried.

    >>> import dhsym
    >>> ik = inverse(dhsym.load("puma560"))
    >>> print(ik.structure)
    spherical wrist: joints 1–3 place the wrist centre (origin of frame 4), joints 4–6 turn ...
    >>> [b.role for b in ik.branches], ik.count
    (['arm', 'elbow', 'wrist'], 8)
    >>> inverse(dhsym.load("planar4r"))
    Traceback (most recent call last):
    ...
    dhsym._structure.StructureError: no closed-form inverse kinematics ...: ...redundant arm...
    """
    if isinstance(robot, str):
        from .library import load

        robot = load(robot)
    joints = len(robot.variables)
    reasons = []
    if joints > 6:
        reasons.append(f"{joints} joints: a redundant arm has infinitely many solutions")
    for size in _sizes(joints):
        label = {3: "spherical wrist", 1: "last joint revolute", 0: "positioning arm"}[size]
        try:
            dec = decouple(robot, size)
            b = _Builder(robot, dec)
            pose = pose_symbols()
            target = _wrist_centre(b, pose) if dec.wrist and dec.arm else pose[:3, 3]
            if dec.arm:
                _position(b, arm_geometry(robot, dec), target)
            if dec.wrist:
                _orientation(b, pose)
        except StructureError as err:
            reasons.append(f"{label}: {err.message}")
            continue
        return InverseKinematics(
            robot, _structure_text(robot, dec), dec, pose, tuple(b.steps), tuple(b.branches)
        )
    raise StructureError(
        f"no closed-form inverse kinematics for {robot.name or 'this table'}: " + "; ".join(reasons)
    )


def _wrist_centre(b: _Builder, pose: Matrix) -> Matrix:
    v = b.dec.centre_in_last
    c = pose[:3, 3] + pose[:3, :3] * v
    names = [sp.Symbol(f"c_{k}", **_REAL) for k in "xyz"]
    point = "wrist centre" if len(b.dec.wrist) == 3 else "point of the last joint's axis"
    if v == Matrix.zeros(3, 1):
        text = f"The {point} is the origin of frame {b.robot.n}: c = p."
    else:
        where = ", ".join(b.robot.notation.text(x) for x in v)
        text = f"The {point} sits at ({where}) in frame {b.robot.n}: c = p + R·({where})."
    for name, value in zip(names, c):
        b.add("wrist centre", text, name, sp.expand(value))
    return Matrix(names)


# --- numbers --------------------------------------------------------------------------------


class SafeSqrt(sp.Function):
    """``sqrt`` that reads a radicand within rounding of 0 as 0 (compile-time only)."""


_ROUNDING = 1e-10


def _safe_sqrt(x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, dtype=float)
    return np.sqrt(np.where((x < 0) & (x > -_ROUNDING), 0.0, x))


def _with_safe_sqrt(e: sp.Expr) -> sp.Expr:
    return e.replace(lambda t: t.is_Pow and t.exp == sp.S.Half, lambda t: SafeSqrt(t.base)).replace(
        lambda t: t.is_Pow and t.exp == -sp.S.Half, lambda t: 1 / SafeSqrt(t.base)
    )


_CHUNK = 1024
_CHECK_CHUNK = 32768  # poses checked at once (bounds the memory of the fk of all branches)
_TWO_PI = 2 * np.pi


def _wrap(x: np.ndarray) -> np.ndarray:
    """Angles to [−π, π] (faster than ``np.remainder``)."""
    return x - _TWO_PI * np.rint(x * (1 / _TWO_PI))


#: |sin θ5| below which θ6 comes from the whole wrist rotation, and below which θ4 = 0
_WRIST_NEAR = 1e-5
_WRIST_ZERO = 1e-12


def _schedule(
    steps: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """The steps as one straight-line program for ``outputs``, subexpressions shared.

    Steps no output needs are dropped; ``cse`` runs over all right-hand sides at once and
    each shared subexpression is placed right after the last step it depends on.
    """
    needed = set().union(*(e.free_symbols for e in outputs)) if outputs else set()
    kept = []
    for lhs, rhs in reversed(steps):
        if lhs in needed:
            kept.append((lhs, rhs))
            needed |= rhs.free_symbols
    steps = kept[::-1]
    exprs = [rhs for _, rhs in steps] + list(outputs)
    repl, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_w"), optimizations=None)
    position = {lhs: i for i, (lhs, _) in enumerate(steps)}
    level: dict[sp.Symbol, int] = {}
    for sym, e in repl:
        deps = [position[s] for s in e.free_symbols if s in position]
        deps += [level[s] for s in e.free_symbols if s in level]
        level[sym] = max(deps, default=-1)
    program = [(sym, e) for sym, e in repl if level[sym] == -1]
    for i, (lhs, _) in enumerate(steps):
        program.append((lhs, reduced[i]))
        program += [(sym, e) for sym, e in repl if level[sym] == i]
    return program, list(reduced[len(steps) :])


def _signed(e: sp.Expr, signs: set[sp.Symbol]) -> tuple[sp.Expr, sp.Expr]:
    """``e = σ · rest`` with σ the product of the branch signs that are factors of ``e``."""
    sigma = sp.Mul(*[f for f in sp.Mul.make_args(e) if f in signs])
    return sigma, (e / sigma if sigma != 1 else e)


def _pull_signs(
    steps: Sequence[tuple[sp.Symbol, sp.Expr]],
    outputs: Sequence[sp.Expr],
    signs: Sequence[sp.Symbol],
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """Move branch signs σ = ±1 out of square roots' neighbours and ``atan2``.

    A step ``x = σ·E`` becomes ``x' = E`` with ``x = σ x'`` downstream, and
    ``atan2(σa Y, σb X) ≡ σa σb atan2(Y, X) + π(1 − σb)/2`` (mod 2π), so that each
    ``atan2`` runs once for the branches it does not depend on. Only used for numbers:
    the angles it changes are wrapped to (−π, π] afterwards.
    """
    sset = set(signs)

    def square_free(e: sp.Expr) -> sp.Expr:
        return e.replace(
            lambda t: t.is_Pow and t.base in sset and t.exp.is_Integer,
            lambda t: t.base ** (int(t.exp) % 2),
        )

    def pull(e: sp.Expr) -> sp.Expr:
        def rewrite(t: sp.atan2) -> sp.Expr:
            sy, Y = _signed(t.args[0], sset)
            sx, X = _signed(t.args[1], sset)
            if sy == 1 and sx == 1:
                return t
            return sx * sy * sp.atan2(Y, X) + sp.pi * (1 - sx) / 2

        return e.replace(lambda t: isinstance(t, sp.atan2), rewrite)

    sub: dict[sp.Symbol, sp.Expr] = {}
    out = []
    for lhs, rhs in steps:
        e = square_free(pull(square_free(rhs.xreplace(sub))))
        sigma, rest = _signed(e, sset)
        if sigma != 1:
            bare = sp.Symbol(f"{lhs.name}_", **_REAL)
            out.append((bare, rest))
            sub[lhs] = sigma * bare
        else:
            out.append((lhs, e))
    return out, [square_free(pull(square_free(o.xreplace(sub)))) for o in outputs]


class Solver:
    """The steps of an :class:`InverseKinematics`, compiled for numpy.

    :meth:`solve` takes one pose ``(4, 4)`` (an :class:`IKSolution`) or a batch
    ``(N, 4, 4)`` (an :class:`IKBatch`: padded arrays with a validity mask). Poses are
    world-to-tool, as ``fk`` gives them; base and tool transforms are undone first.
    Every branch is computed at once by broadcasting the signs.
    """

    def __init__(self, ik: InverseKinematics, values: Mapping[sp.Symbol, sp.Expr]) -> None:
        robot = ik.robot
        self.ik = ik
        self.robot = robot
        self.values = dict(values)
        self.n = len(robot.variables)
        self.revolute = np.array(
            [r.joint is JointType.REVOLUTE for r in robot.table.rows if r.variable is not None]
        )
        self.pose_args = [ik.pose[i, j] for j in range(4) for i in range(3)]
        self.signs = [b.symbol for b in ik.branches]
        wrist_s = [s.lhs for s in ik.steps if s.branch is not None and s.branch.role == "wrist"]
        steps = [(st.lhs, _with_safe_sqrt(st.rhs.xreplace(self.values))) for st in ik.steps]
        singular = {st.lhs: st.singular for st in ik.steps if st.singular is not None}
        self.singular_vars = [robot.variables.index(v) for v in singular]
        free = set().union(*(e.free_symbols for _, e in steps)) if steps else set()
        defined = {lhs for lhs, _ in steps}
        missing = free - defined - set(self.pose_args) - set(self.signs)
        if missing:
            names = ", ".join(sorted(str(s) for s in missing))
            raise DHError(f"no numeric value for {names}: give values for these symbols")
        self._fn = self._compile(steps, list(robot.variables) + wrist_s)
        self._alt = None
        if singular and wrist_s:
            # θ4 at sin θ5 = 0, θ6 from the whole rotation with θ4 as computed, and with θ4 = 0
            (t4, zero4), (t6, whole6) = list(singular.items())
            alts = [zero4, whole6, whole6.xreplace({t4: zero4})]
            alts = [_with_safe_sqrt(e.xreplace(self.values)) for e in alts]
            self._alt = self._compile(steps, alts)
        B = len(self.signs)
        self.shape = (2,) * B
        self._sign_arrays = []
        for k in range(B):
            shape = [1] * (B + 1)
            shape[k + 1] = 2
            self._sign_arrays.append(np.array([1.0, -1.0]).reshape(shape))
        self.branch_signs = np.array(list(itertools.product([1, -1], repeat=B)), dtype=int).reshape(
            2**B, B
        )
        self._base = self._constant(-1, 0) if robot.table.base else None
        self._tool = self._constant(robot.n, robot.n + 1) if robot.table.tool else None
        self._factors: tuple[tuple[str, Callable[[object], np.ndarray], float], ...] | None = None
        self._frames: dict[int | None, Callable[[object], np.ndarray]] = {}

    def frame(self, k: int | None = None) -> Callable[[object], np.ndarray]:
        """The compiled ``^0T_k`` (``None``: the whole ``fk``, world to tool), cached."""
        if k not in self._frames:
            fk = self.robot.fk_function
            self._frames[k] = fk(values=self.values) if k is None else fk(0, k, self.values)
        return self._frames[k]

    def _compile(
        self, steps: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
    ) -> Callable[..., list[object]]:
        program, reduced = _schedule(*_pull_signs(steps, outputs, self.signs))
        return sp.lambdify(  # type: ignore[no-any-return]
            self.pose_args + self.signs,
            reduced,
            modules=[{"SafeSqrt": _safe_sqrt}, "numpy"],
            cse=lambda exprs: (program, exprs),
        )

    def _constant(self, i: int, j: int) -> np.ndarray:
        M = self.robot.transform(i, j).matrix.xreplace(self.values)
        return np.array(M.evalf(), dtype=float)

    # -- raw closed form ----------------------------------------------------------------------
    def raw(self, T: np.ndarray) -> np.ndarray:
        """All branches for poses ``(N, 4, 4)`` (frame 0 to frame n): ``(N, K, n)``, unchecked."""
        N = T.shape[0]
        K = len(self.branch_signs)
        out = np.empty((self.n, N, K))
        tail = (1,) * len(self.signs)
        with np.errstate(invalid="ignore", divide="ignore"):
            for start in range(0, N, _CHUNK):
                block = np.ascontiguousarray(T[start : start + _CHUNK, :3].transpose(2, 1, 0))
                m = block.shape[-1]
                args = [block[j, i].reshape((m,) + tail) for j in range(4) for i in range(3)]
                res = self._fn(*args, *self._sign_arrays)
                full = (m,) + self.shape
                dest = out[:, start : start + m]
                for k in range(self.n):
                    col = np.broadcast_to(np.asarray(res[k], dtype=float), full).reshape(m, K)
                    dest[k] = _wrap(col) if self.revolute[k] else col
                if self._alt is not None:
                    wrist = np.broadcast_to(np.asarray(res[self.n], dtype=float), full)
                    wrist = wrist.reshape(m, K)
                    rows = np.nonzero((np.abs(wrist) < _WRIST_NEAR).any(axis=1))[0]
                    if rows.size:
                        self._singular_wrist(block[..., rows], dest, rows, wrist)
        return out.transpose(1, 2, 0)

    def _singular_wrist(
        self, block: np.ndarray, dest: np.ndarray, rows: np.ndarray, wrist: np.ndarray
    ) -> None:
        """Near ``sin θ5 = 0``: θ6 from the whole wrist rotation; at 0 also θ4 = 0."""
        m = block.shape[-1]
        tail = (1,) * len(self.signs)
        args = [block[j, i].reshape((m,) + tail) for j in range(4) for i in range(3)]
        zero4, whole6, whole6_zero4 = (
            np.broadcast_to(np.asarray(v, dtype=float), (m,) + self.shape).reshape(m, -1)
            for v in self._alt(*args, *self._sign_arrays)  # type: ignore[misc]
        )
        s = np.abs(wrist[rows])
        i4, i6 = self.singular_vars
        wrap = _wrap
        near, zero = s < _WRIST_NEAR, s < _WRIST_ZERO
        dest[i6, rows] = np.where(
            zero, wrap(whole6_zero4), np.where(near, wrap(whole6), dest[i6, rows])
        )
        dest[i4, rows] = np.where(zero, wrap(zero4), dest[i4, rows])

    # -- checked solutions --------------------------------------------------------------------
    def solve(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float = 1e-9,
        singular_tol: float = 1e-6,
    ) -> IKSolution | IKBatch:
        """Every solution of one pose or a batch of poses.

        Parameters
        ----------
        T
            ``(4, 4)`` or ``(N, 4, 4)`` world-to-tool poses; or positions ``(3,)`` /
            ``(N, 3)`` for an arm without a wrist (then ``check="position"``).
        check
            ``"pose"`` keeps a branch only when its ``fk`` reproduces the whole pose within
            ``tol`` (max abs over the 12 entries); ``"position"`` compares positions only;
            ``None`` returns every finite branch unchecked.
        singular_tol
            A solution is flagged near a singularity when a factor of the Jacobian
            determinant is below this fraction of its largest value.
        """
        arr = np.asarray(T, dtype=float)
        if arr.shape[-1] == 3 and arr.ndim in (1, 2):
            if self.ik.decoupling.wrist:
                raise DHError("this arm has a wrist: give a full 4×4 pose, not a position")
            pose = np.zeros(arr.shape[:-1] + (4, 4))
            pose[..., :3, :3] = np.eye(3)
            pose[..., :3, 3] = arr
            pose[..., 3, 3] = 1.0
            arr, check = pose, ("position" if check is not None else None)
        single = arr.ndim == 2
        if arr.shape[-2:] != (4, 4) or arr.ndim not in (2, 3):
            raise DHError(f"expected poses of shape (4, 4) or (N, 4, 4), got {arr.shape}")
        poses = arr.reshape(-1, 4, 4)
        inner = poses
        if self._base is not None:
            inner = np.linalg.inv(self._base) @ inner
        if self._tool is not None:
            inner = inner @ np.linalg.inv(self._tool)
        parts = [
            self._checked(inner[k : k + _CHECK_CHUNK], poses[k : k + _CHECK_CHUNK], check, tol)
            for k in range(0, max(len(poses), 1), _CHECK_CHUNK)
        ]
        q, valid, residual, closeness = (np.concatenate(x) for x in zip(*parts))
        names = tuple(f[0] for f in self._singular_factors())
        near = (closeness < singular_tol) & valid[..., None]
        batch = IKBatch(q, valid, residual, near, names, self.branch_signs, self)
        return batch.solution(0) if single else batch

    def _checked(
        self, inner: np.ndarray, poses: np.ndarray, check: str | None, tol: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Solve a block of poses; residuals, validity and distance from singular factors."""
        q = self.raw(inner)
        N, K, n = q.shape
        with np.errstate(invalid="ignore"):
            got = self.frame()(q.reshape(-1, n)).reshape(N, K, 16)  # NaN rows stay NaN
            cells = [3, 7, 11] if check == "position" else slice(0, 12)
            diff = got[:, :, cells] - poses.reshape(N, 1, 16)[:, :, cells]
            residual = np.abs(diff, out=diff).max(axis=-1, initial=0.0)
            valid = np.isfinite(residual)
            if check is not None:
                valid &= residual <= tol
        _, closeness = self._closeness(q)
        # two branches coincide only where a radicand vanishes, i.e. at a singularity: look
        # for repeats (angles compared by cos and sin) only among poses near one
        suspects = np.nonzero((closeness < 1e-4).any(axis=(1, 2)) & valid.any(axis=1))[0]
        if suspects.size:
            qs, vs = q[suspects], valid[suspects]
            rev = qs[..., self.revolute]
            key = np.concatenate([np.cos(rev), np.sin(rev), qs[..., ~self.revolute]], axis=-1)
            for k in range(1, K):
                close = np.abs(key[:, k : k + 1] - key[:, :k]).max(axis=-1) < 1e-9
                vs[:, k] &= ~(vs[:, :k] & close).any(axis=1)
            valid[suspects] = vs
        q[~valid] = np.nan
        return q, valid, residual, closeness

    def _closeness(self, q: np.ndarray) -> tuple[tuple[str, ...], np.ndarray]:
        """Each singular factor at each solution, as a fraction of its largest value."""
        factors = self._singular_factors()
        N, K, n = q.shape
        out = np.full((N, K, len(factors)), np.inf)
        flat = q.reshape(-1, n)
        with np.errstate(invalid="ignore"):
            for i, (_, fn, scale) in enumerate(factors):
                out[..., i] = np.nan_to_num(np.abs(fn(flat)) / scale, nan=np.inf).reshape(N, K)
        return tuple(f[0] for f in factors), out

    def _singular_factors(self) -> tuple[tuple[str, Callable[[object], np.ndarray], float], ...]:
        if self._factors is None:
            from .singularities import singularities

            try:
                sing: Singularities = singularities(self.robot)
            except StructureError:
                self._factors = ()
                return self._factors
            rng = np.random.default_rng(0)
            sample = rng.uniform(-np.pi, np.pi, (256, self.n))
            sample[:, ~self.revolute] = rng.uniform(0.0, 1.0, (256, int((~self.revolute).sum())))
            found = []
            named = [f for f in sing.factors if f.kind != "constant"]
            for f, fn in zip(named, sing.factor_functions(self.values)):
                scale = float(np.nanmax(np.abs(fn(sample)))) or 1.0
                found.append((f.kind, fn, scale))
            self._factors = tuple(found)
        return self._factors


# --- results --------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class IKSolution:
    """All solutions of one pose: ``q`` is ``(k, n)``, one row per solution (k ≤ 8).

    ``branches`` names each solution (``"right arm, elbow up, wrist not flipped"``);
    ``residual`` is the largest entry error of its ``fk``; ``singular`` names the
    singularities it is near (empty when none). ``np.asarray(solution)`` is ``q``.
    """

    q: np.ndarray
    residual: np.ndarray
    singular: tuple[tuple[str, ...], ...]
    signs: np.ndarray = field(repr=False)
    solver: Solver = field(repr=False)

    @functools.cached_property
    def branches(self) -> tuple[str, ...]:
        """The name of each solution's branch (computed on first use)."""
        return _branch_names(self.solver, self.q, self.signs)

    @property
    def near_singular(self) -> np.ndarray:
        """``(k,)`` True where a solution is near a singular configuration."""
        return np.array([bool(s) for s in self.singular], dtype=bool)

    def __len__(self) -> int:
        return int(self.q.shape[0])

    def __iter__(self):  # type: ignore[no-untyped-def]
        return iter(self.q)

    def __getitem__(self, k: int) -> np.ndarray:
        return self.q[k]  # type: ignore[no-any-return]

    def __array__(self, dtype: object = None, copy: object = None) -> np.ndarray:
        return self.q if dtype is None else self.q.astype(dtype)  # type: ignore[arg-type]


@dataclass(frozen=True, eq=False)
class IKBatch:
    """Solutions of N poses as padded arrays: ``q`` is ``(N, K, n)`` with NaN where invalid.

    ``valid`` ``(N, K)`` marks real, checked, distinct solutions; ``residual`` ``(N, K)``
    the entry error of each branch's ``fk``; ``singular`` ``(N, K, F)`` the
    singularities (``factor_kinds``) each solution is near; ``branch_signs`` ``(K, B)``
    the signs of the branches, in the order of the derivation's ``branches``.
    """

    q: np.ndarray
    valid: np.ndarray
    residual: np.ndarray
    singular: np.ndarray
    factor_kinds: tuple[str, ...]
    branch_signs: np.ndarray
    solver: Solver = field(repr=False)

    @property
    def count(self) -> np.ndarray:
        """``(N,)`` number of solutions of each pose."""
        return self.valid.sum(axis=1)  # type: ignore[no-any-return]

    @property
    def near_singular(self) -> np.ndarray:
        """``(N, K)`` True where a solution is near a singular configuration."""
        return self.singular.any(axis=-1)  # type: ignore[no-any-return]

    def __len__(self) -> int:
        return int(self.q.shape[0])

    def solution(self, i: int) -> IKSolution:
        """The solutions of pose ``i`` (only the valid ones, with their branch names)."""
        keep = self.valid[i]
        sing = tuple(
            tuple(k for k, hit in zip(self.factor_kinds, row) if hit)
            for row in self.singular[i][keep]
        )
        return IKSolution(
            self.q[i][keep], self.residual[i][keep], sing, self.branch_signs[keep], self.solver
        )


def _branch_names(solver: Solver, q: np.ndarray, signs: np.ndarray) -> tuple[str, ...]:
    ik = solver.ik
    parts: list[list[str]] = [[] for _ in range(len(q))]
    for b, col in zip(ik.branches, signs.T):
        if b.role == "elbow":
            up = _elbow_up(solver, q, b) if len(q) else np.zeros(0, dtype=bool)
            words = ["elbow up" if u else "elbow down" for u in up]
        elif b.role == "arm":
            words = ["right arm" if sgn > 0 else "left arm" for sgn in col]
        elif b.role == "wrist":
            words = ["wrist not flipped" if sgn > 0 else "wrist flipped" for sgn in col]
        else:
            var = solver.robot.variables[b.joint - 1]
            words = [f"{var} {'+' if sgn > 0 else '−'}√" for sgn in col]
        for k, w in enumerate(words):
            parts[k].append(w)
    return tuple(", ".join(p) for p in parts)


def _elbow_up(solver: Solver, q: np.ndarray, branch: Branch) -> np.ndarray:
    """True where the elbow lies above the line from the shoulder to the wrist centre.

    "Above" is the side of +z0 for an arm that moves in a vertical plane, and the left of
    the shoulder-to-wrist line seen from above (+z0) for a planar arm. ``q`` is ``(k, n)``.
    """
    robot = solver.robot
    rows = robot.table.joint_rows
    elbow_row = rows[branch.joint - 1]
    shoulder_row = rows[branch.joint - 2]
    s = solver.frame(axis_frame(robot, shoulder_row))(q)[:, :3, 3]
    E = solver.frame(axis_frame(robot, elbow_row))(q)
    e, h = E[:, :3, 3] - s, E[:, :3, 2]
    w = solver.frame(solver.ik.decoupling.centre)(q)[:, :3, 3] - s
    up = h[:, 2]
    planar = np.abs(up) > 0.5
    h_up = h * np.where(up < 0, -1.0, 1.0)[:, None]
    left = np.einsum("ij,ij->i", e, np.cross(h_up, w)) > 0
    w_perp = w - np.einsum("ij,ij->i", w, h)[:, None] * h
    e_perp = e - np.einsum("ij,ij->i", e, h)[:, None] * h
    n = np.cross(h, w_perp)
    n = n * np.where(n[:, 2] < 0, -1.0, 1.0)[:, None]
    above = np.einsum("ij,ij->i", e_perp, n) > 0
    return np.where(planar, left, above)


# --- the numeric solver ---------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class NumericSolution:
    """One local solution from :func:`numeric_ik` — numeric, not closed form, no branches."""

    q: np.ndarray
    converged: bool
    iterations: int
    error: float
    method: str = "numeric: Levenberg–Marquardt on the compiled fk (one local solution)"


def _rotation_error(R: np.ndarray, goal: np.ndarray) -> np.ndarray:
    """The rotation vector (axis times angle) that turns ``R`` into ``goal``, base frame."""
    E = goal @ R.T
    v = 0.5 * np.array([E[2, 1] - E[1, 2], E[0, 2] - E[2, 0], E[1, 0] - E[0, 1]])
    s, c = float(np.linalg.norm(v)), (float(np.trace(E)) - 1.0) / 2.0
    if s > 1e-9:
        return np.arctan2(s, c) / s * v  # type: ignore[no-any-return]
    if c > 0:
        return v
    k = int(np.argmax(np.linalg.norm(E + np.eye(3), axis=0)))  # a half turn: axis from E + I
    axis = (E + np.eye(3))[:, k]
    return np.pi * axis / np.linalg.norm(axis)  # type: ignore[no-any-return]


def numeric_ik(
    robot: Robot,
    T: object,
    q0: object = None,
    *,
    tol: float = 1e-12,
    max_iter: int = 100,
    values: Mapping[object, object] | None = None,
) -> NumericSolution:
    """Levenberg–Marquardt on the compiled ``fk`` and Jacobian, from ``q0`` (default zeros).

    A numeric solver, clearly not the closed form: it finds one solution near its
    start, or none. The error is the position error and the rotation vector from the
    current orientation to the goal, both in the base frame; the step solves
    ``(JᵀJ + λ diag(JᵀJ)) Δq = Jᵀe`` with λ divided by 10 after a successful step and
    multiplied by 10 after a failed one.

    >>> import dhsym
    >>> r = dhsym.load("planar2r")
    >>> sol = numeric_ik(r, r.fk([0.4, 0.9]), [0.3, 0.8])
    >>> sol.converged, np.round(sol.q, 9).tolist()
    (True, [0.4, 0.9])
    """
    fk = robot.fk_function(values=values)
    target = np.asarray(T, dtype=float)
    n = len(robot.variables)
    q = np.zeros(n) if q0 is None else np.asarray(q0, dtype=float).copy()

    def error(q: np.ndarray) -> np.ndarray:
        M = fk(q)
        return np.concatenate(
            [target[:3, 3] - M[:3, 3], _rotation_error(M[:3, :3], target[:3, :3])]
        )

    e = error(q)
    lam = 1e-2
    it = 0
    for it in range(1, max_iter + 1):
        if e @ e < tol**2:
            return NumericSolution(q, True, it - 1, float(np.sqrt(e @ e)))
        J = np.asarray(robot.jacobian(q, values=values))
        H = J.T @ J
        step = np.linalg.solve(H + lam * np.diag(np.diag(H) + 1e-12), J.T @ e)
        trial = q + step
        e_trial = error(trial)
        if e_trial @ e_trial < e @ e:
            q, e, lam = trial, e_trial, max(lam / 10, 1e-12)
        else:
            lam = min(lam * 10, 1e12)
    err = float(np.sqrt(e @ e))
    return NumericSolution(q, err < tol, it, err)


class _CallableModule(type(sys.modules[__name__])):  # type: ignore[misc]
    """``dhsym.inverse(robot)`` works whether the package attribute is this module or
    the function (importing the submodule binds the module to that name)."""

    def __call__(self, robot: Robot | str) -> InverseKinematics:
        return inverse(robot)


sys.modules[__name__].__class__ = _CallableModule
