r"""Checking inverse-kinematics answers: the joint values as formulas in the pose, or numbers.

A question ``ik`` asks for one solution as formulas in the pose symbols of the
derivation (``n_x … a_z``, ``p_x``, ``p_y``, ``p_z``, also written ``px``, ``p_{x}``) and
the robot's lengths; ``ik all`` asks for every solution, each ``±`` written out
(``\pm``, ``±`` or ``+/-``: every choice of the signs must be a solution);
``ik@q1,…,qn`` asks for the numbers of the pose these joint values reach (one solution, or
one per line for ``ik all@…``), rounded or not (a number with d decimals may be off by
``10^-d``; degrees with ``°``).

An answer is a list of statements, one per line (or separated by ``;``):
``theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)``, helpers first or later
(``D = (p_x^2 + p_y^2 - a1^2 - a2^2)/(2 a1 a2)``, ``c2 = D``), in plain math or LaTeX
(``\theta_1 = \operatorname{atan2}(p_y, p_x)``), or the joint values in order
(``0.3, 0.9``). Nothing is executed: each right-hand side goes through the whitelist parser.

The answer is evaluated at 64 fresh random poses (each from a random configuration and,
when the answer keeps the lengths as symbols, random lengths) and compared, angles modulo
2π, with every branch of the key (:func:`dhsym.ik.families.inverse`, each choice
of its signs σ); any branch is right, and the feedback names it. A wrong answer is
explained by recomputing the key under each classic mistake
(:data:`~dhsym.checking.mistakes.registry.IK_MISTAKES`).  The key's closed form, its
pose and its branches' names are prepared once (:mod:`~dhsym.checking.judging.ik_key`).

Examples
--------
>>> from dhsym.checking import Key, check_answer
>>> key = Key.load("planar2r", "ik")
>>> r = check_answer(key, "c2 = (px^2 + py^2 - a1^2 - a2^2)/(2*a1*a2)\n"
...                       "theta2 = atan2(-sqrt(1 - c2^2), c2)\n"
...                       "theta1 = atan2(py, px) - atan2(a2*S2, a1 + a2*C2)")
>>> r.verdict.value, r.message
('correct', 'Right: the branch elbow up.')
>>> r = check_answer(key, "theta2 = acos((px^2 + py^2 - a1^2 - a2^2)/(2*a1*a2))\n"
...                       "theta1 = atan(py/px) - atan2(a2*S2, a1 + a2*C2)")
>>> r.verdict.value, r.kinds
('incorrect', ('atan_for_atan2',))
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
import sympy as sp

from dhsym.ik.steps import pose_symbols

from ..comparing.ik_values import (
    ATOL,
    PoseSample,
    branch_signs,
    joint_distance,
    key_values,
    pose_sample,
)
from ..comparing.sampled_frames import evaluate_or_nan, frames
from ..comparing.tolerances import TOLERANCES
from ..comparing.verdict import CheckResult, Diagnosis, EntryResult, Verdict
from ..mistakes.registry import IK_MISTAKES, IKCase, IKVariants
from ..reading.answer_value import IKAnswer, IKStatement
from ..reading.limits import check_time
from .ik_key import IKPart
from .key import PreparedKey
from .rounding import value_tolerance

if TYPE_CHECKING:
    from dhsym.ik.closed_form import ClosedForm
    from dhsym.robot import Robot

__all__ = ["check_ik", "ik_part"]

#: per row of the answer's values: (which solution, the choice of its signs ±)
_Meta: TypeAlias = list[tuple[int, dict[sp.Symbol, Any]]]


def ik_part(pk: PreparedKey) -> IKPart:
    """The prepared part of an inverse-kinematics key (IK statements are read only for one)."""
    part = pk.part
    if not isinstance(part, IKPart):
        raise TypeError(f"an inverse-kinematics answer to a key prepared as {type(part).__name__}")
    return part


def _tolerance(st: IKStatement) -> float:
    """How far a value written with decimals may be from the exact one: one unit in the
    last digit of the decimals that stand for the value (with at least 3 significant
    digits; :func:`~dhsym.checking.judging.rounding.value_tolerance`: never a constant that a zero
    factor removes or another cancels), in degrees when a degree sign is there."""
    cell = st.cell
    written = value_tolerance(cell.template, cell.literals) if cell.template is not None else 0.0
    tol = max(ATOL, written)
    if st.degrees:
        tol = max(tol * np.pi / 180, ATOL)
    return tol


# --- numbers ---------------------------------------------------------------------------------


def _values(
    ans: IKAnswer, sample: PoseSample, variables: list[sp.Symbol]
) -> tuple[np.ndarray, np.ndarray, _Meta]:
    """The answer's joint values ``(A, size, n)``: one row per solution and choice of signs;
    the tolerance per row and joint; which solution and signs each row is."""
    combos = [
        dict(zip(ans.signs, choice, strict=True))
        for choice in (branch_signs_n(len(ans.signs)) if ans.signs else [()])
    ]
    n, size = len(variables), sample.size
    rows: list[np.ndarray] = []
    tols: list[np.ndarray] = []
    meta: _Meta = []
    for s_index, sol in enumerate(ans.solutions):
        for combo in combos:
            local = dict(sample.env)
            for v in variables:
                local.pop(v, None)  # the answer's own joint values, not the sample's
            for sgn, value in combo.items():
                local[sgn] = np.full(size, float(value))
            pending = [*ans.helpers, *sol.values()]
            memo: dict[object, np.ndarray] = {}
            while pending:
                ready = [st for st in pending if st.expr.free_symbols <= set(local)]
                if not ready:
                    break
                for st in ready:
                    local[st.target] = evaluate_or_nan(st.expr, local, size, memo)
                    pending.remove(st)
            row = np.full((size, n), np.nan)
            tol = np.full(n, ATOL)
            for j, st in sol.items():
                if st.target in local:
                    row[:, j] = local[st.target]
                tol[j] = _tolerance(st)
            rows.append(row)
            tols.append(tol)
            meta.append((s_index, combo))
    return np.array(rows), np.array(tols), meta


def _circular(ans: IKAnswer, given: set[sp.Symbol]) -> list[str]:
    """The joint values of the answer that no order of its statements computes from the
    ``given`` symbols (pose, lengths, signs): ``theta1 = theta1`` and its longer circles."""
    out: list[str] = []
    for sol in ans.solutions:
        known = set(given)
        pending = [*ans.helpers, *sol.values()]
        while True:
            ready = [st for st in pending if st.expr.free_symbols <= known]
            if not ready:
                break
            known |= {st.target for st in ready}
            pending = [st for st in pending if st not in ready]
        out += [str(st.target) for st in sol.values() if st.target not in known]
    return sorted(set(out))


def branch_signs_n(count: int) -> np.ndarray:
    """Every choice of ``count`` signs, ``+1`` first (as :func:`branch_signs`)."""
    import itertools

    return np.array(list(itertools.product([1, -1], repeat=count)), dtype=float)


def _reaches(robot: Robot, q: np.ndarray, sample: PoseSample, position: bool) -> bool:
    """True when the joint values ``q`` ``(size, n)`` reach the sample's poses (or points)."""
    return bool(_reaches_at(robot, q, sample, position).all())


