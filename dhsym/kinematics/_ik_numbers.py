"""The closed form in numbers: the compiled solver over all branches, its results, and a
numeric Levenberg–Marquardt reference (see :mod:`dhsym.kinematics.inverse` for the derivation).

The steps of a derivation are compiled once into one straight-line numpy program (the
steps are its common subexpressions); all branches of a batch of poses are computed at
once by broadcasting the branch signs, each ``atan2`` only over the branches it depends
on. Every branch is then checked by ``fk`` and the singular factors of
:mod:`dhsym.kinematics.singularities` are evaluated at it.

Examples
--------
>>> import dhsym
>>> r = dhsym.load("scara")
>>> batch = r.ik(r.fk([[0.3, 0.5, 0.1, 0.2], [1.0, -0.4, 0.2, 0.0]]))
>>> batch.q.shape, batch.count.tolist()
((2, 2, 4), [2, 2])
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.model.table import JointType

from ._structure import StructureError
from .jacobian import axis_frame

if TYPE_CHECKING:
    from .inverse import Branch, InverseKinematics
    from .robot import Robot
    from .singularities import Singularities

__all__ = ["IKBatch", "IKSolution", "NumericSolution", "Solver", "numeric_ik"]

_REAL = {"real": True}


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
