r"""Rendering through the Jinja2 templates: the environments, and one derivation as a document.

The templates come from :func:`dhsym.explain.templates.loader`: a user folder given
with ``template_dir`` comes first, so a file there replaces the built-in one
of the same name, and ``base/NAME`` always reaches the built-in (to extend it
and override single blocks)::

    ((* extends "base/derivation.tex.j2" *))
    ((* block legend *))((* endblock *))

LaTeX templates use nbconvert-style delimiters (``((* … *))`` statements,
``((( … )))`` expressions, ``((= … =))`` comments) so that TeX braces need no
escaping; Markdown and text templates use Jinja's usual ``{{ … }}``.
Undefined names are errors (``StrictUndefined``). Every string printed by a
template is escaped for its format (LaTeX, Markdown; control characters are
removed from text) unless it is trusted :class:`~dhsym.notation.escape.TeX` from the
printers, so a robot named ``\input{/etc/passwd}`` prints as text.

Examples
--------
>>> from dhsym.explain.derivation import derive
>>> out = render(derive("planar2r"), "latex")
>>> "C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12}" in out
True
>>> print(render(derive("planar2r"), "text").splitlines()[0])
Planar 2R: forward kinematics (standard DH convention)
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from dhsym.errors import DHError
from dhsym.notation.escape import TeX, _clean_text, escape_latex, escape_markdown
from dhsym.notation.tables import text_table

from .templates import loader

if TYPE_CHECKING:  # a derivation renders itself through render(): no import at run time
    import jinja2

    from .data import Document

__all__ = [
    "environment",
    "render",
    "render_template",
]

_KINDS = ("latex", "markdown", "text")


def _text_grid(rows: Sequence[Sequence[object]]) -> list[str]:
    """A matrix as bracketed, column-aligned lines of text."""
    cells = [[getattr(c, "text", c) for c in row] for row in rows]
    widths = [max(len(str(r[k])) for r in cells) for k in range(len(cells[0]))]
    return [
        "[ " + "  ".join(str(c).rjust(w) for c, w in zip(r, widths, strict=True)) + " ]"
        for r in cells
    ]


def _text_columns(items: Sequence[str], width: int = 96) -> list[str]:
    """Short items in as many aligned columns as fit in ``width`` characters."""
    items = [str(i) for i in items]
    if not items:
        return []
    colw = max(map(len, items)) + 3
    ncol = max(1, min(len(items), (width + 3) // colw))
    rows = [items[k : k + ncol] for k in range(0, len(items), ncol)]
    return ["".join(i.ljust(colw) for i in row).rstrip() for row in rows]


def environment(kind: str = "latex", template_dir: str | Path | None = None) -> jinja2.Environment:
    """The Jinja2 environment for ``kind`` (``latex``, ``markdown`` or ``text``).

    Built once per kind and template folder (templates compile once; Jinja2 reloads a
    template file that changes on disk).
    """
    if template_dir is not None:
        template_dir = Path(template_dir).resolve()
    return _environment(kind, template_dir)


@lru_cache(maxsize=8)
def _environment(kind: str, template_dir: Path | None) -> jinja2.Environment:
    import jinja2
    from markupsafe import Markup

    if kind not in _KINDS:
        raise DHError(f"unknown format {kind!r}: expected one of {', '.join(_KINDS)}")
    common: dict[str, Any] = dict(
        loader=loader(template_dir),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        extensions=["jinja2.ext.do"],
    )
    if kind == "text":
        env = jinja2.Environment(autoescape=False, finalize=_clean_text, **common)
        env.filters.update(grid=_text_grid, table=text_table, columns=_text_columns)
        return env
    escape = escape_latex if kind == "latex" else escape_markdown

    def finalize(value: object) -> object:
        if isinstance(value, Markup):
            return value  # macro output, already finalised piece by piece
        if isinstance(value, TeX):
            return Markup(value)
        return Markup(escape(value))

    delimiters: dict[str, Any] = dict(
        block_start_string="((*",
        block_end_string="*))",
        variable_start_string="(((",
        variable_end_string=")))",
        comment_start_string="((=",
        comment_end_string="=))",
    )
    env = jinja2.Environment(
        autoescape=True, finalize=finalize, **(delimiters if kind == "latex" else {}), **common
    )
    env.filters["tex"] = lambda s: Markup(TeX(s))  # for literal LaTeX assembled in a template
    return env


def render_template(env: jinja2.Environment, name: str, **context: object) -> str:
    """Render template ``name``; template mistakes (often in a user folder) become DHError."""
    import jinja2

    try:
        return env.get_template(name).render(**context)
    except jinja2.TemplateError as err:
        line, file = getattr(err, "lineno", None), getattr(err, "filename", None)
        where = f"{file}:{line}: " if line else ""
        raise DHError(f"template {name}: {where}{err.message or err}") from None


def render(
    derivation: Document, fmt: str = "text", *, template_dir: str | Path | None = None
) -> str:
    """One derivation as text, Markdown or a LaTeX fragment.

    The templates are those of the document's ``kind`` (``derivation.txt.j2``,
    ``jacobian.md.j2``, …); a LaTeX fragment is ``fragment.tex.j2`` around ``<kind>.tex.j2``.
    """
    env = environment(fmt, template_dir)
    kind = derivation.kind
    name = {
        "latex": "fragment.tex.j2",
        "markdown": f"{kind}.md.j2",
        "text": f"{kind}.txt.j2",
    }[fmt]
    return render_template(env, name, d=derivation)
