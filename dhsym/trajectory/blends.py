r"""Linear segments with parabolic blends (LSPB, the trapezoidal velocity profile) and the
minimum-time profile under velocity and acceleration limits.

The lecture's derivation (Spong–Hutchinson–Vidyasagar, *Robot Modeling and Control*,
ch. 5; Lynch–Park, *Modern Robotics*, ch. 9): a blend ``[0, t_b]`` of constant
acceleration ``a``, a line of velocity ``V = a t_b``, a blend ``[t_f − t_b, t_f]``
back to rest; symmetry gives ``q(t_f/2) = (q_0 + q_f)/2``, hence

* ``V`` given: ``t_b = (q_0 − q_f + V t_f)/V``, feasible when
  ``|q_f − q_0|/t_f ≤ |V| ≤ 2|q_f − q_0|/t_f``;
* ``a`` given: ``a t_b² − a t_f t_b + (q_f − q_0) = 0``, the smaller root, feasible when
  ``|a| ≥ 4|q_f − q_0|/t_f²``.

Without either, ``V = 1.5 (q_f − q_0)/t_f`` (roboticstoolbox's choice).

Examples
--------
>>> p = lspb(0, 1, 2, v=sp.Rational(3, 4))
>>> [s.coefficients for s in p.joints[0]]
[(0, 0, 9/16), (1/4, 3/4), (3/4, 3/4, -9/16)]
>>> lspb(0, 1, 2, v=2)
Traceback (most recent call last):
...
dhsym.errors.DHError: lspb: V = 2 too large: needs |V| ≤ 2|q_f − q_0|/t_f = 1
"""

from __future__ import annotations

from dataclasses import replace

import sympy as sp

from dhsym.errors import DHError

from .profiles import (
    Derivation,
    Profile,
    Segment,
    _broadcast,
    _positive_time,
    exact_value,
)

__all__ = ["lspb", "minimum_time", "trapezoidal"]


def _holds(cond: sp.Basic) -> bool | None:
    """True / False when a relation is decided (numbers or assumptions), else None."""
    if cond is sp.true or cond is True:
        return True
    if cond is sp.false or cond is False:
        return False
    return None


def _require(cond: sp.Basic, message: str) -> sp.Basic | None:
    """Raise ``message`` when ``cond`` is false; the condition to record when undecided."""
    decided = _holds(cond)
    if decided is False:
        raise DHError(message)
    return None if decided else cond


def _blend_segments(
    q0: sp.Expr, qf: sp.Expr, tf: sp.Expr, tb: sp.Expr, acc: sp.Expr, V: sp.Expr
) -> tuple[Segment, ...]:
    """Blend, line, blend (the line left out when it has no length)."""
    half = acc * tb**2 / 2
    first = Segment(sp.Integer(0), tb, (q0, sp.Integer(0), acc / 2))
    line = Segment(tb, tf - tb, (sp.simplify(q0 + half), V))
    last = Segment(tf - tb, tf, (sp.simplify(qf - half), V, -acc / 2))
    if sp.simplify(tf - 2 * tb) == 0:
        return first, last
    return first, line, last


def _lspb_joint(
    q0: sp.Expr, qf: sp.Expr, tf: sp.Expr, v: sp.Expr | None, a: sp.Expr | None
) -> tuple[tuple[Segment, ...], Derivation]:
    D = qf - q0
    tb, acc_s, vel_s = sp.symbols("t_b a V", real=True)
    t_f = tf
    if D == 0:  # at rest: no blend
        seg = Segment(sp.Integer(0), tf, (q0,))
        return (seg,), Derivation((), (), (), ())
    conds: list[sp.Basic] = []
    sym = sp.sign(D)
    if not sym.is_number:  # symbols of unknown order: the lecture's case q_f > q_0
        sym = sp.Integer(1)
        conds.append(sp.Gt(qf, q0))
    absD = sym * D
    midpoint = sp.Eq(q0 + acc_s * tb**2 / 2 + vel_s * (t_f / 2 - tb), (q0 + qf) / 2, evaluate=False)
    join = sp.Eq(acc_s * tb, vel_s, evaluate=False)
    labels = (r"a t_b = V", r"q(t_f/2) = (q_0 + q_f)/2")
    if a is None:
        V = sp.Rational(3, 2) * D / tf if v is None else sp.Abs(v) * sym
        if v is not None:
            low = _require(
                sp.Ge(sp.Abs(v), absD / tf),
                f"lspb: V = {v} too small: needs |V| ≥ |q_f − q_0|/t_f = {absD / tf}",
            )
            high = _require(
                sp.Le(sp.Abs(v), 2 * absD / tf),
                f"lspb: V = {v} too large: needs |V| ≤ 2|q_f − q_0|/t_f = {2 * absD / tf}",
            )
            conds += [c for c in (low, high) if c is not None]
        t_b = sp.simplify((q0 - qf + V * tf) / V)
        acc = sp.simplify(V / t_b)
        unknowns, solution = (tb, acc_s), (t_b, acc)
        equations = (join.xreplace({vel_s: V}), midpoint.xreplace({vel_s: V}))
    else:
        A = sp.Abs(a) * sym
        c = _require(
            sp.Ge(sp.Abs(a), 4 * absD / tf**2),
            f"lspb: a = {a} too small: needs |a| ≥ 4|q_f − q_0|/t_f² = {4 * absD / tf**2}",
        )
        conds += [c] if c is not None else []
        t_b = sp.simplify(tf / 2 - sp.sqrt(A**2 * tf**2 - 4 * A * D) / (2 * sp.Abs(A)))
        V = sp.simplify(A * t_b)
        acc = A
        unknowns, solution = (tb, vel_s), (t_b, V)
        equations = (join.xreplace({acc_s: A}), midpoint.xreplace({acc_s: A}))
    d = Derivation(labels, equations, unknowns, solution, conditions=tuple(conds))
    return _blend_segments(q0, qf, tf, t_b, acc, V), d


