"""Homework checking: grade DH tables and matrices, explain the mistake, batch a whole class.

One answer::

    >>> from dhsym.checking import Key, check_answer
    >>> r = check_answer(Key.load("planar2r", "T0_2[0,3]"), "a1*c1 + a2*C12")
    >>> r.verdict.value
    'correct'

A class: :func:`grade` (``dhsym grade``) with an :class:`Assignment` file; in a
notebook: :func:`check` (rich result, or a widget without an answer); on an autograder
platform: :mod:`~dhsym.checking.platforms.autograder`; LMS imports:
:mod:`~dhsym.checking.platforms.gradebooks`.
Student text is untrusted throughout: see :class:`AnswerLimits`.

Inside, six sub-rooms: :mod:`~dhsym.checking.reading` (student text to sympy),
:mod:`~dhsym.checking.comparing` (equivalence, table matching, the verdict: what judges and
mistakes share), :mod:`~dhsym.checking.mistakes` (what explains a wrong answer),
:mod:`~dhsym.checking.judging` (against the key), :mod:`~dhsym.checking.grading` (a class,
its report folder) and :mod:`~dhsym.checking.platforms` (autograders, LMS gradebooks,
notebooks). Every name below
is loaded from its sub-room on first use.
"""

from __future__ import annotations

from dhsym._lazy import lazy_exports

# Loaded on first use, so that `dhsym check` imports the checker and not the grading
# machinery (process pools, reports, Dask).
__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "AnswerLimits": "reading.limits",
        "CheckTimeout": "reading.limits",
        "UnreadableAnswer": "reading.limits",
        "read_expression": "reading.answers",
        "read_matrix": "reading.answers",
        "read_answer_table": "reading.answers",
        "Key": "judging.key",
        "TrajectoryKey": "judging.trajectory_key",
        "load_key": "judging.key",
        "check_answer": "judging.checker",
        "prepare": "judging.key",
        "PreparedKeys": "judging.key",
        "render_check": "grading.feedback",
        "render_feedback": "grading.feedback",
        "Assignment": "grading.assignment",
        "ClassList": "grading.variants",
        "run_assignment_tests": "grading.assignment_tests",
        "write_sheets": "grading.sheets",
        "GradeRecord": "grading.records",
        "GradeReport": "grading.batch",
        "grade": "grading.batch",
        "grade_submission": "grading.batch",
        "read_submissions": "grading.submissions",
        "latex_matrix_cells": "reading.latex_input",
        "latex_to_text": "reading.latex_input",
        "Mistake": "mistakes.registry",
        "NameContext": "reading.answer_names",
        "Question": "reading.questions",
        "TableMatch": "comparing.table_match",
        "compare_tables": "comparing.table_match",
        "CheckResult": "comparing.verdict",
        "Diagnosis": "comparing.verdict",
        "EntryResult": "comparing.verdict",
        "Verdict": "comparing.verdict",
        "Rounding": "judging.rounding",
        "SelfCheck": "platforms.selfcheck",
        "assert_answer": "platforms.selfcheck",
        "check": "platforms.selfcheck",
        "check_widget": "platforms.selfcheck",
    },
)

__all__ = [
    "AnswerLimits",
    "Assignment",
    "CheckResult",
    "ClassList",
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
    "TrajectoryKey",
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
    "load_key",
    "prepare",
    "read_answer_table",
    "PreparedKeys",
    "read_expression",
    "read_matrix",
    "read_submissions",
    "render_check",
    "render_feedback",
    "run_assignment_tests",
    "write_sheets",
]
