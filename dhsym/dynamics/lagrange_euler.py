r"""Lagrange–Euler: the energies of each link, M(q), the Christoffel symbols, C and g.

Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, §7.2–7.4:

.. math::

    K = \tfrac12 \dot q^T M(q) \dot q, \quad
    M(q) = \sum_i m_i J_{v_{c_i}}^T J_{v_{c_i}} + J_{\omega_i}^T R_i I_i R_i^T J_{\omega_i},
    \quad P = -\sum_i m_i\, g^T p_{c_i},

    c_{ijk} = \tfrac12\Big(\frac{\partial m_{kj}}{\partial q_i}
      + \frac{\partial m_{ki}}{\partial q_j} - \frac{\partial m_{ij}}{\partial q_k}\Big),
    \quad C_{kj} = \sum_i c_{ijk}\,\dot q_i, \quad g_k = \frac{\partial P}{\partial q_k}.

The Jacobians of each link are written in the link's own frame *i* (where ``I_i`` is
given), so ``R_i I_i R_i^T`` is ``I_i`` itself; they come from the compact transforms
of :class:`~dhsym.kinematics.chain.KinematicChain`, so entries stay in C/S form. Each entry is
expanded and folded by the targeted sum-angle identities (no ``simplify``). A motor's
``Jm G²`` is added to the diagonal of M.

Examples
--------
>>> import dhsym
>>> eom = lagrange(dhsym.load("planar2r"))
>>> print(eom.notation.text(eom.g))
Matrix([
[0],
[0]])
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.jacobian import axis_frame, compact, joint_column
from dhsym.kinematics.simplification import fold_sum_angles, tidy_signs
from dhsym.kinematics.trig_ring import TrigRing, lecture_form

from .equations import EquationsOfMotion
from .model import DynamicModel, dynamic_model

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "potential_energies",
    "christoffel_symbols",
    "coriolis_matrix",
    "lagrange",
    "link_jacobians",
    "RingEquations",
    "ring_energies",
    "ring_equations",
    "tidy",
]

Matrix: TypeAlias = sp.ImmutableMatrix
#: Sums with more terms than this are left expanded by :func:`tidy`, neither folded nor
#: collected (a six-joint arm's entries: folding them costs minutes, shortens them little).
_FOLD_TERMS = 60


def tidy(expr: sp.Expr, parameters: tuple[sp.Symbol, ...] = ()) -> sp.Expr:
    """Expand, fold sum angles (no ``simplify``), and collect by ``parameters`` (``m2*(…)``).

    >>> t1, t2, m, l = sp.symbols("theta1 theta2 m l", real=True)
    >>> tidy(m * l * sp.cos(t1) * sp.cos(t2) - m * l * sp.sin(t1) * sp.sin(t2), (m,))
    l*m*cos(theta1 + theta2)
    """
    e = sp.expand(expr)
    if len(sp.Add.make_args(e)) > _FOLD_TERMS:  # the pair search is quadratic in the terms
        return e
    e = tidy_signs(fold_sum_angles(e))
    if parameters and e.is_Add:
        e = sp.collect(e, parameters)
    return e


def link_jacobians(dm: DynamicModel, i: int) -> tuple[Matrix, Matrix]:
    """``(J_v, J_ω)`` of link ``i``'s centre of mass, 3×n each, written in frame ``i``.

    Column *k* (joint in row ``j ≤ i`` turning about ``z_a`` of its axis frame *a*) is
    ``k ^iR_a (e_z × ^a p_c)`` and ``k ^iR_a e_z`` for a revolute joint, ``k ^iR_a e_z``
    and 0 for a prismatic one; ``^a p_c`` is the centre of mass seen from frame *a* and
    ``k`` the rate of the joint's variable in its cell (``dm.cell_rates``: ``−1`` for
    ``theta: -q1``), the column of :func:`~dhsym.kinematics.jacobian.joint_column`.

    >>> import dhsym
    >>> dm = dynamic_model(dhsym.load("jaco"))
    >>> link_jacobians(dm, 1)[1][:, 0].T  # z_0 is y_1; theta: -theta1 turns it at -thetadot1
    Matrix([[0, -1, 0]])
    """
    robot = dm.robot
    r = Matrix([*dm.links[i - 1].r, 1])
    cols_v, cols_w = [], []
    for row, kind, rate in zip(dm.joints, dm.kinds, dm.cell_rates):
        if row > i:
            cols_v.append(Matrix.zeros(3, 1))
            cols_w.append(Matrix.zeros(3, 1))
            continue
        a = axis_frame(robot, row)
        turn = robot.transform(i, a).matrix[:3, :3]
        lever = (robot.transform(a, i).matrix * r)[:3, 0]
        linear, angular = joint_column(turn, lever, kind, rate)
        cols_v.append(linear)
        cols_w.append(angular)
    Jv = Matrix.hstack(*cols_v).applyfunc(compact)
    Jw = Matrix.hstack(*cols_w).applyfunc(compact)
    return Matrix(Jv), Matrix(Jw)


def christoffel_symbols(
    M: sp.MatrixBase, q: tuple[sp.Symbol, ...], params: tuple[sp.Symbol, ...] = ()
) -> tuple[tuple[tuple[sp.Expr, ...], ...], ...]:
    """Spong's ``c_ijk = ½(∂m_kj/∂q_i + ∂m_ki/∂q_j − ∂m_ij/∂q_k)``, as ``[i][j][k]`` (0-based).

    >>> q1, q2, m = sp.symbols("q1 q2 m", real=True)
    >>> c = christoffel_symbols(sp.Matrix([[m * sp.cos(q2), 0], [0, 1]]), (q1, q2))
    >>> c[0][1][0], c[0][0][1]
    (-m*sin(q2)/2, m*sin(q2)/2)
    """
    n = len(q)
    # Each distinct expression is differentiated and tidied once: M is symmetric (m_kj is
    # m_jk) and c_ijk = c_jik, so about half the entries repeat; the expressions are those
    # of differentiating and tidying every entry (``M.diff(x)`` differentiates each entry).
    derivatives: dict[tuple[sp.Expr, sp.Symbol], sp.Expr] = {}
    tidied: dict[sp.Expr, sp.Expr] = {}

    def dm(x: sp.Symbol, a: int, b: int) -> sp.Expr:  # ∂m_ab/∂x
        key = (M[a, b], x)
        if key not in derivatives:
            derivatives[key] = M[a, b].diff(x)
        return derivatives[key]

    def c(i: int, j: int, k: int) -> sp.Expr:
        e = (dm(q[i], k, j) + dm(q[j], k, i) - dm(q[k], i, j)) / 2
        if e not in tidied:
            tidied[e] = tidy(e, params)
        return tidied[e]

    return tuple(tuple(tuple(c(i, j, k) for k in range(n)) for j in range(n)) for i in range(n))


def coriolis_matrix(
    christoffel: tuple[tuple[tuple[sp.Expr, ...], ...], ...],
    rates: tuple[sp.Symbol, ...],
    params: tuple[sp.Symbol, ...] = (),
) -> Matrix:
    """``C[k, j] = Σ_i c_ijk q̇_i`` (Spong, Eq. 7.51).

    >>> q1, q2, u1, u2 = sp.symbols("q1 q2 u1 u2", real=True)
    >>> c = christoffel_symbols(sp.Matrix([[sp.cos(q2), 0], [0, 1]]), (q1, q2))
    >>> coriolis_matrix(c, (u1, u2))
    Matrix([
    [-u2*sin(q2)/2, -u1*sin(q2)/2],
    [ u1*sin(q2)/2,             0]])
    """
    n = len(rates)
    return Matrix(
        n, n, lambda k, j: tidy(sum(christoffel[i][j][k] * rates[i] for i in range(n)), params)
    )


def potential_energies(dm: DynamicModel) -> tuple[sp.Expr, ...]:
    """Each link's potential energy ``P_i = −m_i gᵀ p_ci`` (``p_ci`` from the compact ``^0T_i``).

    >>> import dhsym
    >>> potential_energies(dynamic_model(dhsym.load("planar2r")))
    (981*m1*rz1/100, 981*m2*rz2/100)
    """
    g0 = Matrix(dm.gravity)
    out = []
    for i, L in enumerate(dm.links, start=1):
        if L.m == 0:
            out.append(sp.Integer(0))
            continue
        pc = (dm.robot.transform(0, i).matrix * Matrix([*L.r, 1]))[:3, 0]
        out.append(-L.m * (g0.T * pc)[0, 0])
    return tuple(out)


@dataclass(frozen=True)
class RingEquations:
    """M, the Christoffel symbols and g of a model as reduced polynomials of one ring, and
    each link's share of M (for its kinetic energy). ``christoffel[i][j][k]`` is ``c_ijk``."""

    ring: TrigRing
    M: tuple[tuple[sp.Poly, ...], ...]
    christoffel: tuple[tuple[tuple[sp.Poly, ...], ...], ...]
    g: tuple[sp.Poly, ...]
    links: tuple[tuple[tuple[sp.Poly, ...], ...] | None, ...]
    potential: tuple[sp.Expr, ...]


