"""Checking an assignment before grading with it: the question tests and the key's own answer.

For every question, :func:`run_assignment_tests` grades the key's own answer (the
entries of its matrix as dhsym prints them, its table, the derivation of its inverse
kinematics or the joint values of an ``ik@`` question) and the question's tests
(:class:`~dhsym.checking.grading.question_tests.QuestionTests`): each right answer must be
graded correct, each wrong one incorrect, naming the expected mistake when one is given.
With ``variants:``, the key's own answer is graded for the sample variant and for
``samples`` drawn ones (ids ``check-1``, ``check-2``, …); the instructor's tests run against
the key as written (the table's symbols, the first value of each drawn joint value).

``dhsym check-assignment hw.yaml`` prints the table; ``dhsym grade`` refuses an assignment
whose tests fail.

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> folder = Path(tempfile.mkdtemp())
>>> _ = (folder / "hw.yaml").write_text(
...     "key: planar2r\\nquestions:\\n  - id: q1\\n    ask: px\\n    tests:\\n"
...     "      right: [a1*C1 + a2*C12]\\n      wrong: [{answer: a1*C1 - a2*C12, mistake: sign}]\\n"
... )
>>> report = run_assignment_tests(Assignment.load(folder / "hw.yaml"))
>>> report.passed, [(r.case, r.got) for r in report.rows]
(True, [('key', 'correct'), ('right', 'correct'), ('wrong', 'incorrect: wrong_sign')])
"""

from __future__ import annotations

from dataclasses import dataclass

from dhsym.errors import DHError

from ..comparing.verdict import CheckResult, Verdict
from ..judging.checker import check_answer
from ..judging.key import AnyKey, PreparedKey, PreparedKeys, TablePart
from ..judging.matrix_key import MatrixPart
from ..judging.trajectory_key import PreparedTrajectory
from ..reading.limits import DEFAULT_ANSWER_LIMITS, AnswerLimits
from .assignment import Assignment
from .question_tests import WrongAnswer
from .variants import Variant

__all__ = ["AssignmentTestReport", "CaseResult", "key_answer", "run_assignment_tests"]


@dataclass(frozen=True)
class CaseResult:
    """One test: the question, the case (``key``, ``right``, ``wrong``), the variant's
    values (empty without variants), the answer, what was expected and what was got."""

    question: str
    case: str
    variant: str
    answer: str
    expected: str
    got: str
    passed: bool
    message: str = ""


@dataclass(frozen=True)
class AssignmentTestReport:
    """Every test of an assignment, in order."""

    rows: tuple[CaseResult, ...]

    @property
    def passed(self) -> bool:
        """True when every test passed."""
        return all(r.passed for r in self.rows)

    @property
    def failures(self) -> tuple[CaseResult, ...]:
        """The tests that failed."""
        return tuple(r for r in self.rows if not r.passed)

    def text(self) -> str:
        """The table ``dhsym check-assignment`` prints, then one line of totals."""
        head = ("question", "case", "variant", "expected", "got", "", "answer")
        body = [
            (
                r.question,
                r.case,
                r.variant or "-",
                r.expected,
                r.got,
                "ok" if r.passed else "FAIL",
                _short(r.answer, 50),
            )
            for r in self.rows
        ]
        widths = [max(len(row[k]) for row in [head, *body]) for k in range(len(head))]
        lines = [
            "  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip()
            for row in [head, *body]
        ]
        lines.insert(1, "  ".join("-" * w for w in widths))
        for r in self.failures:
            if r.message:
                lines.append(f"{r.question} {r.case}: {_short(r.message, 300)}")
        failed = len(self.failures)
        lines.append(f"{len(self.rows) - failed} passed, {failed} failed")
        return "\n".join(lines) + "\n"


