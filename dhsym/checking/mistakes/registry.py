r"""The catalogue of classic DH mistakes, each recognised by recomputing the key under it.

A :class:`Mistake` takes the key (its table rows, the frames asked, the random
sample) and produces *variants*: what a student who made that mistake would have
written.  When the student's wrong entries (or wrong table) equal a variant, the
mistake is the diagnosis.  Matrix variants are numbers at the sample points
(:func:`dhsym.kinematics.numeric.word_product` of the core's link words); table
variants are tables compared cell by cell or as robots
(:func:`dhsym.checking.judging.table_match.compare_tables`).

Kinds: ``wrong_sign`` (at any depth), ``sin_cos_swapped``, ``dropped_term``,
``wrong_joint_index``, ``missing_length``, ``transposed`` (also one 3×3 block),
``other_convention``,
``degrees_as_radians``, ``index_shift``, ``offset_missing``, ``reverse_order``,
``single_wrong_row``; for the Jacobian ``tool_frame``, ``next_axis``,
``prismatic_as_revolute`` (and ``missing_column``, from the shape of the answer); for
``det J`` ``missing_factor``, ``block_determinant``; for inverse kinematics
``atan_for_atan2``, ``lost_branch``, ``wrong_root_sign``; for the dynamics questions
(``M``, ``g``, ``C``, ``c_ijk``, ``tau``) ``parallel_axis``, ``rotational_energy``,
``gravity_direction``, ``l_for_lc``, ``christoffel_indices``, ``inertia_frame``
(:mod:`dhsym.checking.mistakes._dynamics_mistakes`).

Examples
--------
>>> [m.kind for m in MATRIX_MISTAKES][:3]
['transposed', 'other_convention', 'reverse_order']
>>> OffsetMissing().title
'joint offset missing'
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from dhsym.model.table import Convention

from ..judging.table_match import Chain, compare_tables
from ..judging.verdict import Diagnosis
from ..reading.limits import check_time
from ._dynamics_mistakes import DynamicsMistake, dynamics_mistakes
from ._entry_mistakes import (
    DroppedTerm,
    MissingLength,
    SinCosSwapped,
    WrongJointIndex,
    WrongSign,
)
from ._ik_mistakes import IK_MISTAKES, AtanForAtan2, IKCase, IKMistake, LostBranch, WrongRootSign
from ._jacobian_mistakes import (
    DET_MISTAKES,
    JACOBIAN_MISTAKES,
    BlockDeterminant,
    MissingFactor,
    NextAxis,
    PrismaticColumn,
    ToolFrame,
)
from ._mistake_base import MatrixCase, Mistake, TableCase
from ._row_mistakes import DegreesAsRadians, IndexShift, OffsetMissing, SingleWrongRow

__all__ = [
    "DET_MISTAKES",
    "IK_MISTAKES",
    "JACOBIAN_MISTAKES",
    "AtanForAtan2",
    "BlockDeterminant",
    "BlockTransposed",
    "DroppedTerm",
    "DynamicsMistake",
    "dynamics_mistakes",
    "DegreesAsRadians",
    "IKCase",
    "IKMistake",
    "LostBranch",
    "MissingFactor",
    "NextAxis",
    "PrismaticColumn",
    "ToolFrame",
    "WrongRootSign",
    "IndexShift",
    "MATRIX_MISTAKES",
    "MatrixCase",
    "MissingLength",
    "Mistake",
    "OffsetMissing",
    "OtherConvention",
    "ReverseOrder",
    "SinCosSwapped",
    "SingleWrongRow",
    "TABLE_MISTAKES",
    "TableCase",
    "Transposed",
    "WrongJointIndex",
    "WrongSign",
    "diagnose_matrix",
    "diagnose_table",
]

_FORMULA = {
    Convention.STANDARD: "A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)",
    Convention.MODIFIED: "^{i-1}T_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)",
}


class Transposed(Mistake):
    """The matrix (or its rotation part) written transposed."""

    kind, title = "transposed", "matrix transposed"

    def matrix_variants(self, case):
        full = np.asarray(case.cache.setdefault(("full", case.sample.origin), _full(case)))
        yield (
            case.project(np.swapaxes(full, 1, 2)),
            (
                "Rows and columns are exchanged: the columns of ^iT_j are the axes n, s, a of "
                "frame j and its position p, written in frame i."
            ),
        )
        rot = full.copy()
        rot[:, :3, :3] = np.swapaxes(full[:, :3, :3], 1, 2)
        yield (
            case.project(rot),
            (
                "The rotation part is transposed (that is the inverse rotation, R^T = R^-1); "
                "the columns of R are the axes of the new frame in the old one."
            ),
        )


class BlockTransposed(Mistake):
    """One 3×3 block of a 6×n Jacobian written transposed (the rotation block of ^iT_j
    is the mistake ``transposed`` of a whole matrix)."""

    kind, title = "transposed", "one 3×3 block transposed"

    def matrix_variants(self, case):
        vals = np.asarray(case.key_values)
        if vals.ndim != 3 or vals.shape[1] != 6:
            return
        for r in (0, 3):
            for c in range(0, vals.shape[2] - 2, 3):
                out = vals.copy()
                out[:, r : r + 3, c : c + 3] = np.swapaxes(vals[:, r : r + 3, c : c + 3], 1, 2)
                rows = "linear" if r == 0 else "angular"
                yield (
                    out,
                    (
                        f"The {rows} block of columns {c + 1} to {c + 3} is transposed: column "
                        "i of J holds the contribution of joint i."
                    ),
                )


def _full(case: MatrixCase) -> np.ndarray:
    """Values of the full 4×4 key matrix at the sample (also for entry questions)."""
    return case.full_values(case.rows, case.convention)


class ReverseOrder(Mistake):
    """Link matrices (or the four elementary factors) multiplied in reverse order."""

    kind, title = "reverse_order", "product in reverse order"

    def matrix_variants(self, case):
        if abs(case.to - case.frm) > 1:
            yield (
                case.chain_values(case.rows, case.convention, "links"),
                (
                    f"The link matrices are multiplied in reverse order: ^{case.frm}T_{case.to} = "
                    f"A_{min(case.frm, case.to) + 1} ⋯ A_{max(case.frm, case.to)}, first link on "
                    "the left (each factor is expressed in the frame before it)."
                ),
            )
        yield (
            case.chain_values(case.rows, case.convention, "factors"),
            (
                "The elementary transforms are multiplied in reverse order: for this convention "
                f"{_FORMULA[case.convention]}, left to right."
            ),
        )


class OtherConvention(Mistake):
    """The other DH convention's link matrix (or table) used."""

    kind, title = "other_convention", "other DH convention"

    def matrix_variants(self, case):
        other = _other(case.convention)
        yield (
            case.chain_values(case.rows, other),
            (
                f"This is the {other.value} link matrix ({_FORMULA[other]}); the question uses "
                f"the {case.convention.value} convention: {_FORMULA[case.convention]}."
            ),
        )

    def explain_table(self, case):
        key_conv, other = case.key.convention, _other(case.key.convention)
        declared = case.answer.convention is not key_conv
        valid = (
            f"Your table is a valid {other.value}-convention table of this robot, but the "
            f"question asks for the {key_conv.value} convention ({_FORMULA[key_conv]})."
        )
        tries = [(Chain(case.answer.rows, other), valid)]
        if declared:
            tries = [
                (case.answer, valid),
                (
                    Chain(case.answer.rows, key_conv),
                    (
                        f"The columns are labelled for the {other.value} convention, "
                        "but the values "
                        f"are those of the {key_conv.value} convention ({_FORMULA[key_conv]})."
                    ),
                ),
            ]
        for target, detail in tries:
            m = compare_tables(case.key, target, tool_free=case.tool_free, values=case.values)
            if m.same_robot:
                return Diagnosis(self.kind, self.title, detail)
        return None


