r"""Judging a matrix answer: ``^iT_j`` or one entry, the Jacobian, ``det J``, the dynamics.

Each entry is compared with the key's at fresh random points, then proven equal when
the proof is affordable (:mod:`~dhsym.checking.comparing.equivalence`); decimals are
right up to the key's :class:`~dhsym.checking.judging.rounding.Rounding`.  The usual
alternatives are accepted (``-det J``, a Jacobian in the rows ``[ω; v]``), an ``α``/``a``
index shifted by one row is named, and a wrong answer is explained by the mistakes room
(:func:`~dhsym.checking.mistakes.registry.diagnose_matrix`) at the key's diagnosis
samples (:class:`~dhsym.checking.judging.matrix_key.DiagnosisSample`).

Examples
--------
>>> from dhsym.checking.judging.key import Key, prepare
>>> from dhsym.checking.reading.answer_value import read_answer_value
>>> from dhsym.checking.reading.limits import DEFAULT_ANSWER_LIMITS as LIMITS
>>> pk = prepare(Key.load("planar2r", "T0_2[0,3]"))
>>> r = check_matrix(pk, read_answer_value(pk.form(), "a1*C1 + a2*C12"), LIMITS)
>>> r.verdict.value, r.entries[0].proof
('correct', 'exact')
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from dhsym.notation.printers import Notation

from ..comparing.equivalence import (
    EXACT_RTOL,
    Sample,
    agree_precisely,
    cancellation,
    close,
    prove_entry,
    values,
)
from ..comparing.verdict import CheckResult, Diagnosis, EntryResult, Verdict
from ..mistakes.registry import QUESTION_MISTAKES, MatrixCase, diagnose_matrix, mistakes_for
from ..reading.answer_names import NameContext
from ..reading.answer_value import MatrixAnswer, ReadCell
from ..reading.limits import AnswerLimits, check_time
from ..reading.questions import Question
from .key import PreparedKey
from .matrix_key import DeterminantPart, DiagnosisSample, DynamicsPart, MatrixPart, sample_for
from .rounding import rounding_accepts
from .screw_key import ScrewPart, axes_listed

__all__ = ["MISTAKES", "check_matrix", "matrix_part"]


def matrix_part(pk: PreparedKey) -> MatrixPart:
    """The prepared part of a matrix key (a matrix answer is read only for one)."""
    part = pk.part
    if not isinstance(part, MatrixPart):
        raise TypeError(f"a matrix answer to a key prepared as {type(part).__name__}")
    return part


#: the mistakes tried on a wrong answer, by kind of question (the registry's table)
MISTAKES = QUESTION_MISTAKES


def _shown(cell: str) -> str:
    cell = " ".join(cell.split())
    return cell if len(cell) <= 200 else cell[:199] + "…"


def _compare(
    pk: PreparedKey, ans: sp.ImmutableMatrix, cells: tuple[ReadCell, ...], limits: AnswerLimits
) -> tuple[list[EntryResult], list[tuple[int, int]], list[sp.Basic]]:
    """Entry results, wrong positions and the unknown symbols, at fresh random points.

    Per entry: equal at every point → the exact proof if affordable (``exact``), else the
    numbers stand (``numeric``); a proof that says "not equal" is checked once more with
    60-digit numbers.  Not equal → right up to rounding if the key's :class:`Rounding`
    accepts its decimals (``rounding``).
    """
    part = matrix_part(pk)
    q, nota, expected, expected_valued = (
        pk.key.question,
        pk.robot.notation,
        part.expected,
        part.expected_valued,
    )
    unknown = sorted(ans.free_symbols - pk.names.symbols, key=sp.default_sort_key)
    valued = sample_for(pk.key.table, ans) == "valued"
    value_map = pk.key.table.value_map
    sample = Sample.random(part.symbols | set(unknown), fixed=value_map if valued else None)
    # one memo for both at this sample: the answer's subtrees that are the key's (every
    # entry of a right answer written as the key is) take the key's values, not a new walk
    memo: dict[object, np.ndarray] = {}
    kv = values(expected, sample, memo)
    av = values(ans, sample, memo)
    near = np.asarray(close(av, kv, EXACT_RTOL, axis=0))
    entries: list[EntryResult] = []
    wrong: list[tuple[int, int]] = []
    keyed: dict[sp.Basic, int] | None = None  # the key's entries, when an entry is wrong
    for i in range(expected.rows):
        for j in range(expected.cols):
            a, e = ans[i, j], expected[i, j]
            k = i * expected.cols + j
            proof, note = "", ""
            check_time()  # the answer's deadline (see reading.limits.time_limit)
            target = expected_valued[i, j] if valued else e
            if near[i, j]:
                exact = prove_entry(a, target, limits, agreed=True) if not unknown else None
                if exact is None or (exact is False and agree_precisely(a, target)):
                    proof = "numeric"
                elif exact:
                    proof = "exact"
            elif not unknown and cancellation(a, sample, av[:, i, j] - kv[:, i, j], memo):
                # the doubles cannot tell: their difference is the rounding error of the sums
                # the answer cancels; 60-digit numbers or the exact proof decide
                exact = prove_entry(a, target, limits)
                if exact:
                    proof = "exact"
                elif agree_precisely(a, target):
                    proof = "numeric"
            if not proof and cells[k].template is not None:
                note = _rounded(pk, cells[k], sample, kv[:, i, j])
                proof = "rounding" if note else ""
            if not proof:
                wrong.append((i, j))
            where = (q.entry[0] + 1, q.entry[1] + 1) if q.entry else (i + 1, j + 1)
            e_text, e_latex = part.expected_text[k]
            raw = cells[k].text
            if proof or len(raw) > 160:  # right, or long: what the student wrote
                a_text, a_latex = _shown(raw), ""
            else:  # wrong: the student's entry in the key's notation
                if keyed is None:
                    keyed = {entry: n for n, entry in enumerate(expected)}
                a_text, a_latex = _printed(a, keyed, part, nota)
            # a wrong entry's feedback shows the key's entry, converted once per key
            shown = part.expected_mathml.entry(k) if not proof else ""
            entries.append(
                EntryResult(
                    *where, bool(proof), a_text, e_text, a_latex, e_latex, proof, note, shown
                )
            )
    return entries, wrong, unknown


def _printed(
    a: sp.Basic, keyed: dict[sp.Basic, int], part: MatrixPart, nota: Notation
) -> tuple[str, str]:
    """A wrong entry in the key's notation, as (text, LaTeX): an entry that is one of the
    key's entries (a transposed or swapped matrix) takes that entry's forms, printed when
    the key was prepared by the same notation (the same text); else it is printed.

    >>> from dhsym.checking.judging.key import Key, prepare
    >>> pk = prepare(Key.load("planar2r", "T0_2"))
    >>> part, nota = matrix_part(pk), pk.robot.notation
    >>> keyed = {e: n for n, e in enumerate(part.expected)}
    >>> _printed(part.expected[0, 1], keyed, part, nota) == part.expected_text[1]
    True
    >>> _printed(sp.Float(2.0), {sp.Integer(2): 0}, part, nota)  # equal in sympy, not the same
    ('2.00000000000000', '2.0')
    """
    n = keyed.get(a)
    if n is not None and not (a.has(sp.Float) or part.expected[n].has(sp.Float)):
        return part.expected_text[n]
    return nota.text(a), nota.latex(a)


def _rounded(pk: PreparedKey, cell: ReadCell, sample: Sample, key: np.ndarray) -> str:
    """How the cell, written with decimals, is right up to rounding under the key's rule,
    or ``""``."""
    assert cell.template is not None
    env = sample.extended(cell.template.free_symbols - set(sample.symbols)).env
    how = rounding_accepts(pk.key.rounding, cell.template, cell.literals, env, sample.size, key)
    return how or ""


def _diagnosis_values(
    d: DiagnosisSample, ans: sp.ImmutableMatrix, unknown: list[sp.Basic]
) -> tuple[Sample, np.ndarray, np.ndarray]:
    """The key's diagnosis sample (fixed per key: the mistakes' variants were built there
    when the key was prepared), extended with the unknown symbols, the key's and the
    answer's values there."""
    sample = d.sample.extended(unknown)
    return sample, d.key_values, values(ans, sample)


