"""What every command shares: writing its result to a file or standard output, notes on stderr."""

from __future__ import annotations

import sys
from pathlib import Path

__all__ = ["emit", "note_warnings"]


def emit(text: str, output: str | None) -> None:
    """Print ``text``, or write it to ``output`` and say so on standard error."""
    if output:
        Path(output).parent.mkdir(parents=True, exist_ok=True)
        Path(output).write_text(text if text.endswith("\n") else text + "\n", encoding="utf-8")
        print(f"wrote {output}", file=sys.stderr)
    else:
        print(text)


def note_warnings(table: object) -> None:
    """Print what the reader did to the input (``table.warnings``) on standard error, once."""
    for text in getattr(table, "warnings", ()):
        print(f"dhsym: note: {text}", file=sys.stderr)
