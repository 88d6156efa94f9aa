r"""Recursive Newton–Euler on numbers: τ(q, q̇, q̈, g) for a batch of states, no derivation.

The recursion of :mod:`.recursive_newton_euler`, line for line, evaluated with numpy on
float arrays ``(N, 3)`` instead of written out as exact expressions: a link matrix is
the product of its DH word (:func:`~dhsym.kinematics.transforms.link_word`), its
constant elementaries multiplied once into float matrices
(:func:`~dhsym.kinematics.numeric.elementary_stack`) and its joint's elementary
evaluated per state (:func:`~dhsym.kinematics.interpreter.evaluate_many`). Building it
costs milliseconds where writing out the PUMA 560's recursion costs seconds, so the
first numbers of a robot need no symbolic derivation; the exact recursion stays for
the documents and the exported code (:func:`~dhsym.export.program.rne_program`), and
the tests prove the two equal (why the recursion is written apart for numbers, sharing
its geometry: :mod:`.recursive_newton_euler`).

Examples
--------
>>> from dhsym.kinematics.chain import KinematicChain
>>> from dhsym.model.tablefile import read_table_text
>>> from dhsym.dynamics.model import dynamic_model
>>> pendulum = KinematicChain(read_table_text('''
... gravity: [0, -9.81, 0]
... joints: [{type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}]
... '''))
>>> ne = numeric_recursion(dynamic_model(pendulum))
>>> ne.tau([[0.0]], [[0.0]], [[1.0]], [0.0, -9.81, 0.0])  # m g lc + (Izz + m lc²) q̈
array([[10.41]])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.constants import to_float
from dhsym.kinematics.interpreter import EvaluationError, evaluate_many
from dhsym.kinematics.numeric import elementary_stack
from dhsym.kinematics.transforms import link_word
from dhsym.model.table import Elementary, JointType

from .model import DynamicModel
from .recursive_newton_euler import cross, joint_prefix

__all__ = ["NumericLink", "NumericRecursion", "numeric_recursion"]


@dataclass(frozen=True, eq=False)
class NumericLink:
    """One DH row as numbers: its word (constant runs as float ``4×4`` matrices, the
    joint's elementaries kept exact), the fixed part before the joint motion
    (``u = k R_pre e_z``, the joint axis in frame i − 1 times the rate ``k`` of the
    joint's variable in its cell, :attr:`~.model.DynamicModel.cell_rates`, and ``r1``:
    :func:`.recursive_newton_euler.joint_prefix`), its joint (0-based, or
    None for a fixed row) and kind, and the link's mass, centre of mass, inertia about
    it and motor inertia ``Jm G²``."""

    factors: tuple[Elementary | tuple[tuple[float, ...], ...], ...]
    u: tuple[float, float, float]
    r1: tuple[float, float, float]
    joint: int | None
    kind: JointType
    m: float
    rc: tuple[float, float, float]
    inertia: tuple[tuple[float, ...], ...]
    armature: float


def _floats(values: Sequence[sp.Expr], what: str, row: int) -> np.ndarray:
    try:
        return np.array([to_float(v) for v in values], dtype=float)
    except DHError as err:
        raise DHError(f"row {row}, {what}: {err.message}") from None


def _fold(
    word: Sequence[Elementary], variables: frozenset[sp.Symbol], row: int
) -> list[np.ndarray | Elementary]:
    """The word with each run of constant elementaries multiplied into one float matrix."""
    out: list[np.ndarray | Elementary] = []
    for e in word:
        if e.value.free_symbols & variables:
            out.append(e)
            continue
        if e.value.is_zero:
            continue
        (value,) = _floats([e.value], f"{e.kind}{e.axis}", row)
        M = elementary_stack(e.kind, e.axis, [value])[0]
        out.append(out.pop() @ M if out and isinstance(out[-1], np.ndarray) else M)
    return out


def _constant(factors: Sequence[np.ndarray | Elementary], row: int) -> np.ndarray:
    """A folded word without joint elementaries as one ``4×4`` matrix (identity if empty)."""
    P = np.eye(4)
    for f in factors:
        if not isinstance(f, np.ndarray):
            raise DHError(f"row {row}: the joint variable in {f}, before the joint's motion")
        P = P @ f
    return P


Component = np.ndarray | float  # one entry at N states (a float: the same at every state)
Vector = tuple[Component, Component, Component]
Rotation = tuple[Vector, Vector, Vector]  # rows


def _lc(*terms: tuple[Component, float]) -> Component:
    """``Σ x·k`` over pairs with constant ``k``: products by 0 skipped, by 1 not made."""
    out: Component = 0.0
    for x, k in terms:
        if k != 0.0:
            out = out + (x if k == 1.0 else x * k)
    return out


def _add(*vs: Sequence[Component]) -> Vector:
    x, y, z = vs[0]
    for v in vs[1:]:
        x, y, z = x + v[0], y + v[1], z + v[2]
    return (x, y, z)


def _scale(v: Sequence[Component], x: Component) -> Vector:
    return (v[0] * x, v[1] * x, v[2] * x)


def _rt(R: Rotation, v: Sequence[Component]) -> Vector:
    """``Rᵀ v``."""
    (a, b, c), (d, e, f), (g, h, k) = R
    x, y, z = v
    return (a * x + d * y + g * z, b * x + e * y + h * z, c * x + f * y + k * z)


def _r(R: Rotation, v: Sequence[Component]) -> Vector:
    """``R v``."""
    (a, b, c), (d, e, f), (g, h, k) = R
    x, y, z = v
    return (a * x + b * y + c * z, d * x + e * y + f * z, g * x + h * y + k * z)


def _constant_times(M: Sequence[Sequence[float]], v: Sequence[Component]) -> Vector:
    """``M v`` for a constant ``3×3`` ``M`` (zeros skipped)."""
    return tuple(_lc(*((v[k], M[i][k]) for k in range(3))) for i in range(3))  # type: ignore[return-value]


def _times_factor(
    R: list[list[Component]], p: list[Component], F: Sequence[Sequence[float]]
) -> None:
    """``[R p] ← [R p] · F`` for a constant ``4×4`` ``F`` (in place; zeros skipped)."""
    rows = [[_lc(*((R[i][k], F[k][j]) for k in range(3))) for j in range(3)] for i in range(3)]
    for i in range(3):
        p[i] = p[i] + _lc(*((R[i][k], F[k][3]) for k in range(3)))
        R[i] = rows[i]


def _times_elementary(
    R: list[list[Component]], p: list[Component], kind: str, axis: str, x: Component
) -> None:
    """``[R p] ← [R p] · E(x)`` for an elementary rotation or translation (in place)."""
    i = "xyz".index(axis)
    if kind == "T":
        for r in range(3):
            p[r] = p[r] + R[r][i] * x
        return
    j, k = (i + 1) % 3, (i + 2) % 3
    c, s = np.cos(x), np.sin(x)
    for r in range(3):
        R[r][j], R[r][k] = R[r][j] * c + R[r][k] * s, R[r][k] * c - R[r][j] * s


@dataclass(frozen=True, eq=False)
class NumericRecursion:
    """The Newton–Euler recursion of a model with numeric parameters, on batches.

    Every vector is three components, each an array over the states (or a plain float
    for one state, or a constant), so a batch costs a few hundred array operations and
    one state as many float operations; products by the zeros and ones of the DH
    constants are not made.
    """

    links: tuple[NumericLink, ...]
    variables: tuple[sp.Symbol, ...]

    @property
    def n(self) -> int:
        """Number of joint variables."""
        return len(self.variables)

    def tau(self, q: object, qd: object, qdd: object, gravity: object) -> np.ndarray:
        """τ at states ``(N, n)`` with ``gravity`` ``(3,)`` or ``(N, 3)`` (frame 0):
        ``(N, n)``. Motor inertia ``Jm G² q̈`` included, friction not (the compiled
        dynamics add it)."""
        Q, V, A = (np.asarray(x, dtype=float) for x in (q, qd, qdd))
        N = Q.shape[0]
        G = np.asarray(gravity, dtype=float)
        columns: list[list[Component]]
        if N == 1:  # one state: plain floats
            columns = [[float(x) for x in X[0]] for X in (Q, V, A)]
            g: list[Component] = [float(x) for x in G.reshape(-1, 3)[0]]
        else:
            columns = [[X[:, k] for k in range(self.n)] for X in (Q, V, A)]
            g = [G[..., i] for i in range(3)]
        qs, vs, accs = columns
        moving = [f for L in self.links for f in L.factors if isinstance(f, Elementary)]
        env = {v: Q[:, k] for k, v in enumerate(self.variables)}
        try:
            table = evaluate_many([e.value for e in moving], env, N)
        except EvaluationError as err:
            raise DHError(f"joint value: {err}") from None
        values = iter([float(x[0]) for x in table] if N == 1 else list(table))
        zero: Vector = (0.0, 0.0, 0.0)
        w, wd, a = zero, zero, (-g[0], -g[1], -g[2])
        kept = []
        for L in self.links:
            R_rows: list[list[Component]] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
            p: list[Component] = [0.0, 0.0, 0.0]
            for f in L.factors:
                if isinstance(f, Elementary):
                    _times_elementary(R_rows, p, f.kind, f.axis, next(values))
                else:
                    _times_factor(R_rows, p, f)
            R: Rotation = tuple(tuple(r) for r in R_rows)  # type: ignore[assignment]
            u = _rt(R, L.u)
            r2 = _rt(R, (p[0] - L.r1[0], p[1] - L.r1[1], p[2] - L.r1[2]))
            wp, wdp = _rt(R, w), _rt(R, wd)
            r1 = L.r1
            a_A = _rt(R, _add(a, cross(wd, r1), cross(w, cross(w, r1))))
            k = L.joint
            if L.kind is JointType.REVOLUTE and k is not None:
                w_i = _add(wp, _scale(u, vs[k]))
                wd_i = _add(wdp, _scale(cross(wp, u), vs[k]), _scale(u, accs[k]))
            else:
                w_i, wd_i = wp, wdp
            a_i = _add(a_A, cross(wd_i, r2), cross(w_i, cross(w_i, r2)))
            if L.kind is JointType.PRISMATIC and k is not None:
                a_i = _add(a_i, _scale(cross(w_i, u), 2 * vs[k]), _scale(u, accs[k]))
            rc = L.rc
            ac = _add(a_i, cross(wd_i, rc), cross(w_i, cross(w_i, rc)))
            F = _scale(ac, L.m)
            N_i = _add(
                _constant_times(L.inertia, wd_i), cross(w_i, _constant_times(L.inertia, w_i))
            )
            kept.append((R, p, u, r2, F, N_i))
            w, wd, a = w_i, wd_i, a_i
        tau: list[Component] = [0.0] * self.n
        f_next: Vector = zero
        n_next: Vector = zero
        R_next: Rotation | None = None
        p_next: Sequence[Component] = zero
        for i in range(len(self.links) - 1, -1, -1):
            L = self.links[i]
            R, p, u, r2, F, N_i = kept[i]
            if R_next is None:
                f_i, n_i = F, _add(N_i, cross(L.rc, F))
            else:
                fo, no = _r(R_next, f_next), _r(R_next, n_next)
                f_i = _add(F, fo)
                n_i = _add(N_i, no, cross(L.rc, F), cross(p_next, fo))
            k = L.joint
            if k is not None:
                moment = _add(n_i, cross(r2, f_i)) if L.kind is JointType.REVOLUTE else f_i
                t = moment[0] * u[0] + moment[1] * u[1] + moment[2] * u[2]
                tau[k] = t + L.armature * accs[k]
            f_next, n_next, R_next, p_next = f_i, n_i, R, p
        return np.stack([np.broadcast_to(t, (N,)) for t in tau], axis=-1)


def _float_rows(M: np.ndarray) -> tuple[tuple[float, ...], ...]:
    """A matrix's top three rows as plain floats."""
    return tuple(tuple(float(x) for x in row) for row in M[:3])


def _rows(M: np.ndarray | Elementary) -> Elementary | tuple[tuple[float, ...], ...]:
    """A constant factor as rows of plain floats (its top three); an elementary as is."""
    return M if isinstance(M, Elementary) else _float_rows(M)


def numeric_recursion(dm: DynamicModel) -> NumericRecursion:
    """The numeric recursion of ``dm``, whose parameters must all be numbers (the
    model of :func:`~dhsym.dynamics.compiled_dynamics.numeric_model`); raises
    :class:`~dhsym.errors.DHError` naming the row, the field and the symbol otherwise.
    """
    table = dm.robot.table
    variables = frozenset(dm.variables)
    index = {row: k for k, row in enumerate(dm.joints)}
    links = []
    for i, row in enumerate(table.rows, start=1):
        word = link_word(row, table.convention)
        P = _constant(_fold(joint_prefix(word, table.convention), variables, i), i)
        L = dm.links[i - 1]
        k = index.get(i)
        rate = 1.0 if k is None else float(_floats([dm.cell_rates[k]], "rate", i)[0])
        links.append(
            NumericLink(
                tuple(_rows(f) for f in _fold(word, variables, i)),
                tuple(float(x) * rate for x in P[:3, 2]),  # type: ignore[arg-type]
                tuple(float(x) for x in P[:3, 3]),  # type: ignore[arg-type]
                k,
                row.joint,
                float(_floats([L.m], "m", i)[0]),
                tuple(float(x) for x in _floats(L.r, "r", i)),  # type: ignore[arg-type]
                _float_rows(_floats(list(L.I), "I", i).reshape(3, 3)),
                float(_floats([L.Jm * L.G**2], "Jm G^2", i)[0]),
            )
        )
    return NumericRecursion(tuple(links), tuple(dm.variables))