def _index_renames(unknown: list[sp.Symbol], names: NameContext) -> dict[sp.Symbol, sp.Symbol]:
    """``alpha_i`` → ``alpha_im1`` (and back) when only the other index is a key symbol."""
    out = {}
    for s in unknown:
        for a, b in (("_i", "_im1"), ("_im1", "_i"), ("i", "im1")):
            if s.name.endswith(a):
                target = names.symbol(s.name[: -len(a)] + b)
                if target is not None:
                    out[s] = target
                    break
    return out


def _shape_lead(pk: PreparedKey, answer: MatrixAnswer) -> tuple[Diagnosis, ...]:
    """What the answer's shape tells: a Jacobian one column short left out the column of
    a prismatic joint (the reader put zeros there)."""
    k = answer.missing_column
    if k is None:
        return ()
    n = answer.shape[1]
    var = pk.robot.variables[k]
    return (
        Diagnosis(
            "missing_column",
            "column of a prismatic joint missing",
            f"The answer has {n - 1} columns; J has one per joint, {n}: column {k + 1} belongs "
            f"to the prismatic joint {var}, whose column is its axis over zero (no rotation).",
            tuple((i + 1, k + 1) for i in range(6)),
        ),
    )


def check_matrix(pk: PreparedKey, answer: MatrixAnswer, limits: AnswerLimits) -> CheckResult:
    """Check a matrix answer (or one entry), as read, against the key (see the module text)."""
    part = matrix_part(pk)
    key, q, nota = pk.key, pk.key.question, pk.robot.notation
    ans, cells, shape_lead = answer.matrix, answer.cells, _shape_lead(pk, answer)
    entries, wrong, unknown = _compare(pk, ans, cells, limits)
    total = len(entries)
    lead: tuple[Diagnosis, ...] = ()
    renames = _index_renames(unknown, pk.names)
    if renames and len(renames) == len(unknown):
        shown = ", ".join(f"{a} for {b}" for a, b in renames.items())
        lead = (
            Diagnosis(
                "index_shift",
                "α/a index shifted by one row",
                (
                    f"The answer uses {shown}: in the {key.table.convention.value} convention "
                    "link i "
                    "has the parameters of this table's row i."
                ),
            ),
        )
        ans = ans.xreplace(renames)
        entries, wrong, unknown = _compare(pk, ans, cells, limits)
        if not wrong:
            return CheckResult(
                q.spec,
                Verdict.INCORRECT,
                f"The answer is right except for the indices. {lead[0].detail}",
                tuple(entries),
                lead,
                key=key.name,
            )
    if wrong and q.kind == "det":
        flipped = _compare(pk, -ans, cells, limits)
        if not flipped[1]:  # -det J: the rows of J in the other order ([ω; v]) or the joints
            return CheckResult(
                q.spec,
                Verdict.CORRECT,
                "The determinant is right up to its sign, which depends on the order of the "
                "rows of J ([v; ω] or [ω; v]) and of its columns; the singular configurations "
                "are the same.",
                tuple(flipped[0]),
                key=key.name,
            )
    if wrong and q.kind == "jacobian" and q.entry is None and ans.rows == 6:
        cols = ans.cols  # [ω; v]: the same Jacobian with the angular rows first
        swapped = sp.ImmutableMatrix.vstack(ans[3:, :], ans[:3, :])
        order = [*range(3 * cols, 6 * cols), *range(3 * cols)]
        other = _compare(pk, swapped, tuple(cells[k] for k in order), limits)
        if not other[1]:
            return CheckResult(
                q.spec,
                Verdict.CORRECT,
                "The Jacobian is right, in the row order [ω; v] (angular velocity first); "
                "the key writes [v; ω]. Both are used: say which one you write.",
                tuple(other[0]),
                alternative="rows [ω; v]",
                key=key.name,
            )
    if (
        wrong
        and q.kind == "screw"
        and q.part in ("S", "B")
        and ans.shape == (6, 6)
        and isinstance(part, ScrewPart)
        and axes_listed(part, key.table, ans)
    ):  # six axes listed one per row, as S_1 … S_6 are often printed: judged as listed
        ans, cells = (
            sp.ImmutableMatrix(ans.T),
            tuple(cells[(k % 6) * 6 + k // 6] for k in range(36)),
        )
        listed = _compare(pk, ans, cells, limits)
        entries, wrong, unknown = listed
        if not wrong:
            return CheckResult(
                q.spec,
                Verdict.CORRECT,
                "The screw axes are right, listed one per row; as a matrix they are its "
                "columns (rows [ω; v]).",
                tuple(listed[0]),
                alternative="axes as rows",
                key=key.name,
            )
    if not wrong and not shape_lead:
        what = f"{_one(q)} is right" if total == 1 else f"All {total} entries are right"
        rounded = [e for e in entries if e.proof == "rounding"]
        if rounded:
            how = "; ".join(sorted({e.rounding for e in rounded}))
            some = " up to rounding" if total == 1 else f"; {len(rounded)} of them up to rounding"
            what = f"{what}{some} ({how})"
        return CheckResult(q.spec, Verdict.CORRECT, what + ".", tuple(entries), key=key.name)
    d = part.diagnosis(key.table, ans)  # the key's diagnosis sample and its variants
    sample, kv, av = _diagnosis_values(d, ans, unknown)
    case = MatrixCase(
        tuple(key.table.rows),
        key.table.convention,
        q.frm,
        q.to,
        q.entry,
        part.expected,
        ans,
        sample,
        kv,
        av,
        tuple(wrong),
        nota,
        robot=pk.robot,
        singularities=part.singularities if isinstance(part, DeterminantPart) else None,
        dynamics_variants=part.variants if isinstance(part, (DynamicsPart, ScrewPart)) else (),
        prepared=d.variants,
    )
    diagnoses = shape_lead + lead + diagnose_matrix(case, mistakes_for(q.kind))
    if unknown:
        names = ", ".join(str(s) for s in unknown)
        known = ", ".join(str(s) for s in sorted(pk.names.symbols, key=sp.default_sort_key))
        diagnoses = (
            Diagnosis(
                "unknown_symbol",
                "unknown symbols",
                (
                    f"The answer uses {names}, which this robot does not have "
                    f"(its symbols: {known})."
                ),
            ),
        ) + diagnoses
    verb = "is" if len(wrong) == 1 else "are"
    what = f"{_one(q)} is wrong" if total == 1 else f"{len(wrong)} of {total} entries {verb} wrong"
    first = next(
        (d for d in diagnoses if d.kind not in ("unexplained", "unknown_symbol")), diagnoses[0]
    )
    message = f"{what}. Most likely: {first.title}. {first.detail}"
    return CheckResult(q.spec, Verdict.INCORRECT, message, tuple(entries), diagnoses, key=key.name)


def _one(q: Question) -> str:
    """How a one-cell answer is called: the determinant is an answer, not an entry."""
    return "Your determinant" if q.kind == "det" else "The entry"
