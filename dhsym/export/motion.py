"""The trajectory and control parts of the export: programs that run joint by joint.

A :class:`JointwiseProgram` is a straight-line function evaluated once per joint ``j``:
it reads its ``arrays`` at ``j`` (into locals ``<array>_j``), its ``scalars`` as they
are, and writes each output array at ``j``.

* :func:`profile_program`: the cubic or quintic of :mod:`dhsym.trajectory.profiles`
  (coefficients solved exactly from the boundary conditions there, symbols here), as
  ``q, q̇, q̈`` at time ``t``; outside ``[0, t_f]`` each joint rests at its end
  (``q(0)`` before, ``q(t_f)`` after, velocity and acceleration 0), as
  :meth:`~dhsym.trajectory.profiles.Profile.sample` holds it after ``t_f``;
* :func:`lspb_program`: the linear segment with parabolic blends of
  :func:`dhsym.trajectory.lspb` with the line's speed ``v`` given per joint (its segments
  derived there, symbols here), the blend, line or blend chosen by the time; a joint at
  rest stays there, and a speed outside ``|q_f − q_0|/t_f < |v| ≤ 2|q_f − q_0|/t_f`` (the
  blends do not fit) gives NaN;
* :func:`spline_program`: the cubic spline of :func:`dhsym.trajectory.spline` through via
  points at given times: the row of its linear system at one inner via point (the
  continuity of acceleration, from the trajectory room with symbols) that the exported
  code solves by the tridiagonal (Thomas) elimination, and the cubic of each interval
  (:func:`profile_program`'s);
* :func:`computed_torque_program`: the commanded acceleration of computed torque,
  ``v = q̈_ref + K_d (q̇_ref − q̇) + K_p (q_ref − q)`` (diagonal gains), which the exported
  ``rne`` turns into ``τ = rne(q, q̇, v)`` (Spong–Hutchinson–Vidyasagar, *Robot Modeling
  and Control*, inverse dynamics control; Craig, *Introduction to Robotics*, ch. 10).

Examples
--------
>>> prog = profile_program("cubic")
>>> prog.arrays, prog.scalars
(('q0', 'qf', 'v0', 'vf'), ('tf', 't'))
>>> [(name, str(e)) for name, e in computed_torque_program().outputs]
[('v', 'kd_j*(-qd_j + qd_ref_j) + kp_j*(-q_j + q_ref_j) + qdd_ref_j')]
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from dhsym.model.parsing import REAL as _REAL
from dhsym.trajectory.blends import lspb
from dhsym.trajectory.profiles import cubic, quintic
from dhsym.trajectory.via import spline

from .program import Assign, _numbers, _straight_line

__all__ = [
    "Clamp",
    "Inside",
    "JointwiseProgram",
    "Pick",
    "SplineProgram",
    "computed_torque_program",
    "lspb_program",
    "profile_program",
    "spline_program",
]


class Clamp(sp.Function):
    """``Clamp(t, tf)``: ``t`` limited to ``[0, tf]`` (each printer writes min and max)."""

    nargs = 2


class Inside(sp.Function):
    """``Inside(t, tf)``: 1 when ``0 ≤ t ≤ tf``, else 0 (each printer writes comparisons)."""

    nargs = 2


class Pick(sp.Function):
    """``Pick(c, a, b)``: ``a`` when the condition ``c`` holds, else ``b`` (each printer
    writes its conditional; MATLAB a local function ``pick`` of the file, so that only
    the value chosen is used)."""

    nargs = 3


@dataclass(frozen=True)
class JointwiseProgram:
    """A function run once per joint ``j``: locals ``<array>_j`` from ``arrays`` at ``j``,
    the ``scalars`` as given, ``body``, then ``outputs`` (array name, expression) at ``j``;
    ``comment`` says what it computes."""

    name: str
    arrays: tuple[str, ...]
    scalars: tuple[str, ...]
    body: tuple[Assign, ...]
    outputs: tuple[tuple[str, sp.Expr], ...]
    comment: tuple[str, ...]

    def expressions(self) -> tuple[sp.Expr, ...]:
        """Every expression the function evaluates."""
        return (*(e for a in self.body for e in a.expressions()), *(e for _, e in self.outputs))

    @property
    def chooses(self) -> bool:
        """True when it chooses values by a condition (:class:`Pick`): every value is
        computed, the one not chosen may be NaN (NumPy then keeps quiet about it)."""
        return any(e.has(Pick) for e in self.expressions())

    @property
    def locals(self) -> tuple[tuple[str, str], ...]:
        """(local, array) for each array read at ``j``."""
        return tuple((f"{a}_j", a) for a in self.arrays)


def _local(name: str) -> sp.Symbol:
    return sp.Symbol(f"{name}_j", **_REAL)


def _horner(cs: list[sp.Expr], x: sp.Expr) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """``Σ c_k x^k`` and its first two derivatives, each in Horner's form."""

    def horner(terms: list[sp.Expr]) -> sp.Expr:
        out = terms[-1] if terms else sp.Integer(0)
        for term in reversed(terms[:-1]):
            out = term + x * out
        return out

    return (
        horner(cs),
        horner([k * c for k, c in enumerate(cs)][1:]),
        horner([k * (k - 1) * c for k, c in enumerate(cs)][2:]),
    )