def _reaches_at(robot: Robot, q: np.ndarray, sample: PoseSample, position: bool) -> np.ndarray:
    """Per pose ``(size,)``: the joint values ``q`` ``(size, n)`` reach it (never where a
    value is NaN)."""
    env = dict(sample.env)
    real = ~np.isnan(q).any(axis=1)
    for k, v in enumerate(robot.variables):
        env[v] = np.where(real, q[:, k], 0.0)
    T = frames(robot.table, env, sample.size)[:, -1]
    P = pose_symbols()
    goal = np.stack([np.stack([sample.env[P[i, j]] for j in range(4)], -1) for i in range(3)], -2)
    got = T[:, :3, :]
    if position:
        got, goal = got[:, :, 3], goal[:, :, 3]
    with np.errstate(invalid="ignore"):
        near = np.abs(got - goal) <= TOLERANCES.reach_atol
    ok: np.ndarray = real & near.reshape(sample.size, -1).all(axis=1)
    return ok


# --- the check --------------------------------------------------------------------------------


def _valued(pk: PreparedKey, ans: IKAnswer) -> bool:
    """True when the answer writes none of the lengths as symbols (it used their numbers)
    and the table has numbers for them all."""
    table = pk.key.table
    return set(table.constants) <= set(table.value_map) and not (ans.symbols & set(table.constants))


