r"""Self-check in a notebook: ``dhsym.check(answer, key=…, question=…)``.

``check`` returns a :class:`SelfCheck` that Jupyter shows as rich output
(``_repr_html_``, ``_repr_markdown_``): the verdict, the entries that differ (typeset,
as dhsym read them), the most likely mistake, and the key's entries only when the
teacher allows it (``show_key=True``).  Without an answer, ``check(key=…,
question=…)`` returns a small widget (needs ``ipywidgets``): a text area for the
answer (plain math or LaTeX), a live typeset preview of how dhsym reads it, and a
*Check* button.  The answer is untrusted text throughout: it goes through the same
whitelist reader and limits as ``dhsym check``.

Notebook graders (otter-grader test files, nbgrader autograder cells) call
:func:`assert_answer` with the student's variable: it raises ``AssertionError`` with
the feedback text unless the answer is correct, and a clear one for a variable that
holds no answer (``...``, ``None``, a number)::

    assert_answer(q2, key="puma560", question="T0_2")

An assignment's question is checked with ``assignment=`` and the question's id; for an
assignment with variants the student's own key needs their id and the class list the
values were drawn for (and the assignment's secret beside it, so this runs where the
instructor's files are: an autograder, a grading notebook)::

    check(answer, question="q2", assignment="hw.yaml", student="alice", roster="class.csv")

A trajectory or gain question's key is a profile (``key="cubic(q0=0, qf=1, tf=2)"``,
``question="traj a2"``; see :mod:`~dhsym.checking.judging.trajectory_key`).

Examples
--------
>>> r = check("[[C12, -S12, 0, a1*C1 - a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0,0,1,0]]",
...           key="planar2r", question="T0_2")
>>> r.verdict, r.correct
('incorrect', False)
>>> "wrong sign" in r._repr_markdown_(), "a_{1} C_{1} + a_{2} C_{12}" in r._repr_html_()
(True, False)
>>> r.assert_correct()
Traceback (most recent call last):
...
AssertionError: INCORRECT (0 / 1 points). 1 of 16 entries is wrong. Most likely: wrong sign. ...
>>> read_answer(Key.load("planar2r", "T0_2[0,3]"), r"a_1 \cos\theta_1 + a2 C12").latex
'a_{1} C_{1} + a_{2} C_{12}'
>>> check("10", key="gains(omega=10)", question="kd").result.kinds
('kd_without_two',)
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, overload

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.table import DHTable

from ..comparing.verdict import CheckResult
from ..grading.assignment import Assignment
from ..grading.feedback import QuestionFeedback, render_question_text, render_template
from ..grading.variants import ClassList, class_variants, variant_id
from ..judging.checker import check_answer
from ..judging.key import AnyKey, Key, PreparedKeys, load_key
from ..judging.table_judge import table_cells
from ..judging.trajectory_key import PreparedTrajectory, TrajectoryKey
from ..reading.answer_value import IKAnswer, ReadCell, TableAnswer, read_answer_value
from ..reading.answers import expression_cell
from ..reading.limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, CheckTimeout, time_limit

__all__ = [
    "Reading",
    "SelfCheck",
    "assert_answer",
    "assignment_key",
    "check",
    "check_widget",
    "read_answer",
]

_READ_ERRORS = (DHError, RecursionError, MemoryError, OverflowError, ValueError, TypeError)


@dataclass(frozen=True)
class Reading:
    """How dhsym read an answer: LaTeX of the expression or matrix, or the table's cells,
    or why it could not (``error``; empty with everything else for an empty answer)."""

    latex: str = ""
    table: tuple[tuple[str, ...], ...] = ()
    error: str = ""

    def _repr_html_(self) -> str:
        return render_template("selfcheck_reading.html.j2", reading=self)


def read_answer(
    key: AnyKey,
    answer: str | bytes,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    keys: PreparedKeys | None = None,
) -> Reading:
    """Read ``answer`` as ``key``'s question expects (no comparison): the live preview.

    ``keys``: the caller's prepared keys (a widget keeps its own), else a fresh map."""
    keys = keys if keys is not None else PreparedKeys()
    if not (answer.strip() if isinstance(answer, str) else answer.strip()):
        return Reading()
    try:
        with time_limit(min(limits.seconds, 2.0)):
            pk = keys.get(key)
            if isinstance(pk, PreparedTrajectory):  # one expression, in the profile's names
                cell = expression_cell(answer, limits)
                return Reading(latex=sp.latex(ReadCell.read(cell, pk.names, limits, "").value))
            read = read_answer_value(pk.form(), answer, limits)
            if isinstance(read, TableAnswer):
                return Reading(table=table_cells(read.table))
            nota = pk.robot.notation
            if isinstance(read, IKAnswer):  # the statements as equations, in order read
                statements = (*read.helpers, *(st for sol in read.solutions for st in sol.values()))
                return Reading(
                    latex=nota.latex(
                        sp.Tuple(*(sp.Eq(st.target, st.expr, evaluate=False) for st in statements))
                    )
                )
            value = read.matrix[0, 0] if read.shape == (1, 1) else read.matrix
            return Reading(latex=nota.latex(value))
    except CheckTimeout as err:
        return Reading(error=str(err))
    except _READ_ERRORS as err:
        return Reading(error=str(err) if isinstance(err, DHError) else type(err).__name__)


