"""Mistakes in inverse kinematics, each recognised by recomputing the key's steps under it.

An :class:`IKCase` holds the key's joint values for every branch and the student's values
(one row per choice of the ``±`` the student wrote) at the same poses. Each
:class:`IKMistake` recomputes the derivation with the mistake made (``atan(y/x)`` for
``atan2(y, x)``; a sign under a square root) and names it when the student's values equal
the recomputed ones; a *lost branch* is found from which branches the answer covers.
The public names are re-exported by :mod:`dhsym.checking.mistakes.registry`.

Examples
--------
>>> import dhsym
>>> swaps = atan_swaps(dhsym.load("planar2r").inverse().steps)
>>> len(swaps), [str(v) for s in swaps[:2] for v in s.values()]
(4, ['atan(p_y/p_x)', 'atan(a2*sin(theta2)/(a1 + a2*cos(theta2)))'])
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from itertools import islice
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
import sympy as sp

from dhsym.notation.printers import Notation

from ..comparing.ik_values import (
    PoseSample,
    Rewrite,
    branch_signs,
    branch_steps,
    joint_distance,
    key_values,
    same_joints,
)
from ..comparing.verdict import Diagnosis
from ._entry_mistakes import dropped_candidates, sign_candidates
from ._mistake_base import Mistake, Variants

if TYPE_CHECKING:
    from dhsym.ik.closed_form import ClosedForm

__all__ = [
    "IK_MISTAKES",
    "Atan2Swapped",
    "AtanForAtan2",
    "IKCase",
    "IKDroppedTerm",
    "IKMistake",
    "IKStepEdit",
    "IKVariants",
    "IKWrongSign",
    "LostBranch",
    "WrongRootSign",
    "StepEdits",
    "atan_swaps",
    "prepare_ik_variants",
    "root_rewrites",
]

_MAX_TERMS = 12  # terms of a radicand whose sign is flipped one at a time


#: one slip in one step: (the step's left-hand side, its right-hand side, the same with the
#: slip, what the student did)
Edit = tuple[sp.Symbol, sp.Expr, sp.Expr, str]


@dataclass(frozen=True, eq=False)
class StepEdits:
    """One :class:`IKStepEdit` kind's slips in the key's steps and the joint values of every
    key branch with each of them, ``values[e]`` ``(K, size, n)`` (slip ``edits[e]``)."""

    edits: tuple[Edit, ...]
    values: np.ndarray


@dataclass(frozen=True, eq=False)
class IKVariants:
    """The key's joint values at one pose sample, alone (``key``, ``(K, size, n)``) and under
    each catalogued mistake: the whole steps rewritten (``whole``: ``atan`` for ``atan2``, a
    sign under a root) and one slip in one step (``steps``), built when the key is prepared
    (:func:`prepare_ik_variants`), before any answer's clock starts; read-only after."""

    sample: PoseSample
    key: np.ndarray
    whole: Mapping[IKMistake, Variants]
    steps: Mapping[IKStepEdit, StepEdits]


@dataclass(frozen=True, eq=False)
class IKCase:
    """A wrong inverse-kinematics answer and its key, in numbers at the same poses.

    ``key`` is ``(K, size, n)`` (one row per choice of the signs σ, named in ``names``),
    ``answers`` ``(A, size, n)`` (one row per choice of the student's ``±``); ``wrong``
    lists the student's rows that are no branch of the key, ``matched`` the key's
    branches the answer gives; ``every`` is True when the question asks for all of them;
    ``prepared`` the mistakes' variants at the sample, built with the key (None: each
    mistake builds its own when asked).
    """

    ik: ClosedForm
    sample: PoseSample
    key: np.ndarray
    answers: np.ndarray
    wrong: tuple[int, ...]
    matched: tuple[int, ...]
    names: tuple[str, ...]
    tol: np.ndarray
    every: bool
    notation: Notation = field(default_factory=Notation)
    prepared: IKVariants | None = None

    @property
    def revolute(self) -> np.ndarray:
        """Which joints are revolute (compared modulo 2π)."""
        return self.sample.revolute


