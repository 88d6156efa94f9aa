r"""Feedback a student can act on, as Markdown, HTML and plain text (Jinja2 templates).

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

from dhsym.errors import DHError
from dhsym.explain.templates import loader

from .verdict import CheckResult

__all__ = [
    "QuestionFeedback",
    "md_code",
    "md_escape",
    "render_check",
    "render_feedback",
    "render_summary",
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


def _entry_rows(entries: Sequence[object]) -> list[list[str]]:
    """Wrong entries as rows of the plain-text table: position, the answer, the key."""
    return [[f"({e.row},{e.col})", e.answer, e.expected] for e in entries]  # type: ignore[attr-defined]


@lru_cache(maxsize=3)
def _environment(fmt: str):  # noqa: ANN202 - jinja2 is imported lazily
    import jinja2

    from dhsym.notation.escape import _clean_text

    text = fmt == "txt"
    env = jinja2.Environment(
        loader=loader(),
        autoescape=(fmt == "html"),
        undefined=jinja2.StrictUndefined,
        trim_blocks=text,
        lstrip_blocks=text,
        keep_trailing_newline=True,
        **({"finalize": _clean_text} if text else {}),
    )
    env.filters["md"] = md_escape
    env.filters["code"] = md_code
    env.filters["points"] = _points
    if text:
        from dhsym.notation.tables import text_table

        env.filters["table"] = text_table
        env.filters["entry_rows"] = _entry_rows
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
    """One student's feedback page (``fmt`` is ``md``, ``html`` or ``txt``)."""
    if fmt not in ("md", "html", "txt"):
        raise DHError(f"unknown feedback format {fmt!r}: expected md, html or txt")
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
    """Feedback for a single check: ``txt`` is what ``dhsym check`` prints on a terminal,
    ``md`` what it prints with ``--format markdown`` (and notebooks display).

    >>> from dhsym.checking.verdict import CheckResult, EntryResult, Verdict
    >>> e = EntryResult(2, 4, False, "a1*S1 - a2*S12", "a1*S1 + a2*S12")
    >>> r = CheckResult("T0_2", Verdict.INCORRECT, "1 of 16 entries is wrong.",
    ...                 entries=(e,), key="Planar 2R")
    >>> print(render_check(r, "txt"))
    INCORRECT: T0_2 (Planar 2R). 1 of 16 entries is wrong.
    <BLANKLINE>
      entry | your entry     | correct entry
      ------+----------------+---------------
      (2,4) | a1*S1 - a2*S12 | a1*S1 + a2*S12
    <BLANKLINE>
    """
    q = QuestionFeedback("1", result.question, 1, float(result.correct), result)
    return render_feedback({"id": "", "name": ""}, [q], title=result.key or "check", fmt=fmt)


def render_summary(data: Mapping[str, object]) -> str:
    """The class summary page (HTML) from the grading data."""
    return _environment("html").get_template("gradebook_summary.html.j2").render(**data)