def key_answer(pk: PreparedKey | PreparedTrajectory) -> str:
    """The key's own answer as a student could write it: the matrix's entries as dhsym
    prints them, the table in Markdown, the joint values of ``ik@``, the derivation of
    the inverse kinematics (as ``dhsym derive … --what ik`` prints it) or a profile's
    value.

    >>> from dhsym.checking.judging.key import Key
    >>> from dhsym.checking.judging.trajectory_key import TrajectoryKey
    >>> keys = PreparedKeys()
    >>> key_answer(keys.get(Key.load("planar2r", "T0_2[0,3]")))
    'a1*C1 + a2*C12'
    >>> key_answer(keys.get(TrajectoryKey.load("cubic(q0=q0, qf=qf, tf=tf)", "traj a2")))
    '3*(-q_0 + q_f)/t_f**2'
    """
    if isinstance(pk, PreparedTrajectory):
        return pk.part.text
    part, question = pk.part, pk.key.question
    if isinstance(part, MatrixPart):
        texts = [t for t, _ in part.expected_text]
        rows, cols = part.expected.shape
        if rows * cols == 1:
            return texts[0]
        return (
            "["
            + ", ".join(
                "[" + ", ".join(texts[r * cols : (r + 1) * cols]) + "]" for r in range(rows)
            )
            + "]"
        )
    if isinstance(part, TablePart):
        from dhsym.notation.tables import table_markdown

        return table_markdown(pk.key.table)
    if question.pose is not None:
        return ", ".join(f"{x:.15g}" for x in question.pose)
    from dhsym.explain.documents import render_derivation

    return render_derivation(pk.robot, "text", what="ik")


def run_assignment_tests(
    assignment: Assignment,
    *,
    samples: int = 3,
    keys: PreparedKeys | None = None,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    key_answers: bool = True,
) -> AssignmentTestReport:
    """Grade the key's own answer and every question test (see the module docstring);
    ``key_answers=False``: the question tests only (what ``grade`` runs before grading)."""
    keys = keys if keys is not None else PreparedKeys()
    rows: list[CaseResult] = []
    spec = assignment.variants
    variants: list[Variant | None] = [None] if key_answers else []
    if spec is not None and key_answers:
        variants = [spec.sample(), *(spec.draw(f"check-{k}") for k in range(1, samples + 1))]
    for v in variants:
        a = assignment.for_variant(v) if v is not None else assignment
        shown = v.text() if v is not None else ""
        for q in a.questions:
            try:
                text = key_answer(keys.get(q.key))
            except DHError as err:
                rows.append(
                    CaseResult(q.id, "key", shown, "", "correct", "error", False, err.message)
                )
                continue
            rows.append(_row(q.id, "key", shown, q.key, text, None, keys, limits))
    for q in assignment.questions:
        for text in q.tests.right:
            rows.append(_row(q.id, "right", "", q.key, text, None, keys, limits))
        for wrong in q.tests.wrong:
            rows.append(_row(q.id, "wrong", "", q.key, wrong.answer, wrong, keys, limits))
    return AssignmentTestReport(tuple(rows))


def _row(
    qid: str,
    case: str,
    variant: str,
    key: AnyKey,
    answer: str,
    wrong: WrongAnswer | None,
    keys: PreparedKeys,
    limits: AnswerLimits,
) -> CaseResult:
    result = check_answer(key, answer, limits=limits, keys=keys)
    if wrong is None:
        expected, passed = "correct", result.correct
    else:
        expected = "incorrect" + (f": {wrong.mistake}" if wrong.mistake else "")
        passed = result.verdict is Verdict.INCORRECT and (
            not wrong.mistake or wrong.mistake in result.kinds
        )
    return CaseResult(
        qid, case, variant, answer, expected, _got(result), passed, "" if passed else result.message
    )


def _got(result: CheckResult) -> str:
    if result.verdict is Verdict.INCORRECT and result.kinds:
        return "incorrect: " + ", ".join(dict.fromkeys(result.kinds))
    return result.verdict.value


def _short(text: str, width: int) -> str:
    flat = " ".join(text.split())
    return flat if len(flat) <= width else flat[: width - 1] + "…"
