"""The name of a disk-cache entry: a table's canonical form, what is derived from it, and
the versions of dhsym and sympy, hashed with SHA-256.

A new dhsym or sympy derives afresh (its results may differ); equal tables share an
entry whatever their name or file (:func:`dhsym.model.table.canonical_text`). The version
of dhsym is its release and a stamp of its installed code (each module's size and
modification time): a checkout whose code changed between releases derives afresh too.

>>> from dhsym.model.library import load_table
>>> name = entry_name(load_table("puma560"), "transform", "0-6")
>>> name.startswith("transform-"), len(name)
(True, 74)
>>> name == entry_name(load_table("puma560"), "transform", "0-6")
True
>>> name == entry_name(load_table("puma560"), "transform", "0-5")
False
"""

from __future__ import annotations

import hashlib
import re
from functools import lru_cache
from pathlib import Path

import sympy as sp

from dhsym._version import __version__
from dhsym.model.table import DHTable, canonical_text

__all__ = ["code_version", "entry_name", "source_name"]

_KIND = re.compile(r"[a-z][a-z0-9_]{0,31}")


def _check_kind(kind: str) -> None:
    if not _KIND.fullmatch(kind):
        raise ValueError(f"a cache kind is a short lower-case word, not {kind!r}")


@lru_cache(maxsize=1)
def code_version() -> str:
    """dhsym's release and a SHA-256 stamp of its modules (relative path, size and
    modification time of each), read once per process.

    >>> code_version().startswith("dhsym ")
    True
    """
    package = Path(__file__).resolve().parents[1]
    stamp = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        st = path.stat()
        stamp.update(f"{path.relative_to(package)} {st.st_size} {st.st_mtime_ns}\n".encode())
    return f"dhsym {__version__} {stamp.hexdigest()[:16]}"


def entry_name(table: DHTable, kind: str, *parts: str) -> str:
    """``<kind>-<sha256>``: the entry of ``kind`` (``"transform"``, ``"dynamics"``, …)
    derived from ``table``, told apart by ``parts`` (frames, method, values)."""
    _check_kind(kind)
    text = "\n".join(
        [code_version(), f"sympy {sp.__version__}", kind, *parts, canonical_text(table)]
    )
    return f"{kind}-{hashlib.sha256(text.encode()).hexdigest()}"


def source_name(kind: str, source: str) -> str:
    """``<kind>-<sha256>`` of a generated program (its text names everything it depends on).

    >>> name = source_name("lib", "int f(void) { return 1; }")
    >>> name[:4], len(name)
    ('lib-', 68)
    """
    _check_kind(kind)
    text = f"{__version__}\n{kind}\n{source}"
    return f"{kind}-{hashlib.sha256(text.encode()).hexdigest()}"