class IKMistake(Mistake):
    """A kind of inverse-kinematics mistake: variants of the key's joint values."""

    def ik_variants(self, case: IKCase) -> Iterator[tuple[np.ndarray, str]]:
        """(the key's joint values ``(K, size, n)`` under this mistake, what the student did)."""
        return iter(())

    def _variants(self, case: IKCase) -> Variants:
        found = case.prepared.whole.get(self) if case.prepared is not None else None
        return found if found is not None else tuple(self.ik_variants(case))

    def explain_ik(self, case: IKCase) -> Diagnosis | None:
        """A diagnosis when one of the student's wrong rows equals a variant's branch."""
        for vals, detail in self._variants(case):
            for a in case.wrong:
                if any(
                    same_joints(case.answers[a], v, case.revolute, case.tol, nan=True) for v in vals
                ):
                    return Diagnosis(self.kind, self.title, detail)
        return None


def _replacing(mapping: Mapping[sp.Expr, sp.Expr]) -> Rewrite:
    """The rewrite that replaces the nodes of ``mapping`` (as ``xreplace``)."""
    return lambda e: e.xreplace(mapping)


def atan_swaps(steps: Any) -> list[dict[sp.Expr, sp.Expr]]:
    """Each ``atan2(y, x)`` of the steps written ``atan(y/x)``, one at a time, then all."""
    nodes = sorted(set().union(*(st.rhs.atoms(sp.atan2) for st in steps)), key=sp.default_sort_key)
    swaps = [{n: sp.atan(n.args[0] / n.args[1])} for n in nodes]
    if len(nodes) > 1:
        swaps.append({n: sp.atan(n.args[0] / n.args[1]) for n in nodes})
    return swaps


class AtanForAtan2(IKMistake):
    """``atan(y/x)`` where ``atan2(y, x)`` belongs: the angle is 180° off in half the plane."""

    kind, title = "atan_for_atan2", "atan instead of atan2 (quadrant lost)"

    def ik_variants(self, case: IKCase) -> Iterator[tuple[np.ndarray, str]]:
        nota = case.notation
        plain = {b.symbol: 1 for b in case.ik.branches}  # no branch sign (sigma_1) in feedback
        for swap in atan_swaps(case.ik.steps):
            vals = key_values(case.ik, case.sample.env, case.sample.size, _replacing(swap))
            args = [[nota.text(a.xreplace(plain)) for a in n.args] for n in swap]
            shown = ", ".join(f"atan({y}/{x}) for atan2({y}, {x})" for y, x in args)
            yield vals, self._detail(shown)

    @staticmethod
    def _detail(what: str) -> str:
        return (
            f"The answer uses {what}: atan(y/x) gives angles between -90° and 90° only, so it "
            "is 180° off wherever x < 0; atan2(y, x) keeps the quadrant."
        )

    def explain_ik(self, case: IKCase) -> Diagnosis | None:
        found = super().explain_ik(case)
        if found is not None:
            return found
        # the student's own formula with an atan: 180° off at some poses, right at the others
        for a in case.wrong:
            for k in range(len(case.key)):
                d = joint_distance(case.answers[a], case.key[k], case.revolute)
                if np.isnan(d).any():
                    continue
                right = d <= case.tol
                half = np.abs(d - np.pi) <= case.tol
                if (right | half).all() and half.any() and case.revolute[half.any(axis=0)].all():
                    joints = [
                        str(case.ik.robot.variables[j]) for j in np.flatnonzero(half.any(axis=0))
                    ]
                    where = "everywhere" if half.all(axis=0).any() and case.sample.size > 1 else ""
                    what = f"{', '.join(joints)} is 180° off" + (f" {where}" if where else "")
                    detail = (
                        f"{what}: the quadrant is lost, as with atan(y/x) in place of "
                        "atan2(y, x) (atan gives angles between -90° and 90° only)."
                    )
                    return Diagnosis(self.kind, self.title, detail)
        return None


