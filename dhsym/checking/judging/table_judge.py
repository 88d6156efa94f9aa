r"""Judging a DH-table answer: the same robot (maybe with other frame choices), or which row
is wrong and why.

The verdict is :func:`~dhsym.checking.comparing.table_match.compare_tables`' (two tables
that give the same kinematics); a wrong table is explained by the mistakes room
(:func:`~dhsym.checking.mistakes.registry.diagnose_table`), by one slip or by two, both named.

Examples
--------
>>> from dhsym.checking.judging.key import Key, prepare
>>> from dhsym.checking.reading.answer_value import read_answer_value
>>> pk = prepare(Key.load("planar2r", "table"))
>>> right = "theta | d | a | alpha\ntheta1 | 0 | a1 | 0\ntheta2 | 0 | a2 | 0"
>>> check_table(pk, read_answer_value(pk.form(), right)).verdict.value
'correct'
>>> two = "theta | d | a | alpha\ntheta1 | 0 | -a1 | 0\ntheta2 | 0 | -a2 | 0"
>>> r = check_table(pk, read_answer_value(pk.form(), two))
>>> r.message[:59]
'The table is wrong. Most likely two slips, each wrong sign.'
>>> [(d.kind, d.rows) for d in r.diagnoses]
[('wrong_sign', (1,)), ('wrong_sign', (2,))]
>>> table_cells(pk.key.table)[1]
('1', 'theta1', '0', 'a1', '0', 'R')
"""

from __future__ import annotations

from dhsym.model.table import AngleUnit

from ..comparing.table_match import compare_tables, symbolic_values
from ..comparing.verdict import CheckResult, Diagnosis, Verdict
from ..mistakes.registry import TableCase, diagnose_table
from ..reading.answer_value import TableAnswer
from .key import PreparedKey, TablePart, table_cells

__all__ = ["check_table", "table_cells"]


def check_table(pk: PreparedKey, answer: TableAnswer) -> CheckResult:
    """Check a table answer, as read, against the key's table (see the module text)."""
    key = pk.key
    table = key.table
    ans = answer.table
    values_ = table.value_map  # for the diagnosis; the verdict is symbolic first
    # the key's cells were printed when it was prepared
    shown = pk.part.cells if isinstance(pk.part, TablePart) else ()
    expected_table = shown or table_cells(table)
    answer_table = table_cells(ans, table, expected_table)  # the key's rows printed once
    note = (
        " (Your angles were read as degrees, from a value above 2π, a ° or deg mark"
        " or the file's angles: deg.)"
        if answer.degrees and table.angles is not AngleUnit.DEG
        else ""
    )
    judged = symbolic_values(table, ans)
    frames = pk.part.frames if isinstance(pk.part, TablePart) else None
    match = compare_tables(table, ans, tool_free=key.tool_free, values=judged, key_frames=frames)
    if match.same_robot and ans.convention is table.convention:
        if match.same_table:
            return CheckResult(
                "table",
                Verdict.CORRECT,
                "Your table is the key's table." + note,
                key=key.name,
                expected_table=expected_table,
                answer_table=answer_table,
            )
        how = "; ".join(match.differences) or "other but equivalent entries"
        return CheckResult(
            "table",
            Verdict.CORRECT,
            f"Your table is a valid alternative: it describes the same robot "
            f"with other frame choices ({how}).{note}",
            alternative=how,
            key=key.name,
            expected_table=expected_table,
            answer_table=answer_table,
        )
    diagnoses = diagnose_table(TableCase(table, ans, key.tool_free, values_))
    if not diagnoses:
        rows = ()
        diagnoses = (
            Diagnosis(
                "geometry",
                "different robot",
                f"The table describes another robot: {match.reason}.",
                rows=rows,
            ),
        )
    where = (
        f" The geometry first differs at joint {match.diverges_at}: {match.reason}."
        if match.diverges_at and not match.same_robot
        else ""
    )
    if len(diagnoses) == 2:  # two slips (diagnose_table's pairs): both named
        first, second = diagnoses
        likely = (
            f"two slips, {first.title} and {second.title}"
            if first.kind != second.kind
            else f"two slips, each {first.title}"
        )
        message = f"The table is wrong. Most likely {likely}. {first.detail} {second.detail}"
        message += f"{where}{note}"
    else:
        message = (
            f"The table is wrong. Most likely: {diagnoses[0].title}. "
            f"{diagnoses[0].detail}{where}{note}"
        )
    return CheckResult(
        "table",
        Verdict.INCORRECT,
        message,
        diagnoses=diagnoses,
        key=key.name,
        expected_table=expected_table,
        answer_table=answer_table,
    )
