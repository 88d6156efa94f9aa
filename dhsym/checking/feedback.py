r"""Feedback a student can act on, as Markdown and HTML (Jinja2 templates in ``templates/``).

The templates get plain data; the HTML environment autoescapes, the Markdown one
escapes every student-made string with the ``md`` filter (Markdown specials and
``< > &``) or puts it in a code span (``code``).  Only the key's printer output
(``*_latex``) is inserted as math.

Examples
--------
>>> from dhsym.checking.verdict import CheckResult, Verdict
>>> r = CheckResult("T0_2", Verdict.UNREADABLE, "The answer could not be read: <b>",
...                 reason="<b>")
>>> page = render_feedback({"id": "<script>x</script>", "name": "<script>x</script>"},
...                        [QuestionFeedback("q1", "T0_2", 2, 0, r)], fmt="html")
>>> "<script>" in page, "&lt;script&gt;x&lt;/script&gt;" in page
(False, True)
>>> md_escape("a_1 *b* <i>")
'a\\_1 \\*b\\* &lt;i&gt;'
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from dhsym.errors import DHError
from dhsym.explain.templates import loader

from .verdict import CheckResult

__all__ = [
    "QuestionFeedback",
    "md_code",
    "md_escape",
    "render_check",
    "render_feedback",
    "render_question_text",
    "render_summary",
    "render_template",
]

_MD_SPECIAL = re.compile(r"([\\`*_\[\]|~$])")


@dataclass(frozen=True)
class QuestionFeedback:
    """One question of a student's feedback: what was asked, points and the result."""

    id: str
    ask: str
    points: float
    score: float
    result: CheckResult | None


def md_escape(text: object) -> str:
    """Escape a string for Markdown inline text: ``\\ ` * _ [ ] | ~ $`` get a backslash,
    ``< > &`` become entities (no HTML, links, emphasis or math can form)."""
    s = str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    s = _MD_SPECIAL.sub(r"\\\1", s)
    return " ".join(s.splitlines())


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


def _points(x: float) -> str:
    return f"{x:g}"


@lru_cache(maxsize=3)
def _environment(fmt: str):  # noqa: ANN202 - jinja2 is imported lazily
    """Jinja2 environment for ``html`` (autoescaped), ``md`` or ``txt`` (plain text)."""
    import jinja2

    env = jinja2.Environment(
        loader=loader(),
        autoescape=(fmt == "html"),
        undefined=jinja2.StrictUndefined,
        trim_blocks=False,
        keep_trailing_newline=True,
    )
    env.filters["md"] = md_escape
    env.filters["code"] = md_code
    env.filters["points"] = _points
    return env


def render_feedback(
    student: Mapping[str, str],
    questions: Sequence[QuestionFeedback],
    *,
    title: str = "DH homework",
    fmt: str = "md",
    status: str = "graded",
    mathjax_url: str | None = None,
) -> str:
    """One student's feedback page (``fmt`` is ``md`` or ``html``)."""
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
        mathjax_url=mathjax_url,
    )


def render_check(result: CheckResult, fmt: str = "md") -> str:
    """Feedback for a single check (what ``dhsym check`` prints)."""
    q = QuestionFeedback("1", result.question, 1, float(result.correct), result)
    return render_feedback({"id": "", "name": ""}, [q], title=result.key or "check", fmt=fmt)


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

    >>> from dhsym.checking.verdict import CheckResult, EntryResult, Verdict
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
