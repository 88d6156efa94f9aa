"""The general 6R in numbers: the elimination of :mod:`dhsym.ik.general6r.elimination` as a
matrix eigenproblem per pose (Manocha and Canny, "Efficient inverse kinematics for general
6R manipulators", IEEE Trans. Robot. Autom. 10(5), 1994), compiled once per arm.

Per pose, the six combinations ``Nᵀ`` that annihilate ``Q`` remove θ1 and θ2. With
``x = tan(θ/2)`` the six equations in ``x4^i x5^j`` (``i, j ≤ 2``), and the same
multiplied by ``x4``, form a 12×12 matrix polynomial ``Σ(x3) = A x3² + B x3 + C``.
``det Σ(x3) = 0`` is the generalised eigenproblem of the 24×24 companion pencil; its
eigenvectors give x4 and x5, a least-squares solve gives ``s1, c1, s2, c2``, and θ6
follows from ``A6 = (A1 ⋯ A5)⁻¹ T``. Every candidate is polished by Newton steps on the
full pose, checked by dhsym's own forward kinematics and deduplicated modulo 2π.

A leading matrix ``A`` that is singular (a solution at θ3 = π) is handled by a change of
variable ``θ3 = φ + δ`` (a Möbius map of the half-angle tangent), or by the QZ algorithm
when no shift helps. An arrangement of the chain (as given or reversed, 12×12 or 16×16)
is used only after it solves a few random poses of the arm (:func:`_self_test`, part of
compiling: :func:`general_6r`).

Examples
--------
>>> from dhsym.model.table import DHRow, DHTable
>>> rows = [DHRow.revolute(f"q{i}", d=d, a=a, alpha=al) for i, (d, a, al) in enumerate(
...     [(0.3, 0.1, 1.1), (0.2, 0.5, -0.7), (-0.1, 0.4, 0.9), (0.25, 0.15, 1.3),
...      (0.1, 0.2, -1.2), (0.12, 0.05, 0.4)], start=1)]
>>> solver = general_6r(DHTable.from_rows(rows, snap_angles=False, name="random 6R"))
>>> q = np.array([0.3, -1.2, 0.8, 2.0, -0.4, 1.1])
>>> Q = solver.solve(solver.fk(q))
>>> Q.shape[1], bool(np.any(np.all(np.abs(Q - q) < 1e-9, axis=1)))
(6, True)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from dhsym.errors import DHError
from dhsym.kinematics.numeric import compile_word, numeric_rigid_inverse, to_float, word_product
from dhsym.kinematics.transforms import chain_word
from dhsym.model.table import DHTable

from .elimination import (
    M45,
    EliminationMatrices,
    _Chain,
    _Derivation,
    _derive,
    _link_constants,
    _standard,
    _terms,
    elimination_matrices,
)

__all__ = ["General6R", "general_6r"]

_ANGLE_TOL = 1e-3  # |Im θ| of an eigenvalue still taken as a real candidate (polished after)
_SELF_TEST = 6  # random poses every arrangement must solve before it is used


# --- the numbers ----------------------------------------------------------------------------------


def _half_angle_basis() -> np.ndarray:
    """``H`` (9×9): row k holds the products :data:`M45` times ``(1 + x4²)(1 + x5²)`` as
    coefficients of ``x4^i x5^j`` (column ``3i + j``), with ``c = 1 − x²``, ``s = 2x``."""
    one, c, s = (1.0, 0.0, 1.0), (1.0, 0.0, -1.0), (0.0, 2.0, 0.0)
    factors = {"1": (one, one), "s4": (s, one), "c4": (c, one), "s5": (one, s), "c5": (one, c)}
    factors |= {
        f"{a}*{b}": (factors[a][0], factors[b][1]) for a in ("s4", "c4") for b in ("s5", "c5")
    }
    H = np.zeros((9, 9))
    for k, word in enumerate(M45):
        u, v = factors[word]
        H[k] = np.outer(u, v).ravel()
    return H


_HALF = _half_angle_basis()


@dataclass(frozen=True, eq=False)
class _Arrangement:
    """The numbers of one arrangement (the chain as given, or reversed) of one arm."""

    reverse: bool
    base_inv: np.ndarray  # (4, 4)
    tool_inv: np.ndarray  # (4, 4)
    d: np.ndarray  # (6,)
    a: np.ndarray
    ca: np.ndarray
    sa: np.ndarray
    sign: np.ndarray
    offset: np.ndarray
    joint: np.ndarray  # which q drives each link
    P: np.ndarray  # (3, 14, 9): P0, Pc, Ps (the right sides' constants not included)
    G: np.ndarray  # (3, 14, 9): (P0 − Pc, 2 Ps, P0 + Pc) @ H: the x3², x3, 1 coefficients
    p6: np.ndarray  # (3,): the point (−a6, −d6 sα6, −d6 cα6) of T A6⁻¹'s fourth column
    l6: np.ndarray  # (3,): the direction (0, sα6, cα6) of its third column
    K: np.ndarray  # (14 * 9, n_pose): Q (first 8 columns) and the constants, per pose monomial
    pose_exp: np.ndarray  # (n_pose, 6): exponents of px, py, pz, lx, ly, lz
    project: np.ndarray | None = None  # (16, 24) for dependent equations (see _embed)

    def target(self, T: np.ndarray) -> np.ndarray:
        """``base⁻¹ · T · tool⁻¹`` of this arrangement (T inverted first when reversed)."""
        Tt = numeric_rigid_inverse(T) if self.reverse else T
        target: np.ndarray = self.base_inv @ Tt @ self.tool_inv
        return target

    def links(self, theta: np.ndarray) -> np.ndarray:
        """The link matrices ``(k, 6, 4, 4)`` at chain angles ``theta (k, 6)``."""
        c, s = np.cos(theta), np.sin(theta)
        A = np.empty((*theta.shape, 4, 4))
        A[..., 2:, :] = self.fixed_rows  # (0, sα, cα, d), (0, 0, 0, 1)
        A[..., 0, 0], A[..., 1, 0] = c, s
        A[..., 0, 1], A[..., 1, 1] = -s * self.ca, c * self.ca
        A[..., 0, 2], A[..., 1, 2] = s * self.sa, -c * self.sa
        A[..., 0, 3], A[..., 1, 3] = self.a * c, self.a * s
        return A

    @property
    def fixed_rows(self) -> np.ndarray:
        """The last two rows of every link matrix ``(6, 2, 4)``: they do not depend on θ."""
        out = np.zeros((6, 2, 4))
        out[:, 0, 1], out[:, 0, 2], out[:, 0, 3], out[:, 1, 3] = self.sa, self.ca, self.d, 1.0
        return out


def _arrangement(chain: _Chain, reverse: bool, d: _Derivation, H: np.ndarray) -> _Arrangement:
    if reverse:
        chain = chain.reversed()
    L = chain.links
    f = np.array
    base = word_product(chain.base, {}, 1)[0] if chain.base else np.eye(4)
    tool = word_product(chain.tool, {}, 1)[0] if chain.tool else np.eye(4)
    alpha = f([to_float(x.alpha) for x in L])
    vals = _link_constants(L, exact=False)
    P = np.zeros((3, 14, 9))
    right: dict[tuple[int, ...], np.ndarray] = {}
    for side in ("left", "right"):
        for row, part, col, coeff, consts, pose in _terms(d, side):
            v = float(coeff) * math.prod(vals[n] ** e for n, e in consts.items())
            if side == "left":
                P[part, row, col] += v
            else:
                right.setdefault(pose, np.zeros((14, 9)))[row, col] += v
    exps = sorted(right)
    K = np.stack([right[e].ravel() for e in exps], axis=1)
    return _Arrangement(
        reverse,
        numeric_rigid_inverse(base),
        numeric_rigid_inverse(tool),
        f([to_float(x.d) for x in L]),
        f([to_float(x.a) for x in L]),
        np.cos(alpha),
        np.sin(alpha),
        f([float(x.sign) for x in L]),
        f([to_float(x.offset) for x in L]),
        f([x.joint for x in L], dtype=int),
        P,
        np.stack([P[0] - P[1], 2.0 * P[2], P[0] + P[1]]) @ H,
        np.array(
            [-L[5].a, -L[5].d * math.sin(alpha[5]), -L[5].d * math.cos(alpha[5])], dtype=float
        ),
        np.array([0.0, math.sin(alpha[5]), math.cos(alpha[5])]),
        K,
        f(exps, dtype=float),
    )


def _pencil(
    arr: _Arrangement, Tp: np.ndarray, delta: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Σ(x) = A x² + B x + C (12×12 each) at the target ``Tp``, with θ3 = φ + δ, x = tan(φ/2).

    Also returns what back-substitution needs: the QR factors of ``Q``, the constants ``r``
    of the right sides and the (rotated) ``P0, Pc, Ps``.
    """
    R, t = Tp[:3, :3], Tp[:3, 3]
    pl = np.concatenate([R @ arr.p6 + t, R @ arr.l6])
    u = np.prod(pl**arr.pose_exp, axis=1)
    QR = (arr.K @ u).reshape(14, 9)
    Q, r = QR[:, :8], QR[:, 8]
    Qf, Rf = np.linalg.qr(Q, mode="complete")
    P = arr.P
    if delta:
        cd, sd = math.cos(delta), math.sin(delta)
        P = np.stack([P[0], P[1] * cd + P[2] * sd, P[2] * cd - P[1] * sd])
        G = np.stack([P[0] - P[1], 2.0 * P[2], P[0] + P[1]]) @ _HALF
    else:
        G = arr.G.copy()
    rh = np.outer(r, _HALF[8])  # the constants times (1 + x4²)(1 + x5²)
    G[0] -= rh
    G[2] -= rh
    S = Qf[:, 8:].T @ G  # (3, 6, 9): θ1, θ2 eliminated
    return _embed(S, arr.project), Qf[:, :8], Rf[:8], r, P


