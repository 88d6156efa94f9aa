"""The program rewriting of a closed form: its steps as one straight-line program for numbers.

Shared by the solver of :mod:`dhsym.ik.closed_form_solver` (which lambdifies the program for numpy
and for plain floats) and by the exporters of :mod:`dhsym.export` (which print it as C,
MATLAB, Rust …): the functions that only exist at compile time (:class:`SafeSqrt`,
:class:`Wrap`, :class:`Residual`), the square roots read with rounding
(:func:`with_safe_sqrt`), the scheduling of the steps with shared subexpressions
(:func:`schedule`), the branch signs pulled out of ``atan2``, sines and cosines
(:func:`pull_signs`) and the program written out per branch (:func:`per_branch`).

Examples
--------
>>> x = sp.Symbol("x", real=True)
>>> with_safe_sqrt(sp.sqrt(x) + 1 / sp.sqrt(x))
SafeSqrt(x) + 1/SafeSqrt(x)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import sympy as sp

from .steps import REAL

__all__ = [
    "MATH",
    "NUMPY",
    "REMAINDER",
    "ROUNDING",
    "STRETCHED",
    "TAU",
    "Residual",
    "SafeSqrt",
    "WRIST_NEAR",
    "WRIST_ZERO",
    "Wrap",
    "clamped_sqrt",
    "lift_residuals",
    "per_branch",
    "pull_signs",
    "reuse_names",
    "schedule",
    "trig_signs",
    "with_safe_sqrt",
    "wrap",
]

# --- numbers --------------------------------------------------------------------------------


class SafeSqrt(sp.Function):
    """``sqrt`` that reads a radicand within rounding of 0 as 0 (compile-time only)."""


class Wrap(sp.Function):
    """An angle wrapped to [−π, π] (compile-time only)."""


class Residual(sp.Function):
    """``max |d|`` over its arguments, NaN when one is NaN (compile-time only).

    For numpy ``maximum(maximum(abs(d1), abs(d2)), …)``, one difference at a time (NaN
    propagates); for floats ``max(0.0 * (d1 + d2 + …), abs(d1), abs(d2), …)``, whose
    first term, NaN or ±0, is kept by ``max`` when it is NaN (also for an infinity).
    """

    def _numpycode(self, printer: Any) -> str:  # a sympy code printer (untyped)
        maximum = printer._module_format("numpy.maximum")
        args = [f"abs({printer._print(a)})" for a in self.args]
        out = args[0]
        for a in args[1:]:
            out = f"{maximum}({out}, {a})"
        return out

    def _pythoncode(self, printer: Any) -> str:  # a sympy code printer (untyped)
        args = [printer._print(a) for a in self.args]
        return f"max(0.0 * ({' + '.join(args)}), {', '.join(f'abs({a})' for a in args)})"


#: a radicand within this of 0 reads as 0 (:class:`SafeSqrt`)
ROUNDING = 1e-10
#: ``|sin θ5|`` below which θ6 comes from the whole wrist rotation, and below which θ4 = 0
#: (the solver and the exported code both switch there)
WRIST_NEAR = 1e-5
WRIST_ZERO = 1e-12
_TWO_PI = 2 * np.pi
_INV_TWO_PI = 1 / _TWO_PI


def safe_sqrt(x: np.ndarray) -> np.ndarray:
    """``sqrt`` that reads a radicand within :data:`ROUNDING` below 0 as 0 (NaN stays NaN).

    >>> safe_sqrt(np.array([4.0, -1e-12])).tolist()
    [2.0, 0.0]
    """
    x = np.asarray(x, dtype=float)
    return np.sqrt(np.where(x > -ROUNDING, np.maximum(x, 0.0), x))  # NaN stays NaN


def wrap(x: np.ndarray) -> np.ndarray:
    """Angles to [−π, π] (faster than ``np.remainder``)."""
    return x - _TWO_PI * np.rint(x * _INV_TWO_PI)


def safe_sqrt_float(x: float) -> float:
    """:func:`safe_sqrt` of one float."""
    if x >= 0.0:
        return math.sqrt(x)
    return 0.0 if x > -ROUNDING else math.nan


def clamped_sqrt(x: np.ndarray) -> np.ndarray:
    """``sqrt`` that reads every negative radicand as 0 (NaN stays NaN): the arm stretched
    to the boundary of its workspace. For poses that are not exact (rounded, measured):
    the solutions it gives are kept only when their ``fk`` reproduces the pose within its
    tolerance (:mod:`dhsym.ik.accuracy`).

    >>> clamped_sqrt(np.array([4.0, -1e-4, np.nan])).tolist()
    [2.0, 0.0, nan]
    """
    root: np.ndarray = np.sqrt(np.maximum(np.asarray(x, dtype=float), 0.0))  # keeps NaN
    return root


#: the wrap for floats, inline: ``math.remainder(x, 2π)`` is in [−π, π] and keeps NaN; it
#: equals :func:`wrap` except within rounding of ±π, where either end may come out
REMAINDER = sp.Function("remainder")
TAU = sp.Symbol("TWO_PI")
#: the modules ``lambdify`` prints a program with: numpy (a batch) and math (one pose)
NUMPY: tuple[Mapping[str, object], str] = ({"SafeSqrt": safe_sqrt, "Wrap": wrap}, "numpy")
#: numpy with every negative radicand read as 0 (:func:`clamped_sqrt`: the arm stretched)
STRETCHED: tuple[Mapping[str, object], str] = (
    {"SafeSqrt": clamped_sqrt, "Wrap": wrap},
    "numpy",
)
MATH: tuple[Mapping[str, object], str] = (
    {"SafeSqrt": safe_sqrt_float, "TWO_PI": _TWO_PI},
    "math",
)


def with_safe_sqrt(e: sp.Expr) -> sp.Expr:
    """``e`` with every square root (and its inverse) read as :class:`SafeSqrt`: a radicand
    within rounding of 0 counts as 0. The solver and the exported code read roots so."""
    return e.replace(lambda t: t.is_Pow and t.exp == sp.S.Half, lambda t: SafeSqrt(t.base)).replace(
        lambda t: t.is_Pow and t.exp == -sp.S.Half, lambda t: 1 / SafeSqrt(t.base)
    )


def schedule(
    steps: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """The steps as one straight-line program for ``outputs``, subexpressions shared.

    Steps no output needs are dropped; ``cse`` runs over all right-hand sides at once and
    each shared subexpression is placed right after the last step it depends on.
    """
    needed = set().union(*(e.free_symbols for e in outputs)) if outputs else set()
    kept = []
    for lhs, rhs in reversed(steps):
        if lhs in needed:
            kept.append((lhs, rhs))
            needed |= rhs.free_symbols
    steps = kept[::-1]
    exprs = [rhs for _, rhs in steps] + list(outputs)
    repl, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_w"), optimizations=None)
    position = {lhs: i for i, (lhs, _) in enumerate(steps)}
    level: dict[sp.Symbol, int] = {}
    for sym, e in repl:
        deps = [position[s] for s in e.free_symbols if s in position]
        deps += [level[s] for s in e.free_symbols if s in level]
        level[sym] = max(deps, default=-1)
    program = [(sym, e) for sym, e in repl if level[sym] == -1]
    for i, (lhs, _) in enumerate(steps):
        program.append((lhs, reduced[i]))
        program += [(sym, e) for sym, e in repl if level[sym] == i]
    return program, list(reduced[len(steps) :])


def signed(e: sp.Expr, signs: set[sp.Symbol]) -> tuple[sp.Expr, sp.Expr]:
    """``e = σ · rest`` with σ the product of the branch signs that are factors of ``e``."""
    sigma = sp.Mul(*[f for f in sp.Mul.make_args(e) if f in signs])
    return sigma, (e / sigma if sigma != 1 else e)


def shifted(e: sp.Expr, signs: set[sp.Symbol]) -> tuple[sp.Expr, sp.Expr]:
    """``e = rest + shift`` with ``shift = d (σ − 1)`` for each sign σ that ``e`` depends on
    only through a constant multiple of π/2 (e.g. ``π(1 − σ)/2``: the atan2 of −Y, −X)."""
    shift = sp.S.Zero
    for s in sorted(e.free_symbols & signs, key=str):
        d = sp.diff(e, s)
        if not d.free_symbols and (2 * d / sp.pi).is_Integer:
            shift += d * (s - 1)
            e = e.xreplace({s: 1})
    return shift, e


def trig_signs(e: sp.Expr, signs: set[sp.Symbol]) -> sp.Expr:
    """``sin`` and ``cos`` with the branch signs σ = ±1 taken out of their arguments.

    An argument odd in σ: ``cos(σx) = cos x``, ``sin(σx) = σ sin x``; an argument that moves
    by kπ between σ = +1 and σ = −1: ``cos(x + kπ(1 − σ)/2) = σᵏ cos x`` (the same for sin).
    Both are identities for σ = ±1, so each sine and cosine is computed only over the
    branches its argument really depends on.
    """

    def rule(t: sp.Expr) -> sp.Expr:
        arg = t.args[0]
        for s in sorted(arg.free_symbols & signs, key=str):
            plus, minus = arg.xreplace({s: 1}), arg.xreplace({s: -1})
            if sp.expand(plus + minus) == 0:
                factor = s if isinstance(t, sp.sin) else sp.S.One
                return factor * trig_signs(t.func(plus), signs)
            k = sp.expand((minus - plus) / sp.pi)
            if k.is_Integer:
                return s ** (int(k) % 2) * trig_signs(t.func(plus), signs)
        return t

    return e.replace(
        lambda t: isinstance(t, (sp.sin, sp.cos)) and bool(t.args[0].free_symbols & signs), rule
    )


def pull_signs(
    steps: Sequence[tuple[sp.Symbol, sp.Expr]],
    outputs: Sequence[sp.Expr],
    signs: Sequence[sp.Symbol],
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """Move branch signs σ = ±1 out of square roots' neighbours, ``atan2``, sin and cos.

    A step ``x = σ·E`` becomes ``x' = E`` with ``x = σ x'`` downstream, a step
    ``x = E + π(1 − σ)/2`` becomes ``x' = E`` with ``x = x' + π(1 − σ)/2`` downstream, and
    ``atan2(σa Y, σb X) ≡ σa σb atan2(Y, X) + π(1 − σb)/2`` (mod 2π), so that each
    ``atan2`` (and each sine and cosine, :func:`trig_signs`; ``|σx| = |x|``,
    ``wrap(σx) = σ wrap(x)``) runs once for the branches it does not depend on. Only
    used for numbers: the angles it changes are wrapped to [−π, π] afterwards.
    """
    sset = set(signs)

    def square_free(e: sp.Expr) -> sp.Expr:
        return e.replace(
            lambda t: t.is_Pow and t.base in sset and t.exp.is_Integer,
            lambda t: t.base ** (int(t.exp) % 2),
        )

    def pull(e: sp.Expr) -> sp.Expr:
        def rewrite(t: sp.atan2) -> sp.Expr:
            sy, Y = signed(t.args[0], sset)
            sx, X = signed(t.args[1], sset)
            if sy == 1 and sx == 1:
                return t
            return sx * sy * sp.atan2(Y, X) + sp.pi * (1 - sx) / 2

        def odd(t: Wrap) -> sp.Expr:  # the wrap is odd (exactly, in floats too)
            sigma, rest = signed(t.args[0], sset)
            return sigma * Wrap(rest)

        e = e.replace(lambda t: isinstance(t, sp.atan2), rewrite)
        e = square_free(trig_signs(square_free(e), sset))

        def unsigned(t: sp.Abs) -> sp.Expr:  # |σx| = |x|
            return sp.Abs(signed(t.args[0], sset)[1])

        e = e.replace(lambda t: isinstance(t, sp.Abs), unsigned)
        return e.replace(lambda t: isinstance(t, Wrap), odd)

    sub: dict[sp.Symbol, sp.Expr] = {}
    out = []
    for lhs, rhs in steps:
        e = pull(square_free(rhs.xreplace(sub)))
        sigma, rest = signed(e, sset)
        shift = sp.S.Zero
        if sigma == 1:
            shift, rest = shifted(e, sset)
        if sigma != 1 or shift != 0:
            bare = sp.Symbol(f"{lhs.name}_", **REAL)
            out.append((bare, rest))
            sub[lhs] = sigma * bare + shift
        else:
            out.append((lhs, e))
    return out, [pull(square_free(o.xreplace(sub))) for o in outputs]


def per_branch(
    program: Sequence[tuple[sp.Symbol, sp.Expr]],
    outputs: Sequence[sp.Expr],
    signs: Sequence[sp.Symbol],
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[list[sp.Expr]]]:
    """The program written out for every branch, for scalars: the signs become numbers.

    A line that depends on the signs S (directly or through earlier lines) is repeated
    once per combination of S; a line that does not is computed once. The outputs are
    lines too (an angle that depends on one sign is wrapped twice, not once per branch)
    and are returned as one list per branch, in the order of :attr:`Solver.branch_signs`.
    """
    sset = set(signs)
    deps: dict[sp.Symbol, tuple[sp.Symbol, ...]] = {}
    bound: dict[tuple[sp.Symbol, tuple[int, ...]], sp.Expr] = {}

    def bind(e: sp.Expr, choice: Mapping[sp.Symbol, int]) -> sp.Expr:
        rep: dict[sp.Symbol, sp.Expr] = {s: sp.Integer(choice[s]) for s in e.free_symbols & sset}
        for x in e.free_symbols:
            if x in deps:
                rep[x] = bound[(x, tuple(choice[s] for s in deps[x]))]
        return e.xreplace(rep)

    names = [sp.Symbol(f"_out{i}") for i in range(len(outputs))]
    lines = []
    for sym, e in [*program, *zip(names, outputs)]:
        used = set(e.free_symbols & sset).union(*(deps[x] for x in e.free_symbols if x in deps))
        d = deps[sym] = tuple(s for s in signs if s in used)
        for combo in itertools.product((1, -1), repeat=len(d)):
            value = bind(e, dict(zip(d, combo)))
            if value.is_Number or value.is_Symbol:
                bound[(sym, combo)] = value
                continue
            name = sym
            if d:
                tag = "".join("p" if c > 0 else "m" for c in combo)
                name = sp.Symbol(f"{sym.name}__{tag}", **sym.assumptions0)
            lines.append((name, value))
            bound[(sym, combo)] = name
    outs = []
    for combo in itertools.product((1, -1), repeat=len(signs)):
        choice = dict(zip(signs, combo))
        outs.append([bound[(o, tuple(choice[s] for s in deps[o]))] for o in names])
    return lines, outs


def reuse_names(
    program: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """The program with a line's name bound again once its value is no longer needed.

    For numpy: rebinding a name frees the array it held, so a block's temporaries are
    few at any time and reused (fewer cache misses and page faults than when every
    intermediate array lives until the function returns).
    """
    alias: dict[sp.Symbol, sp.Expr] = {}  # lines x = y: y itself (lambdify reads a line
    lines = []  # x = argument as "x is that argument" everywhere, so x must not be reused)
    for sym, e in program:
        e = e.xreplace(alias)
        if e.is_Symbol:
            alias[sym] = e
        else:
            lines.append((sym, e))
    program, outputs = lines, [o.xreplace(alias) for o in outputs]
    last: dict[sp.Symbol, int] = {}
    for i, (_, e) in enumerate(program):
        for x in e.free_symbols:
            last[x] = i
    for o in outputs:
        for x in o.free_symbols:
            last[x] = len(program)
    defined = {sym for sym, _ in program}
    rename: dict[sp.Symbol, sp.Symbol] = {}
    free: list[sp.Symbol] = []
    out = []
    for i, (sym, e) in enumerate(program):
        free += [rename[x] for x in e.free_symbols if x in defined and last[x] == i]
        name = free.pop() if free else sym
        out.append((name, e.xreplace(rename)))
        rename[sym] = name
        if sym not in last:  # never used: its name is free again at once
            free.append(name)
    return out, [o.xreplace(rename) for o in outputs]


def lift_residuals(
    program: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """Each argument of a :class:`Residual` (a line or an output) becomes a line of the
    program of its own (for floats it is printed twice: in the sum that catches NaN and
    in its ``abs``)."""
    names = sp.numbered_symbols("_d")
    lines: list[tuple[sp.Symbol, sp.Expr]] = []

    def lift(e: sp.Expr) -> sp.Expr:
        if not isinstance(e, Residual):
            return e
        args = []
        for a in e.args:
            if not a.is_Symbol:
                sym = next(names)
                lines.append((sym, a))
                a = sym
            args.append(a)
        return Residual(*args)

    for sym, e in program:
        e = lift(e)
        lines.append((sym, e))
    return lines, [lift(o) for o in outputs]