def _sample(pk: PreparedKey, ans: IKAnswer) -> PoseSample:
    """Fresh random poses for the verdict (with the table's lengths when the answer uses
    their numbers), or the question's pose."""
    part = ik_part(pk)
    if part.pose is not None:
        return part.pose
    return pose_sample(pk.robot, values=pk.key.table.value_map if _valued(pk, ans) else None)


def _diagnosis(pk: PreparedKey, ans: IKAnswer) -> IKVariants:
    """The key's diagnosis poses for this answer (the question's pose, or the random poses
    drawn by prepare_ik) with the key's values there under each mistake."""
    part = ik_part(pk)
    return part.diagnosis[part.pose is None and _valued(pk, ans)]


def _entries(
    pk: PreparedKey,
    ans: IKAnswer,
    ik: ClosedForm,
    key: np.ndarray,
    answers: np.ndarray,
    tols: np.ndarray,
    meta: _Meta,
    revolute: np.ndarray,
) -> tuple[EntryResult, ...]:
    """One entry per solution and joint (row: the solution, column: the joint): right when
    the joint agrees, for every choice of ``±``, with the nearest branch of the key."""
    nota = pk.robot.notation
    variables = list(pk.robot.variables)
    signs = branch_signs(ik)
    steps = {st.lhs: st for st in ik.steps}
    out = []
    for s_index, sol in enumerate(ans.solutions):
        rows = [r for r, (s, _) in enumerate(meta) if s == s_index]
        right = np.ones(len(variables), dtype=bool)
        nearest = 0
        for r in rows:
            with np.errstate(invalid="ignore"):
                ok = joint_distance(answers[r][None], key, revolute) <= tols[r]  # (K, size, n)
            k = int(np.argmax(ok.sum(axis=(1, 2))))
            nearest = k if r == rows[0] else nearest
            right &= ok[k].all(axis=0)
        sub = {b.symbol: int(signs[nearest, j]) for j, b in enumerate(ik.branches)}
        for j, v in enumerate(variables):
            st = sol.get(j)
            expected = steps[v].rhs.xreplace(sub) if v in steps else sp.nan
            good = st is not None and bool(right[j])
            shown = st is not None and not good
            out.append(
                EntryResult(
                    s_index + 1,
                    j + 1,
                    good,
                    nota.text(st.expr) if st and shown else (st.text if st else ""),
                    f"{nota.text(v)} = {nota.text(expected)}",
                    nota.latex(st.expr) if st and shown else "",
                    f"{nota.latex(v)} = {nota.latex(expected)}",
                    "numeric" if good else "",
                )
            )
    return tuple(out)