def root_rewrites(node: sp.Pow) -> list[sp.Expr]:
    """``sqrt(R)`` with the sign of ``R`` flipped, then of each of its terms in turn.

    >>> D = sp.Symbol("D", real=True)
    >>> root_rewrites(sp.sqrt(1 - D**2))
    [sqrt(-(1 - D**2)), sqrt(-D**2 - 1), sqrt(D**2 + 1)]
    """
    R = node.base
    out = [sp.Pow(sp.Mul(-1, R, evaluate=False), sp.S.Half, evaluate=False)]
    terms = sp.Add.make_args(R)
    if len(terms) > 1:
        out += [sp.Pow(R - 2 * t, sp.S.Half, evaluate=False) for t in terms[:_MAX_TERMS]]
    return out


class WrongRootSign(IKMistake):
    """A sign under a square root: ``sqrt(D² − 1)`` for ``sqrt(1 − D²)``, ``+d3²`` for ``−d3²``."""

    kind, title = "wrong_root_sign", "wrong sign under the square root"

    def ik_variants(self, case: IKCase) -> Iterator[tuple[np.ndarray, str]]:
        steps = case.ik.steps
        nodes = sorted(
            {p for st in steps for p in st.rhs.atoms(sp.Pow) if p.exp == sp.S.Half},
            key=sp.default_sort_key,
        )
        nota = case.notation
        for node in nodes:
            for new in root_rewrites(node):
                vals = key_values(
                    case.ik,
                    case.sample.env,
                    case.sample.size,
                    _replacing({node: new}),
                )
                detail = (
                    f"A sign under the square root is wrong: the answer takes "
                    f"sqrt({nota.text(new.base)}) where the derivation has "
                    f"sqrt({nota.text(node.base)})."
                )
                yield vals, detail


def _branch_part(name: str, j: int, count: int) -> str | None:
    """Part ``j`` of a branch name ``"right arm, elbow up, wrist not flipped"`` (``None``
    when the name has no parts, e.g. ``"branch 3"``).

    >>> _branch_part("right arm, elbow up, wrist flipped", 2, 3), _branch_part("branch 2", 0, 1)
    ('wrist flipped', None)
    """
    parts = name.split(", ")
    return parts[j] if len(parts) == count and not name.startswith("branch ") else None


class LostBranch(IKMistake):
    """Only one sign of a ``±`` given where the question asks for every solution."""

    kind, title = "lost_branch", "a branch is lost"

    def explain_ik(self, case: IKCase) -> Diagnosis | None:
        if not case.every or not case.matched:
            return None
        K = len(case.key)
        valid = [k for k in range(K) if not np.isnan(case.key[k]).any()]
        missing = [k for k in valid if k not in case.matched]
        if not missing:
            return None
        from ..comparing.ik_values import branch_signs

        signs = branch_signs(case.ik)
        parts = []
        for j, b in enumerate(case.ik.branches):
            given = {int(signs[k, j]) for k in case.matched}
            if len(given) == 1 and {int(signs[k, j]) for k in valid} == {1, -1}:
                # the branch's own name (as the IK results word it), never sigma_k
                words = {
                    _branch_part(case.names[k], j, len(case.ik.branches)) for k in case.matched
                }
                word = words.pop() if len(words) == 1 else None
                parts.append(
                    f"only the {word} branch (θ{b.joint})"
                    if word
                    else f"only one sign of the root for θ{b.joint} ({b.role})"
                )
        lost = "; ".join(parts) if parts else ", ".join(case.names[k] for k in missing)
        detail = (
            f"The answer gives {len(case.matched)} of the {len(valid)} solutions; missing: "
            f"{', '.join(case.names[k] for k in missing)}. "
            + (f"The other sign is a solution too: {lost}." if parts else "")
        )
        return Diagnosis(self.kind, self.title, detail.strip())


#: The most rewrites of one kind tried in the steps (a count: the diagnosis is the same on
#: every machine).
_MAX_REWRITES = 60
#: The key branches nearest to a wrong row that the rewrites are recomputed on.
_NEAREST = 2


