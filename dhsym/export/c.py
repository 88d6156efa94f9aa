"""C99 (``math.h`` only): ``<prefix>.h`` and ``<prefix>.c``, row-major arrays.

::

    void <prefix>_fk(const double q[N], double T[16]);
    void <prefix>_jacobian(const double q[N], double J[6*N]);
    int  <prefix>_ik(const double T[16], double tol, double q[][N], double residual[]);
    /* count; every branch within tol (<= 0: dhsym's rule for poses as they come), a branch
       near a pose that is not exact refined on fk and jacobian first, as robot.ik */

With symbolic lengths each function takes ``const double p[<PREFIX>_NPARAMS]`` last.

Sines, cosines and ``atan2`` are the file's own (``dh_sincos_n``, ``dh_sincos``,
``dh_atan2``: ``templates/export/c_math.j2``, within 2 ulp of libm's, libm itself outside
their range): the fk takes every angle in one call, which gcc -O2 vectorises; the IK
takes those of one level that are known together in one call (:func:`sincos_pairs`).

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x", real=True)
>>> CPrinter().doprint(sp.atan2(x, sp.Symbol("y")) + x**2)
'pow(x, 2) + dh_atan2(x, y)'
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import sympy as sp
from sympy.printing.c import C99CodePrinter

from .languages import Language

if TYPE_CHECKING:
    from .program import Assign

__all__ = [
    "LANGUAGE",
    "CPrinter",
    "NativePrinter",
    "SinCos",
    "SinCosGroup",
    "TrigPrinting",
    "sincos_pairs",
]


@dataclass(frozen=True)
class SinCos:
    """``sin`` and ``cos`` of one angle, named ``sin`` and ``cos`` in the generated code."""

    sin: str
    cos: str
    angle: sp.Expr
    level: int


@dataclass(frozen=True)
class SinCosGroup:
    """Pairs of one level taken together: one call of the file's ``dh_sincos_n`` (two
    angles at a time with SSE2), or of ``dh_sincos`` for one."""

    pairs: tuple[SinCos, ...]
    level: int

    @property
    def size(self) -> int:
        """The length of the call's arrays: the pairs, made even (the last angle again)."""
        return len(self.pairs) + len(self.pairs) % 2


def sincos_pairs(body: Sequence[Assign]) -> list[Assign | SinCosGroup]:
    """``body`` with each ``s = sin(x)``, ``c = cos(x)`` of one angle (at one level, no
    singular value) as one :class:`SinCos`, in the earliest group of its level that comes
    after what its angle reads (a group stands where its first pair stood).

    >>> import sympy as sp
    >>> from dhsym.export.program import Assign
    >>> q1, q2 = sp.symbols("q1 q2", real=True)
    >>> body = [Assign("c1", sp.cos(q1)), Assign("c12", sp.cos(q1 + q2)),
    ...         Assign("s1", sp.sin(q1)), Assign("w0", 2 * q1), Assign("s12", sp.sin(q1 + q2)),
    ...         Assign("q3", q1 - q2), Assign("c3", sp.cos(sp.Symbol("q3", real=True))),
    ...         Assign("s3", sp.sin(sp.Symbol("q3", real=True)))]
    >>> [[(p.sin, p.cos) for p in a.pairs] if isinstance(a, SinCosGroup) else a.name
    ...  for a in sincos_pairs(body)]
    [[('s1', 'c1'), ('s12', 'c12')], 'w0', 'q3', [('s3', 'c3')]]
    """
    trig: dict[tuple[type, sp.Expr, int], Assign] = {}
    for a in body:
        if isinstance(a.expr, (sp.sin, sp.cos)) and a.alt is None:
            trig.setdefault((type(a.expr), a.expr.args[0], a.level), a)
    out: list[Assign | list[SinCos]] = []
    where: dict[str, int] = {}  # a name's place in out
    done: set[str] = set()
    for a in body:
        if a.name in done:
            continue
        if isinstance(a.expr, (sp.sin, sp.cos)) and a.alt is None:
            x = a.expr.args[0]
            s, c = trig.get((sp.sin, x, a.level)), trig.get((sp.cos, x, a.level))
            if s is not None and c is not None:
                pair = SinCos(s.name, c.name, x, a.level)
                done |= {s.name, c.name}
                after = max((where.get(v.name, -1) for v in x.free_symbols), default=-1)
                group = next(
                    (
                        k
                        for k in range(after + 1, len(out))
                        if isinstance(g := out[k], list) and g[0].level == a.level
                    ),
                    None,
                )
                if group is None:
                    group = len(out)
                    out.append([])
                members = out[group]
                assert isinstance(members, list)
                members.append(pair)
                where[s.name] = where[c.name] = group
                continue
        where[a.name] = len(out)
        out.append(a)
    return [SinCosGroup(tuple(g), g[0].level) if isinstance(g, list) else g for g in out]


