r"""The registry of classic DH mistakes: which are tried for which question, and in what order.

The mistakes themselves live in plug-in modules by family (table rows, matrix entries,
whole matrices, Jacobians, inverse kinematics, dynamics, products of exponentials); this
module lists them per kind of question (:data:`MATRIX_MISTAKES`, :data:`TABLE_MISTAKES`,
:data:`JACOBIAN_MISTAKES`, :data:`DET_MISTAKES`, :data:`IK_MISTAKES`, :data:`SCREW_MISTAKES`),
re-exports them as the public catalogue, and finds the one that explains a wrong answer
(:func:`diagnose_matrix`, :func:`diagnose_table`).

A :class:`Mistake` takes the key (its table rows, the frames asked, the random
sample) and produces *variants*: what a student who made that mistake would have
written.  When the student's wrong entries (or wrong table) equal a variant, the
mistake is the diagnosis.  Matrix variants are numbers at the sample points
(:func:`dhsym.kinematics.numeric.word_product` of the core's link words); table
variants are tables compared cell by cell or as robots
(:func:`dhsym.checking.comparing.table_match.compare_tables`).

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
(:mod:`dhsym.checking.mistakes._dynamics_mistakes`); for a product of exponentials (``S``,
``B``, ``Mhome``, ``Js``, ``Jb``, ``T(theta)``) ``omega_cross_q``, ``body_for_space``,
``space_for_body``, ``wrong_home``, ``rows_swapped`` (:data:`SCREW_MISTAKES`,
:mod:`dhsym.checking.mistakes._screw_mistakes`);
for the trajectory and gain questions
(``traj a<k>``, ``tb``, ``kp``, ``kd``) ``tf_for_tf_squared``,
``boundary_velocity_left_out``, ``blend_time_wrong_limit``, ``kd_without_two``,
``kp_not_squared`` (:data:`TRAJECTORY_MISTAKES`, from
:mod:`dhsym.checking.mistakes.trajectory_mistakes`).

Examples
--------
>>> [m.kind for m in MATRIX_MISTAKES][:3]
['transposed', 'other_convention', 'reverse_order']
>>> OffsetMissing().title
'joint offset missing'
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

from ..comparing.verdict import Diagnosis
from ..reading.limits import check_time
from ._dynamics_mistakes import DynamicsMistake, dynamics_mistakes, variant_matrices
from ._entry_mistakes import (
    PAIR_BUDGET,
    DroppedTerm,
    EntryMistake,
    MissingLength,
    SinCosSwapped,
    WrongJointIndex,
    WrongSign,
    explain_pairs,
)
from ._ik_mistakes import (
    IK_MISTAKES,
    AtanForAtan2,
    IKCase,
    IKMistake,
    IKStepEdit,
    IKVariants,
    LostBranch,
    StepEdits,
    WrongRootSign,
    prepare_ik_variants,
)
from ._jacobian_mistakes import (
    DET_MISTAKES,
    JACOBIAN_MISTAKES,
    BlockDeterminant,
    MissingFactor,
    NextAxis,
    PrismaticColumn,
    ToolFrame,
)
from ._matrix_mistakes import BlockTransposed, OtherConvention, ReverseOrder, Transposed
from ._mistake_base import MatrixCase, Mistake, TableCase, prepare_variants

# Variants is a type alias: re-exported here, kept out of __all__ (autodoc cannot format it)
from ._mistake_base import Variants as Variants
from ._row_mistakes import (
    DegreesAsRadians,
    IndexShift,
    OffsetMissing,
    SingleWrongRow,
    explain_table_pairs,
)
from ._screw_mistakes import SCREW_MISTAKES, ScrewMistake, screw_variants
from .trajectory_mistakes import TRAJECTORY_MISTAKES, TrajectoryMistake

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
    "IKStepEdit",
    "IKVariants",
    "LostBranch",
    "MissingFactor",
    "NextAxis",
    "PrismaticColumn",
    "ToolFrame",
    "WrongRootSign",
    "IndexShift",
    "ENTRY_MISTAKES",
    "MATRIX_MISTAKES",
    "MatrixCase",
    "PAIR_BUDGET",
    "QUESTION_MISTAKES",
    "MissingLength",
    "Mistake",
    "OffsetMissing",
    "OtherConvention",
    "ReverseOrder",
    "SinCosSwapped",
    "SingleWrongRow",
    "SCREW_MISTAKES",
    "ScrewMistake",
    "TABLE_MISTAKES",
    "TABLE_PAIR_MISTAKES",
    "StepEdits",
    "TableCase",
    "TRAJECTORY_MISTAKES",
    "TrajectoryMistake",
    "Transposed",
    "WrongJointIndex",
    "WrongSign",
    "diagnose_matrix",
    "diagnose_table",
    "mistakes_for",
    "prepare_ik_variants",
    "prepare_variants",
    "screw_variants",
    "variant_matrices",
]

MATRIX_MISTAKES: tuple[Mistake, ...] = (
    Transposed(),
    OtherConvention(),
    ReverseOrder(),
    IndexShift(),
    OffsetMissing(),
    DegreesAsRadians(),
)
ENTRY_MISTAKES: tuple[EntryMistake, ...] = (
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
#: the table mistakes composed in pairs (two slips in one table; one wrong row is tried as
#: the second slip after these, :func:`diagnose_table`)
TABLE_PAIR_MISTAKES: tuple[Mistake, ...] = (
    IndexShift(),
    OffsetMissing(),
    DegreesAsRadians(),
    WrongSign(),
)

#: the mistakes tried on a wrong matrix answer, by kind of question (the others: the
#: matrix ones, :data:`MATRIX_MISTAKES`)
QUESTION_MISTAKES: Mapping[str, tuple[Mistake, ...]] = {
    "jacobian": (*JACOBIAN_MISTAKES, BlockTransposed()),
    "det": DET_MISTAKES,
    "dynamics": dynamics_mistakes(),
    "screw": SCREW_MISTAKES,
}


def mistakes_for(kind: str) -> tuple[Mistake, ...]:
    """The whole-matrix mistakes tried on a wrong answer to a question of ``kind``.

    >>> [m.kind for m in mistakes_for("jacobian")]
    ['tool_frame', 'next_axis', 'prismatic_column', 'transposed']
    >>> mistakes_for("matrix") == MATRIX_MISTAKES
    True
    """
    return QUESTION_MISTAKES.get(kind, MATRIX_MISTAKES)


def diagnose_matrix(
    case: MatrixCase, mistakes: tuple[Mistake, ...] = MATRIX_MISTAKES
) -> tuple[Diagnosis, ...]:
    """Explain a wrong matrix: one mistake for all wrong entries, else entry by entry,
    each mistake named once with the entries it explains, then two slips of the entries'
    kinds together (:func:`~dhsym.checking.mistakes._entry_mistakes.explain_pairs`: by
    what each slip changes, then by composing within :data:`PAIR_BUDGET` candidates) in
    the entries still unexplained: of two kinds, then two of one kind (within another
    :data:`PAIR_BUDGET`).

    ``mistakes`` are the kinds of the question (``^iT_j``: :data:`MATRIX_MISTAKES`;
    ``J``: :data:`JACOBIAN_MISTAKES`; ``det J``: :data:`DET_MISTAKES`).
    """
    for m in mistakes:
        check_time()  # the answer's deadline (see reading.limits.time_limit)
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
    for same in (False, True):  # two slips in one place: of two kinds, then of one kind
        if not left:
            break
        pairs = explain_pairs(replace(case, wrong=tuple(left)), ENTRY_MISTAKES, same=same)
        found.extend(pairs)
        done = {e for d in pairs for e in d.entries}
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
    """Explain a wrong table with the first table mistake that reproduces it, else with two
    slips that do (:func:`~dhsym.checking.mistakes._row_mistakes.explain_table_pairs`, two
    diagnoses naming each other, within :data:`PAIR_BUDGET` tables compared):
    two named slips of :data:`TABLE_PAIR_MISTAKES`, then one of them with one wrong cell,
    or two rows with one wrong cell each, are tried before the catch-all of one wrong row
    (a twist's sign flipped and written in radians in one row is both, not just a wrong
    row).

    >>> import dhsym
    >>> import sympy as sp
    >>> from dhsym.checking.comparing.table_match import Chain
    >>> key = dhsym.load_table("puma560")
    >>> rows = list(key.rows)
    >>> rows[1], rows[4] = replace(rows[1], a=-rows[1].a), replace(rows[4], alpha=sp.pi / 2)
    >>> answer = Chain(tuple(rows), key.convention)
    >>> [(d.kind, d.rows) for d in diagnose_table(TableCase(key, answer))]
    [('wrong_sign', (2,)), ('wrong_sign', (5,))]
    """
    for m in TABLE_MISTAKES:
        check_time()
        if isinstance(m, SingleWrongRow):  # the catch-all of one row: two named slips first
            pairs = explain_table_pairs(case, TABLE_PAIR_MISTAKES)
            if pairs:
                return pairs
        d = m.explain_table(case)
        if d is not None:
            return (d,)
    return ()