def profile_program(kind: str) -> JointwiseProgram:
    """The ``cubic`` or ``quintic`` of :mod:`dhsym.trajectory.profiles` with symbolic ends
    per joint (arrays ``q0, qf, v0, vf`` and, quintic, ``a0, af``) and one duration ``tf``,
    evaluated at ``t``: outputs ``q``, ``qd``, ``qdd``.

    >>> prog = profile_program("quintic")
    >>> [name for name, _ in prog.outputs]
    ['q', 'qd', 'qdd']
    >>> prog.comment[5]
    'c2 = a0_j/2'
    """
    ends = {"cubic": ("q0", "qf", "v0", "vf"), "quintic": ("q0", "qf", "v0", "vf", "a0", "af")}
    if kind not in ends:
        raise ValueError(f"no exported profile {kind!r}")
    tf = sp.Symbol("tf", positive=True)
    t = sp.Symbol("t", **_REAL)
    s = {a: _local(a) for a in ends[kind]}
    make = cubic if kind == "cubic" else quintic
    profile = make(s["q0"], s["qf"], tf, *(s[a] for a in ends[kind][2:]))
    (segment,) = profile.joints[0]
    tc = sp.Symbol("tc", **_REAL)
    taken = {"tf", "t", "tc", "j", "q", "qd", "qdd", *ends[kind], *(x.name for x in s.values())}
    cs = [sp.Symbol(f"c{k}", **_REAL) for k in range(len(segment.coefficients))]
    taken |= {c.name for c in cs}
    body, reduced = _straight_line(list(segment.coefficients), {}, taken)
    body = [Assign("tc", Clamp(t, tf)), *body]
    body += [Assign(c.name, e) for c, e in zip(cs, reduced)]

    inside = Inside(t, tf)
    q, qd, qdd = _horner(cs, tc)
    qd, qdd = inside * qd, inside * qdd
    said = [
        f"The {kind} of each joint from its boundary conditions at 0 and tf:",
        "q = sum of c_k tc^k in the local time tc = t limited to [0, tf]",
        "(at rest outside it), with",
        *(f"c{k} = {c}" for k, c in enumerate(segment.coefficients)),
    ]
    return JointwiseProgram(
        kind,
        ends[kind],
        ("tf", "t"),
        tuple(body),
        tuple(zip(("q", "qd", "qdd"), (_numbers(q), _numbers(qd), _numbers(qdd)))),
        tuple(said),
    )


def computed_torque_program() -> JointwiseProgram:
    """The commanded acceleration ``v = qdd_ref + kd (qd_ref − qd) + kp (q_ref − q)`` of
    computed torque, joint by joint; the torque is the exported ``rne(q, qd, v)``.

    >>> computed_torque_program().arrays
    ('q', 'qd', 'q_ref', 'qd_ref', 'qdd_ref', 'kp', 'kd')
    """
    arrays = ("q", "qd", "q_ref", "qd_ref", "qdd_ref", "kp", "kd")
    s = {a: _local(a) for a in arrays}
    v = s["qdd_ref"] + s["kd"] * (s["qd_ref"] - s["qd"]) + s["kp"] * (s["q_ref"] - s["q"])
    return JointwiseProgram(
        "computed_torque",
        arrays,
        (),
        (),
        (("v", _numbers(v)),),
        (
            "Computed torque (inverse dynamics control): tau = rne(q, qd, v) with the",
            "commanded acceleration v = qdd_ref + kd (qd_ref - qd) + kp (q_ref - q),",
            "so that the error e = q_ref - q obeys e'' + kd e' + kp e = 0 on the exact model.",
        ),
    )


