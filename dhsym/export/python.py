"""A NumPy module ``<prefix>.py``: ``fk(q)``, ``jacobian(q)``, ``ik(T)``.

``fk`` and ``jacobian`` take one configuration ``(n,)`` or a batch ``(..., n)``;
``ik`` one pose ``(4, 4)`` and returns ``(k, n)``. ``NJOINTS`` and
``MAX_IK_SOLUTIONS`` as in C.

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x", real=True)
>>> PythonPrinter().doprint(sp.atan2(x, sp.Symbol("y")) + x**2)
'x**2 + numpy.arctan2(x, y)'
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sympy.printing.numpy import NumPyPrinter

from .languages import Language

if TYPE_CHECKING:
    import sympy as sp

__all__ = ["LANGUAGE", "PythonPrinter"]


class PythonPrinter(NumPyPrinter):
    """sympy's NumPy printer; ``SafeSqrt`` is a helper of the module, ``T[i, j]`` indexes."""

    def _print_SafeSqrt(self, expr: sp.Expr) -> str:
        return f"_safe_sqrt({self._print(expr.args[0])}, stretch)"

    def _print_Coulomb(self, expr: sp.Expr) -> str:
        v, up, down = (self._print(a) for a in expr.args)
        return f"numpy.where({v} > 0, {up}, numpy.where({v} < 0, {down}, 0.0))"

    def _print_Clamp(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"numpy.clip({t}, 0.0, {tf})"

    def _print_Inside(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"numpy.where(({t} >= 0) & ({t} <= {tf}), 1.0, 0.0)"

    def _print_Pick(self, expr: sp.Expr) -> str:
        c, a, b = (self._print(x) for x in expr.args)
        return f"numpy.where({c}, {a}, {b})"


LANGUAGE = Language(
    name="python",
    printer=PythonPrinter,
    files=(("python_module.py.j2", "{prefix}.py", None),),
    comment="#",
    note="import {prefix} (needs numpy)",
)