def _embed(S: np.ndarray, project: np.ndarray | None) -> np.ndarray:
    """The square matrix polynomial ``(3, n, n)`` from the six equations ``S (3, 6, 9)``.

    Generic arms: the six and the six times x4, on ``x4^i x5^j`` (``i ≤ 3, j ≤ 2``): 12×12.
    When the six equations are dependent (an arm with zero lengths and right or straight
    twists, the Jaco), the six times ``1, x4, x5, x4 x5`` on ``x4^i x5^j`` (``i, j ≤ 3``),
    24×16, reduced to 16×16 by a fixed random combination of rows ``project``: every true
    root stays a root; the extra ones are dropped by the pose check.
    """
    if project is None:
        big = np.zeros((3, 12, 12))
        big[:, :6, :9] = S  # x4^i x5^j, i <= 2
        big[:, 6:, 3:] = S  # the same times x4
        return big
    tall = np.zeros((3, 24, 16))
    cols = np.array([4 * (c // 3) + c % 3 for c in range(9)])
    for m, shift in enumerate((0, 4, 1, 5)):  # times 1, x4, x5, x4 x5
        tall[:, 6 * m : 6 * m + 6, cols + shift] = S
    return project @ tall


def _eigen(big: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """Eigenvalues x, vectors (24, k) of the companion of ``(A x² + B x + C) v = 0``, and the
    size of ``A⁻¹ [C B]`` (large when A is nearly singular: a root near x = ∞)."""
    A, B, C = big
    n = len(A)
    try:
        X = np.linalg.solve(A, np.concatenate([C, B], axis=1))
    except np.linalg.LinAlgError:
        return np.empty(0), np.empty((2 * n, 0)), math.inf
    size = float(np.abs(X).max())
    M = np.zeros((2 * n, 2 * n))
    M[:n, n:] = np.eye(n)
    M[n:] = -X
    x, W = np.linalg.eig(M)
    return x, W, size


def _eigen_qz(big: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The same pencil by the QZ algorithm, infinite eigenvalues included (needs scipy,
    else ImportError: the caller then keeps the companion matrix)."""
    from scipy.linalg import eig

    A, B, C = big
    n = len(A)
    L = np.zeros((2 * n, 2 * n))
    M = np.zeros((2 * n, 2 * n))
    L[:n, n:] = M[:n, :n] = np.eye(n)
    L[n:, :n], L[n:, n:] = -C, -B
    M[n:, n:] = A
    (alpha, beta), W = eig(L, M, homogeneous_eigvals=True)
    with np.errstate(all="ignore"):
        x = np.where(np.abs(beta) > 1e-14 * np.abs(alpha), alpha / beta, 1e16)
    return x, W


def _candidates(arr: _Arrangement, Tp: np.ndarray, angle_tol: float = _ANGLE_TOL) -> np.ndarray:
    """Chain angles ``(k, 6)`` of every real eigenvalue (``|Im θ| < angle_tol``), before
    polishing."""
    best = None
    for delta in _SHIFTS:
        found = _pencil(arr, Tp, delta), delta
        x, W, size = _eigen(found[0][0])
        if size < 1e8:
            break
        best = best if best is not None and best[0] <= size else (size, found, x, W)
    else:  # every shift leaves A nearly singular: QZ (scipy) on the unshifted pencil
        try:
            found = _pencil(arr, Tp, 0.0), 0.0
            x, W = _eigen_qz(found[0][0])
        except ImportError:  # no scipy: the companion matrix of the best-conditioned shift
            assert best is not None  # set by every shift of the loop above
            _, found, x, W = best
    (big, Q1, R8, r, P), delta = found
    with np.errstate(all="ignore"):
        phi = 2.0 * np.arctan(x.astype(complex))
    real = np.isfinite(phi) & (np.abs(phi.imag) < angle_tol)
    if not real.any():
        return np.empty((0, 6))
    phi = phi.real[real]
    W = W[:, real]
    n = len(W) // 2
    V = np.where(np.abs(x[real]) > 1.0, W[n:], W[:n])  # w = [v; x v]: the better half
    k = np.arange(V.shape[1])
    top = V[np.argmax(np.abs(V), axis=0), k]
    J = n // 4
    V = (V * (np.conj(top) / np.abs(top))).real.reshape(4, J, -1)  # [i, j]: x4^i x5^j
    # x5 = v[i, j+1] / v[i, j] and x4 = v[i+1, j] / v[i, j], from the pair of largest norm
    n5 = (V[:, :-1] ** 2 + V[:, 1:] ** 2).reshape(4 * (J - 1), -1)
    i5, j5 = np.divmod(np.argmax(n5, axis=0), J - 1)
    th5 = 2.0 * np.arctan2(V[i5, j5 + 1, k], V[i5, j5, k])
    i4, j4 = np.divmod(np.argmax((V[:3] ** 2 + V[1:] ** 2).reshape(3 * J, -1), axis=0), J)
    th4 = 2.0 * np.arctan2(V[i4 + 1, j4, k], V[i4, j4, k])
    # back-substitution: Q m12 = P(θ3) m45 − r, least squares through Q's QR factors
    c4, s4, c5, s5 = np.cos(th4), np.sin(th4), np.cos(th5), np.sin(th5)
    m45 = np.stack([s4 * s5, s4 * c5, c4 * s5, c4 * c5, s4, c4, s5, c5, np.ones_like(s4)])
    rhs = P[0] @ m45 + (P[1] @ m45) * np.cos(phi) + (P[2] @ m45) * np.sin(phi) - r[:, None]
    m12 = np.linalg.solve(R8, Q1.T @ rhs)
    theta = np.stack(
        [
            np.arctan2(m12[4], m12[5]),
            np.arctan2(m12[6], m12[7]),
            phi + delta,
            th4,
            th5,
            np.zeros_like(th5),
        ],
        axis=1,
    )
    A = arr.links(theta)
    M = A[:, 0] @ A[:, 1] @ A[:, 2] @ A[:, 3] @ A[:, 4]
    M6 = numeric_rigid_inverse(M) @ Tp  # = A6 = Rz(θ6) …: its first column is (c6, s6, 0)
    theta[:, 5] = np.arctan2(M6[:, 1, 0], M6[:, 0, 0])
    return theta


_SHIFTS = (0.0, 0.9, 2.3)  # θ3 = φ + δ: a Möbius map of x3 when A is nearly singular


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def _polish(arr: _Arrangement, theta: np.ndarray, Tp: np.ndarray, steps: int = 10) -> np.ndarray:
    """Newton steps on the full pose until the error is at round-off.

    The error is ``(Δp, ω)``: the position error and the small rotation ω with
    ``[ω]× ≈ ½ (R* Rᵀ − R R*ᵀ)`` taking R to the target R*; the Jacobian is the geometric
    one (joint axis z_{i−1} through origin o_{i−1}: ``(z × (p − o), z)``). Candidates whose
    first error exceeds ``_FAR`` (times the arm's reach) are extra roots of the projected
    pencil, not near any solution, and are dropped before the first step.
    """
    reach = 1.0 + float(np.abs(arr.a).sum() + np.abs(arr.d).sum())
    for it in range(steps):
        A = arr.links(theta)
        F = [A[:, 0]]
        for i in range(1, 6):
            F.append(F[-1] @ A[:, i])
        T = F[-1]
        e = np.empty((theta.shape[0], 6))
        e[:, :3] = Tp[:3, 3] - T[:, :3, 3]
        W = Tp[:3, :3] @ T[:, :3, :3].transpose(0, 2, 1)
        e[:, 3] = 0.5 * (W[:, 2, 1] - W[:, 1, 2])
        e[:, 4] = 0.5 * (W[:, 0, 2] - W[:, 2, 0])
        e[:, 5] = 0.5 * (W[:, 1, 0] - W[:, 0, 1])
        size = np.abs(e).max(axis=1)
        if it == 0:
            near = size < _FAR * reach
            theta, e, size, T, F = theta[near], e[near], size[near], T[near], [f[near] for f in F]
        todo = size > 1e-14
        if not todo.any():
            break
        Fs = np.stack(F[:5], axis=1)[todo]  # frames 1 … 5 (frame 0 is the identity)
        k = len(Fs)
        z = np.empty((k, 6, 3))
        o = np.zeros((k, 6, 3))
        z[:, 0] = (0.0, 0.0, 1.0)
        z[:, 1:] = Fs[..., :3, 2]
        o[:, 1:] = Fs[..., :3, 3]
        J = np.concatenate([_cross(z, T[todo][:, None, :3, 3] - o), z], axis=2)
        J = J.transpose(0, 2, 1)  # (k, 6 error components, 6 joints)
        try:
            step = np.linalg.solve(J, e[todo][..., None])[..., 0]
        except np.linalg.LinAlgError:  # a singular configuration: least squares, one by one
            step = np.array([np.linalg.lstsq(j, r, rcond=None)[0] for j, r in zip(J, e[todo])])
        theta = theta.copy()
        theta[todo] += np.clip(step, -0.5, 0.5)
        if np.abs(step).max() < 1e-9:  # Newton from this close lands at round-off: the fk
            break  # check of solve() confirms it without another evaluation here
    return theta


_FAR = 0.05  # first pose error (times the reach) beyond which a candidate is no solution


@dataclass(frozen=True, eq=False)
class General6R:
    """The compiled general-6R solver of one numeric table (:func:`general_6r` builds it).

    ``solve(T)`` returns every real solution ``(k, 6)``, ``k ≤ 16``, each reproducing ``T``
    by forward kinematics to ``tol`` (metres and rotation-matrix entries), distinct modulo
    2π, angles in ``(−π, π]``, sorted. ``matrices()`` gives the exact elimination matrices.
    """

    table: DHTable
    arrangement: _Arrangement = field(repr=False)
    fk: Callable[[np.ndarray], np.ndarray] = field(repr=False)
    tol: float = 1e-9

    def __repr__(self) -> str:
        size = "12×12" if self.arrangement.project is None else "16×16"
        return f"General6R({self.table.name!r}, eliminated joint {self.eliminated}, {size} pencil)"

    @property
    def eliminated(self) -> int:
        """The joint (1-based, table numbering) whose half-angle tangent is the eigenvalue."""
        return int(self.arrangement.joint[2]) + 1

    def matrices(self) -> EliminationMatrices:
        """The exact matrices ``P(θ3) m45 = Q m12`` (:func:`elimination_matrices`)."""
        return elimination_matrices(self.table)

    def solve(self, T: np.ndarray, *, within: float = 0.0) -> np.ndarray:
        """Every real solution of the pose ``T`` (4×4), each checked by ``fk``: ``(k, 6)``.

        ``within`` also keeps the polished candidates whose largest entry error is within
        it (a rounded pose a little out of reach: a pair of roots that rounding turned
        complex polishes to the arm stretched towards the pose, not onto it): a double root
        that a pose error ε splits moves by about √ε, so eigenvalues with ``|Im θ|`` up to
        ``√within`` are candidates too."""
        T = np.asarray(T, dtype=float)
        if T.shape != (4, 4) or not np.isfinite(T).all():
            raise DHError(f"expected one finite 4×4 pose, got shape {T.shape}")
        arr = self.arrangement
        Tp = arr.target(T)
        theta = _candidates(arr, Tp, max(_ANGLE_TOL, math.sqrt(within)))
        if not len(theta):
            return np.empty((0, 6))
        if within:
            # out of reach Newton may wander: the candidates after 10 and 30 steps, and as
            # they came (near a singularity the real part of a pair that rounding made
            # complex can be the closest to the pose, 4e-4 on the Jaco rounded to 3
            # decimals, while Newton from it wanders 2.6 rad away to 6e-3)
            theta = np.concatenate([_polish(arr, theta, Tp), _polish(arr, theta, Tp, 30), theta])
        else:
            theta = _polish(arr, theta, Tp)
        q = np.empty_like(theta)
        q[:, arr.joint] = arr.sign * (theta - arr.offset)
        q = np.remainder(q + math.pi, 2 * math.pi) - math.pi
        q[q <= -math.pi + 1e-15] = math.pi
        scale = max(1.0, float(np.abs(T[:3, 3]).max()))
        err = np.abs(self.fk(q)[:, :3, :] - T[:3, :]).max(axis=(1, 2))
        q = q[(err < self.tol * scale) | (err <= within)]
        return _distinct(q)


def _distinct(q: np.ndarray, tol: float = 1e-6) -> np.ndarray:
    """Rows of ``q`` distinct modulo 2π (the first of each cluster), sorted."""
    diff = q[:, None, :] - q[None, :, :]
    near = (np.abs(np.remainder(diff + math.pi, 2 * math.pi) - math.pi) < tol).all(axis=2)
    keep = ~np.tril(near, -1).any(axis=1)
    out = q[keep]
    rows: np.ndarray = out[np.lexsort(out.T[::-1])]
    return rows


def general_6r(
    table: DHTable, *, fk: Callable[[np.ndarray], np.ndarray] | None = None, tol: float = 1e-9
) -> General6R:
    """Compile the general-6R solver of a six-joint revolute table with numeric constants.

    The chain as given (θ3 eliminated) is tried first, then reversed (θ4 eliminated), each
    with the 12×12 pencil and then with the 16×16 one (:func:`_embed`); an arrangement is
    used when ``Q`` has full rank, ``Σ(x)`` is regular and it solves a few random poses of
    the arm. Raises :class:`~dhsym.errors.DHError` for a table that is not
    six revolute joints with numbers, or an arm on which the elimination degenerates
    (parallel or intersecting axes: use the closed-form families, ``robot.ik``).

    ``fk`` checks every solution: ``Q (k, 6) -> (k, 4, 4)``, world to tool; by default
    the table's elementary word compiled by :func:`~dhsym.kinematics.numeric.compile_word`
    (a robot's ``Robot.fk_function()`` may be passed instead).

    >>> from dhsym.model.library import builtin_table
    >>> puma = general_6r(builtin_table("puma560"))
    >>> puma
    General6R('PUMA 560', eliminated joint 4, 16×16 pencil)
    >>> len(puma.solve(puma.fk(np.array([0.1, -0.5, 0.3, 1.0, 0.7, -0.2]))))
    8
    >>> general_6r(builtin_table("stanford"))
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: row 3, field type: joint 3 is prismatic: the general 6R solver ...
    """
    chain = _standard(table)
    if fk is None:  # the kernel's numeric word: built in milliseconds, whatever the twists
        ends = (-1 if table.base else 0, table.n + 1 if table.tool else table.n)
        fk = compile_word(chain_word(table, *ends), table.variables, table.value_map)
    d = _derive()
    # a fixed combination of rows (deterministic): 24 dependent equations -> 16
    project = np.random.default_rng(16).standard_normal((16, 24)) / math.sqrt(24.0)
    reasons = []
    for rows in (None, project):
        for reverse in (False, True):
            arr = replace(_arrangement(chain, reverse, d, _HALF), project=rows)
            solver = General6R(table, arr, fk, tol)
            why = _self_test(solver)
            if why is None:
                return solver
            size = "12×12" if rows is None else "16×16"
            reasons.append(f"eliminating θ{int(arr.joint[2]) + 1} ({size}): {why}")
    raise DHError(
        f"{table.name or 'this arm'}: the general 6R elimination degenerates on this arm "
        f"({'; '.join(reasons)}). Arms with intersecting or parallel axes (spherical "
        "wrist, three parallel axes) are solved by their closed-form family (robot.ik)"
    )


def _self_test(solver: General6R) -> str | None:
    """Why this arrangement cannot be trusted on this arm, or None."""
    rng = np.random.default_rng(20260)
    arr = solver.arrangement
    for _ in range(_SELF_TEST):
        q = rng.uniform(-math.pi, math.pi, 6)
        T = solver.fk(q)
        big, Q1, R8, r, _ = _pencil(arr, arr.target(T), 0.0)
        sv = np.abs(np.diag(R8))
        if sv.min() < 1e-9 * sv.max():
            return "Q loses rank (the products of the right side's joints are dependent)"
        x = rng.normal(size=2)
        S = [big[0] * t * t + big[1] * t + big[2] for t in x]
        if max(np.linalg.cond(s) for s in S) > 1e11:
            return "Σ(x3) is singular for every x3"
        Q = solver.solve(T)
        if not len(Q) or np.abs(np.angle(np.exp(1j * (Q - q)))).max(axis=1).min() > 1e-6:
            return "a random pose was not recovered"
    return None
