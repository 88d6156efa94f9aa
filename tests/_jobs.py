"""Small jobs for the runner tests, in a module that imports only the standard library.

A sandbox's child imports this module when it unpickles a job: it must be quick,
since that happens inside the job's deadline.
"""

from __future__ import annotations

import os
import re


def stuck_or_square(n: int) -> int:
    """``n * n``; for a negative ``n`` a regular expression that backtracks for ages.

    No signal interrupts a regular expression (it runs in C): only killing the
    process stops it, which is what a job of a hostile answer needs.
    """
    if n < 0:
        re.match(r"(a+)+$", "a" * 40 + "b")
    return n * n


def die(_: object) -> None:
    """End the process at once, as a crash would."""
    os._exit(3)