def lspb_program() -> JointwiseProgram:
    """The linear segment with parabolic blends of :func:`dhsym.trajectory.lspb` per
    joint, from ``q0`` to ``qf`` in ``tf`` with the line's speed ``v`` (its sign is the
    motion's), evaluated at ``t``: outputs ``q``, ``qd``, ``qdd``.

    The segments are the trajectory room's, derived with symbols; ``tb`` the blend
    time, ``vline`` the line's velocity. At rest outside ``[0, tf]``; a joint with
    ``qf = q0`` stays there; NaN when the blends do not fit (``tb`` not in ``(0, tf/2]``,
    the same as ``|q_f − q_0|/t_f < |v| ≤ 2|q_f − q_0|/t_f``).

    >>> prog = lspb_program()
    >>> prog.arrays
    ('q0', 'qf', 'v')
    >>> [(a.name, str(a.expr)) for a in prog.body[:3]]  # doctest: +NORMALIZE_WHITESPACE
    [('dq', '-q0_j + qf_j'), ('vline', 'Abs(v_j)*sign(dq)'),
     ('tb', '(-dq + tf*vline)/vline')]
    """
    tf = sp.Symbol("tf", positive=True)
    t = sp.Symbol("t", **_REAL)
    s = {a: _local(a) for a in ("q0", "qf", "v")}
    D, V, tb, tc, tau = (sp.Symbol(n, **_REAL) for n in ("dq", "vline", "tb", "tc", "tau"))
    speed = sp.Symbol("speed", positive=True)  # the derivation's V, for q_f > q_0
    blend, line, last = lspb(s["q0"], s["qf"], tf, v=speed).joints[0]
    # written with tb = (q0 − qf + V tf)/V (the sign of V the motion's: the algebra holds
    # for both directions), so that each coefficient reads as the lecture's
    tb_expr = blend.end.xreplace({speed: V})

    def written(e: sp.Expr) -> sp.Expr:
        return sp.simplify(e.xreplace({speed: V}).subs(s["q0"] - s["qf"] + tf * V, tb * V))

    segs = [
        (
            written(g.start),
            [written(c) for c in g.coefficients] + [sp.Integer(0)] * (3 - len(g.coefficients)),
        )
        for g in (blend, line, last)
    ]
    # a time on a boundary belongs to the segment before it (as Profile.sample has it)
    first, second = tc <= tb, tc <= written(line.end)

    def by_time(values: list[sp.Expr]) -> sp.Expr:
        later = values[1] if values[1] == values[2] else Pick(second, values[1], values[2])
        return Pick(first, values[0], later)

    cs = [sp.Symbol(f"c{k}", **_REAL) for k in range(3)]
    body = [
        Assign("dq", s["qf"] - s["q0"]),
        Assign("vline", sp.Abs(s["v"]) * sp.sign(D)),
        Assign("tb", tb_expr.subs(s["q0"] - s["qf"], -D)),
        Assign("tc", Clamp(t, tf)),
        Assign("tau", tc - by_time([start for start, _ in segs])),
        *(Assign(c.name, by_time([cs_[k] for _, cs_ in segs])) for k, c in enumerate(cs)),
    ]
    q, qd, qdd = _horner(cs, tau)
    at_rest = sp.Eq(D, 0)
    unfit = sp.Or(tb <= 0, 2 * tb > tf)
    inside = Inside(t, tf)
    outputs = (
        ("q", Pick(at_rest, s["q0"], Pick(unfit, sp.nan, q))),
        ("qd", Pick(at_rest, 0, Pick(unfit, sp.nan, inside * qd))),
        ("qdd", Pick(at_rest, 0, Pick(unfit, sp.nan, inside * qdd))),
    )
    said = [
        "The linear segment with parabolic blends of each joint from q0 to qf in tf,",
        "the line's speed v given: its velocity vline = |v| sign(qf - q0), the blend",
        "time tb = (q0 - qf + vline tf)/vline; blend, line, blend with coefficients",
        *(
            f"{name}: " + ", ".join(f"c{k} = {c}" for k, c in enumerate(cs_))
            for name, (_, cs_) in zip(("blend [0, tb]", "line", "blend [tf - tb, tf]"), segs)
        ),
        "in the local time tau from the segment's start (t limited to [0, tf], at rest",
        "outside it). A joint with qf = q0 stays at q0; NaN when the blends do not fit",
        "(tb not in (0, tf/2]: |qf - q0|/tf < |v| <= 2 |qf - q0|/tf is needed).",
    ]
    return JointwiseProgram(
        "lspb",
        ("q0", "qf", "v"),
        ("tf", "t"),
        tuple(Assign(a.name, _numbers(a.expr)) for a in body),
        tuple((name, _numbers(e)) for name, e in outputs),
        tuple(said),
    )


