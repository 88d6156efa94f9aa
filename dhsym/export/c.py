"""C99 (``math.h`` only): ``<prefix>.h`` and ``<prefix>.c``, row-major arrays.

::

    void <prefix>_fk(const double q[N], double T[16]);
    void <prefix>_jacobian(const double q[N], double J[6*N]);
    int  <prefix>_ik(const double T[16], double tol, double q[][N], double residual[]);
    /* count; every branch within tol (<= 0: dhsym's rule for poses as they come), a branch
       near a pose that is not exact refined on fk and jacobian first, as robot.ik */

With symbolic lengths each function takes ``const double p[<PREFIX>_NPARAMS]`` last.

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x", real=True)
>>> CPrinter().doprint(sp.atan2(x, sp.Symbol("y")) + x**2)
'pow(x, 2) + atan2(x, y)'
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sympy.printing.c import C99CodePrinter

from .languages import Language

if TYPE_CHECKING:
    import sympy as sp

__all__ = ["LANGUAGE", "CPrinter", "NativePrinter"]


class CPrinter(C99CodePrinter):
    """sympy's C99 printer, with the solver's ``SafeSqrt`` as a helper of the file (its
    ``stretch``: a local of the IK function, set for a pose that is not exact)."""

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
    (:func:`dhsym.export.shared_library.native_source`): ``SafeSqrt`` with the
    function's ``stretch`` (as :class:`CPrinter`), ``remainder`` of C99, and a
    ``Residual`` as nested ``nan_max`` of its magnitudes (NaN when any difference is).

    >>> import sympy as sp
    >>> from dhsym.ik.rewriting import Residual
    >>> x, y = sp.symbols("x y", real=True)
    >>> NativePrinter().doprint(Residual(x, y - 1))
    'nan_max(fabs(x), fabs(y - 1))'
    """

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
)