@dataclass(frozen=True)
class SelfCheck:
    """The result of :func:`check`, shown as rich output in a notebook."""

    result: CheckResult
    key: AnyKey
    show_key: bool = False
    points: float = 1.0

    @property
    def verdict(self) -> str:
        """``correct``, ``incorrect`` or ``unreadable``."""
        return self.result.verdict.value

    @property
    def correct(self) -> bool:
        """True for a correct answer."""
        return self.result.correct

    def _data(self) -> dict[str, object]:
        r = self.result
        lead = next(
            (d for d in r.diagnoses if d.kind not in ("unexplained", "unknown_symbol")), None
        )
        return {
            "r": r,
            "question": self.key.question,
            "robot": _about(self.key),
            "wrong": [e for e in r.entries if not e.correct],
            "lead": lead,
            "show_key": self.show_key,
        }

    def _repr_html_(self) -> str:
        return render_template("selfcheck.html.j2", **self._data())

    def _repr_markdown_(self) -> str:
        return render_template("selfcheck.md.j2", **self._data())

    def feedback_text(self) -> str:
        """The plain-text feedback (what a notebook grader shows for a failed test)."""
        score = self.points if self.correct else 0.0
        qf = QuestionFeedback("1", self.result.question, self.points, score, self.result)
        return render_question_text(qf, show_key=self.show_key)

    def assert_correct(self) -> None:
        """Raise ``AssertionError`` with the feedback unless the answer is correct (for
        otter-grader test files and nbgrader autograder cells)."""
        if not self.correct:
            raise AssertionError(self.feedback_text())


def _about(key: AnyKey) -> str:
    """What a key is about, for the title: the robot's name, or the profile."""
    return key.name if isinstance(key, TrajectoryKey) else key.table.name or key.name


def assignment_key(
    assignment: str | Path | Assignment,
    question: str,
    *,
    student: str | None = None,
    roster: str | Path | ClassList | None = None,
    keys: PreparedKeys | None = None,
) -> AnyKey:
    """The key of the question ``question`` (its id) of an assignment; with variants,
    ``student``'s own key (their values drawn for the class list ``roster``).

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "hw.yaml").write_text("key: planar2r\\nquestions: [{id: q1, ask: px}]\\n")
    >>> assignment_key(folder / "hw.yaml", "q1").question.label
    'T0_2[0,3]'
    """
    a = assignment if isinstance(assignment, Assignment) else Assignment.load(assignment, keys)
    if a.variants is not None:
        if student is None or roster is None:
            raise DHError(
                "this assignment draws values per student: give student='<id>' and "
                "roster='<class list CSV>'"
            )
        cl = roster if isinstance(roster, ClassList) else ClassList.load(roster)
        variant = class_variants(a.variants, cl.ids).get(variant_id(student))
        if variant is None:
            raise DHError(f"{student!r} is not on the class list {cl.file or ''}".rstrip())
        a = a.for_variant(variant)
    found = [q.key for q in a.questions if q.id == str(question)]
    if not found:
        ids = ", ".join(q.id for q in a.questions)
        raise DHError(f"the assignment has no question {str(question)[:40]!r}: its ids are {ids}")
    return found[0]


def _key(
    key: str | Path | DHTable | AnyKey | None,
    question: str | None,
    tool_free: bool,
    keys: PreparedKeys | None = None,
    assignment: str | Path | Assignment | None = None,
    student: str | None = None,
    roster: str | Path | ClassList | None = None,
) -> AnyKey:
    """The key asked for; one loaded here is prepared into ``keys`` (to check it), so
    that the check that follows does not prepare it again."""
    if assignment is not None:
        if key is not None or question is None:
            raise DHError("with assignment=, give question='<question id>' and no key")
        return assignment_key(assignment, question, student=student, roster=roster, keys=keys)
    if student is not None:
        raise DHError("student= is for an assignment's question: give assignment='hw.yaml'")
    if isinstance(key, (Key, TrajectoryKey)):
        return key
    if key is None:
        raise DHError(
            "give the key: a built-in robot (key='puma560'), a table file, a table or a "
            "profile (key='cubic(q0=0, qf=1, tf=2)')"
        )
    if question is None:
        raise DHError(
            "give the question: table, T<i>_<j>, A<k>, arm, px/py/pz or T<i>_<j>[r,c]; of a "
            "profile traj a<k>, tb, vmax, q@<t>, kp or kd"
        )
    return load_key(key, question, tool_free=tool_free, keys=keys)


