"""Where the Jinja2 templates come from: the one loader for handouts, derivations and feedback.

The built-in templates are the top-level ``templates/`` folder of the source tree,
shipped in the wheel as the package data ``dhsym/templates`` (``pyproject.toml``
maps one onto the other). A folder given as ``template_dir`` comes first, so a
file there replaces the built-in one of the same name, and ``base/NAME`` always
reaches the built-in one (to extend it and override single blocks).

Examples
--------
>>> (builtin_dir() / "handout.tex.j2").is_file()
True
>>> "{{" in loader().get_source(None, "base/feedback.md.j2")[0]
True
"""

from __future__ import annotations

from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

from dhsym.errors import DHError

if TYPE_CHECKING:  # jinja2 is imported when a document is rendered
    import jinja2

__all__ = ["builtin_dir", "loader"]

_MARKER = "handout.tex.j2"


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


def loader(template_dir: str | Path | None = None) -> jinja2.BaseLoader:
    """A Jinja2 loader: ``template_dir`` first, then the built-in templates, ``base/`` prefix."""
    import jinja2

    loaders: list[jinja2.BaseLoader] = []
    if template_dir is not None:
        if not Path(template_dir).is_dir():
            raise DHError(f"template folder {template_dir} does not exist")
        loaders.append(jinja2.FileSystemLoader(str(template_dir)))
    builtin = str(builtin_dir())
    loaders += [
        jinja2.FileSystemLoader(builtin),
        jinja2.PrefixLoader({"base": jinja2.FileSystemLoader(builtin)}),
    ]
    return jinja2.ChoiceLoader(loaders)
