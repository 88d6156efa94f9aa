r"""Feedback a student can act on, as Markdown, HTML and plain text (Jinja2 templates).

The templates get plain data; the HTML environment autoescapes, the Markdown one
escapes every student-made string with the ``md`` filter (Markdown specials and
``< > &``) or puts it in a code span (``code``).  Only the key's printer output
(``*_latex``) is inserted as math.

Examples
--------
>>> from dhsym.checking.comparing.verdict import CheckResult, Verdict
>>> r = CheckResult("T0_2", Verdict.UNREADABLE, "The answer could not be read: <b>",
...                 reason="<b>")
>>> page = render_feedback({"id": "<script>x</script>", "name": "<script>x</script>"},
...                        [QuestionFeedback("q1", "T0_2", 2, 0, r)], fmt="html")
>>> "<script>" in page, "&lt;script&gt;x&lt;/script&gt;" in page
(False, True)
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from dhsym.errors import DHError
from dhsym.notation.escape import escape_markdown
from dhsym.notation.templates import FEEDBACK, environment

from ..comparing.verdict import CheckResult

if TYPE_CHECKING:  # jinja2 is imported when a page is rendered
    import jinja2

__all__ = [
    "QuestionFeedback",
    "md_code",
    "check_text",
    "load_feedback_templates",
    "md_math",
    "render_chart",
    "render_check",
    "render_feedback",
    "render_question_text",
    "render_summary",
    "render_template",
]


@dataclass(frozen=True)
class QuestionFeedback:
    """One question of a student's feedback: what was asked, points and the result."""

    id: str
    ask: str
    points: float
    score: float
    result: CheckResult | None


def md_code(text: object) -> str:
    """A Markdown code span that shows ``text`` literally (fence longer than any backtick run).

    >>> md_code("a`b")
    '``a`b``'
    """
    s = " ".join(str(text).splitlines()).replace("|", "\\|")
    longest = max((len(m) for m in re.findall(r"`+", s)), default=0)
    fence = "`" * (longest + 1)
    pad = " " if s.startswith("`") or s.endswith("`") else ""
    return f"{fence}{pad}{s}{pad}{fence}"


def md_math(tex: object) -> str:
    r"""LaTeX for ``$…$`` inside a Markdown table: ``|`` would end the cell, ``\vert`` does not.

    >>> md_math(r"\left|{a_{1}}\right| + \|x\|")
    '\\left\\vert {a_{1}}\\right\\vert  + \\Vert x\\Vert '
    """
    return " ".join(str(tex).splitlines()).replace("\\|", "\\Vert ").replace("|", "\\vert ")


def _points(x: float) -> str:
    return f"{x:g}"


def _mathml(tex: object) -> object:
    """Printer LaTeX as MathML, marked safe for the autoescaping HTML environment."""
    from markupsafe import Markup

    from dhsym.notation.mathml import latex_mathml

    return Markup(latex_mathml(str(tex)))  # noqa: S704 - MathML built from an element tree


_FILTERS = (
    ("md", escape_markdown),
    ("code", md_code),
    ("mdmath", md_math),
    ("points", _points),
    ("mathml", _mathml),
)


def load_feedback_templates() -> None:
    """Compile the feedback pages' templates and import the MathML converter now: a grading
    run's template process does it once, and the sandbox children it forks render their
    first page without compiling or importing anything.

    >>> load_feedback_templates()
    """
    for fmt in ("md", "html"):
        _environment(fmt).get_template(f"feedback.{fmt}.j2")
    _mathml("x")


def _environment(fmt: str) -> jinja2.Environment:
    """The environment for ``html`` (autoescaped), ``md`` or ``txt`` (plain text): the
    one renderer's :data:`~dhsym.notation.templates.FEEDBACK` family, with the filters."""
    return environment(fmt, FEEDBACK, filters=_FILTERS)


def render_feedback(
    student: Mapping[str, str],
    questions: Sequence[QuestionFeedback],
    *,
    title: str = "DH homework",
    fmt: str = "md",
    status: str = "graded",
    flags: Sequence[str] = (),
    values: Sequence[tuple[str, str]] = (),
) -> str:
    """One student's feedback page (``fmt`` is ``md`` or ``html``); ``flags`` are notes;
    ``values`` the student's own values (name, as printed) of an assignment with variants."""
    if fmt not in ("md", "html"):
        raise DHError(f"unknown feedback format {fmt!r}: expected md or html")
    template = _environment(fmt).get_template(f"feedback.{fmt}.j2")
    return template.render(
        title=title,
        student={"id": str(student.get("id", "")), "name": str(student.get("name", ""))},
        questions=list(questions),
        score=sum(q.score for q in questions),
        max_score=sum(q.points for q in questions),
        status=status,
        flags=[str(f) for f in flags],
        values=[(str(k), str(v)) for k, v in values],
    )


