r"""The typical mistakes of trajectory and gain questions, each recomputing the key under
that mistake (the way the other mistake plug-ins do): a student's answer that equals one
of these is named in the feedback.

* ``tf_for_tf_squared``: a power of ``t_f`` one too low (``3(q_f − q_0)/t_f`` for
  ``3(q_f − q_0)/t_f²``);
* ``boundary_velocity_left_out``: the coefficients of a profile with given end
  velocities computed as if they were 0;
* ``blend_time_wrong_limit``: the blend time of the other limit (the velocity limit's
  ``v/a`` where the motion never reaches it, ``√(D/a)`` where it does) or the other root
  of ``a t_b² − a t_f t_b + D = 0``;
* ``kd_without_two``: ``K_d = ζω`` for ``2ζω``; ``kp_not_squared``: ``K_p = ω`` for ``ω²``.

Examples
--------
>>> tf, q0, qf = sp.symbols("t_f q_0 q_f", positive=True)
>>> lower_time_power(3 * (qf - q0) / tf**2, tf)
(-3*q_0 + 3*q_f)/t_f
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import sympy as sp

__all__ = ["TrajectoryMistake", "TRAJECTORY_MISTAKES", "lower_time_power"]


def lower_time_power(expr: sp.Expr, tf: sp.Symbol) -> sp.Expr:
    """``expr`` with every power ``t_f^k`` (``k ≥ 2``, also in denominators) one lower."""

    def lower(p: sp.Pow) -> sp.Expr:
        k = p.exp
        if k.is_Integer and abs(int(k)) >= 2:
            return tf ** (k - sp.sign(k))
        return p

    return expr.replace(lambda e: isinstance(e, sp.Pow) and e.base == tf, lower)


@dataclass(frozen=True)
class TrajectoryMistake:
    """One mistake: its ``kind``, a ``title`` and the ``detail`` for the student, and
    ``wrong``: the key's value recomputed under the mistake from the key's
    ``(question, values)`` (None when the mistake does not apply)."""

    kind: str
    title: str
    detail: str
    wrong: Callable[[str, dict[str, sp.Expr]], sp.Expr | None]


def _tf_power(question: str, v: dict[str, sp.Expr]) -> sp.Expr | None:
    """The key in the symbol ``t_f`` (``key_tf``, ``tf_symbol``) with the power lowered,
    then ``t_f``'s value (``t_f``) put back."""
    key, tf = v.get("key_tf"), v.get("tf_symbol")
    if key is None or not isinstance(tf, sp.Symbol):
        return None
    wrong = lower_time_power(key, tf)
    if wrong == key:
        return None
    return wrong.xreplace({tf: v["t_f"]}) if "t_f" in v else wrong


def _velocity_left_out(question: str, v: dict[str, sp.Expr]) -> sp.Expr | None:
    return v.get("key_at_rest")


def _wrong_limit(question: str, v: dict[str, sp.Expr]) -> sp.Expr | None:
    return v.get("blend_other") if question == "tb" else None


def _kd_without_two(question: str, v: dict[str, sp.Expr]) -> sp.Expr | None:
    return v["key"] / 2 if question == "kd" else None


def _kp_not_squared(question: str, v: dict[str, sp.Expr]) -> sp.Expr | None:
    return v["omega"] if question == "kp" and "omega" in v else None


#: The catalogue, most likely first.
TRAJECTORY_MISTAKES: Sequence[TrajectoryMistake] = (
    TrajectoryMistake(
        "tf_for_tf_squared",
        "t_f for t_f²",
        "A power of t_f is one too low: the condition at t_f puts t_f^k beside a_k "
        "(for a2, 3(q_f − q_0)/t_f², not /t_f).",
        _tf_power,
    ),
    TrajectoryMistake(
        "boundary_velocity_left_out",
        "boundary velocity left out",
        "This is the coefficient of a motion from rest to rest: the velocities given at the "
        "ends enter the conditions q̇(0) = v_0 and q̇(t_f) = v_f.",
        _velocity_left_out,
    ),
    TrajectoryMistake(
        "blend_time_wrong_limit",
        "blend time from the wrong limit",
        "This blend time belongs to the other case: check first whether the motion reaches "
        "the velocity limit (|q_f − q_0| ≥ v²/a) and take the smaller root of "
        "a t_b² − a t_f t_b + (q_f − q_0) = 0.",
        _wrong_limit,
    ),
    TrajectoryMistake(
        "kd_without_two",
        "K_d without the factor 2",
        "Matching s² + K_d s + K_p with s² + 2ζω s + ω² gives K_d = 2ζω.",
        _kd_without_two,
    ),
    TrajectoryMistake(
        "kp_not_squared",
        "K_p = ω",
        "Matching s² + K_d s + K_p with s² + 2ζω s + ω² gives K_p = ω², the square.",
        _kp_not_squared,
    ),
)