def ring_equations(dm: DynamicModel, say: Callable[[str], None] = lambda _m: None) -> RingEquations:
    """M, ``c_ijk`` and g of ``dm`` as polynomials of a :class:`TrigRing` (steps 1–3 of the
    module docstring); ``say`` is told each stage."""
    n = dm.n
    say("link Jacobians")
    jacobians: list[tuple[Matrix, Matrix] | None] = []
    for i, L in enumerate(dm.links, start=1):
        if L.m == 0 and L.I.is_zero_matrix:
            jacobians.append(None)
        else:
            jacobians.append(link_jacobians(dm, i))
    heights = [sp.expand(p) for p in potential_energies(dm)]
    pieces = [e for J in jacobians if J for part in J for e in part] + heights
    ring = TrigRing.of(pieces, dm.variables)
    say("inertia matrix")
    zero = ring.poly(sp.Integer(0))
    M = [[zero for _ in range(n)] for _ in range(n)]
    shares: list[tuple[tuple[sp.Poly, ...], ...] | None] = []
    for J, L in zip(jacobians, dm.links):
        if J is None:
            shares.append(None)
            continue
        Pv = [[ring.poly(e) for e in J[0].row(r)] for r in range(3)]
        Pw = [[ring.poly(e) for e in J[1].row(r)] for r in range(3)]
        Mi = [[zero for _ in range(n)] for _ in range(n)]
        for j, k in itertools.combinations_with_replacement(range(n), 2):
            acc = zero
            if L.m != 0:
                acc = sum((Pv[r][j] * Pv[r][k] for r in range(3)), zero) * ring.poly(L.m)
            for a, b in itertools.product(range(3), repeat=2):
                if L.I[a, b] != 0 and not Pw[a][j].is_zero and not Pw[b][k].is_zero:
                    acc += Pw[a][j] * Pw[b][k] * ring.poly(L.I[a, b])
            Mi[j][k] = Mi[k][j] = ring.reduce(acc)
            M[j][k] += acc
        shares.append(tuple(tuple(row) for row in Mi))
    for j, arm in enumerate(dm.armature()):
        M[j][j] += ring.poly(arm)
    for j, k in itertools.combinations_with_replacement(range(n), 2):
        M[j][k] = M[k][j] = ring.reduce(M[j][k])
    say("Christoffel symbols")
    dM = [[[ring.diff(M[k][j], i) for j in range(n)] for k in range(n)] for i in range(n)]
    half = ring.poly(sp.Rational(1, 2))
    cs: dict[tuple[int, int, int], sp.Poly] = {}
    for i, j, k in itertools.product(range(n), repeat=3):  # c_ijk = c_jik
        if i <= j:
            cs[i, j, k] = ring.reduce((dM[i][k][j] + dM[j][k][i] - dM[k][i][j]) * half)
    christoffel = tuple(
        tuple(tuple(cs[min(i, j), max(i, j), k] for k in range(n)) for j in range(n))
        for i in range(n)
    )
    say("gravity vector")
    P = ring.poly(sp.Add(*heights))
    return RingEquations(
        ring,
        tuple(tuple(row) for row in M),
        christoffel,
        tuple(ring.diff(P, k) for k in range(n)),
        tuple(shares),
        tuple(heights),
    )