def _other(c: Convention) -> Convention:
    return Convention.MODIFIED if c is Convention.STANDARD else Convention.STANDARD


MATRIX_MISTAKES: tuple[Mistake, ...] = (
    Transposed(),
    OtherConvention(),
    ReverseOrder(),
    IndexShift(),
    OffsetMissing(),
    DegreesAsRadians(),
)
ENTRY_MISTAKES: tuple[Mistake, ...] = (
    WrongSign(),
    SinCosSwapped(),
    WrongJointIndex(),
    MissingLength(),
    DroppedTerm(),
)
TABLE_MISTAKES: tuple[Mistake, ...] = (
    OtherConvention(),
    IndexShift(),
    OffsetMissing(),
    DegreesAsRadians(),
    WrongSign(),
    SingleWrongRow(),
)


def diagnose_matrix(
    case: MatrixCase, mistakes: tuple[Mistake, ...] = MATRIX_MISTAKES
) -> tuple[Diagnosis, ...]:
    """Explain a wrong matrix: one mistake for all wrong entries, else entry by entry.

    ``mistakes`` are the kinds of the question (``^iT_j``: :data:`MATRIX_MISTAKES`;
    ``J``: :data:`JACOBIAN_MISTAKES`; ``det J``: :data:`DET_MISTAKES`).
    """
    for m in mistakes:
        check_time()  # the answer's deadline (see _limits.time_limit)
        d = m.explain_matrix(case)
        if d is not None:
            return (d,)
    found, left = [], list(case.wrong)
    for m in (*ENTRY_MISTAKES, *mistakes):
        check_time()
        if not left:
            break
        sub = replace(case, wrong=tuple(left))
        d = m.explain_matrix(sub, partial=True)
        if d is not None:
            found.append(d)
            done = set(d.entries)
            left = [p for p in left if case.label(p) not in done]
    if left:
        where = ", ".join(case.where(p) for p in left)
        found.append(
            Diagnosis(
                "unexplained",
                "wrong entry",
                (
                    f"Entry {where} is wrong and none of the usual mistakes explains it: "
                    "compare it "
                    "with the correct entry below, term by term."
                ),
                tuple(case.label(p) for p in left),
            )
        )
    return tuple(found)


def diagnose_table(case: TableCase) -> tuple[Diagnosis, ...]:
    """Explain a wrong table with the first table mistake that reproduces it."""
    for m in TABLE_MISTAKES:
        check_time()
        d = m.explain_table(case)
        if d is not None:
            return (d,)
    return ()