@overload
def check(
    answer: None = None,
    key: str | Path | DHTable | AnyKey | None = None,
    question: str | None = None,
    *,
    tool_free: bool = False,
    show_key: bool = False,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    assignment: str | Path | Assignment | None = None,
    student: str | None = None,
    roster: str | Path | ClassList | None = None,
) -> object: ...


@overload
def check(
    answer: str | bytes,
    key: str | Path | DHTable | AnyKey | None = None,
    question: str | None = None,
    *,
    tool_free: bool = False,
    show_key: bool = False,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    assignment: str | Path | Assignment | None = None,
    student: str | None = None,
    roster: str | Path | ClassList | None = None,
) -> SelfCheck: ...


def check(
    answer: str | bytes | None = None,
    key: str | Path | DHTable | AnyKey | None = None,
    question: str | None = None,
    *,
    tool_free: bool = False,
    show_key: bool = False,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    assignment: str | Path | Assignment | None = None,
    student: str | None = None,
    roster: str | Path | ClassList | None = None,
) -> SelfCheck | object:
    """Check ``answer`` against ``key`` (a built-in robot, a table file, a table or a
    :class:`Key`) and ``question``; with no answer, return :func:`check_widget`.

    Or against the question ``question`` (its id) of ``assignment``: for an assignment
    with variants, ``student``'s own key (:func:`assignment_key`, with the class list
    ``roster``)."""
    keys = PreparedKeys()  # the key prepared once, for loading it and for this check
    k = _key(key, question, tool_free, keys, assignment, student, roster)
    if answer is None:
        return check_widget(k, show_key=show_key, limits=limits)
    return SelfCheck(check_answer(k, answer, limits=limits, keys=keys), k, show_key)


def assert_answer(
    answer: object,
    key: str | Path | DHTable | AnyKey | None = None,
    question: str | None = None,
    *,
    tool_free: bool = False,
    show_key: bool = False,
    assignment: str | Path | Assignment | None = None,
    student: str | None = None,
    roster: str | Path | ClassList | None = None,
) -> None:
    """Raise ``AssertionError`` (the feedback as its message) unless ``answer`` is a
    correct answer: the one line of an otter-grader test or an nbgrader test cell
    (``assignment``, ``student``, ``roster`` as in :func:`check`).

    >>> assert_answer("a1*C1 + a2*C12", key="planar2r", question="px")
    >>> assert_answer(..., key="planar2r", question="px")
    Traceback (most recent call last):
    ...
    AssertionError: No answer yet: put your answer in the variable as text ...
    """
    if not isinstance(answer, (str, bytes)):
        raise AssertionError(
            "No answer yet: put your answer in the variable as text (a string: plain math "
            f"or LaTeX); it holds {type(answer).__name__}."
        )
    check(
        answer,
        key,
        question,
        tool_free=tool_free,
        show_key=show_key,
        assignment=assignment,
        student=student,
        roster=roster,
    ).assert_correct()


def check_widget(
    key: str | Path | DHTable | AnyKey | None = None,
    question: str | None = None,
    *,
    tool_free: bool = False,
    show_key: bool = False,
    answer: str = "",
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
) -> object:
    """An ipywidgets box: the answer's text area (plain or LaTeX), a live typeset preview
    of how dhsym reads it, a *Check* button and the result.  CSS classes
    ``dhsym-answer``, ``dhsym-preview``, ``dhsym-check``, ``dhsym-verdict`` mark the parts."""
    try:
        import ipywidgets as w
    except ImportError:
        raise DHError(
            "the self-check widget needs ipywidgets (pip install ipywidgets); "
            "or call check(answer, key=…, question=…)"
        ) from None
    keys = PreparedKeys()  # this widget's key, prepared once for every keystroke and check
    k = _key(key, question, tool_free, keys)
    q = k.question
    title = w.HTMLMath(render_template("selfcheck_title.html.j2", question=q, robot=_about(k)))
    area = w.Textarea(
        value=answer,
        placeholder="Your answer: plain math (C1, a1*C12, [[…], […]]) or LaTeX",
        layout=w.Layout(width="100%", height="8em"),
    )
    preview = w.HTMLMath(read_answer(k, answer, limits, keys)._repr_html_())
    button = w.Button(description="Check", button_style="primary", icon="check")
    verdict = w.HTMLMath("")
    for widget, css in ((area, "answer"), (preview, "preview"), (button, "check")):
        widget.add_class(f"dhsym-{css}")
    verdict.add_class("dhsym-verdict")

    def on_text(change: dict[str, Any]) -> None:
        preview.value = read_answer(k, change["new"], limits, keys)._repr_html_()

    def on_check(_: object) -> None:
        verdict.value = SelfCheck(
            check_answer(k, area.value, limits=limits, keys=keys), k, show_key
        )._repr_html_()

    area.observe(on_text, names="value")
    button.on_click(on_check)
    return w.VBox([title, area, preview, button, verdict])