def ring_energies(
    dm: DynamicModel, eq: RingEquations
) -> tuple[tuple[sp.Expr, ...], tuple[sp.Expr, ...]]:
    """Each link's kinetic energy ``½ q̇ᵀ M_i q̇`` (its share of M, in the lecture form) and
    potential energy (collected by the masses)."""
    qd = dm.rates
    kinetic = []
    for share in eq.links:
        terms = []
        for j, k in itertools.combinations_with_replacement(range(dm.n), 2):
            if share is not None and not share[j][k].is_zero:
                weight = sp.Rational(1, 2) if j == k else sp.Integer(1)
                terms.append(weight * lecture_form(eq.ring, share[j][k]) * qd[j] * qd[k])
        kinetic.append(sp.Add(*terms))
    return tuple(kinetic), tuple(tidy(p, dm.masses) for p in eq.potential)


def _ring_lagrange(dm: DynamicModel) -> EquationsOfMotion:
    """Lagrange–Euler through :func:`ring_equations`: each entry one term per trigonometric
    monomial (what :func:`lagrange` does from :data:`RING_JOINTS` joints on)."""
    eq = ring_equations(dm)
    ring, n = eq.ring, dm.n
    M = Matrix(n, n, lambda j, k: lecture_form(ring, eq.M[j][k]))
    christoffel = tuple(
        tuple(tuple(lecture_form(ring, c) for c in cj) for cj in ci) for ci in eq.christoffel
    )
    C = Matrix(n, n, lambda k, j: sp.Add(*(christoffel[i][j][k] * dm.rates[i] for i in range(n))))
    g = Matrix([lecture_form(ring, p) for p in eq.g])
    qd, qdd = Matrix(dm.rates), Matrix(dm.accelerations)
    kinetic, potential = ring_energies(dm, eq)
    tau = Matrix(M * qdd + C * qd + g)
    return EquationsOfMotion("lagrange", dm, M, C, g, tau, christoffel, tuple(kinetic), potential)


