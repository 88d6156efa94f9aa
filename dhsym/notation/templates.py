r"""The one template renderer: where the Jinja2 templates come from, their formats, and how
each family of templates is rendered (documents, feedback, generated code).

The built-in templates are the top-level ``templates/`` folder of the source tree,
shipped in the wheel as the package data ``dhsym/templates`` (``pyproject.toml``
maps one onto the other). A folder given as ``template_dir`` comes first, so a
file there replaces the built-in one of the same name, and ``base/NAME`` always
reaches the built-in one (to extend it and override single blocks).

One vocabulary of formats (:data:`FORMATS`): ``latex``, ``markdown``, ``html`` and
``text``; the file suffixes ``tex``, ``md`` and ``txt`` are accepted for them
(:func:`format_name`), and a template of format *f* is named ``NAME.<suffix>.j2``
(:func:`format_suffix`).

Three families of templates share the loader and differ in how they are written
(:class:`Family`): :data:`DOCUMENT` (derivations and handouts: every printed value
escaped for its format unless it is trusted :class:`~dhsym.notation.escape.TeX`,
LaTeX with nbconvert-style delimiters ``((* … *))``, ``((( … )))``, ``((= … =))``),
:data:`FEEDBACK` (feedback pages: HTML autoescaped, Markdown escaped by its filters)
and :data:`CODE` (generated source code in ``templates/export``: nothing escaped,
user text reaches it only through safe comment lines).

The notation room holds it because every room that writes a document or a file
(export, explain, checking) ranks above it (``scripts/import_graph.py``).

Examples
--------
>>> (builtin_dir() / "handout.tex.j2").is_file()
True
>>> "{{" in loader().get_source(None, "base/feedback.md.j2")[0]
True
>>> format_name("md"), format_suffix("latex")
('markdown', 'tex')
>>> env = environment("latex", DOCUMENT)
>>> env.from_string(r"\section{((( name )))}").render(name="50% \\input")
'\\section{50\\% \\textbackslash{}input}'
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

from dhsym.errors import DHError

from .escape import TeX, clean_text, escape_latex, escape_markdown

if TYPE_CHECKING:  # jinja2 is imported when a document is rendered
    import jinja2

__all__ = [
    "CODE",
    "DOCUMENT",
    "FEEDBACK",
    "PAGE",
    "FORMATS",
    "Family",
    "builtin_dir",
    "environment",
    "format_name",
    "format_suffix",
    "loader",
    "render_template",
]

_MARKER = "handout.tex.j2"

#: The formats of templates, each with the suffix its template files carry.
FORMATS: dict[str, str] = {"latex": "tex", "markdown": "md", "html": "html", "text": "txt"}
_ALIASES = {suffix: name for name, suffix in FORMATS.items()}

#: A filter a template may use: its name and the function.
Filters = tuple[tuple[str, Callable[..., Any]], ...]


@dataclass(frozen=True)
class Family:
    """How a family of templates is written: whitespace control and escaping.

    ``trim``: Jinja's ``trim_blocks`` and ``lstrip_blocks`` (a block tag's line vanishes);
    ``escape``: every printed value is escaped for the format by the environment (LaTeX,
    Markdown) or cleaned of control characters (text) unless it is trusted ``TeX``,
    and LaTeX templates use the ``((* … *))`` delimiters; otherwise only HTML is
    autoescaped and a template escapes with its filters; ``folder``: the templates'
    subfolder of ``templates/`` (its names are given without it).
    """

    name: str
    trim: bool
    escape: bool
    folder: str = ""


#: Derivations and handouts (:mod:`dhsym.explain`).
DOCUMENT = Family("document", trim=True, escape=True)
#: Feedback pages and class summaries (:mod:`dhsym.checking`).
FEEDBACK = Family("feedback", trim=False, escape=False)
#: Pages of their own (the 3D view, :mod:`dhsym.view`): HTML autoescaped, scripts passed in
#: as trusted markup built by dhsym.
PAGE = Family("page", trim=False, escape=False)
#: Generated source code (:mod:`dhsym.export`), in ``templates/export``.
CODE = Family("code", trim=True, escape=False, folder="export")

_LATEX_DELIMITERS: dict[str, Any] = dict(
    block_start_string="((*",
    block_end_string="*))",
    variable_start_string="(((",
    variable_end_string=")))",
    comment_start_string="((=",
    comment_end_string="=))",
)


def format_name(fmt: str) -> str:
    """The format ``fmt`` names, in :data:`FORMATS`' words (``md`` is ``markdown``).

    >>> format_name("tex"), format_name("text")
    ('latex', 'text')
    >>> format_name("docx")
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: unknown format 'docx': expected one of latex, markdown, html, text
    """
    name = _ALIASES.get(fmt, fmt)
    if name not in FORMATS:
        raise DHError(f"unknown format {fmt!r}: expected one of {', '.join(FORMATS)}")
    return name


def format_suffix(fmt: str) -> str:
    """The suffix of ``fmt``'s template files (``feedback.md.j2``).

    >>> format_suffix("markdown"), format_suffix("txt")
    ('md', 'txt')
    """
    return FORMATS[format_name(fmt)]


@lru_cache(maxsize=1)
def builtin_dir() -> Path:
    """The folder of the built-in templates (package data, or the source tree's ``templates/``)."""
    packaged = Path(str(resources.files("dhsym"))) / "templates"
    source = Path(__file__).resolve().parents[2] / "templates"
    for folder in (packaged, source):
        if (folder / _MARKER).is_file():
            return folder
    raise DHError(
        f"dhsym's templates are missing (looked in {packaged} and {source}); "
        "reinstall dhsym from its wheel or source tree"
    )


def loader(template_dir: str | Path | None = None, folder: str = "") -> jinja2.BaseLoader:
    """A Jinja2 loader: ``template_dir`` first, then the built-in templates, ``base/`` prefix.

    ``folder`` is a subfolder of the built-in templates to load from (``export``).
    """
    import jinja2

    loaders: list[jinja2.BaseLoader] = []
    if template_dir is not None:
        if not Path(template_dir).is_dir():
            raise DHError(f"template folder {template_dir} does not exist")
        loaders.append(jinja2.FileSystemLoader(str(template_dir)))
    builtin = str(builtin_dir() / folder) if folder else str(builtin_dir())
    loaders += [
        jinja2.FileSystemLoader(builtin),
        jinja2.PrefixLoader({"base": jinja2.FileSystemLoader(builtin)}),
    ]
    return jinja2.ChoiceLoader(loaders)


def environment(
    fmt: str,
    family: Family = DOCUMENT,
    template_dir: str | Path | None = None,
    filters: Filters = (),
) -> jinja2.Environment:
    """The Jinja2 environment for templates of format ``fmt`` and ``family``.

    Built once per format, family, template folder and filters (templates compile once;
    Jinja2 reloads a template file that changes on disk). Undefined names are errors.

    >>> environment("md", FEEDBACK) is environment("markdown", FEEDBACK)
    True
    """
    folder = None if template_dir is None else Path(template_dir).resolve()
    return _environment(format_name(fmt), family, folder, filters)


@lru_cache(maxsize=16)
def _environment(
    fmt: str, family: Family, template_dir: Path | None, filters: Filters
) -> jinja2.Environment:
    import jinja2
    from markupsafe import Markup

    common: dict[str, Any] = dict(
        loader=loader(template_dir, family.folder),
        undefined=jinja2.StrictUndefined,
        trim_blocks=family.trim,
        lstrip_blocks=family.trim,
        keep_trailing_newline=True,
    )
    if not family.escape:
        # source code and text are not HTML: user text goes through filters or comment()
        env = jinja2.Environment(autoescape=(fmt == "html"), **common)  # noqa: S701
    elif fmt in ("text", "html"):
        if fmt == "html":
            raise DHError(f"the {family.name} templates have no html format")
        env = jinja2.Environment(
            autoescape=False, finalize=clean_text, extensions=["jinja2.ext.do"], **common
        )
    else:
        escape = escape_latex if fmt == "latex" else escape_markdown

        def finalize(value: object) -> object:
            if isinstance(value, Markup):
                return value  # macro output, already finalised piece by piece
            if isinstance(value, TeX):
                return Markup(value)  # noqa: S704 - trusted printer output
            return Markup(escape(value))  # noqa: S704 - escaped just now

        env = jinja2.Environment(
            autoescape=True,
            finalize=finalize,
            extensions=["jinja2.ext.do"],
            **(_LATEX_DELIMITERS if fmt == "latex" else {}),
            **common,
        )
        # for literal LaTeX assembled in a template
        env.filters["tex"] = lambda s: Markup(TeX(s))  # noqa: S704
    env.filters.update(filters)
    return env


def render_template(env: jinja2.Environment, name: str, **context: object) -> str:
    """Render template ``name``; template mistakes (often in a user folder) become DHError.

    >>> render_template(environment("text"), "nothing.txt.j2")
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: template nothing.txt.j2: nothing.txt.j2
    """
    import jinja2

    try:
        return env.get_template(name).render(**context)
    except jinja2.TemplateError as err:
        line, file = getattr(err, "lineno", None), getattr(err, "filename", None)
        where = f"{file}:{line}: " if line else ""
        raise DHError(f"template {name}: {where}{err.message or err}") from None
