"""Built-in robots from the lectures, loadable by name, and planar nR chains.

Examples
--------
>>> "puma560" in builtin_names()
True
>>> builtin_table("planar2r").name
'Planar 2R'
>>> planar_chain(8).n
8
>>> load_table("planar20r").n
20
>>> load_table("puma650")
Traceback (most recent call last):
...
dhsym.errors.DHError: no built-in robot or table file 'puma650': did you mean 'puma560'? ...
"""

from __future__ import annotations

import difflib
import re
from importlib import resources
from pathlib import Path

from dhsym.errors import DHError

from .table import DHRow, DHTable
from .tablefile import read_table, read_table_text

__all__ = ["builtin_names", "builtin_table", "load_table", "planar_chain"]

_PLANAR = re.compile(r"^planar(\d+)r$")


def builtin_names() -> list[str]:
    """Names of the robots shipped with dhsym (file stems in ``dhsym/model/robots``)."""
    files = resources.files("dhsym.model").joinpath("robots").iterdir()
    return sorted(f.name[:-5] for f in files if f.name.endswith(".yaml"))


def planar_chain(n: int) -> DHTable:
    """A planar nR chain: ``θ_k``, ``d = 0``, ``a_k``, ``α = 0`` (the 2R and 4R of IRob2305,
    Lecture 5, for any n)."""
    if not 1 <= n <= 60:
        raise DHError(f"planar chains have 1 to 60 joints; got {n}")
    rows = [DHRow.revolute(f"theta{k}", a=f"a{k}") for k in range(1, n + 1)]
    return DHTable.from_rows(
        rows,
        name=f"Planar {n}R",
        angles="deg",
        source="IRob2305 Introduction to Robotics, Lecture 5 (Denavit-Hartenberg parameters, "
        "forward kinematics), Examples 2 and 3, extended to n joints",
    )


def builtin_table(name: str) -> DHTable:
    """The table of a built-in robot by name (``planarNr`` for any N up to 60)."""
    key = name.strip().lower().replace("-", "").replace(" ", "")
    m = _PLANAR.match(key)
    if key in builtin_names():
        text = (
            resources.files("dhsym.model")
            .joinpath("robots")
            .joinpath(f"{key}.yaml")
            .read_text("utf-8")
        )
        return read_table_text(text, file=f"{key}.yaml")
    if m:
        return planar_chain(int(m.group(1)))
    names = builtin_names()
    close = difflib.get_close_matches(key, names, n=1, cutoff=0.6)
    hint = f"did you mean {close[0]!r}? " if close else ""
    raise DHError(
        f"no built-in robot or table file {name!r}: {hint}built-in robots are "
        + ", ".join(names)
        + ", planarNr"
    )


def load_table(name_or_path: str | Path) -> DHTable:
    """A table from a file path (``.yaml``/``.yml``) or a built-in name."""
    p = Path(name_or_path)
    if p.suffix.lower() in (".yaml", ".yml", ".json") or p.exists():
        return read_table(p)
    return builtin_table(str(name_or_path))