class TrigPrinting:
    """The printing of ``sin``, ``cos`` and ``atan2`` as the functions named ``trig`` +
    ``sin`` (``dh_sin``: the file's own, ``templates/export/c_math.j2``; ``""``: libm's)."""

    trig = "dh_"
    _print: Callable[[object], str]  # the code printer's own (declared for the type checker)

    def _print_sin(self, expr: sp.Expr) -> str:
        return f"{self.trig}sin({self._print(expr.args[0])})"

    def _print_cos(self, expr: sp.Expr) -> str:
        return f"{self.trig}cos({self._print(expr.args[0])})"

    def _print_atan2(self, expr: sp.Expr) -> str:
        y, x = (self._print(a) for a in expr.args)
        return f"{self.trig}atan2({y}, {x})"


class CPrinter(TrigPrinting, C99CodePrinter):
    """sympy's C99 printer, with the solver's ``SafeSqrt`` as a helper of the file (its
    ``stretch``: a local of the IK function, set for a pose that is not exact) and the
    file's own ``dh_sin``, ``dh_cos``, ``dh_atan2``."""

    def _print_SafeSqrt(self, expr: sp.Expr) -> str:
        return f"safe_sqrt({self._print(expr.args[0])}, stretch)"

    def _print_Coulomb(self, expr: sp.Expr) -> str:
        v, up, down = (self._print(a) for a in expr.args)
        return f"({v} > 0.0 ? {up} : ({v} < 0.0 ? {down} : 0.0))"

    def _print_Clamp(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"fmin(fmax({t}, 0.0), {tf})"

    def _print_Inside(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"({t} >= 0.0 && {t} <= {tf} ? 1.0 : 0.0)"

    def _print_Pick(self, expr: sp.Expr) -> str:
        c, a, b = (self._print(x) for x in expr.args)
        return f"({c} ? {a} : {b})"


class NativePrinter(CPrinter):
    """The C printer of the solver's program for one pose
    (:func:`dhsym.export.shared_library.native_source`) and of the numeric dynamics' rows
    (libm's ``sin``, ``cos``, ``atan2``, as NumPy evaluates them): ``SafeSqrt`` with the
    function's ``stretch`` (as :class:`CPrinter`), ``remainder`` of C99, and a
    ``Residual`` as nested ``nan_max`` of its magnitudes (NaN when any difference is).

    >>> import sympy as sp
    >>> from dhsym.ik.rewriting import Residual
    >>> x, y = sp.symbols("x y", real=True)
    >>> NativePrinter().doprint(Residual(x, y - 1))
    'nan_max(fabs(x), fabs(y - 1))'
    """

    trig = ""

    def _print_remainder(self, expr: sp.Expr) -> str:
        x, y = (self._print(a) for a in expr.args)
        return f"remainder({x}, {y})"

    _print_Remainder = _print_remainder

    def _print_Residual(self, expr: sp.Expr) -> str:
        out = f"fabs({self._print(expr.args[0])})"
        for a in expr.args[1:]:
            out = f"nan_max({out}, fabs({self._print(a)}))"
        return out


LANGUAGE = Language(
    name="c",
    printer=CPrinter,
    files=(("c_header.h.j2", "{prefix}.h", None), ("c_source.c.j2", "{prefix}.c", None)),
    comment=" *",
    note="gcc -std=c99 -O2 -c {prefix}.c (link with -lm)",
    extra={"sincos_pairs": sincos_pairs},
)
