r"""Time profiles of one joint or of a joint vector: piecewise polynomials with exact
coefficients, derived from their boundary conditions, sampled by code generated once.

Every profile of the room is a :class:`Profile`: for each joint a tuple of
:class:`Segment`\ s, each a polynomial in its own local time ``τ = t − start``
(Craig, *Introduction to Robotics*, ch. 7, writes each segment so), with exact
coefficients (sympy numbers or symbols); the :class:`Derivation` that gave them (the
boundary conditions as a linear system, solved exactly) and the conditions the
profile assumed (feasibility of a blend). :meth:`Profile.sample` evaluates
``(q, q̇, q̈)`` over an array of times with floats converted once
(:func:`~dhsym.kinematics.numeric.compile_exprs`).

This module holds the polynomials (:func:`cubic`, :func:`quintic`) and the machinery;
:mod:`.blends` the linear segments with parabolic blends and :mod:`.via` the via
points build on it.

Examples
--------
>>> q0, qf, tf = sp.symbols("q0 qf tf", positive=True)
>>> p = quintic(q0, qf, tf)
>>> p.coefficients[3]
10*(-q0 + qf)/tf**3
>>> q, qd, qdd = quintic(0, 1, 2).sample([0.0, 1.0, 2.0])
>>> q.tolist(), qd.tolist()
([0.0, 0.5, 1.0], [0.0, 0.9375, 0.0])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.numeric import compile_exprs
from dhsym.model.entries import as_expr
from dhsym.model.table import symbol_values

__all__ = [
    "Derivation",
    "Profile",
    "Segment",
    "cubic",
    "exact_value",
    "polynomial_segment",
    "quintic",
    "time_symbol",
]

#: The time of every profile's expressions (real, nonnegative).
TIME = sp.Symbol("t", nonnegative=True)


def time_symbol() -> sp.Symbol:
    """The symbol ``t`` of every profile's expressions.

    >>> time_symbol()
    t
    """
    return TIME


def exact_value(value: object, name: str) -> sp.Expr:
    """A profile's input as an exact sympy expression: numbers (floats as the decimal
    written), sympy objects, or text through the whitelist parser (never ``sympify``);
    ``name`` names the argument in the error.

    >>> exact_value(0.25, "q0"), exact_value(np.int64(3), "tf")
    (1/4, 3)
    >>> exact_value([1], "q0")
    Traceback (most recent call last):
    ...
    dhsym.errors.TableError: field q0: expected a number or expression, got list
    """
    if isinstance(value, np.generic):
        value = value.item()
    return as_expr(value, field=name)


@dataclass(frozen=True)
class Segment:
    """One polynomial piece ``q(t) = Σ a_k τ^k`` with ``τ = t − start`` on ``[start, end]``."""

    start: sp.Expr
    end: sp.Expr
    coefficients: tuple[sp.Expr, ...]

    def position(self, t: sp.Expr = TIME) -> sp.Expr:
        """The exact position at ``t`` (a number or the symbol ``t``).

        >>> Segment(sp.Integer(1), sp.Integer(2), (sp.Integer(3), sp.Integer(4))).position()
        4*t - 1
        """
        tau = t - self.start
        return sp.expand(sum((a * tau**k for k, a in enumerate(self.coefficients)), sp.Integer(0)))


@dataclass(frozen=True, repr=False)
class Derivation:
    r"""How a profile's unknowns follow from its conditions: the ``equations`` (each
    with its ``labels``, e.g. ``q(t_f) = q_f``), as the linear system ``matrix ·
    unknowns = rhs`` when linear, solved exactly (``solution``, one per unknown).

    Printed through sympy's printers (``sp.latex(d)``, ``str(d)``): the system, then the
    solution.
    """

    labels: tuple[str, ...]
    equations: tuple[sp.Eq, ...]
    unknowns: tuple[sp.Symbol, ...]
    solution: tuple[sp.Expr, ...]
    matrix: sp.ImmutableMatrix | None = None
    rhs: sp.ImmutableMatrix | None = None
    #: the assumptions the solution needs (a blend that fits), as sympy relations
    conditions: tuple[sp.Basic, ...] = ()

    def _sympystr(self, printer: Any) -> str:
        lines = [f"{printer._print(e.lhs)} = {printer._print(e.rhs)}" for e in self.equations]
        if self.matrix is not None and self.rhs is not None:
            lines.append(f"A * {printer._print(list(self.unknowns))} = b, with")
            for k, row in enumerate(self.matrix.tolist()):
                lines.append(f"{'A = ' if k == 0 else '    '}{printer._print(row)}")
            lines.append(f"b = {printer._print(list(self.rhs))}")
        lines += [f"given {printer._print(c)}" for c in self.conditions]
        lines += [f"{printer._print(u)} = {printer._print(s)}" for u, s in self.pairs]
        return "\n".join(lines)

    def _latex(self, printer: Any) -> str:
        rows = [f"{printer._print(e.lhs)} &= {printer._print(e.rhs)}" for e in self.equations]
        if self.matrix is not None and self.rhs is not None:
            x = sp.Matrix(self.unknowns)
            rows.append(
                f"{printer._print(self.matrix)}{printer._print(x)} &= {printer._print(self.rhs)}"
            )
        rows += [rf"&\text{{given }} {printer._print(c)}" for c in self.conditions]
        rows += [f"{printer._print(u)} &= {printer._print(s)}" for u, s in self.pairs]
        return r"\begin{aligned}" + r" \\ ".join(rows) + r"\end{aligned}"

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {sp.latex(self)}$"

    def __str__(self) -> str:
        return str(sp.sstr(self))

    def __repr__(self) -> str:
        return str(self)

    @property
    def pairs(self) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
        """``(unknown, value)`` in order."""
        return tuple(zip(self.unknowns, self.solution))

    def check(self) -> bool:
        """True when the solution satisfies every equation exactly (``simplify`` to 0).

        >>> quintic(*sp.symbols("q0 qf tf", positive=True)).derivation().check()
        True
        """
        sub = dict(self.pairs)
        return all(sp.simplify((e.lhs - e.rhs).xreplace(sub)) == 0 for e in self.equations)


@dataclass(frozen=True)
class _Numbers:
    """A profile's breakpoints and coefficients as floats, per joint."""

    starts: tuple[np.ndarray, ...]  # (S,) per joint
    ends: np.ndarray  # (n,) the end time of each joint
    coefficients: tuple[np.ndarray, ...]  # (S, K) per joint