def check_ik(pk: PreparedKey, ans: IKAnswer) -> CheckResult:
    """Check an inverse-kinematics answer, as read
    (:func:`~dhsym.checking.reading.answer_value.read_answer_value`), against the key (see
    the module text)."""
    key, q, part = pk.key, pk.key.question, ik_part(pk)
    ik = part.ik
    robot = pk.robot
    nota = robot.notation
    variables = list(robot.variables)
    known = set(part.symbols) | set(variables) | {st.target for st in ans.helpers} | set(ans.signs)
    unknown = sorted(ans.symbols - known, key=sp.default_sort_key)
    missing = sorted(
        {str(variables[j]) for sol in ans.solutions for j in range(len(variables)) if j not in sol}
    )
    if unknown or missing:
        parts = []
        if missing:
            parts.append(f"The answer does not give {', '.join(missing)}.")
        if unknown:
            used = ", ".join(map(str, unknown))
            parts.append(
                f"The answer uses {used}, which is neither a pose symbol (n_x … a_z, p_x, "
                "p_y, p_z), a length of this robot, a joint variable nor defined in the answer."
            )
        kind = "unknown_symbol" if unknown else "missing_joint"
        d = Diagnosis(kind, "unknown symbols" if unknown else "joint missing", " ".join(parts))
        return CheckResult(q.spec, Verdict.INCORRECT, " ".join(parts), diagnoses=(d,), key=key.name)
    circular = _circular(ans, set(part.symbols) | set(ans.signs))
    if circular:
        text = (
            f"{', '.join(circular)} cannot be computed from the pose: each is defined through "
            "itself or through a value that needs it (a joint value must come from p, n, s, "
            "a and the lengths)."
        )
        d = Diagnosis("circular", "defined through itself", text)
        return CheckResult(q.spec, Verdict.INCORRECT, text, diagnoses=(d,), key=key.name)
    position = not ik.decoupling.wrist
    sample = _sample(pk, ans)
    result = _judge(pk, ans, ik, sample, position)
    if result[0]:
        return _correct(pk, ans, ik, sample, result, position)
    prepared = _diagnosis(pk, ans)  # the key's values under each mistake, built with the key
    dsample, key_d = prepared.sample, prepared.key
    answers, tols, meta = _values(ans, dsample, variables)
    m = _match(key_d, answers, tols, dsample, robot, position)
    wrong = m.wrong
    valid_k = [k for k in range(len(key_d)) if not np.isnan(key_d[k]).any()]
    names = part.branch_names  # at the question's pose, or in general
    case = IKCase(
        ik,
        dsample,
        key_d,
        answers,
        tuple(wrong),
        tuple(int(k) for k in np.flatnonzero(np.asarray(m.hits.any(axis=0)).all(axis=1))),
        names,
        tols.max(axis=0) if len(tols) else np.full(len(variables), ATOL),
        q.every,
        nota,
        prepared,
    )
    found = []
    for mistake in IK_MISTAKES:
        check_time()  # the answer's deadline, before each mistake's search
        found.append((mistake.kind, mistake.explain_ik(case)))
    diagnoses = tuple(d for kind, d in found if d is not None and kind != "lost_branch")
    domain = _domain(m, key_d, answers, wrong, names)
    if domain is not None:  # the branch itself where both have values: the reason comes first
        diagnoses = (domain, *diagnoses)
    if wrong and not diagnoses:
        diagnoses = (
            Diagnosis(
                "unexplained",
                "not a solution",
                "These joint values do not reach the pose (the forward kinematics of the "
                "answer misses it) and none of the usual mistakes explains it: compare each "
                "joint with the derivation, step by step.",
            ),
        )
    diagnoses += tuple(d for kind, d in found if d is not None and kind == "lost_branch")
    if not diagnoses:  # all right, but not all of them (seen on the fresh draw)
        diagnoses = (
            Diagnosis(
                "lost_branch",
                "a branch is lost",
                f"The answer gives {len(case.matched)} of the {len(valid_k)} solutions.",
            ),
        )
    entries = _entries(pk, ans, ik, key_d, answers, tols, meta, dsample.revolute)
    what = (
        "Not every solution is given"
        if not wrong
        else f"{len(wrong)} of {len(answers)} answers (solutions and choices of ±) "
        f"{'is' if len(wrong) == 1 else 'are'} wrong"
        if len(answers) > 1
        else "The answer is not a solution"
    )
    first = diagnoses[0]
    message = f"{what}. Most likely: {first.title}. {first.detail}"
    given = result[1]  # each key branch given or not, at the verdict's own poses
    branches = (
        tuple((names[k], bool(given.given[k])) for k in np.flatnonzero(given.exists))
        if q.every
        else ()
    )
    return CheckResult(
        q.spec, Verdict.INCORRECT, message, entries, diagnoses, key=key.name, branches=branches
    )