@dataclass(frozen=True)
class SplineProgram:
    """The cubic spline through via points (:func:`dhsym.trajectory.spline`) as exported
    code: for each joint, the velocities at the inner via points solve a tridiagonal
    system whose row at one via point is ``row`` (scalars ``qa, qb, qc``: the joint's
    values at the via points before, at and after it; ``ha, hb``: the intervals before
    and after it; outputs ``lower, diag, upper, rhs``: ``lower v_a + diag v_b + upper v_c
    = rhs``), and the interval holding the time is ``segment``, the exported cubic
    between two via points and their velocities; ``comment`` says what it computes."""

    row: JointwiseProgram
    segment: JointwiseProgram
    comment: tuple[str, ...]


def spline_program() -> SplineProgram:
    """The row of the spline's linear system at an inner via point, derived by
    :func:`dhsym.trajectory.spline` on three via points with symbols (the continuity of
    the acceleration there), and the cubic of one interval (:func:`profile_program`).

    >>> prog = spline_program()
    >>> [(name, str(e)) for name, e in prog.row.outputs][:3]
    [('lower', '2.0/ha'), ('diag', '4.0*(ha + hb)/(ha*hb)'), ('upper', '2.0/hb')]
    >>> prog.segment.name, prog.segment.arrays
    ('cubic', ('q0', 'qf', 'v0', 'vf'))
    """
    qa, qb, qc, va, vc = (sp.Symbol(n, **_REAL) for n in ("qa", "qb", "qc", "va", "vc"))
    ha, hb = sp.symbols("ha hb", positive=True)
    derivation = spline([qa, qb, qc], [0, ha, ha + hb], va, vc).derivation()
    (equation,), (vb,) = derivation.equations, derivation.unknowns
    residual = sp.expand(equation.lhs - equation.rhs)
    lower, diag, upper = (sp.factor(residual.coeff(x)) for x in (va, vb, vc))
    rhs = -residual.xreplace({va: 0, vb: 0, vc: 0})
    rhs = sum((sp.factor(rhs.coeff(h**-2)) / h**2 for h in (ha, hb)), sp.Integer(0))
    plain = {ha: sp.Symbol("ha", **_REAL), hb: sp.Symbol("hb", **_REAL)}
    outputs = tuple(
        (name, _numbers(e.xreplace(plain)))
        for name, e in (("lower", lower), ("diag", diag), ("upper", upper), ("rhs", rhs))
    )
    row = JointwiseProgram(
        "spline_row",
        (),
        ("qa", "qb", "qc", "ha", "hb"),
        (),
        outputs,
        ("The acceleration continuous at a via point b between a and c:",),
    )
    said = [
        "The cubic spline of each joint through the m via points (rows of via) at the",
        "times (from 0, increasing), with velocities v0 and vf at the ends and the",
        "acceleration continuous at every inner via point b (between a and c,",
        "intervals ha and hb before and after it):",
        *(
            f"{name} = {e}"
            for name, e in zip(("lower", "diag", "upper", "rhs"), (lower, diag, upper, rhs))
        ),
        "lower v_a + diag v_b + upper v_c = rhs, a tridiagonal system in the",
        "velocities at the inner via points, solved by elimination (Thomas);",
        "then the cubic of the interval holding t between its two via points and",
        "velocities. At rest outside [0, times[m - 1]].",
    ]
    return SplineProgram(row, profile_program("cubic"), tuple(said))