@dataclass(frozen=True)
class Profile:
    """A time profile: for each joint its polynomial segments on ``[0, duration]``.

    ``kind`` names the profile (``"cubic"``, ``"quintic"``, ``"lspb"``, ``"minimum
    time"``, ``"via"``, ``"spline"``); ``joints`` the segments of each joint; ``scalar``
    when it was made for one joint (``sample`` then gives ``(N,)`` arrays, else ``(N,
    n)``); ``derivations`` one per joint; ``conditions`` the assumptions the profile
    needs (in the derivations too).
    """

    kind: str
    joints: tuple[tuple[Segment, ...], ...]
    derivations: tuple[Derivation, ...]
    scalar: bool = True
    names: tuple[str, ...] = field(default=(), compare=False)

    # --- exact ---------------------------------------------------------------------
    @property
    def n(self) -> int:
        """The number of joints."""
        return len(self.joints)

    @property
    def duration(self) -> sp.Expr:
        """The end time ``t_f`` (the latest end of any joint).

        >>> cubic([0, 0], [1, 2], 3).duration
        3
        """
        ends = [segs[-1].end for segs in self.joints]
        return ends[0] if len(set(ends)) == 1 else sp.Max(*ends)

    @property
    def coefficients(self) -> tuple[sp.Expr, ...]:
        """The coefficients ``a_0, a_1, …`` of a one-segment profile of one joint."""
        if self.n != 1 or len(self.joints[0]) != 1:
            raise DHError(
                f"coefficients: a {self.kind} profile of {self.n} joints and "
                f"{len(self.joints[0])} segments has coefficients per segment: use .joints"
            )
        return self.joints[0][0].coefficients

    @property
    def conditions(self) -> tuple[sp.Basic, ...]:
        """The assumptions of every joint's derivation."""
        return tuple(c for d in self.derivations for c in d.conditions)

    def derivation(self, joint: int = 1) -> Derivation:
        """The derivation of joint ``joint`` (1-based).

        >>> print(cubic(*sp.symbols("q0 qf tf", positive=True)).derivation())
        a0 = q0
        a1 = 0
        a0 + a1*tf + a2*tf**2 + a3*tf**3 = qf
        a1 + 2*a2*tf + 3*a3*tf**2 = 0
        A * [a0, a1, a2, a3] = b, with
        A = [1, 0, 0, 0]
            [0, 1, 0, 0]
            [1, tf, tf**2, tf**3]
            [0, 1, 2*tf, 3*tf**2]
        b = [q0, 0, qf, 0]
        a0 = q0
        a1 = 0
        a2 = 3*(-q0 + qf)/tf**2
        a3 = -2*(-q0 + qf)/tf**3
        """
        if not 1 <= joint <= len(self.derivations):
            raise DHError(f"derivation: joint {joint} is not one of 1 … {len(self.derivations)}")
        return self.derivations[joint - 1]

    def expression(self, joint: int = 1) -> sp.Expr:
        """The position of joint ``joint`` as one exact expression in ``t`` (a ``Piecewise``
        when there are several segments).

        >>> cubic(0, 1, 1).expression()
        -2*t**3 + 3*t**2
        """
        segs = self.joints[joint - 1]
        if len(segs) == 1:
            return segs[0].position()
        pieces = [(s.position(), TIME <= s.end) for s in segs[:-1]]
        return sp.Piecewise(*pieces, (segs[-1].position(), True))

    def at(self, t: object) -> tuple[sp.Expr, ...]:
        """The exact positions at time ``t`` (one per joint).

        >>> quintic(0, 1, 2).at(sp.Rational(1, 2))
        (53/512,)
        """
        time = exact_value(t, "t")
        return tuple(_segment_at(segs, time).position(time) for segs in self.joints)

    # --- numbers --------------------------------------------------------------------
    def _numbers(self, values: object = None) -> _Numbers:
        exprs: list[sp.Expr] = []
        for segs in self.joints:
            for s in segs:
                exprs += [s.start, s.end, *s.coefficients]
        if values is not None:
            if not isinstance(values, Mapping):
                raise DHError("sample: values must be a mapping {name or symbol: number}")
            # names match the profile's symbols whatever their assumptions
            by_name = {str(k): v for k, v in symbol_values(values).items()}
            symbols = set().union(*(e.free_symbols for e in exprs))
            given = {x: by_name[x.name] for x in symbols if x.name in by_name}
            exprs = [e.xreplace(given) for e in exprs]
        free = sorted(set().union(*(e.free_symbols for e in exprs)), key=str)
        if free:
            raise DHError(
                f"sample: no numeric value for {', '.join(map(str, free))}: "
                "give values={name: number}"
            )
        flat = compile_exprs(exprs, (), floats=True)()
        starts, ends, coeffs, k = [], [], [], 0
        width = max(len(s.coefficients) for segs in self.joints for s in segs)
        for segs in self.joints:
            st, cs = [], []
            for s in segs:
                m = len(s.coefficients)
                st.append(flat[k])
                row = list(flat[k + 2 : k + 2 + m]) + [0.0] * (width - m)
                cs.append(row)
                last_end = flat[k + 1]
                k += 2 + m
            starts.append(np.array(st, dtype=float))
            ends.append(last_end)
            coeffs.append(np.array(cs, dtype=float))
        return _Numbers(tuple(starts), np.array(ends), tuple(coeffs))

    @cached_property
    def _floats(self) -> _Numbers:
        return self._numbers()

    def sample(
        self, t: object, *, values: object = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities and accelerations at the times ``t`` (an array ``(N,)``).

        ``(N,)`` arrays for one joint, ``(N, n)`` for a joint vector; ``values`` gives
        numbers for the symbols of a symbolic profile. Times must lie in ``[0, t_f]``
        (a joint that ends early rests at its end). The floats are made once per profile
        (and once per call with ``values``); the evaluation is a product of the powers of
        ``τ`` with the coefficient matrix, segment by segment.

        >>> q, qd, qdd = cubic([0, 1], [1, 3], 2).sample(np.linspace(0, 2, 3))
        >>> q
        array([[0. , 1. ],
               [0.5, 2. ],
               [1. , 3. ]])
        >>> cubic(0, 1, 2).sample([3.0])
        Traceback (most recent call last):
        ...
        dhsym.errors.DHError: sample: times outside [0, 2.0] (3.0)
        """
        nums = self._floats if values is None else self._numbers(values)
        ts = np.asarray(t, dtype=float)
        if ts.ndim != 1:
            ts = ts.reshape(-1)
        tf = float(nums.ends.max())
        slack = 1e-12 * max(1.0, tf)
        if ts.size and (ts.min() < -slack or ts.max() > tf + slack or not np.isfinite(ts).all()):
            bad = ts[(ts < -slack) | (ts > tf + slack) | ~np.isfinite(ts)][0]
            raise DHError(f"sample: times outside [0, {tf}] ({bad})")
        # joints first, times last: every pass over the samples is contiguous
        out = np.empty((3, self.n, ts.size))
        shared = _shared_breaks(nums)
        if shared is not None:  # every joint has the same segments: one product per segment
            _evaluate(ts, shared, np.stack(nums.coefficients, axis=-1), nums.ends.max(), out)
        else:
            for j in range(self.n):
                ends = min(float(nums.ends[j]), tf)
                coeffs = nums.coefficients[j][..., None]
                _evaluate(ts, nums.starts[j], coeffs, ends, out[:, j : j + 1, :])
        if self.scalar:
            return out[0, 0], out[1, 0], out[2, 0]
        return out[0].T, out[1].T, out[2].T


def _shared_breaks(nums: _Numbers) -> np.ndarray | None:
    first = nums.starts[0]
    same = all(s.shape == first.shape and np.array_equal(s, first) for s in nums.starts)
    return first if same and np.all(nums.ends == nums.ends[0]) else None


def _evaluate(
    ts: np.ndarray, starts: np.ndarray, C: np.ndarray, end: float, out: np.ndarray
) -> None:
    """Fill ``out`` ``(3, n, N)`` with q, q̇, q̈ of segments ``starts`` ``(S,)`` with
    coefficients ``C`` ``(S, K, n)``; after ``end`` each joint rests at its end value.

    One product per segment: the stacked coefficients of q, q̇ and q̈ ``(3n, K)`` times
    the powers ``τ^k`` ``(K, N)``."""
    S, K, n = C.shape
    k = np.arange(K, dtype=float)
    W = np.zeros((S, 3, n, K))
    W[:, 0] = np.swapaxes(C, 1, 2)
    W[:, 1, :, : K - 1] = np.swapaxes(C[:, 1:, :] * k[1:, None], 1, 2)
    if K > 2:
        W[:, 2, :, : K - 2] = np.swapaxes(C[:, 2:, :] * (k[2:] * k[1:-1])[:, None], 1, 2)
    stacked = W.reshape(S, 3 * n, K)
    late = ts > end
    tt = np.where(late, end, ts) if late.any() else ts
    seg = np.clip(np.searchsorted(starts, tt, side="left") - 1, 0, S - 1) if S > 1 else None
    flat = out.reshape(3 * n, -1) if out.flags.c_contiguous else None
    for s in range(S):
        idx = slice(None) if seg is None else np.nonzero(seg == s)[0]
        tau = tt[idx] - starts[s] if starts[s] else tt[idx]
        P = np.empty((K, tau.size))
        P[0] = 1.0
        for p in range(1, K):
            np.multiply(P[p - 1], tau, out=P[p])
        values = stacked[s] @ P
        if flat is not None:
            flat[:, idx] = values
        else:
            out[:, :, idx] = values.reshape(3, n, -1)
    if late.any():
        out[1:, :, late] = 0.0


def _segment_at(segs: Sequence[Segment], t: sp.Expr) -> Segment:
    for s in segs:
        after = sp.simplify(t - s.end) <= 0
        if after not in (sp.true, sp.false):
            raise DHError(f"at: cannot tell whether t = {t} is before {s.end}: give numbers")
        if after is sp.true:
            return s
    return segs[-1]


# --- polynomials from boundary conditions ------------------------------------------------
def _vector(value: object, name: str) -> tuple[list[sp.Expr], bool]:
    """The joint values of ``value`` (one number or a sequence), and whether it was one."""
    if isinstance(value, (str, sp.Basic)) or np.ndim(value) == 0:  # type: ignore[arg-type]
        return [exact_value(value, name)], True
    seq = list(np.asarray(value, dtype=object).reshape(-1))
    if not seq:
        raise DHError(f"{name}: no joint values")
    return [exact_value(v, f"{name}[{k}]") for k, v in enumerate(seq)], False


def _broadcast(
    named: dict[str, object],
) -> tuple[list[dict[str, sp.Expr]], bool]:
    """Per-joint values of the named arguments (scalars repeat), and whether all were one."""
    parts = {k: _vector(v, k) for k, v in named.items()}
    n = max(len(v) for v, _ in parts.values())
    for k, (v, _) in parts.items():
        if len(v) not in (1, n):
            raise DHError(f"{k}: {len(v)} joint values where the others have {n}")
    scalar = all(s for _, s in parts.values())
    return [{k: (v[j] if len(v) > 1 else v[0]) for k, (v, _) in parts.items()} for j in range(n)], (
        scalar
    )


def _positive_time(tf: sp.Expr, name: str = "tf") -> None:
    if tf.is_number and not bool(tf > 0):
        raise DHError(f"{name}: a duration must be positive, got {tf}")


def polynomial_segment(
    start: sp.Expr, duration: sp.Expr, at_start: Sequence[sp.Expr], at_end: Sequence[sp.Expr]
) -> tuple[Segment, Derivation]:
    r"""The polynomial of least degree with position, velocity, … ``at_start`` (τ = 0)
    and ``at_end`` (τ = ``duration``): the boundary conditions written as a linear
    system in its coefficients and solved exactly (Spong–Hutchinson–Vidyasagar,
    *Robot Modeling and Control*, ch. 5 on trajectory planning; Craig ch. 7).

    >>> seg, d = polynomial_segment(sp.Integer(0), sp.Integer(1), [0, 0], [1, 0])
    >>> seg.coefficients
    (0, 0, 3, -2)
    """
    m = len(at_start) + len(at_end)
    first = [_as_basic(v) for v in at_start]
    last = [_as_basic(v) for v in at_end]
    # the printed unknowns carry no assumptions: a student's a0 (an acceleration) is
    # another symbol; the rows of the system are built from the derivatives of τ^k
    a = sp.symbols(f"a0:{m}")
    names = ["q", r"\dot q", r"\ddot q"]
    labels, eqs, rows = [], [], []
    for where, vals, point in (("0", first, sp.Integer(0)), ("t_f", last, duration)):
        for order, v in enumerate(vals):
            row = [
                sp.ff(k, order) * point ** (k - order) if k >= order else sp.Integer(0)
                for k in range(m)
            ]
            rows.append(row)
            lhs = sum((c * x for c, x in zip(row, a)), sp.Integer(0))
            eqs.append(sp.Eq(lhs, v, evaluate=False))
            labels.append(f"{names[order]}({where}) = {sp.latex(v)}")
    A, b = sp.Matrix(rows), sp.Matrix(first + last)
    # solved with the positions as q0 and q0 + Δ, so that each coefficient reads as the
    # lecture writes it: a multiple of (q_f − q_0) plus the terms of the other conditions
    p0, delta = sp.Dummy("q0"), sp.Dummy("delta")
    b_solved = list(b)
    b_solved[0], b_solved[len(first)] = p0, p0 + delta
    back = {p0: first[0], delta: last[0] - first[0]}
    coeffs = tuple(_lecture_form(c, delta).xreplace(back) for c in A.LUsolve(sp.Matrix(b_solved)))
    d = Derivation(
        labels=tuple(labels),
        equations=tuple(eqs),
        unknowns=tuple(a),
        solution=coeffs,
        matrix=sp.ImmutableMatrix(A),
        rhs=sp.ImmutableMatrix(b),
    )
    return Segment(start, start + duration, coeffs), d


def _as_basic(v: object) -> sp.Expr:
    """A condition given by the code of this room: a sympy object or a Python int."""
    if isinstance(v, sp.Basic):
        return v
    if isinstance(v, int):
        return sp.Integer(v)
    raise DHError(f"expected an exact value, got {type(v).__name__}: use exact_value first")


def _lecture_form(c: sp.Expr, delta: sp.Symbol) -> sp.Expr:
    """``c`` (linear in ``delta``) as ``factor(k)·delta + factor(rest)``."""
    c = sp.expand(c)
    k = c.coeff(delta)
    return sp.factor(k) * delta + sp.factor(sp.expand(c - k * delta))


def _polynomial(
    kind: str, tf: object, ends: dict[str, object], at_start: Sequence[str], at_end: Sequence[str]
) -> Profile:
    T = exact_value(tf, "tf")
    _positive_time(T)
    rows, scalar = _broadcast(ends)
    joints, derivations = [], []
    for row in rows:
        seg, d = polynomial_segment(
            sp.Integer(0), T, [row[k] for k in at_start], [row[k] for k in at_end]
        )
        joints.append((seg,))
        derivations.append(d)
    return Profile(kind, tuple(joints), tuple(derivations), scalar)


def cubic(q0: object, qf: object, tf: object, v0: object = 0, vf: object = 0) -> Profile:
    r"""The cubic through ``q(0) = q0``, ``q(tf) = qf`` with velocities ``v0``, ``vf``:
    ``a0 = q0``, ``a1 = v0``, ``a2 = 3(q_f − q_0)/t_f² − (2v_0 + v_f)/t_f``, ``a3 =
    −2(q_f − q_0)/t_f³ + (v_0 + v_f)/t_f²`` (Craig, *Introduction to Robotics*, ch. 7).

    Joint vectors give one cubic per joint, all with the same ``tf``.

    >>> cubic(0, 1, 1).coefficients
    (0, 0, 3, -2)
    >>> q0, qf, tf, v0, vf = sp.symbols("q0 qf tf v0 vf", real=True)
    >>> cubic(q0, qf, tf, v0, vf).coefficients[2]
    -(2*v0 + vf)/tf + 3*(-q0 + qf)/tf**2
    """
    return _polynomial(
        "cubic", tf, {"q0": q0, "qf": qf, "v0": v0, "vf": vf}, ("q0", "v0"), ("qf", "vf")
    )


def quintic(
    q0: object,
    qf: object,
    tf: object,
    v0: object = 0,
    vf: object = 0,
    a0: object = 0,
    af: object = 0,
) -> Profile:
    r"""The quintic with positions, velocities and accelerations given at ``0`` and ``tf``;
    at rest at both ends ``a3 = 10(q_f − q_0)/t_f³``, ``a4 = −15(q_f − q_0)/t_f⁴``,
    ``a5 = 6(q_f − q_0)/t_f⁵`` (Spong–Hutchinson–Vidyasagar, *Robot Modeling and
    Control*; Lynch–Park, *Modern Robotics*, ch. 9, the quintic time scaling).

    >>> quintic(0, 1, 1).coefficients
    (0, 0, 0, 10, -15, 6)
    """
    return _polynomial(
        "quintic",
        tf,
        {"q0": q0, "qf": qf, "v0": v0, "vf": vf, "a0": a0, "af": af},
        ("q0", "v0", "a0"),
        ("qf", "vf", "af"),
    )