class IKStepEdit(IKMistake):
    """One step of the derivation written with one slip (:meth:`rewrites`): every slip is
    recomputed on every key branch when the key is prepared (:meth:`build_edits`); a wrong
    row of the answer is compared with the key branches nearest to it only, in the steps
    that row's wrong joints need (first those its right joints do not need: a slip there
    would usually move them too), at most :data:`_MAX_REWRITES` of them."""

    def rewrites(self, case: IKCase) -> Iterator[tuple[sp.Symbol, sp.Expr, sp.Expr, str]]:
        """(a step's left-hand side, its right-hand side, the same with the slip, what the
        student did)."""
        return iter(())

    def explain_ik(self, case: IKCase) -> Diagnosis | None:
        table = self._edits(case)
        edits = table.edits
        variables = list(case.ik.robot.variables)
        for a in case.wrong:
            row = case.answers[a]
            if np.isnan(row).any(axis=1).all():
                continue  # no value anywhere: nothing a slip in one step could be told by
            with np.errstate(invalid="ignore"):
                near = joint_distance(row[None], case.key, case.revolute) <= case.tol
            counts = near.sum(axis=(1, 2))
            # the nearest branches (a wrong joint may match another branch by chance)
            for k in (int(x) for x in np.argsort(-counts, kind="stable")[:_NEAREST]):
                exists = ~np.isnan(case.key[k]).any(axis=1)  # the poses where branch k is real
                right = (near[k] | ~exists[:, None]).all(axis=0)
                needs = _needs(case.ik)
                order = [st.lhs for st in case.ik.steps]
                wrong_joints = sorted(
                    (v for v, ok in zip(variables, right) if not ok),
                    key=lambda v: order.index(v) if v in order else len(order),
                )
                if not wrong_joints:
                    continue
                right_steps = set().union(*(needs[v] for v, ok in zip(variables, right) if ok))
                core = needs[wrong_joints[0]]  # the slip is upstream of the first wrong joint
                wrong_steps = set().union(*(needs[v] for v in wrong_joints))
                # where only the wrong joints look first; then the rest of what the first wrong
                # joint needs (a right joint may depend on a step only through a sign, as on
                # atan2(0, S5)), then the rest of what the wrong joints need
                groups = (core - right_steps, core & right_steps, wrong_steps - core)
                tried = [e for g in groups for e, ed in enumerate(edits) if ed[0] in g]
                for e in tried[:_MAX_REWRITES]:
                    if same_joints(row, table.values[e, k], case.revolute, case.tol, nan=True):
                        return Diagnosis(self.kind, self.title, edits[e][3])
        return None

    def build_edits(self, case: IKCase) -> StepEdits:
        """Every slip of this kind (:meth:`rewrites`) and the joint values of every key
        branch with it, at the case's sample (built once, when the key is prepared)."""
        ik, sample = case.ik, case.sample
        edits = tuple(self.rewrites(case))
        variables = list(ik.robot.variables)
        index = {st.lhs: i for i, st in enumerate(ik.steps)}
        K = len(branch_signs(ik))
        out = np.full((len(edits), K, sample.size, len(variables)), np.nan)
        for k in range(K):
            base = branch_steps(ik, sample.env, sample.size, k)
            for e, (lhs, _, new, _) in enumerate(edits):
                got = branch_steps(ik, sample.env, sample.size, k, (index[lhs], new), base)
                for j, v in enumerate(variables):
                    if v in got:
                        out[e, k, :, j] = got[v]
        return StepEdits(edits, out)

    def _edits(self, case: IKCase) -> StepEdits:
        found = case.prepared.steps.get(self) if case.prepared is not None else None
        return found if found is not None else self.build_edits(case)


def _needs(ik: ClosedForm) -> dict[sp.Symbol, set[sp.Symbol]]:
    """Each step's left-hand side → the steps it is computed from, itself included."""
    out: dict[sp.Symbol, set[sp.Symbol]] = {}
    for st in ik.steps:
        out[st.lhs] = {st.lhs}.union(*(out[s] for s in st.rhs.free_symbols if s in out))
    for v in ik.robot.variables:
        out.setdefault(v, set())
    return out


def _shown(case: IKCase, e: sp.Expr) -> str:
    """``e`` as the feedback shows it: in the key's notation, no branch sign σ."""
    plain = {b.symbol: 1 for b in case.ik.branches}
    return case.notation.text(e.xreplace(plain))


