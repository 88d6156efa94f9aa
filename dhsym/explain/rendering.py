r"""Derivations and handouts from Jinja2 templates: text, Markdown, LaTeX and PDF.

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
>>> import dhsym
>>> out = render_derivation(dhsym.load("planar2r"), fmt="latex")
>>> "C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12}" in out
True
>>> print(render_derivation(dhsym.load("planar2r"), fmt="text").splitlines()[0])
Planar 2R: forward kinematics (standard DH convention)
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

from dhsym.errors import DHError
from dhsym.kinematics.robot import Robot
from dhsym.notation.escape import TeX, _clean_text, escape_latex, escape_markdown
from dhsym.notation.tables import text_table

from .derivation import Derivation, as_robot, derive, general_link
from .latex import compile_pdf
from .templates import loader

__all__ = [
    "environment",
    "render",
    "render_derivation",
    "render_handout",
    "write_handout",
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


def environment(kind: str = "latex", template_dir: str | Path | None = None) -> object:
    """The Jinja2 environment for ``kind`` (``latex``, ``markdown`` or ``text``)."""
    import jinja2
    from markupsafe import Markup

    if kind not in _KINDS:
        raise DHError(f"unknown format {kind!r}: expected one of {', '.join(_KINDS)}")
    common = dict(
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

    delimiters = dict(
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


def _render(env: object, name: str, **context: object) -> str:
    """Render template ``name``; template mistakes (often in a user folder) become DHError."""
    import jinja2

    try:
        return env.get_template(name).render(**context)  # type: ignore[attr-defined]
    except jinja2.TemplateError as err:
        where = f"{err.filename}:{err.lineno}: " if getattr(err, "lineno", None) else ""
        raise DHError(f"template {name}: {where}{err.message or err}") from None


def render(
    derivation: Derivation, fmt: str = "text", *, template_dir: str | Path | None = None
) -> str:
    """One derivation as text, Markdown or a LaTeX fragment."""
    env = environment(fmt, template_dir)
    name = {
        "latex": "fragment.tex.j2",
        "markdown": "derivation.md.j2",
        "text": "derivation.txt.j2",
    }[fmt]
    return _render(env, name, d=derivation)


def render_derivation(
    robot: Robot | str | Path,
    fmt: str = "text",
    frm: int = 0,
    to: int | None = None,
    **options: object,
) -> str:
    """``^{frm}T_{to}`` of ``robot`` derived step by step, as text, Markdown or LaTeX.

    ``options`` go to :func:`dhsym.explain.derivation.derive` (``factors``, ``numeric``,
    ``compact``, ``check``, ``width``) except ``template_dir``.
    """
    template_dir = options.pop("template_dir", None)
    d = derive(robot, frm=frm, to=to, **options)  # type: ignore[arg-type]
    return render(d, fmt, template_dir=template_dir)  # type: ignore[arg-type]


_DERIVE_OPTIONS = ("frm", "to", "factors", "numeric", "compact", "check", "width")


def _derivations(
    robots: Sequence[Robot | str | Path | Derivation], options: dict[str, object]
) -> list[Derivation]:
    """Derive each robot; ``check=True`` applies to those with numbers for every length."""
    out = []
    for r in robots:
        if isinstance(r, Derivation):
            out.append(r)
            continue
        opts = dict(options)
        robot = as_robot(r)
        if opts.get("check") is True and set(robot.table.constants) - set(robot.table.value_map):
            opts["check"] = None
        out.append(derive(robot, **opts))  # type: ignore[arg-type]
    return out


def _unique_keys(derivations: Sequence[Derivation]) -> list[str]:
    keys: list[str] = []
    for d in derivations:
        key, k = d.key, 2
        while key in keys:
            key, k = f"{d.key}-{k}", k + 1
        keys.append(key)
    return keys


def render_handout(
    robots: Sequence[Robot | str | Path | Derivation],
    *,
    title: str | None = None,
    course: str = "",
    author: str = "",
    date: str = "",
    mode: str = "answers",
    convention_note: bool = False,
    template_dir: str | Path | None = None,
    figures: dict[str, str] | None = None,
    **options: object,
) -> str:
    r"""A standalone LaTeX handout for one or more robots.

    ``mode`` is ``answers`` (full derivations) or ``problems`` (table and
    questions with space for answers). ``figures`` maps a robot's key (its
    name in lower case, ``-`` separated) to a graphics file next to the
    ``.tex``. Other options go to :func:`~dhsym.explain.derivation.derive`;
    ``check=True`` checks the robots whose lengths all have numbers.

    >>> tex = render_handout(["planar2r"], title=r"\input{/etc/passwd}")
    >>> r"\textbackslash{}input\{/etc/passwd\}" in tex, r"\input{/etc" in tex
    (True, False)
    """
    if mode not in ("answers", "problems"):
        raise DHError(f"unknown mode {mode!r}: expected 'answers' or 'problems'")
    unknown = set(options) - set(_DERIVE_OPTIONS)
    if unknown:
        raise DHError(f"unknown handout option(s): {', '.join(sorted(unknown))}")
    ds = _derivations(robots, options)
    items = [
        {"d": d, "key": k, "figure": _graphic((figures or {}).get(k))}
        for d, k in zip(ds, _unique_keys(ds), strict=True)
    ]
    if title is None:
        title = "Forward kinematics: " + ", ".join(d.name for d in ds)
    env = environment("latex", template_dir)
    return _render(
        env,
        "handout.tex.j2",
        items=items,
        title=title,
        course=course,
        author=author,
        date=date,
        mode=mode,
        convention_note=convention_note,
        general={c: general_link(c) for c in ("standard", "modified")},
    )


def _graphic(name: str | None) -> TeX | None:
    """A graphics file name that LaTeX reads as it is (no escaping needed or allowed)."""
    if name is None:
        return None
    if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._-]*\.(pdf|png|jpg)", name):
        raise DHError(f"figure file names are letters, digits, '.', '_' and '-'; got {name!r}")
    return TeX(name)


def _figures(robots: Sequence[Robot], keys: Sequence[str], folder: Path, stem: str) -> dict:
    try:
        from dhsym.plot.figures import plot_robot
    except ImportError as err:
        raise DHError(f"--figure needs matplotlib, which is not available ({err})") from None
    out = {}
    for robot, key in zip(robots, keys, strict=True):
        name = f"{stem}-{key}-home.pdf"
        fig = plot_robot(robot, None)
        fig.savefig(folder / name, bbox_inches="tight")  # type: ignore[attr-defined]
        out[key] = name
    return out


def write_handout(
    robots: Sequence[Robot | str | Path],
    output: str | Path,
    *,
    pdf: bool = False,
    figure: bool = False,
    keep_aux: bool = False,
    **options: object,
) -> Path:
    """Write the handout's ``.tex`` (and figures); with ``pdf=True`` compile it.

    ``options`` are those of :func:`render_handout`. Returns the path of the
    PDF when compiled, else of the ``.tex``. LaTeX's auxiliary files stay in a
    temporary folder unless ``keep_aux``.
    """
    out = Path(output)
    if out.suffix != ".tex":
        raise DHError(f"the handout file must end in .tex, got {out.name}")
    out.parent.mkdir(parents=True, exist_ok=True)
    loaded = [as_robot(r) for r in robots]
    derive_opts = {k: options.pop(k) for k in _DERIVE_OPTIONS if k in options}
    ds = _derivations(loaded, derive_opts)
    figures = None
    if figure:
        stem = re.sub(r"[^A-Za-z0-9-]+", "-", out.stem).strip("-") or "handout"
        figures = _figures(loaded, _unique_keys(ds), out.parent, stem)
    out.write_text(render_handout(ds, figures=figures, **options), encoding="utf-8")
    return compile_pdf(out, keep_aux=keep_aux) if pdf else out


# --- command line -----------------------------------------------------------------------------