def render_check(result: CheckResult, fmt: str = "md") -> str:
    """Feedback for a single check: ``txt`` is what ``dhsym check`` prints on a terminal,
    ``md`` what it prints with ``--format markdown`` (and notebooks display)."""
    if fmt == "txt":
        return check_text(result)
    q = QuestionFeedback("1", result.question, 1, float(result.correct), result)
    return render_feedback({"id": "", "name": ""}, [q], title=result.key or "check", fmt=fmt)


def check_text(result: CheckResult) -> str:
    """One check as plain text for a terminal: no markup, control characters removed.

    A terminal message rather than a document, so it is built here and not from a
    template: ``dhsym check`` then starts without Jinja2.

    >>> from dhsym.checking.comparing.verdict import CheckResult, Diagnosis, EntryResult, Verdict
    >>> e = EntryResult(2, 4, False, "a1*S1 - a2*S12", "a1*S1 + a2*S12")
    >>> ok = EntryResult(1, 4, True, "a1*C1 + a2*C12", "a1*C1 + a2*C12")
    >>> d = Diagnosis("wrong_sign", "wrong sign", "a2*S12 has the wrong sign.", ((2, 4),))
    >>> print(check_text(CheckResult("T0_2[:,3]", Verdict.INCORRECT, "1 of 2 entries is wrong.",
    ...                              diagnoses=(d,), entries=(ok, e), key="Planar 2R")))
    INCORRECT: T0_2[:,3] (Planar 2R). 1 of 2 entries is wrong.
      - wrong sign (entries (2,4)): a2*S12 has the wrong sign.
    <BLANKLINE>
      entry | your entry     | correct entry
      ------+----------------+---------------
      (2,4) | a1*S1 - a2*S12 | a1*S1 + a2*S12
    The other entry is right.
    <BLANKLINE>
    """
    from dhsym.notation.escape import clean_text
    from dhsym.notation.tables import text_table

    where = f" ({result.key})" if result.key else ""
    lines = [f"{result.verdict.value.upper()}: {result.question}{where}. {result.message}"]
    for d in result.diagnoses:
        at = ""
        if d.entries and len(result.entries) > 1:  # a one-cell answer has no entries to name
            at += " (entries " + ", ".join(f"({r},{c})" for r, c in d.entries) + ")"
        if d.rows:
            at += " (rows " + ", ".join(map(str, d.rows)) + ")"
        lines.append(f"  - {d.title}{at}: {d.detail}")
    wrong = [e for e in result.entries if not e.correct]
    if wrong:
        rows = [[f"({e.row},{e.col})", e.answer, e.expected] for e in wrong]
        lines += [
            "",
            *("  " + t for t in text_table(["entry", "your entry", "correct entry"], rows)),
        ]
        rest = len(result.entries) - len(wrong)
        if rest:
            lines.append(
                "The other entry is right." if rest == 1 else f"The other {rest} entries are right."
            )
    tables = [("Your table:", result.answer_table)]
    if not result.correct:
        tables.append(("The key's table:", result.expected_table))
    for title, table in tables:
        if table:
            lines += ["", title, *("  " + t for t in text_table(table[0], table[1:]))]
    return "\n".join(clean_text(line) for line in lines) + "\n"


def render_chart(data: Mapping[str, object]) -> str:
    """The class summary's chart (SVG, autoescaped as HTML is) from
    :func:`~dhsym.checking.grading.report.chart_data`."""
    return _environment("html").get_template("gradebook_chart.svg.j2").render(**data)


def render_summary(data: Mapping[str, object]) -> str:
    """The class summary page (HTML) from the grading data."""
    return _environment("html").get_template("gradebook_summary.html.j2").render(**data)


def render_template(name: str, **data: object) -> str:
    """Render ``templates/<name>``; the format (``html``, ``md``, ``txt``) is the name's
    second suffix (``selfcheck.html.j2``), and decides escaping as described above."""
    fmt = Path(name).with_suffix("").suffix.lstrip(".")
    if fmt not in ("md", "html", "txt"):
        raise DHError(f"template {name!r}: expected a .html.j2, .md.j2 or .txt.j2 name")
    return _environment(fmt).get_template(name).render(**data)


def render_question_text(q: QuestionFeedback, *, show_key: bool = True) -> str:
    """One question's feedback as plain text (an autograder's per-test output).

    With ``show_key=False`` the key's entries and table are left out (for platforms
    where students resubmit after reading the output).

    >>> from dhsym.checking.comparing.verdict import CheckResult, EntryResult, Verdict
    >>> r = CheckResult("A1", Verdict.INCORRECT, "1 of 16 entries is wrong.",
    ...                 (EntryResult(2, 4, False, "d1", "-d1"),))
    >>> print(render_question_text(QuestionFeedback("q1", "A1", 2, 0, r)))
    INCORRECT (0 / 2 points). 1 of 16 entries is wrong.
    <BLANKLINE>
    entry (2,4): yours   d1
                 correct -d1
    >>> "correct -d1" in render_question_text(QuestionFeedback("q1", "A1", 2, 0, r),
    ...                                       show_key=False)
    False
    """
    return render_template("feedback_question.txt.j2", q=q, show_key=show_key).strip("\n")
