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

from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.jacobian import axis_frame, compact
from dhsym.kinematics.simplification import fold_sum_angles, tidy_signs
from dhsym.model.table import JointType

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
    "tidy",
]

Matrix: TypeAlias = sp.ImmutableMatrix
_EZ = Matrix([0, 0, 1])
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
    ``^iR_a (e_z × ^a p_c)`` and ``^iR_a e_z`` for a revolute joint, ``^iR_a e_z`` and 0
    for a prismatic one; ``^a p_c`` is the centre of mass seen from frame *a*.
    """
    robot = dm.robot
    r = Matrix([*dm.links[i - 1].r, 1])
    cols_v, cols_w = [], []
    for row, kind in zip(dm.joints, dm.kinds):
        if row > i:
            cols_v.append(Matrix.zeros(3, 1))
            cols_w.append(Matrix.zeros(3, 1))
            continue
        a = axis_frame(robot, row)
        turn = robot.transform(i, a).matrix[:3, :3]
        axis = turn * _EZ
        if kind is JointType.REVOLUTE:
            lever = (robot.transform(a, i).matrix * r)[:3, 0]
            cols_v.append(turn * Matrix([-lever[1], lever[0], 0]))
            cols_w.append(axis)
        else:
            cols_v.append(axis)
            cols_w.append(Matrix.zeros(3, 1))
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
    dM = [M.diff(x) for x in q]  # dM[i][k, j] = ∂m_kj/∂q_i
    return tuple(
        tuple(
            tuple(tidy((dM[i][k, j] + dM[j][k, i] - dM[k][i, j]) / 2, params) for k in range(n))
            for j in range(n)
        )
        for i in range(n)
    )


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


def lagrange(robot: KinematicChain, model: DynamicModel | None = None) -> EquationsOfMotion:
    """The equations of motion by Lagrange–Euler (see the module docstring)."""
    dm = model or dynamic_model(robot)
    n = dm.n
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
