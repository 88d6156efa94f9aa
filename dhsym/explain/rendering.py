r"""Rendering the document templates: their environments, and one derivation as a document.

The renderer is the one of :mod:`dhsym.notation.templates` (the
:data:`~dhsym.notation.templates.DOCUMENT` family): a user folder given
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
from pathlib import Path
from typing import TYPE_CHECKING

from dhsym.errors import DHError
from dhsym.notation import templates
from dhsym.notation.tables import text_table
from dhsym.notation.templates import DOCUMENT, format_name, format_suffix, render_template

if TYPE_CHECKING:  # a derivation renders itself through render(): no import at run time
    import jinja2

    from dhsym.notation.templates import Filters

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


_TEXT: Filters = (("grid", _text_grid), ("table", text_table), ("columns", _text_columns))


def environment(kind: str = "latex", template_dir: str | Path | None = None) -> jinja2.Environment:
    """The Jinja2 environment of the document templates for ``kind`` (``latex``,
    ``markdown`` or ``text``): :func:`dhsym.notation.templates.environment` of the
    :data:`~dhsym.notation.templates.DOCUMENT` family, with the text filters
    (``grid``, ``table``, ``columns``) for ``text``.
    """
    fmt = format_name(kind)
    if fmt not in _KINDS:
        raise DHError(f"unknown format {kind!r}: expected one of {', '.join(_KINDS)}")
    return templates.environment(fmt, DOCUMENT, template_dir, _TEXT if fmt == "text" else ())


def render(
    derivation: Document, fmt: str = "text", *, template_dir: str | Path | None = None
) -> str:
    """One derivation as text, Markdown or a LaTeX fragment.

    The templates are those of the document's ``kind`` (``derivation.txt.j2``,
    ``jacobian.md.j2``, …); a LaTeX fragment is ``fragment.tex.j2`` around ``<kind>.tex.j2``.
    """
    env = environment(fmt, template_dir)
    suffix = format_suffix(fmt)
    name = "fragment.tex.j2" if suffix == "tex" else f"{derivation.kind}.{suffix}.j2"
    return render_template(env, name, d=derivation)
