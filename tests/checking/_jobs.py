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


def regex_worst_case(job: tuple[str, int, tuple[str, ...], str, str, str, int]) -> float:
    """Run the matching functions ``ops`` of a pattern on a built worst-case text; seconds."""
    import time

    pattern, flags, ops, prefix, filler, kind, n = job
    p = re.compile(pattern, flags)
    text = worst_case_text(prefix, filler, kind, n)
    start = time.perf_counter()
    for op in ops:
        if op in ("sub", "subn"):
            getattr(p, op)("", text)
        elif op == "finditer":
            list(p.finditer(text))
        else:
            getattr(p, op)(text)
    return time.perf_counter() - start


def worst_case_text(prefix: str, filler: str, kind: str, n: int) -> str:
    """``n`` characters: a matching prefix then a long run, or a repeated unit; never a match."""
    if kind == "run":
        return prefix + filler * n + "\x00"
    unit = prefix + filler if kind == "pairs" else prefix
    return unit * max(1, n // max(1, len(unit))) + "\x00"


def sleep_naming_the_process(job: tuple[float, str]) -> None:
    """Sleep ``seconds``, after writing this process's id into ``folder`` (a file named by
    the id, holding the seconds), so that a test can see whether the process is gone."""
    import time

    seconds, folder = job
    with open(os.path.join(folder, str(os.getpid())), "w", encoding="ascii") as f:
        f.write(repr(seconds))
    time.sleep(seconds)


def is_gone(pid: int) -> bool:
    """Whether the process ``pid`` no longer runs (ended and reaped, or a zombie)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as f:
            return f.read().rsplit(")", 1)[1].split()[0] in ("Z", "X")
    except FileNotFoundError:
        return True


def die_or_square(n: int) -> int:
    """``n * n``; a negative ``n`` ends the process at once (exit code 3)."""
    if n < 0:
        os._exit(3)
    return n * n


class Counter:
    """A worker's state for :func:`count_calls`: how many jobs it has run."""

    def __init__(self) -> None:
        self.calls = 0


def count_calls(_: object, state: Counter) -> tuple[int, int]:
    """(this process's id, the number of jobs its state has seen, this one included)."""
    state.calls += 1
    return os.getpid(), state.calls


def warm_counter(state: Counter) -> None:
    """Warm a :class:`Counter` as a template does before it forks: it starts at 100."""
    state.calls = 100
