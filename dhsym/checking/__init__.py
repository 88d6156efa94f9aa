"""Homework checking: grade DH tables and matrices, explain the mistake, batch a whole class.

One answer::

    >>> from dhsym.checking import Key, check_answer
    >>> r = check_answer(Key.load("planar2r", "T0_2[0,3]"), "a1*c1 + a2*C12")
    >>> r.verdict.value
    'correct'

A class: :func:`grade` (``dhsym grade``) with an :class:`Assignment` file; in a
notebook: :func:`check` (rich result, or a widget without an answer); on an autograder
platform: :mod:`~dhsym.checking.autograder`; LMS imports: :mod:`~dhsym.checking.gradebooks`.
Student text is untrusted throughout: see :class:`AnswerLimits`.
"""

from __future__ import annotations

from dhsym._lazy import lazy_exports

# Loaded on first use, so that `dhsym check` imports the checker and not the grading
# machinery (process pools, reports, Dask).
__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "AnswerLimits": "_limits",
        "CheckTimeout": "_limits",
        "UnreadableAnswer": "_limits",
        "read_expression": "answers",
        "read_matrix": "answers",
        "read_table": "answers",
        "Key": "checker",
        "check_answer": "checker",
        "prepare": "checker",
        "PreparedKeys": "checker",
        "render_check": "feedback",
        "render_feedback": "feedback",
        "Assignment": "grading",
        "GradeRecord": "records",
        "GradeReport": "grading",
        "grade": "grading",
        "grade_submission": "grading",
        "read_submissions": "grading",
        "latex_matrix_cells": "latex_input",
        "latex_to_text": "latex_input",
        "Mistake": "mistakes",
        "NameContext": "names",
        "Question": "questions",
        "TableMatch": "tables",
        "compare_tables": "tables",
        "CheckResult": "verdict",
        "Diagnosis": "verdict",
        "EntryResult": "verdict",
        "Verdict": "verdict",
        "Rounding": "rounding",
        "SelfCheck": "selfcheck",
        "assert_answer": "selfcheck",
        "check": "selfcheck",
        "check_widget": "selfcheck",
    },
)

__all__ = [
    "AnswerLimits",
    "Assignment",
    "CheckResult",
    "CheckTimeout",
    "Diagnosis",
    "EntryResult",
    "GradeRecord",
    "GradeReport",
    "Key",
    "Mistake",
    "NameContext",
    "Question",
    "Rounding",
    "SelfCheck",
    "TableMatch",
    "UnreadableAnswer",
    "Verdict",
    "assert_answer",
    "check",
    "check_answer",
    "check_widget",
    "compare_tables",
    "grade",
    "grade_submission",
    "latex_matrix_cells",
    "latex_to_text",
    "prepare",
    "PreparedKeys",
    "read_expression",
    "read_matrix",
    "read_submissions",
    "read_table",
    "render_check",
    "render_feedback",
]
