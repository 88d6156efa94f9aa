"""The closed-form solver's programs kept in the disk cache (:mod:`dhsym.cache`).

A program is what ``lambdify`` compiles: its arguments, its named steps (the common
subexpressions, in order) and its outputs. Rewriting the steps of a derivation into one
(:mod:`dhsym.ik.rewriting`) takes a good part of a first answer; a warm process reads the
program back (verified by the store, read by :mod:`dhsym.cache.codec` without running
code) and only compiles it. The entry is named by the table's canonical form, the
versions (:func:`dhsym.cache.keys.entry_name`), the kind of program, the numeric values
and the text of the derivation's steps: another table, another version or another
derivation never reads it.

Dummies have no stable name: they are written as symbols named ``_k0``, ``_k1``, … (with
their assumptions), and the solver's undefined ``remainder`` as :class:`Remainder`; the
program is compiled from these renamed expressions cold and warm alike.

>>> import sympy as sp
>>> x = sp.Dummy("x", real=True)
>>> y = sp.Symbol("y")
>>> args, steps, outputs = stable_names([x], [(y, x + 1)], [2 * y])
>>> args, steps, outputs
((_k0,), ((y, _k0 + 1),), (2*y,))
>>> args[0].is_real, type(args[0]).__name__
(True, 'Symbol')
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import sympy as sp
from sympy.core.function import AppliedUndef

from .rewriting import REMAINDER, Residual, SafeSqrt, Wrap

__all__ = ["Remainder", "kept_program", "stable_names"]

Steps = tuple[tuple[sp.Symbol, sp.Expr], ...]


class Remainder(sp.Function):
    """``math.remainder(x, y)`` (compile-time only): the solver's inline wrap, as a class
    the codec can write."""

    def _pythoncode(self, printer: Any) -> str:  # a sympy code printer (untyped)
        x, y = (printer._print(a) for a in self.args)
        return f"remainder({x}, {y})"


#: dhsym's own functions a kept program may hold (:func:`dhsym.cache.codec.read_exprs`)
EXTRA: Mapping[str, type] = {c.__name__: c for c in (SafeSqrt, Wrap, Residual, Remainder)}


def stable_names(
    args: Sequence[sp.Symbol], steps: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[Any]
) -> tuple[tuple[sp.Symbol, ...], Steps, tuple[Any, ...]]:
    """``args``, ``steps`` and ``outputs`` with each ``Dummy`` a symbol ``_k<i>`` (same
    assumptions, numbered in order of first appearance) and ``remainder`` a
    :class:`Remainder`."""
    found: dict[sp.Dummy, sp.Symbol] = {}

    def note(e: sp.Basic) -> None:
        for d in sorted(e.atoms(sp.Dummy), key=sp.default_sort_key):
            if d not in found:
                found[d] = sp.Symbol(f"_k{len(found)}", **d._assumptions_orig)

    for a in args:
        note(a)
    for s, e in steps:
        note(s)
        note(e)
    for o in outputs:
        note(o)

    def fix(e: Any) -> Any:
        e = e.xreplace(found) if found else e
        if e.has(REMAINDER):
            e = e.replace(
                lambda t: isinstance(t, AppliedUndef) and t.func == REMAINDER,
                lambda t: Remainder(*t.args),
            )
        return e

    return (
        tuple(fix(a) for a in args),
        tuple((fix(s), fix(e)) for s, e in steps),
        tuple(fix(o) for o in outputs),
    )


def kept_program(
    name: Callable[[], str | None],
    build: Callable[[], tuple[Sequence[sp.Symbol], Sequence[Any], Sequence[Any]]],
) -> tuple[tuple[sp.Symbol, ...], Steps, tuple[Any, ...]]:
    """The program ``(args, steps, outputs)`` that ``build()`` makes (its Dummies given
    stable names), kept in the disk cache as entry ``name()`` through the one reader and
    writer of programs, :func:`dhsym.kinematics.numeric.kept_tuples` (``None``, or the
    cache off: built, not kept). A kept entry is read back (verified) instead of calling
    ``build``; one this version cannot read is built again and rewritten."""
    from dhsym.kinematics.numeric import kept_tuples

    def ready() -> list[sp.Tuple]:
        args, steps, outputs = stable_names(*build())
        lhs = sp.Tuple(*(s for s, _ in steps))
        return [sp.Tuple(*args), lhs, sp.Tuple(*(e for _, e in steps)), sp.Tuple(*outputs)]

    args, lhs, rhs, outputs = kept_tuples(name, ready, 4, EXTRA)
    return tuple(args.args), tuple(zip(lhs.args, rhs.args)), tuple(outputs.args)


def derivation_text(*parts: object) -> str:
    """A SHA-256 of the text of ``parts`` (a derivation's steps, the values): part of an
    entry's name, so that another derivation never reads the entry.

    >>> len(derivation_text([1, 2], {"a": 3}))
    64
    """
    return hashlib.sha256("\n".join(str(p) for p in parts).encode()).hexdigest()
