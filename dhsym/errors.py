"""Error types of dhsym.

Every error that comes from user input carries *where* it happened: the
file, the row (1-based, as in the lecture tables) and the field (column).

Examples
--------
>>> err = TableError("expected a number or expression", file="arm.yaml", row=2, field="alpha")
>>> str(err)
'arm.yaml: row 2, field alpha: expected a number or expression'
>>> isinstance(err, DHError)
True
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "DHError",
    "TableError",
    "ParseError",
    "GeometryError",
    "ChainError",
    "FormatError",
    "echoed",
]


class DHError(Exception):
    """Base class of every error raised by dhsym on bad input.

    Parameters
    ----------
    message
        What was wrong and what was expected.
    file, row, field
        Where it happened, when known. ``row`` is 1-based.
    """

    def __init__(
        self,
        message: str,
        *,
        file: str | None = None,
        row: int | None = None,
        field: str | None = None,
    ) -> None:
        self.message = message
        self.file = file
        self.row = row
        self.field = field
        super().__init__(self.__str__())

    def located(self, **where: object) -> DHError:
        """Return a copy of this error with missing location parts filled in."""
        loc: dict[str, Any] = {"file": self.file, "row": self.row, "field": self.field}
        for key, value in where.items():
            if loc.get(key) is None:
                loc[key] = value
        return type(self)(self.message, **loc)

    def __str__(self) -> str:
        parts = []
        if self.file:
            parts.append(str(self.file))
        where = []
        if self.row is not None:
            where.append(f"row {self.row}")
        if self.field:
            where.append(f"field {self.field}")
        head = ": ".join(p for p in [", ".join(parts), ", ".join(where)] if p)
        return f"{head}: {self.message}" if head else self.message


class TableError(DHError):
    """A DH table (file, rows or values) is not valid."""


class ParseError(DHError):
    """A text expression could not be read by the whitelist parser."""


class GeometryError(DHError):
    """Joint axes or frames do not describe a valid serial chain."""


class ChainError(DHError):
    """A chain of named frames is missing a link or does not close."""


class FormatError(DHError):
    """A file of another tool (URDF, XML) cannot be read: ``field`` names the element."""


def echoed(value: object, limit: int = 60) -> str:
    """``repr(value)`` for an error message, cut to about ``limit`` characters: user input
    is echoed so the user can find it, never in full (a 100 kB option is not echoed as such).

    >>> echoed("digits=4"), echoed("x" * 1000, 10)
    ("'digits=4'", "'xxxxxxxx… (1000 characters)")
    """
    text = repr(value)
    if len(text) <= limit:
        return text
    size = len(value) if isinstance(value, (str, bytes)) else len(text)
    return f"{text[: limit - 1]}… ({size} characters)"