def lspb(q0: object, qf: object, tf: object, v: object = None, a: object = None) -> Profile:
    r"""Linear segment with parabolic blends from ``q0`` to ``qf`` in ``tf``, at rest at
    both ends; the line's velocity ``v`` or the blends' acceleration ``a`` given (not
    both), or neither (``V = 1.5 (q_f − q_0)/t_f``). See the module docstring for the
    derivation; an infeasible ``v`` or ``a`` raises :class:`~dhsym.errors.DHError`, and a
    condition that cannot be decided for symbols is kept in ``conditions``.

    >>> lspb(0, 1, 1).derivation().pairs
    ((t_b, 1/3), (a, 9/2))
    >>> q0, qf, tf, a = sp.symbols("q0 qf tf a", positive=True)
    >>> lspb(q0, qf, tf, a=a).conditions
    (qf > q0, a >= (-4*q0 + 4*qf)/tf**2)
    """
    if v is not None and a is not None:
        raise DHError("lspb: give the line's velocity v or the blend acceleration a, not both")
    named: dict[str, object] = {"q0": q0, "qf": qf}
    if v is not None:
        named["v"] = v
    if a is not None:
        named["a"] = a
    T = exact_value(tf, "tf")
    _positive_time(T)
    rows, scalar = _broadcast(named)
    joints, derivations = [], []
    for row in rows:
        segs, d = _lspb_joint(row["q0"], row["qf"], T, row.get("v"), row.get("a"))
        joints.append(segs)
        derivations.append(d)
    return Profile("lspb", tuple(joints), tuple(derivations), scalar)


#: roboticstoolbox's name for :func:`lspb`.
trapezoidal = lspb


def minimum_time(q0: object, qf: object, vmax: object, amax: object) -> Profile:
    r"""The fastest rest-to-rest motion with ``|q̇| ≤ vmax`` and ``|q̈| ≤ amax``: full
    acceleration, cruise at ``vmax``, full deceleration, taking ``t_f = D/v + v/a``
    (``D = |q_f − q_0|``) when ``D ≥ v²/a``; else a triangle, ``t_f = 2√(D/a)``
    (Lynch–Park, *Modern Robotics*, ch. 9). Joint vectors: each joint's own minimum
    time, all timed to the slowest (the others blend with their ``amax`` over that
    time).

    >>> p = minimum_time(0, 2, 1, 1)
    >>> p.duration, [s.end for s in p.joints[0]]
    (3, [1, 2, 3])
    >>> minimum_time([0, 0], [1, 4], 1, 4).duration
    17/4
    """
    rows, scalar = _broadcast({"q0": q0, "qf": qf, "vmax": vmax, "amax": amax})
    times = []
    for row in rows:
        D, v, acc = sp.Abs(row["qf"] - row["q0"]), row["vmax"], row["amax"]
        for name in ("vmax", "amax"):
            if _holds(sp.Gt(row[name], 0)) is False:
                raise DHError(f"minimum_time: {name} must be positive, got {row[name]}")
        cruise = _holds(sp.Ge(D, v**2 / acc))
        if cruise is None:
            raise DHError(
                "minimum_time: cannot tell whether the velocity limit is reached "
                f"(|q_f − q_0| ≥ v²/a, {D} ≥ {v**2 / acc}): give numbers or assumptions"
            )
        times.append(D / v + v / acc if cruise else 2 * sp.sqrt(D / acc))
    T = sp.Max(*times) if len(times) > 1 else times[0]
    if len(times) > 1 and isinstance(T, sp.Max):
        raise DHError("minimum_time: cannot tell which joint is the slowest: give numbers")
    if T == 0:
        raise DHError("minimum_time: q0 and qf are equal: there is no motion to time")
    tf = sp.Symbol("t_f", positive=True)
    joints, derivations = [], []
    for row, t_j in zip(rows, times):
        segs, d = _lspb_joint(row["q0"], row["qf"], T, None, row["amax"])
        joints.append(segs)
        timing = sp.Eq(tf, t_j, evaluate=False)
        derivations.append(
            replace(
                d,
                labels=("t_f (the joint's minimum time)", *d.labels),
                equations=(timing, *d.equations),
                unknowns=(tf, *d.unknowns),
                solution=(t_j, *d.solution),
            )
        )
    return Profile("minimum time", tuple(joints), tuple(derivations), scalar)
