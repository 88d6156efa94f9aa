"""C++17, header-only, std only: ``<prefix>.hpp`` with namespace ``<prefix>``.

``<prefix>::fk(q, T)``, ``<prefix>::jacobian(q, J)``, ``<prefix>::ik(T, q)`` on
row-major arrays (as in C), and ``<prefix>::NJOINTS``, ``<prefix>::MAX_IK_SOLUTIONS``.

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x", real=True)
>>> CppPrinter().doprint(sp.cos(x) + 2.0 * x)
'2.0*x + detail::dh_cos(x)'
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sympy.printing.cxx import CXX17CodePrinter

from .c import TrigPrinting, sincos_pairs
from .languages import Language

if TYPE_CHECKING:
    import sympy as sp

__all__ = ["LANGUAGE", "CppPrinter"]


class CppPrinter(TrigPrinting, CXX17CodePrinter):
    """sympy's C++17 printer, with the solver's ``SafeSqrt`` as a helper of the header and
    the header's own ``detail::dh_sin``, ``dh_cos``, ``dh_atan2``."""

    trig = "detail::dh_"

    def _print_SafeSqrt(self, expr: sp.Expr) -> str:
        return f"detail::safe_sqrt({self._print(expr.args[0])}, stretch)"

    def _print_Coulomb(self, expr: sp.Expr) -> str:
        v, up, down = (self._print(a) for a in expr.args)
        return f"({v} > 0.0 ? {up} : ({v} < 0.0 ? {down} : 0.0))"

    def _print_Clamp(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"std::fmin(std::fmax({t}, 0.0), {tf})"

    def _print_Inside(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"({t} >= 0.0 && {t} <= {tf} ? 1.0 : 0.0)"

    def _print_Pick(self, expr: sp.Expr) -> str:
        c, a, b = (self._print(x) for x in expr.args)
        return f"({c} ? {a} : {b})"


LANGUAGE = Language(
    name="cpp",
    printer=CppPrinter,
    files=(("cpp_header.hpp.j2", "{prefix}.hpp", None),),
    comment="//",
    note='#include "{prefix}.hpp" (C++17, header-only)',
    extra={"sincos_pairs": sincos_pairs},
)
