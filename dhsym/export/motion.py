"""The trajectory and control parts of the export: programs that run joint by joint.

A :class:`JointwiseProgram` is a straight-line function evaluated once per joint ``j``:
it reads its ``arrays`` at ``j`` (into locals ``<array>_j``), its ``scalars`` as they
are, and writes each output array at ``j``.

* :func:`profile_program`: the cubic or quintic of :mod:`dhsym.trajectory.profiles`
  (coefficients solved exactly from the boundary conditions there, symbols here), as
  ``q, q̇, q̈`` at time ``t``; outside ``[0, t_f]`` each joint rests at its end
  (``q(0)`` before, ``q(t_f)`` after, velocity and acceleration 0), as
  :meth:`~dhsym.trajectory.profiles.Profile.sample` holds it after ``t_f``;
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
from dhsym.trajectory.profiles import cubic, quintic

from .program import Assign, _numbers, _straight_line

__all__ = ["Clamp", "Inside", "JointwiseProgram", "computed_torque_program", "profile_program"]


class Clamp(sp.Function):
    """``Clamp(t, tf)``: ``t`` limited to ``[0, tf]`` (each printer writes min and max)."""

    nargs = 2


class Inside(sp.Function):
    """``Inside(t, tf)``: 1 when ``0 ≤ t ≤ tf``, else 0 (each printer writes comparisons)."""

    nargs = 2


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
    def locals(self) -> tuple[tuple[str, str], ...]:
        """(local, array) for each array read at ``j``."""
        return tuple((f"{a}_j", a) for a in self.arrays)


def _local(name: str) -> sp.Symbol:
    return sp.Symbol(f"{name}_j", **_REAL)


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

    def horner(terms: list[sp.Expr]) -> sp.Expr:
        out = terms[-1]
        for term in reversed(terms[:-1]):
            out = term + tc * out
        return out

    inside = Inside(t, tf)
    q = horner(cs)
    qd = inside * horner([k * c for k, c in enumerate(cs)][1:])
    qdd = inside * horner([k * (k - 1) * c for k, c in enumerate(cs)][2:])
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
