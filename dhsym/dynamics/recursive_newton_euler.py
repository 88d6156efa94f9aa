r"""Recursive Newton–Euler: velocities and accelerations outward, forces and torques inward.

Craig, *Introduction to Robotics*, §6.5 (modified DH) and Luh, Walker and Paul (standard
DH), written once for both conventions. A link matrix is ``Pre · Rz(θ) Tz(d) · Post``:
the joint moves about (along) the axis through the point ``A`` = origin of ``Pre``
(standard: ``Pre = I``, ``Post = Tx(a) Rx(α)``; modified: ``Pre = Rx(α) Tx(a)``,
``Post = I``), and ``u`` is its unit vector times the rate ``k`` of the joint variable
in its cell (``θ = k q + c``: the joint turns at ``k q̇``, and ``u · moment`` is the
generalized force of ``q``; ``k = 1`` but for cells such as the Jaco's ``-theta1``,
:attr:`~.model.DynamicModel.cell_rates`). Every vector of link *i* is written in frame
*i*, with ``R = ^{i-1}R_i``, ``r_1 = o_{i-1} → A`` (fixed in link i−1), ``r_2 = A → o_i``
and ``r_c`` the centre of mass:

.. math::

    \omega_i &= R^T\omega_{i-1} + u\,\dot q_i, \qquad
    \dot\omega_i = R^T\dot\omega_{i-1} + (R^T\omega_{i-1})\times u\,\dot q_i + u\,\ddot q_i \\
    a_i &= R^T\big(a_{i-1} + \dot\omega_{i-1}\times r_1
          + \omega_{i-1}\times(\omega_{i-1}\times r_1)\big)
          + \dot\omega_i\times r_2 + \omega_i\times(\omega_i\times r_2)
          \;[+\,2\omega_i\times u\,\dot d_i + u\,\ddot d_i] \\
    a_{c_i} &= a_i + \dot\omega_i\times r_c + \omega_i\times(\omega_i\times r_c), \quad
    F_i = m_i a_{c_i}, \quad N_i = I_i\dot\omega_i + \omega_i\times I_i\omega_i \\
    f_i &= F_i + {}^iR_{i+1} f_{i+1}, \quad
    n_i = N_i + {}^iR_{i+1} n_{i+1} + r_c\times F_i + p_{i+1}\times {}^iR_{i+1} f_{i+1} \\
    \tau_i &= u^T(n_i + r_2\times f_i)\ \text{(revolute)}, \quad
    \tau_i = u^T f_i\ \text{(prismatic)}

with ``a_0 = −g`` (gravity enters as an acceleration of the base). The torque is the
moment about the joint's own axis, so the same lines are right in both conventions
(roboticstoolbox's symbolic ``rne`` is not, for modified DH). Motor inertia ``Jm G² q̈``
is added on the joint variable ``q`` itself.

The recursion is written three times, once for each thing it computes with, and the tests
prove the three equal: here on exact expressions, each step kept with its equation for the
documents (and, with Khalil's first moments, for the regressor); on float arrays, component
by component with the products by the DH constants' zeros and ones left out, for a robot's
first numbers without a derivation (:mod:`.numeric_recursion`); and arranged for few
operations for generated code (Khalil and Dombre's ``U_i``, moments about the joint's
point, a wrist's last link carried: the export room's ``rne_program``). One function
generic over its arithmetic would carry the step record, the skipped zeros and that
rearrangement as options of every line; the three share the geometry instead
(:func:`joint_prefix`, :func:`cross`). The control room has no recursion of its own: its
computed torque and simulation call the compiled dynamics.

Examples
--------
>>> import dhsym
>>> eom = newton_euler(dhsym.load("planar2r"))
>>> [s.name for s in eom.steps if s.link == 1]
['omega', 'omegadot', 'a', 'ac', 'F', 'N', 'f', 'n', 'tau']
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, TypeAlias

import sympy as sp

from dhsym.kinematics.transforms import plain_product
from dhsym.model.table import Convention, Elementary, JointType

from .equations import EquationsOfMotion, NEStep
from .lagrange_euler import christoffel_symbols, coriolis_matrix, tidy
from .model import DynamicModel, dynamic_model

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["cross", "joint_prefix", "newton_euler", "rne_expressions"]

Matrix: TypeAlias = sp.ImmutableMatrix
_EZ = Matrix([0, 0, 1])
_ZERO3 = Matrix.zeros(3, 1)

_EQUATIONS = {
    "omega": "ω_i = R^T ω_{i-1} + u q̇_i",
    "omegadot": "ω̇_i = R^T ω̇_{i-1} + R^T ω_{i-1} × u q̇_i + u q̈_i",
    "a": (
        "a_i = R^T(a_{i-1} + ω̇_{i-1} × r_1 + ω_{i-1} × (ω_{i-1} × r_1))"
        " + ω̇_i × r_2 + ω_i × (ω_i × r_2)"
    ),
    "ac": "a_ci = a_i + ω̇_i × r_c + ω_i × (ω_i × r_c)",
    "F": "F_i = m_i a_ci",
    "N": "N_i = I_i ω̇_i + ω_i × I_i ω_i",
    "f": "f_i = F_i + R_{i+1} f_{i+1}",
    "n": "n_i = N_i + R_{i+1} n_{i+1} + r_c × F_i + p_{i+1} × R_{i+1} f_{i+1}",
    "tau": "τ_i = u · (n_i + r_2 × f_i)  (prismatic: u · f_i)",
}


def cross(a: Any, b: Any) -> tuple[Any, Any, Any]:
    """``a × b`` by components, for any three-component vectors: exact entries here, float
    arrays in :mod:`.numeric_recursion`.

    >>> cross((1, 0, 0), (0, 1, 0))
    (0, 0, 1)
    """
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _cross(a: sp.MatrixBase, b: sp.MatrixBase) -> Matrix:
    return Matrix(cross(a, b))


def joint_prefix(word: Sequence[Elementary], convention: Convention) -> tuple[Elementary, ...]:
    """The fixed elementaries of a link's word before its joint's motion (``Pre`` above):
    none in the standard convention, ``Rx(α) Tx(a)`` in the modified one.

    >>> import dhsym
    >>> from dhsym.kinematics.transforms import link_word
    >>> t = dhsym.load_table("puma560_modified")
    >>> [e.kind + e.axis for e in joint_prefix(link_word(t.rows[1], t.convention), t.convention)]
    ['Rx', 'Tx']
    """
    return () if convention is Convention.STANDARD else tuple(word[:2])


def _split(row_word: Sequence[Elementary], convention: Convention) -> tuple[Matrix, Matrix]:
    """``(R_pre, t_pre)`` of the fixed part before the joint motion of one link matrix."""
    P = plain_product(joint_prefix(row_word, convention))
    return Matrix(P[:3, :3]), Matrix(P[:3, 3])


def rne_expressions(
    dm: DynamicModel,
    qd: Sequence[sp.Expr] | None = None,
    qdd: Sequence[sp.Expr] | None = None,
    *,
    gravity: Sequence[sp.Expr] | None = None,
    clean: Callable[[sp.Expr], sp.Expr] | None = None,
    record: list[NEStep] | None = None,
    first_moments: Sequence[tuple[sp.Expr, Matrix, Matrix]] | None = None,
) -> Matrix:
    """τ of the Newton–Euler recursion, as an n×1 matrix (see the module docstring).

    ``qd``, ``qdd`` default to the model's rate and acceleration symbols, ``gravity`` to
    the model's; ``clean`` is applied to every entry of every step (``None``: the raw
    nested expression, what the compiler takes); ``record`` collects the steps.

    ``first_moments`` gives each link as ``(m, h, L)``: mass, first moment ``h = m r`` and
    inertia ``L`` about the link origin (Khalil's parameters, in which τ is linear). Then
    ``F = m a + ω̇ × h + ω × (ω × h)`` and the moment about the origin is
    ``N = L ω̇ + ω × L ω + h × a``.
    """
    robot = dm.robot
    table = robot.table
    n_rows = table.n
    qd = list(dm.rates if qd is None else qd)
    qdd = list(dm.accelerations if qdd is None else qdd)
    g0 = Matrix(dm.gravity if gravity is None else gravity)
    fix = clean or (lambda e: e)

    def keep(sweep: str, name: str, i: int, v: sp.MatrixBase) -> Matrix:
        v = Matrix(v).applyfunc(fix)
        if record is not None:
            record.append(NEStep(sweep, name, i, Matrix(v), _EQUATIONS[name]))
        return Matrix(v)

    index = {row: k for k, row in enumerate(dm.joints)}
    w, wd, a = _ZERO3, _ZERO3, Matrix(-g0)
    geometry = []
    forces = []
    for i in range(1, n_rows + 1):
        row = table.rows[i - 1]
        L = dm.links[i - 1]
        T = robot.transform(i - 1, i).matrix
        R, p = Matrix(T[:3, :3]), Matrix(T[:3, 3])
        Rt = R.T
        R_pre, r1 = _split(robot.link_word(i), table.convention)
        k = index.get(i)
        rate = sp.Integer(1) if k is None else dm.cell_rates[k]
        u = (rate * (Rt * R_pre * _EZ)).applyfunc(sp.expand)  # the axis times the rate
        r2 = Rt * (p - r1)
        wp, wdp = Rt * w, Rt * wd
        a_A = Rt * (a + _cross(wd, r1) + _cross(w, _cross(w, r1)))
        if row.joint is JointType.REVOLUTE and k is not None:
            w_i = keep("outward", "omega", i, wp + u * qd[k])
            wd_i = keep("outward", "omegadot", i, wdp + _cross(wp, u) * qd[k] + u * qdd[k])
        else:
            w_i = keep("outward", "omega", i, wp)
            wd_i = keep("outward", "omegadot", i, wdp)
        acc = a_A + _cross(wd_i, r2) + _cross(w_i, _cross(w_i, r2))
        if row.joint is JointType.PRISMATIC and k is not None:
            acc = acc + 2 * _cross(w_i, u) * qd[k] + u * qdd[k]
        a_i = keep("outward", "a", i, acc)
        if first_moments is not None:
            m, h, Lo = first_moments[i - 1]
            rc = _ZERO3  # moments are taken about the link origin
            F = m * a_i + _cross(wd_i, h) + _cross(w_i, _cross(w_i, h))
            N = Lo * wd_i + _cross(w_i, Lo * w_i) + _cross(h, a_i)
        else:
            rc = Matrix(L.r)
            ac = keep("outward", "ac", i, a_i + _cross(wd_i, rc) + _cross(w_i, _cross(w_i, rc)))
            F = keep("outward", "F", i, L.m * ac)
            N = keep("outward", "N", i, L.I * wd_i + _cross(w_i, L.I * w_i))
        geometry.append((u, r2, rc, k, row.joint))
        forces.append((F, N))
        w, wd, a = w_i, wd_i, a_i
    tau: list[sp.Expr] = [sp.Integer(0)] * dm.n
    f_next, n_next = _ZERO3, _ZERO3
    for i in range(n_rows, 0, -1):
        u, r2, rc, k, joint = geometry[i - 1]
        F, N = forces[i - 1]
        if i < n_rows:
            T = robot.transform(i, i + 1).matrix
            R_next, p_next = Matrix(T[:3, :3]), Matrix(T[:3, 3])
            fo, no = R_next * f_next, R_next * n_next
        else:
            fo, no, p_next = _ZERO3, _ZERO3, _ZERO3
        f_i = keep("inward", "f", i, F + fo)
        n_i = keep("inward", "n", i, N + no + _cross(rc, F) + _cross(p_next, fo))
        if k is not None:
            L = dm.links[i - 1]
            if joint is JointType.REVOLUTE:
                t = (u.T * (n_i + _cross(r2, f_i)))[0, 0]
            else:
                t = (u.T * f_i)[0, 0]
            t = t + L.Jm * L.G**2 * qdd[k]
            tau[k] = keep("inward", "tau", i, Matrix([t]))[0, 0]
        f_next, n_next = f_i, n_i
    return Matrix(tau)


def newton_euler(
    robot: KinematicChain, model: DynamicModel | None = None, *, tidy_steps: bool | None = None
) -> EquationsOfMotion:
    """The equations of motion by recursive Newton–Euler, with the recursion as steps.

    τ comes from the recursion; ``M = ∂τ/∂q̈``, ``g = τ(q̇ = 0, q̈ = 0)`` are read off it,
    and ``C`` from the Christoffel symbols of that ``M``. Each step is expanded and folded
    (``tidy_steps``, by default for arms of up to four joints: beyond, the expanded steps
    grow to pages and the recursion is kept nested, as it is compiled).
    """
    dm = model or dynamic_model(robot)
    params = dm.masses
    steps: list[NEStep] = []
    if tidy_steps is None:
        tidy_steps = dm.n <= 4
    if not tidy_steps:  # nested throughout; M, g and c_ijk from runs at unit rates
        tau = rne_expressions(dm, record=steps)
        n, qd = dm.n, dm.rates
        zeros, unit = [0] * n, sp.eye(n)
        g = rne_expressions(dm, qd=zeros, qdd=zeros)
        cols = [rne_expressions(dm, qd=zeros, qdd=unit[:, j], gravity=(0, 0, 0)) for j in range(n)]
        M = Matrix.hstack(*cols)

        def h(v: sp.MatrixBase) -> Matrix:  # the velocity term at rates v: Σ c_ijk v_i v_j
            return rne_expressions(dm, qd=list(v), qdd=zeros, gravity=(0, 0, 0))

        single = [h(unit[:, j]) for j in range(n)]
        pairs = {
            (i, j): (h(unit[:, i] + unit[:, j]) - single[i] - single[j]) / 2
            for i in range(n)
            for j in range(i + 1, n)
        }

        def c(i: int, j: int) -> Matrix:  # symmetric in i, j
            return single[i] if i == j else pairs[(min(i, j), max(i, j))]

        chris = tuple(
            tuple(tuple(c(i, j)[k] for k in range(n)) for j in range(n)) for i in range(n)
        )
        C = Matrix(n, n, lambda k, j: sum(chris[i][j][k] * qd[i] for i in range(n)))
        return EquationsOfMotion(
            "newton-euler", dm, M, C, Matrix(g), tau, chris, steps=tuple(steps)
        )
    tau = rne_expressions(dm, clean=lambda e: tidy(e, params), record=steps)
    zero = {s: 0 for s in (*dm.rates, *dm.accelerations)}
    g = Matrix([tidy(t.xreplace(zero), params) for t in tau])
    M = Matrix(dm.n, dm.n, lambda r, c: tidy(sp.diff(tau[r], dm.accelerations[c]), params))
    chris = christoffel_symbols(M, dm.variables, params)
    C = coriolis_matrix(chris, dm.rates, params)
    return EquationsOfMotion("newton-euler", dm, M, C, g, tau, chris, steps=tuple(steps))
