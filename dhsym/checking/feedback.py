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

from .verdict import CheckResult

__all__ = [
    "QuestionFeedback",
    "md_code",
    "md_escape",
    "md_math",
    "render_check",
    "render_feedback",
    "render_summary",
    "templates_dir",
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


def templates_dir() -> Path:
    """The project's ``templates/`` folder (next to the ``dhsym`` package)."""
    here = Path(__file__).resolve().parents[2] / "templates"
    if not (here / "feedback.md.j2").is_file():
        raise DHError(f"feedback templates not found in {here}")
    return here


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


def md_math(tex: object) -> str:
    r"""LaTeX for ``$…$`` inside a Markdown table: ``|`` would end the cell, ``\vert`` does not.

    >>> md_math(r"\left|{a_{1}}\right| + \|x\|")
    '\\left\\vert {a_{1}}\\right\\vert  + \\Vert x\\Vert '
    """
    return " ".join(str(tex).splitlines()).replace("\\|", "\\Vert ").replace("|", "\\vert ")


def _points(x: float) -> str:
    return f"{x:g}"


@lru_cache(maxsize=2)
def _environment(fmt: str):  # noqa: ANN202 - jinja2 is imported lazily
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        autoescape=(fmt == "html"),
        undefined=jinja2.StrictUndefined,
        trim_blocks=False,
        keep_trailing_newline=True,
    )
    env.filters["md"] = md_escape
    env.filters["code"] = md_code
    env.filters["mdmath"] = md_math
    env.filters["points"] = _points
    return env


def render_feedback(
    student: Mapping[str, str],
    questions: Sequence[QuestionFeedback],
    *,
    title: str = "DH homework",
    fmt: str = "md",
    status: str = "graded",
    flags: Sequence[str] = (),
    mathjax_url: str | None = None,
) -> str:
    """One student's feedback page (``fmt`` is ``md`` or ``html``); ``flags`` are notes."""
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
        mathjax_url=mathjax_url,
    )


def render_check(result: CheckResult, fmt: str = "md") -> str:
    """Feedback for a single check (what ``dhsym check`` prints)."""
    q = QuestionFeedback("1", result.question, 1, float(result.correct), result)
    return render_feedback({"id": "", "name": ""}, [q], title=result.key or "check", fmt=fmt)


def render_summary(data: Mapping[str, object]) -> str:
    """The class summary page (HTML) from the grading data."""
    return _environment("html").get_template("gradebook_summary.html.j2").render(**data)
