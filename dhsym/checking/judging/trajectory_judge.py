r"""Judging an answer to a trajectory or gain question: one expression, compared with the
key at fresh random points, then proven equal when affordable; decimals right up to the
key's :class:`~dhsym.checking.judging.rounding.Rounding`; a wrong answer equal to the key
under a catalogued mistake (:mod:`~dhsym.checking.mistakes.trajectory_mistakes`, values
derived once by :func:`~dhsym.checking.judging.trajectory_key.prepare_trajectory`) is
named in the feedback.

The answer is read once by the reader every kind shares
(:class:`~dhsym.checking.reading.answer_value.ReadCell`: plain math or LaTeX, the
whitelist parser, never ``sympify``) with the names ``q0``, ``qf``, ``tf``, ``v0``,
``vf``, ``V``, ``a``, ``vmax``, ``amax``, ``omega``, ``zeta`` (also ``q_0``, ``t_f``,
``\omega``, …).  Symbols that are positive in the key (``t_f``, ``ω``, …) are sampled
positive, and points where the key has no real value (a blend that does not fit) are
left out.

Examples
--------
>>> from dhsym.checking.judging.checker import check_answer
>>> key = TrajectoryKey.load("cubic(q0=0, qf=1, tf=2)", "traj a2")
>>> check_answer(key, "3/4").correct
True
>>> r = check_answer(key, "3/2")
>>> r.verdict.value, r.kinds
('incorrect', ('tf_for_tf_squared',))
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..comparing.equivalence import Sample, agree_precisely, cancellation, close, values
from ..comparing.verdict import CheckResult, Diagnosis, EntryResult, Verdict
from ..mistakes.trajectory_mistakes import TRAJECTORY_MISTAKES
from ..reading.answer_value import ReadCell
from ..reading.answers import expression_cell
from ..reading.limits import AnswerLimits, check_time, expansion_terms, time_left
from .rounding import rounding_accepts
from .trajectory_key import PreparedTrajectory, TrajectoryKey, trajectory_sample

__all__ = ["check_trajectory"]

_MAX_PROOF_OPS = 400


def _exactly_equal(answer: sp.Expr, key: sp.Expr, limits: AnswerLimits) -> bool:
    """True when ``answer - key`` cancels to 0 (a rational function of the symbols and
    roots); skipped for answers whose expansion is large (each step of the check is
    bounded by size: the deadline is cooperative) or when the deadline is near."""
    difference = answer - key
    if difference == 0:
        return True
    if sp.count_ops(answer) > _MAX_PROOF_OPS or expansion_terms(difference) > limits.proof_terms:
        return False
    if time_left() < limits.proof_seconds:
        return False
    try:
        return bool(sp.cancel(sp.together(difference)) == 0)
    except (RecursionError, MemoryError, sp.PolynomialError):
        return False


def check_trajectory(
    pt: PreparedTrajectory, answer: str | bytes, limits: AnswerLimits
) -> CheckResult:
    """Check ``answer`` (text, untrusted) against the prepared trajectory key ``pt``.

    Reading errors are raised (:func:`~dhsym.checking.judging.checker.check_answer`
    turns them into an unreadable verdict with the reason)."""
    key, part = pt.key, pt.part
    q = key.question
    cell = expression_cell(answer, limits)
    read = ReadCell.read(cell, pt.names, limits, "the answer")
    ans = read.value
    unknown = sorted(ans.free_symbols - pt.names.symbols, key=sp.default_sort_key)
    sample = trajectory_sample(
        part.expected.free_symbols | {w for _, v in part.wrong for w in v.free_symbols},
        part.expected,
    )
    if unknown:
        sample = sample.extended(unknown)
    kv = np.broadcast_to(values(part.expected, sample), (sample.size,))
    av = np.broadcast_to(values(ans, sample), (sample.size,))
    check_time()
    proof, note = "", ""
    near = bool(close(av, kv))
    if not unknown and (near or cancellation(ans, sample, av - kv)):
        # equal at every point, or a difference the doubles cannot tell from the rounding
        # error of the sums the answer cancels: the exact proof or 60-digit numbers decide
        if _exactly_equal(ans, part.expected, limits):
            proof = "exact"
        elif agree_precisely(ans, part.expected):
            proof = "numeric"
    if not proof and read.template is not None:
        note = _rounded(key, read, sample, kv)
        proof = "rounding" if note else ""
    shown = " ".join(cell.split())
    shown = shown if len(shown) <= 200 else shown[:199] + "…"
    wrong_text = "" if proof else sp.sstr(ans)
    entry = EntryResult(
        1,
        1,
        bool(proof),
        shown if proof or len(cell) > 160 else wrong_text,
        part.text,
        "" if proof else sp.latex(ans),
        part.latex,
        proof,
        note,
    )
    if proof:
        how = f" up to rounding ({note})" if note else ""
        return CheckResult(
            q.spec, Verdict.CORRECT, f"The answer is right{how}.", (entry,), key=key.name
        )
    found = []
    by_kind = {m.kind: m for m in TRAJECTORY_MISTAKES}
    for kind, value in part.wrong:
        check_time()
        wv = np.broadcast_to(values(value, sample), (sample.size,))
        if close(av, wv) or (read.template is not None and _rounded(key, read, sample, wv)):
            m = by_kind[kind]
            found.append(Diagnosis(m.kind, m.title, m.detail, ((1, 1),)))
    if unknown:
        names = ", ".join(str(s) for s in unknown)
        found.insert(
            0,
            Diagnosis(
                "unknown_symbol",
                "unknown symbols",
                f"The answer uses {names}, which the question does not have (its names: "
                "q0, qf, tf, v0, vf, V, a, vmax, amax, omega, zeta).",
            ),
        )
    lead = next((d for d in found if d.kind != "unknown_symbol"), None)
    message = (
        f"The answer is wrong. Most likely: {lead.title}. {lead.detail}"
        if lead is not None
        else "The answer is wrong: write the conditions of the profile and solve them again."
    )
    return CheckResult(q.spec, Verdict.INCORRECT, message, (entry,), tuple(found), key=key.name)


def _rounded(key: TrajectoryKey, read: ReadCell, sample: Sample, target: np.ndarray) -> str:
    """How the answer, written with decimals, equals ``target`` up to the key's rounding
    rule, or ``""``."""
    assert read.template is not None
    env = sample.extended(read.template.free_symbols - set(sample.symbols)).env
    how = rounding_accepts(
        key.rounding, read.template, read.literals, env, sample.size, np.asarray(target, float)
    )
    return how or ""