#: From this many joints on, :func:`lagrange` works in the polynomial ring of the sines and
#: cosines (:func:`ring_equations`): the entry-by-entry folding is quadratic in the terms.
RING_JOINTS = 4


def lagrange(robot: KinematicChain, model: DynamicModel | None = None) -> EquationsOfMotion:
    """The equations of motion by Lagrange–Euler (see the module docstring)."""
    dm = model or dynamic_model(robot)
    n = dm.n
    if n >= RING_JOINTS:
        return _ring_lagrange(dm)
    params = dm.masses
    qd = Matrix(dm.rates)
    energies = potential_energies(dm)
    M = sp.zeros(n, n)
    kinetic, potential = [], []
    for i, L in enumerate(dm.links, start=1):
        if L.m == 0 and L.I.is_zero_matrix:
            kinetic.append(sp.Integer(0))
            potential.append(sp.Integer(0))
            continue
        Jv, Jw = link_jacobians(dm, i)
        Mi = L.m * Jv.T * Jv + Jw.T * L.I * Jw
        M = M + Mi
        kinetic.append(tidy((qd.T * Mi * qd)[0, 0] / 2, params))
        potential.append(tidy(energies[i - 1], params))
    M = Matrix((M + sp.diag(*dm.armature())).applyfunc(lambda e: tidy(e, params)))
    q = dm.variables
    christoffel = christoffel_symbols(M, q, params)
    C = coriolis_matrix(christoffel, dm.rates, params)
    P = sum(potential, sp.Integer(0))
    g = Matrix([tidy(sp.diff(P, x), params) for x in q])
    qdd = Matrix(dm.accelerations)
    tau = Matrix((M * qdd + C * qd + g).applyfunc(lambda e: tidy(e, params)))
    return EquationsOfMotion(
        "lagrange", dm, M, C, g, tau, christoffel, tuple(kinetic), tuple(potential)
    )
