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
compiles the steps once (``lambdify`` with the steps as the common subexpressions), with
the ``fk`` check, into a numpy function over a batch of poses and all branches at once and
into a function of plain floats for one pose (see :mod:`dhsym.kinematics._ik_numbers`).

Results. One pose ``(4, 4)`` gives an :class:`IKSolution`: ``q`` is ``(k, n)`` (k ≤ 8,
only real, checked, distinct solutions) with a name per solution and the singularities
each one is near. A batch ``(N, 4, 4)`` gives an :class:`IKBatch`: ``q`` is padded to
``(N, K, n)`` with NaN, ``valid`` ``(N, K)`` is the mask, ``K = 2^(number of branches)``.
By default a branch is kept only when its ``fk`` reproduces the whole pose to ``1e-9``
(``check="pose"``). An arm with fewer than six joints cannot reach every pose, so a branch
that only matches the coordinates it solves is dropped: a planar 2R has one solution for
a whole pose and two (elbow up and down) for a position ``(3,)``. Near a singularity a
solution is flagged (``singular``) with the kind of the singular factor (from
:mod:`dhsym.kinematics.singularities`); at ``sin θ5 = 0`` only ``θ4 + θ6`` is defined
and ``θ4 = 0``.

Arms without such structure get a :class:`~dhsym.kinematics._structure.StructureError` naming
what is missing; :func:`numeric_ik` is a separate, clearly numeric Levenberg–Marquardt
solver on the compiled ``fk``.

Examples
--------
>>> import dhsym
>>> import numpy as np
>>> ik = inverse(dhsym.load("planar2r"))
>>> for step in ik.steps:
...     print(ik.text(step))
D_2 = (p_x**2 + p_y**2 - a1**2 - a2**2)/(2*a1*a2)
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

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import sympy as sp

from dhsym.model.table import Elementary, JointType
from dhsym.notation.layout import Sentence, sentence, word_expr

from ._ik_numbers import IKBatch, IKSolution, NumericSolution, Solver, numeric_ik
from ._structure import ArmGeometry, Decoupling, StructureError, arm_geometry, decouple
from .jacobian import _values, compact
from .numeric import values_key
from .simplification import compose, trig_coefficients
from .transforms import chain_word, plain_product

