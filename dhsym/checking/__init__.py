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

from ._limits import AnswerLimits, CheckTimeout, UnreadableAnswer
from .answers import read_expression, read_matrix, read_table
from .checker import Key, check_answer, prepare
from .feedback import render_check, render_feedback
from .grading import Assignment, GradeReport, grade, grade_submission, read_submissions
from .latex_input import latex_matrix_cells, latex_to_text
from .mistakes import Mistake
from .names import NameContext
from .questions import Question
from .rounding import Rounding
from .selfcheck import SelfCheck, assert_answer, check, check_widget
from .tables import TableMatch, compare_tables
from .verdict import CheckResult, Diagnosis, EntryResult, Verdict

__all__ = [
    "AnswerLimits",
    "Assignment",
    "CheckResult",
    "CheckTimeout",
    "Diagnosis",
    "EntryResult",
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
    "read_expression",
    "read_matrix",
    "read_submissions",
    "read_table",
    "render_check",
    "render_feedback",
]
