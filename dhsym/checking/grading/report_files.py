"""The report folder's files: safe names for student ids, atomic writes, CSV cells.

Every path is checked to stay inside the report folder, every file is written to a
temporary name and renamed, and CSV cells that a spreadsheet would run as a formula
are quoted.

Examples
--------
>>> safe_name("con", set())
'con-...'
>>> safe_name("../../etc/passwd", set()).startswith("etc_passwd-")
True
>>> csv_cell("=HYPERLINK()")
"'=HYPERLINK()"
"""

from __future__ import annotations

import hashlib
import os
import re
from pathlib import Path

from dhsym.errors import DHError

__all__ = [
    "CACHE_NAME",
    "csv_cell",
    "inside",
    "inside_folder",
    "name_base",
    "safe_name",
    "write_atomic",
]

CACHE_NAME = ".dhsym-grading-cache.json"

_RESERVED = frozenset(
    {
        "con",
        "prn",
        "aux",
        "nul",
        *(f"com{i}" for i in range(10)),
        *(f"lpt{i}" for i in range(10)),
    }
)


def name_base(student: str) -> str:
    """The file-name form of a student id before it is made unique (ids equal here collide).

    >>> name_base("Ann Lee"), name_base("ann_lee"), name_base("../..")
    ('Ann_Lee', 'ann_lee', 'student')
    """
    return re.sub(r"[^A-Za-z0-9._-]+", "_", student).strip("._-")[:60] or "student"


def safe_name(student: str, used: set[str]) -> str:
    """A file name for a student id: ``[A-Za-z0-9._-]``, no leading dot, unique, short."""
    base = name_base(student)
    name = base
    if name != student or name.lower() in used or name.lower() in _RESERVED:
        name = f"{base}-{hashlib.sha1(student.encode('utf-8', 'replace')).hexdigest()[:8]}"
    while name.lower() in used:
        name += "_"
    used.add(name.lower())
    return name


def inside(root: Path, *parts: str) -> Path:
    """``root / parts``, resolved; an error if that leaves the (resolved) report folder."""
    path = root.joinpath(*parts).resolve()
    if not path.is_relative_to(root):
        raise DHError(f"refusing to write outside the report folder: {path}")
    return path


def inside_folder(root: Path, folder: Path, name: str) -> Path:
    """:func:`inside` for a plain file ``name`` (no ``/``, no leading dot) in ``folder``,
    a folder that :func:`inside` resolved in ``root``: one ``lstat`` instead of resolving
    every part of the path again; only a symbolic link is resolved (and refused when it
    leads out of ``root``).

    >>> import tempfile
    >>> root = Path(tempfile.mkdtemp()).resolve()
    >>> folder = inside(root, "feedback")
    >>> inside_folder(root, folder, "a.md") == inside(root, "feedback", "a.md")
    True
    """
    if "/" in name or name.startswith(".") or os.sep in name:
        raise DHError(f"not a plain file name: {name!r}")
    path = folder / name
    return inside(root, *path.relative_to(root).parts) if path.is_symlink() else path


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to a temporary file beside ``path``, then rename it over ``path``.

    Text that is not valid Unicode (a lone surrogate from a file name that is not
    UTF-8) is written with ``\\x`` escapes, never an encoding error.
    """
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_bytes(text.encode("utf-8", "backslashreplace"))
    os.replace(tmp, path)


def csv_cell(value: object) -> str:
    """``value`` as a CSV cell that a spreadsheet shows as text, never runs as a formula."""
    s = str(value)
    return "'" + s if s[:1] in ("=", "+", "-", "@", "\t", "\r") else s
