"""Resource limits for untrusted answers: sizes, a time limit and a cost estimate.

Everything a student typed is bounded three ways: its size (bytes, cells),
the whitelist parser's :class:`~dhsym.model.parsing.ParseLimits`, and the symbolic
work done on it — an *estimate* of the expansion size refuses hopeless
expressions before sympy starts, and :func:`time_limit` stops what slips
through (``SIGALRM``; in a non-main thread only the estimate applies).  Grading
adds process isolation on top (:mod:`dhsym.checking._runner`): a process that
overruns its deadline is killed, whatever it was doing.

Time limits come from users (``--timeout``, ``time_limit:``) and are checked by
:func:`check_seconds`: finite, above 0, at most :data:`MAX_SECONDS`.

Examples
--------
>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> expansion_terms((x + y) ** 3), expansion_terms(sp.cos(x + y) * x)
(4, 2)
>>> AnswerLimits().max_bytes
100000
>>> check_seconds("2.5", "--timeout")
2.5
>>> check_seconds(float("inf"), "--timeout")
Traceback (most recent call last):
...
dhsym.errors.DHError: --timeout: expected a time limit in seconds above 0 and at most 3600, got inf
"""

from __future__ import annotations

import math
import signal
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.parsing import ParseLimits

__all__ = [
    "AnswerLimits",
    "AnswerTimeout",
    "CheckTimeout",
    "DEFAULT_ANSWER_LIMITS",
    "MAX_SECONDS",
    "UnreadableAnswer",
    "check_seconds",
    "expansion_terms",
    "time_limit",
]

MAX_SECONDS = 3600.0


class UnreadableAnswer(DHError):
    """An answer that cannot be read: too large, not text, or not a table/matrix."""


class CheckTimeout(DHError):
    """Checking one answer took longer than its time limit."""


class AnswerTimeout(BaseException):  # noqa: N818 - an interruption, like KeyboardInterrupt
    """The grading time limit of one answer ran out.

    Not an ``Exception``: no ``except Exception`` inside sympy or the checker can
    swallow it, so the grader always learns that the answer timed out (a timeout is
    never mistaken for a verdict, and never cached).
    """


def check_seconds(value: object, what: str, *, file: str | None = None) -> float:
    """``value`` as a time limit in seconds: finite, above 0, at most :data:`MAX_SECONDS`.

    ``what`` names the option (``--timeout``), or with ``file`` the field of that file.
    """
    number: float | None = None
    if isinstance(value, (int, float, str)) and not isinstance(value, bool):
        try:
            number = float(value)
        except (ValueError, OverflowError):
            number = None
    if number is None or not (0 < number <= MAX_SECONDS):  # also refuses nan and inf
        shown = value if isinstance(value, (int, float)) else repr(value)
        problem = (
            f"expected a time limit in seconds above 0 and at most {MAX_SECONDS:g}, got {shown}"
        )
        if file is not None:
            raise DHError(problem, file=file, field=what)
        raise DHError(f"{what}: {problem}")
    return number


@dataclass(frozen=True)
class AnswerLimits:
    """Limits applied to one answer.

    Parameters
    ----------
    max_bytes
        Size of the answer text (UTF-8 bytes).
    max_rows, max_columns
        Rows and columns of a table or matrix answer.
    parse
        Limits of the whitelist parser, per cell.
    max_terms
        Largest estimated number of terms an exact proof may expand to.
    seconds
        Time limit of one check (symbolic work included).
    proof_seconds
        Time limit of the exact proof of one entry.
    """

    max_bytes: int = 100_000
    max_rows: int = 64
    max_columns: int = 16
    parse: ParseLimits = field(
        default_factory=lambda: ParseLimits(max_length=20_000, max_depth=40, max_symbols=60)
    )
    max_terms: int = 20_000
    seconds: float = 5.0
    proof_seconds: float = 1.0

    def __post_init__(self) -> None:
        for name in ("max_bytes", "max_rows", "max_columns", "max_terms"):
            value = getattr(self, name)
            if not isinstance(value, int) or isinstance(value, bool) or value < 1:
                raise DHError(f"AnswerLimits.{name}: expected a positive integer, got {value!r}")
        if self.seconds != 0:  # 0: no limit inside the check (the caller enforces one)
            check_seconds(self.seconds, "time limit")
        check_seconds(self.proof_seconds, "proof time limit")


DEFAULT_ANSWER_LIMITS = AnswerLimits()


@contextmanager
def time_limit(
    seconds: float | None, error: Callable[[str], BaseException] = CheckTimeout
) -> Iterator[None]:
    """Raise ``error`` (:class:`CheckTimeout`) in the block after ``seconds`` (main thread, POSIX).

    Elsewhere (a worker thread, Windows) the block runs unlimited: callers keep
    their work bounded with :func:`expansion_terms` there.  Limits nest: an
    outer limit gets back what is left of it (it fires at once if the inner block
    outlived it).

    >>> with time_limit(1.0):
    ...     sum(range(10))
    45
    """
    usable = (
        seconds is not None
        and seconds > 0
        and hasattr(signal, "setitimer")
        and threading.current_thread() is threading.main_thread()
    )
    if not usable:
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise error(f"checking took longer than the time limit of {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, expire)
    old_delay, _ = signal.getitimer(signal.ITIMER_REAL)
    start = time.monotonic()
    signal.setitimer(signal.ITIMER_REAL, float(seconds))
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        if old_delay:  # an outer limit was running: give it what is left of it
            left = old_delay - (time.monotonic() - start)
            signal.setitimer(signal.ITIMER_REAL, max(left, 1e-4))


def expansion_terms(expr: sp.Basic, cap: int = 10**9) -> int:
    """An upper estimate of the number of terms of ``expand(expand_trig(expr))``.

    Sums add, products multiply, ``b**n`` takes the multinomial count, and
    ``cos``/``sin`` of a sum of ``k`` terms (or of ``m*x``) count ``2**(k-1)``
    (or ``m``) terms.  The result is capped at ``cap``.

    >>> import sympy as sp
    >>> a, b, c = sp.symbols("a b c")
    >>> expansion_terms((a + b + c) ** 20) > 200
    True
    """
    memo: dict[sp.Basic, int] = {}

    def count(e: sp.Basic) -> int:
        if e in memo:
            return memo[e]
        if e.is_Atom:
            n = 1
        elif e.is_Add:
            n = sum(count(a) for a in e.args)
        elif e.is_Mul:
            n = 1
            for a in e.args:
                n = min(cap, n * count(a))
        elif e.is_Pow:
            base, exp = e.args
            m = count(base)
            if exp.is_Integer and exp > 0 and m > 1:
                k = int(exp)
                n = math.comb(k + m - 1, m - 1) if m < 10_000 and k < 10_000 else cap
            else:  # 1/x, sqrt(x): no expansion beyond the base itself
                n = m
        elif isinstance(e, (sp.sin, sp.cos, sp.tan)):
            arg = e.args[0]
            terms = sp.Add.make_args(arg)
            coeff = max((abs(t.as_coeff_Mul()[0]) for t in terms), default=1)
            mult = int(min(coeff, 10_000)) if coeff.is_Rational and coeff.q == 1 else 1
            n = min(cap, 2 ** min(len(terms) - 1, 60) * max(mult, 1))
        else:
            n = 1
            for a in e.args:
                n = min(cap, n * count(a))
        n = min(cap, max(1, n))
        memo[e] = n
        return n

    return count(expr)