def _close(a: np.ndarray, b: np.ndarray, revolute: np.ndarray, tol: np.ndarray) -> np.ndarray:
    """Per point: ``a`` and ``b`` (``(size, n)``) agree in every joint (angles mod 2π)."""
    d = joint_distance(a, b, revolute)
    scale = np.where(revolute, 1.0, 1.0 + np.abs(np.nan_to_num(b)))
    with np.errstate(invalid="ignore"):
        ok: np.ndarray = np.all(d <= tol * scale, axis=-1)
    return ok


@dataclass(frozen=True, eq=False)
class _Match:
    """How the answer's rows compare with the key's branches, point by point.

    ``hits[a, k, p]``: row ``a`` is branch ``k`` at point ``p``; ``branch[a]`` the branch a
    row is at every point (None: none, or it changes with the pose); ``wrong`` the rows that
    are no solution at some point; ``covered`` True when every distinct branch is given at
    every point; ``given[k]`` True when the rows that are solutions give branch ``k`` (or
    one equal to it) at every point where it exists, ``exists[k]`` when it exists at some.
    """

    hits: np.ndarray
    branch: dict[int, int | None]
    wrong: list[int]
    covered: bool
    given: np.ndarray
    exists: np.ndarray


def _match(
    key: np.ndarray,
    answers: np.ndarray,
    tols: np.ndarray,
    sample: PoseSample,
    robot: Robot,
    position: bool,
) -> _Match:
    """Each answer row against every key branch at every point; a row that is no branch
    but whose forward kinematics reaches the pose at a point is a solution there."""
    rev = sample.revolute
    hits = np.array(
        [
            [_close(a_row, k_row, rev, t) for k_row in key]
            for a_row, t in zip(answers, tols, strict=True)
        ]
    )
    hits = hits.reshape(len(answers), len(key), sample.size)
    branch: dict[int, int | None] = {}
    wrong = []
    real = ~np.isnan(key).any(axis=2)  # (K, size): where each branch exists
    for a in range(len(answers)):
        every = np.flatnonzero(hits[a].all(axis=1))
        if len(every):
            branch[a] = int(every[0])
        elif hits[a].any(axis=0).all() or (
            tols[a].max() <= ATOL and _reaches(robot, answers[a], sample, position)
        ):
            branch[a] = None  # a solution at every pose, of a branch that changes with it
        elif (
            where := _where_real(
                hits[a], real, answers[a], partial(_reaches_at, robot, answers[a], sample, position)
            )
        ) is not None:
            branch[a] = where  # the branch wherever it exists, and no value where it does not
        else:
            wrong.append(a)
    same = np.array([[_close(k1, k2, rev, np.full(len(rev), ATOL)) for k2 in key] for k1 in key])
    given = np.asarray(hits.any(axis=0))  # (K, size): a branch the answer gives at that point
    covered = bool(
        all(
            (same[k, :, p] & given[:, p]).any() or not real[k, p]
            for k in range(len(key))
            for p in range(sample.size)
        )
    )
    right_rows = [a for a in range(len(answers)) if a not in wrong]
    solved: np.ndarray = (
        np.asarray(hits[right_rows].any(axis=0)) if right_rows else np.zeros_like(real)
    )
    each = np.array(
        [
            all((same[k, :, p] & solved[:, p]).any() or not real[k, p] for p in range(sample.size))
            for k in range(len(key))
        ]
    ).astype(bool)
    return _Match(hits, branch, wrong, covered, each, real.any(axis=1))


#: The fewest poses of a sample at which a key branch must exist for an answer to be judged
#: as that branch where it exists (fewer: no evidence; the answer must be a solution
#: everywhere, or another branch).
MIN_REAL_POSES = 8


