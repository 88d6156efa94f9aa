"""Comma-separated numbers given on the command line (``--q 90,-45`` or ``--check pi/2,0``).

Each value goes through the whitelist parser :func:`dhsym.parsing.parse_expression`,
so ``pi/2`` and ``sqrt(2)/2`` are numbers and nothing is evaluated. Used by the
sub-commands of :mod:`dhsym.cli`, :mod:`dhsym.plotting` and :mod:`dhsym.rendering`, with
:func:`check_count` for counts such as ``--samples``.

Examples
--------
>>> parse_number_list("pi/2, 0.5", "--q")
[1.5707963267948966, 0.5]
>>> parse_number_list("1, a2", "--check")
Traceback (most recent call last):
...
dhsym.errors.DHError: --check value 2 (a2) must be a real number
"""

from __future__ import annotations

from .errors import DHError
from .parsing import parse_expression

__all__ = ["check_count", "parse_number_list"]


def check_count(value: int, option: str, low: int, high: int) -> int:
    """``value`` if ``low <= value <= high``; otherwise a one-line error naming ``option``.

    Counts the user chooses (samples, dots per inch) size arrays and pictures: an
    unbounded one is gigabytes of memory or an hour of work.

    >>> check_count(20, "--samples", 0, 100_000)
    20
    >>> check_count(10**11, "--samples", 0, 100_000)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: --samples must be from 0 to 100000, got 100000000000
    """
    if not low <= value <= high:
        raise DHError(f"{option} must be from {low} to {high}, got {value}")
    return value


def parse_number_list(text: str, option: str) -> list[float]:
    """The numbers of ``text`` (comma separated) as floats; ``option`` names them in errors."""
    values = []
    for k, part in enumerate(text.split(","), start=1):
        expr = parse_expression(part, field=f"{option} value {k}")
        if expr.free_symbols or not expr.is_number or not expr.is_real:
            raise DHError(f"{option} value {k} ({part.strip()}) must be a real number")
        values.append(float(expr))
    return values