class Atan2Swapped(IKStepEdit):
    """``atan2(x, y)`` where ``atan2(y, x)`` belongs: the angle reflected about 45°."""

    kind, title = "atan2_swapped", "atan2 arguments swapped"

    def rewrites(self, case: IKCase) -> Iterator[tuple[sp.Symbol, sp.Expr, sp.Expr, str]]:
        for st in case.ik.steps:
            for node in sorted(st.rhs.atoms(sp.atan2), key=sp.default_sort_key):
                y, x = node.args
                yield (
                    st.lhs,
                    st.rhs,
                    st.rhs.xreplace({node: sp.atan2(x, y)}),
                    f"In {case.notation.text(st.lhs)} the arguments of atan2 are swapped: "
                    f"atan2({_shown(case, y)}, {_shown(case, x)}) takes y (the sine side) "
                    "first, then x.",
                )


class IKWrongSign(IKStepEdit):
    """One term of a step with the wrong sign (at any depth), the entries' own candidates
    (:func:`~dhsym.checking.mistakes._entry_mistakes.sign_candidates`)."""

    kind, title = "wrong_sign", "wrong sign"

    def rewrites(self, case: IKCase) -> Iterator[tuple[sp.Symbol, sp.Expr, sp.Expr, str]]:
        for st in case.ik.steps:
            for new, term in islice(sign_candidates(st.rhs), 1, None):  # not the whole step
                if term is None or term.has(*(b.symbol for b in case.ik.branches)):
                    continue  # a branch sign flipped is the other branch, not a slip
                yield (
                    st.lhs,
                    st.rhs,
                    new,
                    f"In {case.notation.text(st.lhs)} the term {_shown(case, term)} has the "
                    "wrong sign.",
                )


class IKDroppedTerm(IKStepEdit):
    """One term of a step left out (an offset such as ``d1`` or ``a_x*d6``), the entries'
    own candidates (:func:`~dhsym.checking.mistakes._entry_mistakes.dropped_candidates`)."""

    kind, title = "dropped_term", "a term is missing"

    def rewrites(self, case: IKCase) -> Iterator[tuple[sp.Symbol, sp.Expr, sp.Expr, str]]:
        for st in case.ik.steps:
            for new, term in dropped_candidates(st.rhs):
                yield (
                    st.lhs,
                    st.rhs,
                    new,
                    f"In {case.notation.text(st.lhs)} the term {_shown(case, term)} is missing "
                    "(an offset left out?).",
                )


IK_MISTAKES: tuple[IKMistake, ...] = (
    AtanForAtan2(),
    WrongRootSign(),
    Atan2Swapped(),
    IKWrongSign(),
    IKDroppedTerm(),
    LostBranch(),
)


def prepare_ik_variants(
    ik: ClosedForm, sample: PoseSample, names: tuple[str, ...], notation: Notation
) -> IKVariants:
    """The key's joint values at ``sample`` alone and under every catalogued mistake
    (:data:`IK_MISTAKES`), built once, when the key is prepared: a wrong answer's diagnosis
    then only compares.

    >>> import dhsym
    >>> from dhsym.checking.comparing.ik_values import pose_sample
    >>> robot = dhsym.load("planar2r")
    >>> ik = robot.inverse()
    >>> v = prepare_ik_variants(ik, pose_sample(robot, size=8), ("up", "down"), robot.notation)
    >>> v.key.shape, sorted(m.kind for m in v.whole)
    ((2, 8, 2), ['atan_for_atan2', 'wrong_root_sign'])
    >>> sorted(m.kind for m in v.steps)
    ['atan2_swapped', 'dropped_term', 'wrong_sign']
    """
    key = key_values(ik, sample.env, sample.size)
    n = len(ik.robot.variables)
    case = IKCase(ik, sample, key, key, (), (), names, np.zeros(n), False, notation)
    whole: dict[IKMistake, Variants] = {}
    steps: dict[IKStepEdit, StepEdits] = {}
    for m in IK_MISTAKES:
        if isinstance(m, IKStepEdit):
            steps[m] = m.build_edits(case)
        elif type(m).ik_variants is not IKMistake.ik_variants:
            whole[m] = tuple(m.ik_variants(case))
    return IKVariants(sample, key, MappingProxyType(whole), MappingProxyType(steps))