if TYPE_CHECKING:
    from .robot import Robot

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
    a prismatic ``±√``) or ``"wrist"`` (flip); ``joint`` is the joint it decides;
    ``sentence`` says what each sign means (a :class:`~dhsym.notation.layout.Sentence`).
    """

    symbol: sp.Symbol
    role: str
    joint: int
    sentence: Sentence

    @property
    def text(self) -> str:
        """The sentence in plain text."""
        return self.sentence.text()


@dataclass(frozen=True)
class Step:
    """One line of the derivation: ``lhs = rhs``, exact, with the sentence that explains it.

    ``part`` is ``"wrist centre"``, ``"position"`` or ``"orientation"``; ``sentence``
    the words with their math (a :class:`~dhsym.notation.layout.Sentence`, printed by
    each format); ``equation`` is the equation this step solves (when it solves one);
    ``branch`` the sign it introduces; ``singular`` the value used instead when the
    wrist is singular (``sin θ5 = 0``: only ``θ4 + θ6`` is determined, so ``θ4`` is set
    to 0).
    """

    part: str
    sentence: Sentence
    lhs: sp.Symbol
    rhs: sp.Expr
    equation: sp.Eq | None = None
    branch: Branch | None = None
    singular: sp.Expr | None = None

    @property
    def text(self) -> str:
        """The sentence in plain text."""
        return self.sentence.text()


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

    def add(
        self, part: str, text: Sentence | str, lhs: sp.Symbol, rhs: sp.Expr, **kw: object
    ) -> sp.Symbol:
        words = text if isinstance(text, Sentence) else Sentence(text)
        self.steps.append(Step(part, words, lhs, rhs, **kw))  # type: ignore[arg-type]
        return lhs

    def branch(self, role: str, var: sp.Symbol, template: str, **math: object) -> Branch:
        """A new sign σ_j; ``template`` may use ``{s}`` (σ_j), ``{plus}``, ``{minus}``."""
        j = self.number[var]
        sigma = sp.Symbol(f"sigma_{j}", **_REAL)
        words = sentence(template, s=sigma, plus=sp.Eq(sigma, 1), minus=sp.Eq(sigma, -1), **math)
        b = Branch(sigma, role, j, words)
        self.branches.append(b)
        return b

    def tidy(self, e: sp.Expr) -> sp.Expr:
        return compact(sp.factor_terms(e))


def _capital(words: str) -> str:
    return words[:1].upper() + words[1:]


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
                "{plus}: right arm (the point in front of the shoulder, {front}); "
                "{minus}: left arm",
                front=sp.Gt(r, 0),
            )
            sigma = arm.symbol
            reach = sp.sqrt(ux**2 + uy**2 - e**2)
            b.add(
                "position",
                sentence(
                    "Joint 1 turns the arm about {z0}; the point keeps the shoulder offset "
                    "{e} from the plane of the arm, so its reach in that plane is",
                    z0=sp.Symbol("z_0"),
                    e=sp.Eq(sp.Symbol("e"), e),
                ),
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
                sentence(
                    "The angle of the point minus the angle of {re} in the arm's frame:",
                    re=sp.Tuple(r, sp.Symbol("e")),
                ),
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
                    sentence(
                        "The determinant of the two linear equations in {c} and {s}:",
                        c=sp.cos(var),
                        s=sp.sin(var),
                    ),
                    delta,
                    t(det),
                )
                value = sp.atan2(t(A1 * R2 - A2 * R1) / delta, t(R1 * B2 - R2 * B1) / delta)
            text = sentence(
                "With the joints before known, {one} and {two} are linear in {c} and {s}: "
                "one atan2.",
                one=equations[i].name,
                two=equations[j].name,
                c=sp.cos(var),
                s=sp.sin(var),
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
                sentence("{eq} is linear in {v}:", eq=_capital(eq.name), v=var),
                var,
                b.tidy(-C / A),
                equation=eq.shown,
            )
            return True
        if len(coeffs) == 3 and two:
            A, B, C = coeffs
            br = b.branch("reach", var, "{s} = ±1: the sign of the square root for {v}", v=var)
            if B == 0:
                value = br.symbol * sp.sqrt(b.tidy(-C / A))
            else:
                value = (-B + br.symbol * sp.sqrt(b.tidy(B**2 - 4 * A * C))) / (2 * A)
            b.add(
                "position",
                sentence("{eq} is quadratic in {v}:", eq=_capital(eq.name), v=var),
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
    br = b.branch("elbow", var, "{plus} and {minus}: the two elbow configurations (up and down)")
    s = br.symbol
    text = "{eq} leaves {v} alone (the law of cosines): {name} with"
    if B == 0 or A == 0:
        D = sp.Symbol(f"D_{j}", **_REAL)
        trig = sp.cos(var) if B == 0 else sp.sin(var)
        b.add(
            "position",
            sentence(text, eq=_capital(eq.name), v=var, name=sp.Eq(trig, D)),
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
        sentence(text, eq=_capital(eq.name), v=var, name=sp.Eq(_show(A, B, var), Ks)),
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
                sentence(
                    "An entry of the wrist's rotation {Rw} (the arm's rotation transposed "
                    "times {R}):",
                    Rw=sp.Symbol("R_w"),
                    R=sp.Symbol("R"),
                ),
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
    j5 = b.number[wvars[1]]
    cx5 = sp.Symbol(f"c_{j5}", **_REAL)
    wrist_word = [Elementary("R", "z", xs[0]), Elementary("R", "x", a4)]
    wrist_word += [Elementary("R", "z", xs[1]), Elementary("R", "x", a5)]
    wrist_word += [Elementary("R", "z", xs[2])]
    b.add(
        "orientation",
        sentence(
            "Entry (3, 3) of {word} depends on {v} alone:",
            word=word_expr(wrist_word),
            v=wvars[1],
        ),
        cx5,
        b.tidy((c4 * c5 - m(2, 2)) / (s4 * s5)),
    )
    br = b.branch(
        "wrist",
        wvars[1],
        "{plus}: wrist not flipped ({up}); {minus}: flipped",
        up=sp.Gt(sp.sin(wvars[1]), 0),
    )
    sg = br.symbol
    sx5 = sp.Symbol(f"s_{j5}", **_REAL)
    v = sp.expand(-(c4 * s5 * cx5 + s4 * c5))
    qq = sp.expand(s4 * c5 * cx5 + c4 * s5)
    if v == 0:  # twists of ±90°: the third column is (±s cos θ4, ±s sin θ4, c)
        b.add(
            "orientation",
            sentence(
                "The rest of column 3 has length {length}; two signs: the wrist flip.",
                length=sp.Abs(sp.sin(wvars[1])),
            ),
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
        sentence("{v} from its sine and cosine:", v=wvars[1]),
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
        sentence("Column 3 of the wrist's rotation gives {v}:", v=wvars[0]),
        wvars[0],
        _solve_joint_from_entry(x4, xs[0], wvars[0]),
        singular=_solve_joint_from_entry(sp.Integer(0), xs[0], wvars[0]),
    )
    b.add(
        "orientation",
        sentence("Row 3 of the wrist's rotation gives {v}:", v=wvars[2]),
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
    return [0] if joints in (1, 2) else []  # more than six joints: redundant, nothing to try


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
        cache = self.robot._extra_cache
        key = ("ik-solver", values_key(values))  # the values as given: converted only once
        if key not in cache:
            cache[key] = Solver(self, _values(self.robot, values))
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


def inverse(robot: Robot) -> InverseKinematics:
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
    dhsym.kinematics._structure.StructureError: no closed-form inverse kinematics ...
    """
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
    cs, ps, rs = sp.symbols("c p R")
    if v == Matrix.zeros(3, 1):
        text = sentence(
            f"The {point} is the origin of frame {b.robot.n}: {{same}}.", same=sp.Eq(cs, ps)
        )
    else:
        text = sentence(
            f"The {point} sits at {{v}} in frame {b.robot.n}: {{c}} = {{p}} + {{R}} {{v}}, with "
            "{R} the rotation of the pose.",
            v=sp.Tuple(*v),
            c=cs,
            p=ps,
            R=rs,
        )
    for name, value in zip(names, c):
        b.add("wrist centre", text, name, sp.expand(value))
    return Matrix(names)
