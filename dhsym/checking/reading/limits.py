"""Resource limits for untrusted answers: sizes, a time limit and a cost estimate.

Everything a student typed is bounded three ways: its size (bytes, cells),
the whitelist parser's :class:`~dhsym.model.parsing.ParseLimits`, and the symbolic
work done on it — an *estimate* of the expansion size refuses hopeless
expressions before sympy starts, and :func:`time_limit` sets a deadline that travels
with the call (a context variable, checked between the checker's steps by
:func:`check_time`; no signal or timer of the host process is touched).  Grading
adds process isolation on top (:mod:`dhsym.checking.grading.sandbox`): a process that
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
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field

import sympy as sp

from dhsym.errors import DHError, echoed
from dhsym.model.parsing import ParseLimits

__all__ = [
    "AnswerLimits",
    "AnswerTimeout",
    "CheckTimeout",
    "DEFAULT_ANSWER_LIMITS",
    "MAX_SECONDS",
    "UnreadableAnswer",
    "check_seconds",
    "check_time",
    "echoed",
    "expansion_terms",
    "time_left",
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
        shown = value if isinstance(value, (int, float)) else echoed(value)
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
    proof_terms
        Largest estimated number of terms of a proof that only confirms numbers that
        already agree (a larger entry is decided by its 64 points).
    seconds
        Time limit of one check (symbolic work included).
    proof_seconds
        Time an exact proof needs at least: with less left before the deadline, the
        proof is skipped and the numbers decide.
    """

    max_bytes: int = 100_000
    max_rows: int = 64
    max_columns: int = 16
    parse: ParseLimits = field(
        default_factory=lambda: ParseLimits(max_length=20_000, max_depth=40, max_symbols=60)
    )
    max_terms: int = 20_000
    proof_terms: int = 200
    seconds: float = 5.0
    proof_seconds: float = 1.0

    def __post_init__(self) -> None:
        for name in ("max_bytes", "max_rows", "max_columns", "max_terms", "proof_terms"):
            value = getattr(self, name)
            if not isinstance(value, int) or isinstance(value, bool) or value < 1:
                raise DHError(f"AnswerLimits.{name}: expected a positive integer, got {value!r}")
        if self.seconds != 0:  # 0: no limit inside the check (the caller enforces one)
            check_seconds(self.seconds, "time limit")
        check_seconds(self.proof_seconds, "proof time limit")


DEFAULT_ANSWER_LIMITS = AnswerLimits()


@dataclass(frozen=True)
class _Deadline:
    """When the innermost running limit ends, what it raises, and its length."""

    end: float
    error: Callable[[str], BaseException]
    seconds: float


#: The deadline of the running check, per thread and task (a context variable: it travels
#: with the call, like :func:`decimal.localcontext`; no signal, no timer, nothing global).
_DEADLINE: ContextVar[_Deadline | None] = ContextVar("dhsym_deadline", default=None)


@contextmanager
def time_limit(
    seconds: float | None, error: Callable[[str], BaseException] = CheckTimeout
) -> Iterator[None]:
    """A deadline ``seconds`` from now for the block: :func:`check_time` raises ``error``
    (:class:`CheckTimeout`) once it has passed.

    The deadline travels with the call (a context variable: each thread and task has its
    own), so nothing of the host process is touched: no signal handler, no timer.  The
    checker calls :func:`check_time` between its steps (entries, sample points, mistakes,
    proofs), and bounds each step by size (:func:`expansion_terms`, the parser's limits),
    so an answer is answered or refused within its limit; a grading run also kills a
    sandbox child that outlives its deadline.  Limits nest: the earliest deadline rules.

    >>> with time_limit(1.0):
    ...     check_time()
    ...     sum(range(10))
    45
    """
    if seconds is None or seconds <= 0:
        yield
        return
    outer = _DEADLINE.get()
    mine = _Deadline(time.monotonic() + float(seconds), error, float(seconds))
    token = _DEADLINE.set(mine if outer is None or mine.end < outer.end else outer)
    try:
        yield
    finally:
        _DEADLINE.reset(token)


def time_left() -> float:
    """Seconds until the running deadline (``inf`` without one).

    >>> time_left()
    inf
    """
    limit = _DEADLINE.get()
    return math.inf if limit is None else limit.end - time.monotonic()


def check_time() -> None:
    """Raise the running limit's error if its deadline has passed (see :func:`time_limit`)."""
    limit = _DEADLINE.get()
    if limit is not None and time.monotonic() > limit.end:
        raise limit.error(f"checking took longer than the time limit of {limit.seconds:g} s")


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
            coeff = max((abs(t.as_coeff_Mul()[0]) for t in terms), default=sp.Integer(1))
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
