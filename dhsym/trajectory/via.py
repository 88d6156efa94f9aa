r"""Motion through via points: straight segments joined by blends (:func:`mstraj`,
:func:`via_blends`), cubics with the via velocities chosen by a rule (:func:`via_cubic`)
and cubic splines with continuous acceleration (:func:`spline`).

:func:`mstraj` follows roboticstoolbox's ``mstraj`` (Corke, *Robotics, Vision and
Control*), exact: each segment's time is the slowest joint's at its speed limit (or
given), rounded up to the sample time; the segments are joined by blends of duration
``tacc`` (half of it at the start and at the end) that are quintics with the two lines'
velocities at their ends, so the path passes near, not through, the via points.

:func:`via_blends` is Craig's rule (*Introduction to Robotics*, ch. 7, linear function
with parabolic blends for a path with via points): given each segment's duration and the
size of each blend's acceleration, the lines run through the via points at their times
(the first and last through the point next to the end) and parabolic blends of the
given acceleration join them, their durations computed.

:func:`spline` passes through every via point at the given times: one cubic per interval
(:func:`~dhsym.trajectory.profiles.cubic`'s conditions, positions and velocities at both
ends), the unknown velocities at the inner via points chosen so that the acceleration is
continuous there (Spong–Hutchinson–Vidyasagar, *Robot Modeling and Control*; Craig,
*Introduction to Robotics*, ch. 7): a tridiagonal linear system, solved exactly.

:func:`via_cubic` passes through every via point at the given times too, one cubic per
interval, but chooses the velocity at each inner via point by the rule of the lectures
(Spong–Hutchinson–Vidyasagar, *Robot Modeling and Control*, ch. 5, and Craig,
*Introduction to Robotics*, ch. 7, cubic polynomials for a path with via points): with
the slopes ``d_k = (q_k − q_{k−1})/(t_k − t_{k−1})`` of the straight lines between
neighbouring via points, ``v_k = (d_k + d_{k+1})/2`` when ``d_k`` and ``d_{k+1}`` have
the same sign, else ``v_k = 0``. Velocity is continuous, acceleration in general not;
:func:`spline` is the variant with continuous acceleration.

Examples
--------
>>> s = spline([0, 1, 0], [0, 1, 2])
>>> s.derivation().pairs
((v_1, 0),)
>>> [seg.coefficients for seg in s.joints[0]]
[(0, 0, 3, -2), (1, 0, -3, 2)]
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from dhsym.errors import DHError

from .profiles import Derivation, Profile, Segment, exact_value, polynomial_segment

__all__ = ["mstraj", "spline", "via_blends", "via_cubic"]


def _rows(via: object, name: str) -> tuple[list[list[sp.Expr]], bool]:
    """The via points as exact rows ``(m, n)``, and whether they were scalars."""
    arr = np.asarray(via, dtype=object)
    if arr.ndim not in (1, 2) or arr.shape[0] < 2:
        raise DHError(
            f"{name}: expected at least two via points, one per row, got shape {arr.shape}"
        )
    scalar = arr.ndim == 1
    arr = arr.reshape(arr.shape[0], -1)
    return [
        [exact_value(x, f"{name}[{i}][{j}]") for j, x in enumerate(row)]
        for i, row in enumerate(arr)
    ], scalar


def _per_joint(value: object, n: int, name: str) -> list[sp.Expr]:
    arr = np.asarray(value, dtype=object).reshape(-1)
    if arr.size not in (1, n):
        raise DHError(f"{name}: expected 1 or {n} values, got {arr.size}")
    vals = [exact_value(x, name) for x in arr]
    return vals * n if len(vals) == 1 else vals


def _ceil_to(x: sp.Expr, dt: sp.Expr) -> sp.Expr:
    return sp.ceiling(x / dt) * dt


def _blend(
    start: sp.Expr, duration: sp.Expr, q0: sp.Expr, v0: sp.Expr, q1: sp.Expr, v1: sp.Expr
) -> Segment:
    """A blend of ``mstraj`` from ``(q0, v0)`` to ``(q1, v1)``, at rest in acceleration at
    both ends (the quintic of :func:`~.profiles.polynomial_segment`)."""
    zero = sp.Integer(0)
    seg, _ = polynomial_segment(start, duration, [q0, v0, zero], [q1, v1, zero])
    return seg


def mstraj(
    via: object,
    dt: object,
    tacc: object,
    qdmax: object = None,
    tsegment: object = None,
    q0: object = None,
    qd0: object = None,
    qdf: object = None,
) -> Profile:
    r"""A multi-segment motion through the rows of ``via`` (roboticstoolbox's ``mstraj``,
    as a profile in continuous time).

    Parameters
    ----------
    via
        The via points ``(m, n)``; the first is the start unless ``q0`` is given.
    dt
        The sample time: segment and blend times are rounded up to multiples of it.
    tacc
        The blend time (one, or one per segment).
    qdmax, tsegment
        The joints' speed limits (each segment as long as its slowest joint needs, and
        at least two blends), or each segment's time: one of the two.
    q0, qd0, qdf
        The start (when not the first via point), the start and end velocities.

    roboticstoolbox returns the samples at ``dt, 2dt, …`` labelled ``0, dt, …``;
    this profile's ``sample(k·dt)`` is its row ``k − 1``.

    >>> p = mstraj([[0, 0], [1, 2], [2, 2]], dt=sp.Rational(1, 10), tacc=sp.Rational(1, 5),
    ...            qdmax=[1, 1])
    >>> p.duration, [s.end for s in p.joints[0]]
    (33/10, [1/10, 2, 11/5, 16/5, 33/10])
    """
    rows, _ = _rows(via, "via")
    n = len(rows[0])
    if q0 is None:
        start, targets = rows[0], rows[1:]
    else:
        start, targets = _per_joint(q0, n, "q0"), rows
    step = exact_value(dt, "dt")
    if not bool(step > 0):
        raise DHError(f"mstraj: dt must be positive, got {step}")
    if (qdmax is None) == (tsegment is None):
        raise DHError("mstraj: give qdmax (the joints' speed limits) or tsegment, one of the two")
    ns = len(targets)
    blends = _per_joint(tacc, ns, "tacc")
    limits = None if qdmax is None else _per_joint(qdmax, n, "qdmax")
    times = None if tsegment is None else _per_joint(tsegment, ns, "tsegment")
    zero = [sp.Integer(0)] * n
    v_prev = zero if qd0 is None else _per_joint(qd0, n, "qd0")
    v_end = zero if qdf is None else _per_joint(qdf, n, "qdf")
    joints: list[list[Segment]] = [[] for _ in range(n)]
    T_syms = sp.symbols(f"T1:{ns + 1}", positive=True)
    seg_times: list[sp.Expr] = []
    clock = sp.Integer(0)
    q_prev, pos = start, start
    half = sp.Integer(0)
    for k, q_next in enumerate(targets):
        tacc_seg = _ceil_to(blends[k], step)
        half = _ceil_to(tacc_seg / 2, step)
        first = half if k == 0 else tacc_seg
        dq = [b - a for a, b in zip(q_prev, q_next)]
        if limits is not None:
            need = [first + _ceil_to(sp.Abs(d) / v, step) for d, v in zip(dq, limits)]
            tseg = sp.Max(*need, 2 * tacc_seg)
        else:
            assert times is not None
            tseg = times[k]
        line = tseg - 2 * half
        if not bool(line >= 0):
            raise DHError(
                f"mstraj: segment {k + 1} of {tseg} s is shorter than its blends (2·{half} s)"
            )
        seg_times.append(tseg)
        qd = [d / tseg for d in dq]
        into = [a + half * v for a, v in zip(q_prev, qd)]  # where the straight line starts
        if first > 0:
            for j in range(n):
                joints[j].append(_blend(clock, first, pos[j], v_prev[j], into[j], qd[j]))
        clock += first
        if line > 0:
            for j in range(n):
                joints[j].append(Segment(clock, clock + line, (into[j], qd[j])))
        clock += line
        pos = [a + (tseg - half) * v for a, v in zip(q_prev, qd)]
        q_prev, v_prev = q_next, qd
    if half > 0:
        for j in range(n):
            joints[j].append(_blend(clock, half, pos[j], v_prev[j], q_prev[j], v_end[j]))
    labels = tuple(f"T_{k + 1} (segment {k + 1})" for k in range(ns))
    eqs = tuple(sp.Eq(s, v, evaluate=False) for s, v in zip(T_syms, seg_times))
    d = Derivation(labels, eqs, tuple(T_syms), tuple(seg_times))
    return Profile("via", tuple(tuple(j) for j in joints), (d,) * n, scalar=False)


def _via_times(times: Sequence[object], m: int, who: str) -> list[sp.Expr]:
    """The exact times of ``m`` via points: from 0, increasing."""
    ts = [exact_value(t, f"times[{i}]") for i, t in enumerate(times)]
    if len(ts) != m:
        raise DHError(f"{who}: {m} via points but {len(ts)} times")
    if ts[0] != 0:
        raise DHError(f"{who}: times must start at 0, got {ts[0]}")
    for i in range(1, m):
        if not bool(ts[i] > ts[i - 1]):
            raise DHError(f"{who}: times must increase: times[{i}] = {ts[i]} ≤ {ts[i - 1]}")
    return ts


def spline(via: object, times: Sequence[object], v0: object = 0, vf: object = 0) -> Profile:
    r"""The cubic spline through ``via`` (``(m,)`` or ``(m, n)``) at ``times`` (from 0,
    increasing), with velocities ``v0`` and ``vf`` at the ends and continuous
    acceleration at every inner via point.

    >>> q = spline([0, 1, 3, 2], [0, 1, 2, 3]).sample([1 - 1e-9, 1 + 1e-9])[2]
    >>> bool(abs(q[0] - q[1]) < 1e-6)
    True
    """
    rows, scalar = _rows(via, "via")
    m, n = len(rows), len(rows[0])
    ts = _via_times(times, m, "spline")
    start_v, end_v = _per_joint(v0, n, "v0"), _per_joint(vf, n, "vf")
    v = sp.symbols(f"v_1:{m - 1}", real=True) if m > 2 else ()
    joints, derivations = [], []
    for j in range(n):
        speeds = [start_v[j], *v, end_v[j]]
        segs = [
            polynomial_segment(
                ts[i], ts[i + 1] - ts[i], [rows[i][j], speeds[i]], [rows[i + 1][j], speeds[i + 1]]
            )[0]
            for i in range(m - 1)
        ]
        eqs = []
        for i in range(m - 2):
            h = ts[i + 1] - ts[i]
            a_end = 2 * segs[i].coefficients[2] + 6 * segs[i].coefficients[3] * h
            a_start = 2 * segs[i + 1].coefficients[2]
            eqs.append(sp.Eq(sp.expand(a_end), sp.expand(a_start), evaluate=False))
        if v:
            A, b = sp.linear_eq_to_matrix([e.lhs - e.rhs for e in eqs], v)
            sol = tuple(sp.factor(x) for x in A.LUsolve(b))
            fill = dict(zip(v, sol))
            segs = [
                Segment(s.start, s.end, tuple(sp.factor(c.xreplace(fill)) for c in s.coefficients))
                for s in segs
            ]
            labels = tuple(f"q''(t_{i + 1}^-) = q''(t_{i + 1}^+)" for i in range(m - 2))
            derivations.append(
                Derivation(
                    labels, tuple(eqs), tuple(v), sol, sp.ImmutableMatrix(A), sp.ImmutableMatrix(b)
                )
            )
        else:
            derivations.append(Derivation((), (), (), ()))
        joints.append(tuple(segs))
    return Profile("spline", tuple(joints), tuple(derivations), scalar)


def _sgn(x: sp.Expr) -> sp.Expr:
    sign = sp.sign(x)
    if not sign.is_number:
        raise DHError(f"via_blends: cannot tell the direction of {x}: give numbers")
    return sp.Integer(1) if sign == 0 else sign


def _craig_joint(
    theta: Sequence[sp.Expr], td: Sequence[sp.Expr], acc: Sequence[sp.Expr], joint: int
) -> tuple[tuple[Segment, ...], Derivation]:
    """Craig's equations for one joint: the blend accelerations and durations, the line
    velocities and durations, then the segments (blend, line, blend, …, blend)."""
    n = len(theta)
    T = [sp.Integer(0)]
    for d in td:
        T.append(T[-1] + d)
    vel: list[sp.Expr] = [sp.Integer(0)] * (n - 1)
    acc_s: list[sp.Expr] = [sp.Integer(0)] * n
    tb: list[sp.Expr] = [sp.Integer(0)] * n
    where = f"joint {joint}: " if joint else ""
    acc_s[0] = _sgn(theta[1] - theta[0]) * sp.Abs(acc[0])
    disc = td[0] ** 2 - 2 * (theta[1] - theta[0]) / acc_s[0]
    if bool(disc < 0):
        raise DHError(f"via_blends: {where}the first blend's acceleration is too small")
    tb[0] = sp.simplify(td[0] - sp.sqrt(disc))
    vel[0] = sp.simplify((theta[1] - theta[0]) / (td[0] - tb[0] / 2))
    acc_s[-1] = _sgn(theta[-2] - theta[-1]) * sp.Abs(acc[-1])
    disc = td[-1] ** 2 + 2 * (theta[-1] - theta[-2]) / acc_s[-1]
    if bool(disc < 0):
        raise DHError(f"via_blends: {where}the last blend's acceleration is too small")
    tb[-1] = sp.simplify(td[-1] - sp.sqrt(disc))
    vel[-1] = sp.simplify((theta[-1] - theta[-2]) / (td[-1] - tb[-1] / 2))
    for k in range(1, n - 2):
        vel[k] = (theta[k + 1] - theta[k]) / td[k]
    for k in range(1, n - 1):
        dv = vel[k] - vel[k - 1]
        acc_s[k] = _sgn(dv) * sp.Abs(acc[k])
        tb[k] = sp.simplify(dv / acc_s[k])
    segs: list[Segment] = []
    # the lines: through via point k at T_k (the first: through via point 2 at T_2)
    for k in range(n - 1):
        anchor = k + 1 if k == 0 else k
        start = T[0] + tb[0] if k == 0 else T[k] + tb[k] / 2
        end = T[-1] - tb[-1] if k == n - 2 else T[k + 1] - tb[k + 1] / 2
        if bool(end < start):
            raise DHError(
                f"via_blends: {where}the blends around segment {k + 1} overlap: "
                "give larger accelerations or longer durations"
            )
        b_start = sp.Integer(0) if k == 0 else T[k] - tb[k] / 2
        # the blend starts on the line before it, which runs through via point k at T_k
        b_value = theta[0] if k == 0 else theta[k] + vel[k - 1] * (b_start - T[k])
        b_vel = sp.Integer(0) if k == 0 else vel[k - 1]
        segs.append(Segment(b_start, start, (b_value, b_vel, acc_s[k] / 2)))
        line_value = theta[anchor] + vel[k] * (start - T[anchor])
        segs.append(Segment(start, end, (sp.simplify(line_value), vel[k])))
    last_start = T[-1] - tb[-1]
    last_value = theta[-2] + vel[-1] * (last_start - T[-2])
    segs.append(Segment(last_start, T[-1], (sp.simplify(last_value), vel[-1], acc_s[-1] / 2)))
    segs = [sg for sg in segs if sp.simplify(sg.end - sg.start) != 0]
    names = [sp.Symbol(f"t_{k + 1}", real=True) for k in range(n)]
    names += [sp.Symbol(f"v_{k + 1}{k + 2}", real=True) for k in range(n - 1)]
    values = [*tb, *vel]
    eqs = tuple(sp.Eq(x, v, evaluate=False) for x, v in zip(names, values))
    labels = tuple(f"blend {k + 1}" for k in range(n)) + tuple(
        f"line {k + 1}{k + 2}" for k in range(n - 1)
    )
    return tuple(segs), Derivation(labels, eqs, tuple(names), tuple(values))


def via_blends(via: object, durations: Sequence[object], acc: object) -> Profile:
    r"""Craig's linear segments with parabolic blends through via points: ``via`` ``(m,)``
    or ``(m, n)``, the ``durations`` of the ``m − 1`` segments between them, and the size
    of each blend's acceleration (one, one per via point, or ``(m, n)``). The blend
    durations ``t_k`` and the line velocities ``v_jk`` are the derivation's solution.

    >>> p = via_blends([0, 1, 3], [1, 1], 8)
    >>> p.derivation().pairs[:3]
    ((t_1, 1 - sqrt(3)/2), (t_2, -sqrt(2)/2 + sqrt(3)/2), (t_3, 1 - sqrt(2)/2))
    """
    rows, scalar = _rows(via, "via")
    m, n = len(rows), len(rows[0])
    if m < 3:
        raise DHError("via_blends: at least three via points (for two, use lspb)")
    td = [exact_value(d, f"durations[{k}]") for k, d in enumerate(durations)]
    if len(td) != m - 1:
        raise DHError(f"via_blends: {m} via points need {m - 1} durations, got {len(td)}")
    for k, d in enumerate(td):
        if not bool(d > 0):
            raise DHError(f"via_blends: durations[{k}] must be positive, got {d}")
    arr = np.asarray(acc, dtype=object)
    if arr.ndim == 0:
        accs = [[exact_value(acc, "acc")] * n for _ in range(m)]
    elif arr.ndim == 1 and arr.size == m:
        accs = [[exact_value(a, f"acc[{k}]")] * n for k, a in enumerate(arr)]
    elif arr.shape == (m, n):
        accs = [
            [exact_value(a, f"acc[{k}][{j}]") for j, a in enumerate(r)] for k, r in enumerate(arr)
        ]
    else:
        raise DHError(
            f"via_blends: acc must be one value, {m} values or ({m}, {n}), got {arr.shape}"
        )
    joints, derivations = [], []
    for j in range(n):
        segs, d = _craig_joint(
            [r[j] for r in rows], td, [a[j] for a in accs], 0 if n == 1 else j + 1
        )
        joints.append(segs)
        derivations.append(d)
    return Profile("via blends", tuple(joints), tuple(derivations), scalar)


def _quotient(num: sp.Expr, den: sp.Expr) -> sp.Expr:
    """``num/den`` as written (unevaluated when ``den`` is not 1)."""
    if den == 1:
        return num
    return sp.Mul(num, sp.Pow(den, -1, evaluate=False), evaluate=False)


def _half(x: sp.Expr) -> sp.Expr:
    """``x/2`` as the lecture writes it, ``(d_1 + d_2)/2``."""
    return sp.Mul(sp.Rational(1, 2), x, evaluate=False)


def _via_velocity(before: sp.Expr, after: sp.Expr, where: str) -> tuple[sp.Expr, str]:
    """The rule at one via point: the average of the slopes ``before`` and ``after``
    when they have the same sign, else 0; and the sentence saying which case it was."""
    product = sp.simplify(before * after)
    if not product.is_number:
        raise DHError(
            f"via_cubic: {where}cannot tell whether the slopes {before} and {after} "
            "have the same sign: give numbers"
        )
    if bool(product > 0):
        return sp.simplify((before + after) / 2), "same sign: the average of the slopes"
    return sp.Integer(0), "the sign changes or a slope is 0: at rest"


def via_cubic(via: object, times: Sequence[object], v0: object = 0, vf: object = 0) -> Profile:
    r"""Cubics through ``via`` (``(m,)`` or ``(m, n)``) at ``times`` (from 0, increasing),
    with velocities ``v0`` and ``vf`` at the ends and the velocity at each inner via
    point chosen by the lectures' rule (see the module docstring): the average of the
    adjacent slopes when they have the same sign, else 0. Each interval is
    :func:`~dhsym.trajectory.profiles.cubic`'s polynomial between its two via points
    and velocities; the derivation lists the slopes and the chosen velocities.

    >>> p = via_cubic([0, 1, 3, 2], [0, 1, 2, 3])
    >>> p.derivation().pairs
    ((d_1, 1), (d_2, 2), (d_3, -1), (v_1, 3/2), (v_2, 0))
    >>> [seg.coefficients for seg in p.joints[0]]
    [(0, 0, 3/2, -1/2), (1, 3/2, 3, -5/2), (3, 0, -3, 2)]
    """
    rows, scalar = _rows(via, "via")
    m, n = len(rows), len(rows[0])
    ts = _via_times(times, m, "via_cubic")
    start_v, end_v = _per_joint(v0, n, "v0"), _per_joint(vf, n, "vf")
    d_syms = sp.symbols(f"d_1:{m}", real=True)
    v_syms = sp.symbols(f"v_1:{m - 1}", real=True) if m > 2 else ()
    joints, derivations = [], []
    for j in range(n):
        where = f"joint {j + 1}: " if n > 1 else ""
        slopes = [
            sp.simplify((rows[i + 1][j] - rows[i][j]) / (ts[i + 1] - ts[i])) for i in range(m - 1)
        ]
        chosen, said = [], []
        for k in range(m - 2):
            value, why = _via_velocity(slopes[k], slopes[k + 1], f"{where}via point {k + 1}: ")
            chosen.append(value)
            said.append(f"v_{k + 1} ({why})")
        speeds = [start_v[j], *chosen, end_v[j]]
        segs = tuple(
            polynomial_segment(
                ts[i], ts[i + 1] - ts[i], [rows[i][j], speeds[i]], [rows[i + 1][j], speeds[i + 1]]
            )[0]
            for i in range(m - 1)
        )
        d_eqs = [
            sp.Eq(d, _quotient(rows[i + 1][j] - rows[i][j], ts[i + 1] - ts[i]), evaluate=False)
            for i, d in enumerate(d_syms)
        ]
        v_eqs = [
            sp.Eq(v, _half(d_syms[k] + d_syms[k + 1]) if x != 0 else x, evaluate=False)
            for k, (v, x) in enumerate(zip(v_syms, chosen))
        ]
        labels = (
            *(f"d_{i + 1} (the slope from via point {i} to {i + 1})" for i in range(m - 1)),
            *said,
        )
        derivations.append(
            Derivation(
                labels,
                (*d_eqs, *v_eqs),
                (*d_syms, *v_syms),
                (*slopes, *chosen),
            )
        )
        joints.append(segs)
    return Profile("via cubic", tuple(joints), tuple(derivations), scalar)