def _where_real(
    hits: np.ndarray, real: np.ndarray, row: np.ndarray, reaches: Callable[[], np.ndarray]
) -> int | None:
    """The key branch ``k`` that the answer's ``row`` ``(size, n)`` is wherever ``k`` exists,
    having no value (NaN, or complex: NaN in the sample) exactly where ``k`` does not; or
    None.  ``hits`` ``(K, size)``: the row is branch ``k`` at that pose; ``real``
    ``(K, size)``: branch ``k`` exists there.  Where ``k`` does not exist a value is also
    right when it reaches the pose (``reaches``, computed only then): it is another
    solution there, never a wrong one.
    """
    has = ~np.isnan(row).any(axis=1)
    extra: np.ndarray | None = None
    for k in np.argsort(-(hits & real).sum(axis=1), kind="stable"):
        exists = real[k]
        if exists.sum() < MIN_REAL_POSES or not (hits[k] | ~exists).all():
            continue
        outside = has & ~exists  # a value where the branch has none
        if outside.any():
            extra = reaches() if extra is None else extra
            if not extra[outside].all():
                continue
        return int(k)
    return None


def _domain(
    m: _Match, key: np.ndarray, answers: np.ndarray, wrong: list[int], names: tuple[str, ...]
) -> Diagnosis | None:
    """The reason a wrong row is wrong when it is a key branch wherever both have values,
    but has values where that branch has none (that do not reach the pose), or none where
    it exists."""
    real = ~np.isnan(key).any(axis=2)
    for a in wrong:
        has = ~np.isnan(answers[a]).any(axis=1)
        for k in np.argsort(-(m.hits[a] & real).sum(axis=1), kind="stable"):
            both = real[k] & has
            if real[k].sum() < MIN_REAL_POSES or not both.any() or not m.hits[a, k][both].all():
                continue
            missing = int((real[k] & ~has).sum())
            extra = int((~real[k] & has).sum())
            parts = []
            if missing:
                parts.append(
                    f"has no value at {missing} of the {int(real[k].sum())} poses where the "
                    "branch exists"
                )
            if extra:
                parts.append(
                    f"has a value at {extra} poses where the branch does not exist (its square "
                    "root is of a negative number there), and that value does not reach the pose"
                )
            return Diagnosis(
                "branch_domain",
                "right only where both have a value",
                f"The answer is the branch {names[k]} wherever both have a value, but it "
                + " and ".join(parts)
                + ": a formula for one branch is real exactly where that branch exists.",
            )
    return None


def _judge(
    pk: PreparedKey, ans: IKAnswer, ik: ClosedForm, sample: PoseSample, position: bool
) -> tuple[bool, _Match, _Meta]:
    variables = list(pk.robot.variables)
    key = key_values(ik, sample.env, sample.size)
    answers, tols, meta = _values(ans, sample, variables)
    m = _match(key, answers, tols, sample, pk.robot, position)
    right = not m.wrong and (m.covered or not pk.key.question.every)
    return right, m, meta


def _correct(
    pk: PreparedKey,
    ans: IKAnswer,
    ik: ClosedForm,
    sample: PoseSample,
    result: tuple[bool, _Match, _Meta],
    position: bool,
) -> CheckResult:
    _, m, meta = result
    matched = m.branch
    q = pk.key.question
    ks = sorted({k for k in matched.values() if k is not None})
    names = list(ik_part(pk).branch_names)  # set by prepare_ik
    if q.every:
        message = f"Right: every solution is given ({len(ks)} branches)."
    elif len(ks) == 1:
        message = f"Right: the branch {names[ks[0]]}."
    elif ks:
        message = (
            "Right: each choice of the signs is a solution ("
            + "; ".join(names[k] for k in ks)
            + ")."
        )
    else:
        message = "Right: the joint values reach the pose."
    key = key_values(ik, sample.env, sample.size)
    answers, tols, _ = _values(ans, sample, list(pk.robot.variables))
    entries = _entries(pk, ans, ik, key, answers, tols, meta, sample.revolute)
    return CheckResult(q.spec, Verdict.CORRECT, message, entries, key=pk.key.name)
