r"""Checking one answer against a key: read it once, then the kind's judge compares and explains.

The key is prepared once (:mod:`~dhsym.checking.judging.key`); the answer is read into
the value its question expects (:func:`~dhsym.checking.reading.answer_value.read_answer_value`)
and judged by its kind's judge: :mod:`~dhsym.checking.judging.matrix_judge`,
:mod:`~dhsym.checking.judging.table_judge` or :mod:`~dhsym.checking.judging.ik_check`;
an answer to a trajectory or gain question (its key a profile,
:class:`~dhsym.checking.judging.trajectory_key.TrajectoryKey`) by
:mod:`~dhsym.checking.judging.trajectory_judge`.

Examples
--------
>>> key = Key.load("planar2r", "T0_2")
>>> r = check_answer(key, r"\begin{bmatrix} C_{12} & -S_{12} & 0 & a_1 C_1 + a_2 C_{12} \\"
...                       r" S_{12} & C_{12} & 0 & a_1 S_1 + a_2 S_{12} \\ 0&0&1&0 \\ 0&0&0&1"
...                       r"\end{bmatrix}")
>>> r.verdict.value, r.entries[3].proof
('correct', 'exact')
>>> r = check_answer(key, "[[C12, -S12, 0, a1*C1 - a2*C12], [S12, C12, 0, a1*S1 + a2*S12],"
...                       " [0, 0, 1, 0]]")
>>> r.verdict.value, r.kinds, r.diagnoses[0].entries
('incorrect', ('wrong_sign',), ((1, 4),))
>>> check_answer(key, "__import__('os').system('ls')").verdict.value
'unreadable'
"""

from __future__ import annotations

from dhsym.errors import DHError

from ..comparing.verdict import CheckResult, Verdict
from ..reading.answer_value import IKAnswer, TableAnswer, read_answer_value
from ..reading.limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, CheckTimeout, time_limit
from .ik_check import check_ik
from .key import AnyKey, Key, PreparedKey, PreparedKeys, prepare
from .matrix_judge import check_matrix
from .table_judge import check_table
from .trajectory_judge import check_trajectory
from .trajectory_key import PreparedTrajectory, TrajectoryKey, prepare_trajectory

__all__ = ["check_answer"]


def _unreadable(key: AnyKey, reason: str) -> CheckResult:
    return CheckResult(
        key.question.spec,
        Verdict.UNREADABLE,
        f"The answer could not be read: {reason}",
        reason=reason,
        key=key.name,
    )


def check_answer(
    key: AnyKey,
    answer: str | bytes,
    *,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    keys: PreparedKeys | None = None,
) -> CheckResult:
    """Check one answer (text or bytes, untrusted) against ``key``.

    Never raises on bad answers: they come back ``unreadable`` with the reason (parse
    errors, limits, answers too large to process). A key that cannot be prepared raises
    its :class:`~dhsym.errors.DHError`; an exception of any other kind is a bug of dhsym
    and is raised too, never disguised as an unreadable answer.
    The whole check runs under ``limits.seconds`` (where a time limit is possible).
    ``keys`` is the caller's map of prepared keys (a grading worker's): without it the
    key is prepared for this one check.
    """
    # a fault of the key raises here: it is never the answer's
    pk: PreparedKey | PreparedTrajectory
    if isinstance(key, TrajectoryKey):
        pk = keys.get(key) if keys is not None else prepare_trajectory(key)
    elif isinstance(key, Key):
        pk = keys.get(key) if keys is not None else prepare(key)
    else:
        raise DHError(
            "check_answer: expected a Key (Key.load(robot, question)) or a TrajectoryKey, "
            f"got {type(key).__name__}"
        )
    try:
        with time_limit(limits.seconds):
            if isinstance(pk, PreparedTrajectory):  # one expression, read by its judge
                return check_trajectory(pk, answer, limits)
            read = read_answer_value(pk.form(), answer, limits)  # the one reading
            # the reading's type is the kind's: a table, IK statements or a matrix
            if isinstance(read, TableAnswer):
                return check_table(pk, read)
            if isinstance(read, IKAnswer):
                return check_ik(pk, read)
            return check_matrix(pk, read, limits)
    except CheckTimeout as err:
        return _unreadable(key, str(err))
    except DHError as err:
        return _unreadable(key, str(err))
    except (RecursionError, MemoryError, OverflowError) as err:  # an answer too large to handle
        return _unreadable(key, f"it could not be processed ({type(err).__name__})")
    # Anything else is a bug of dhsym, not a fault of the answer: it propagates, and the
    # grading run reports it as that submission's internal error while the batch goes on.
