"""A Rust module ``<prefix>.rs`` without crates: ``fk``, ``jacobian``, ``ik``.

``pub fn fk(q: &[f64; NJOINTS]) -> [f64; 16]``, ``pub fn jacobian(q) -> [f64; 6 * NJOINTS]``
(row-major), ``pub fn ik(t: &[f64; 16], q: &mut [[f64; NJOINTS]; MAX_IK_SOLUTIONS]) -> usize``,
and the constants ``NJOINTS``, ``MAX_IK_SOLUTIONS``.

Examples
--------
>>> import sympy as sp
>>> r = sp.Symbol("r", real=True)
>>> RustPrinter().doprint(sp.atan2(sp.Float(-0.5), r) + 2 * r**2)
'2.0*r.powi(2) + (-0.5_f64).atan2(r)'
"""

from __future__ import annotations

import sympy as sp
from sympy.printing.codeprinter import CodePrinter
from sympy.printing.rust import RustCodePrinter

from .languages import Language

__all__ = ["LANGUAGE", "RustPrinter"]


class RustPrinter(RustCodePrinter):
    """sympy's Rust printer; every number is an ``f64`` (``2.0``), a negative receiver of
    a method is parenthesised, ``SafeSqrt`` is a helper of the module, the pose is ``t``."""

    def _print_Float(self, expr: sp.Float, _type: bool = False) -> str:
        ret = super()._print_Float(expr, _type)
        return f"({ret})" if _type and expr < 0 else ret

    def _print_Integer(self, expr: sp.Integer, _type: bool = False) -> str:
        ret = f"{int(expr)}.0" + ("_f64" if _type else "")
        return f"({ret})" if _type and expr < 0 else ret

    def _print_Mul(self, expr: sp.Mul) -> str:
        # sympy's Rust _print_Mul re-multiplies float-cast factors and can lose the
        # brackets of a sum (0.1*c5*(c2*w13 - w12) -> 0.1*c5*-w12 + c2*w13); every number
        # here is already a float, so the generic printer is right
        return str(CodePrinter._print_Mul(self, expr))

    def _print_Pow(self, expr: sp.Pow) -> str:
        base, exp = expr.args
        if exp.is_Integer and exp != -1:
            inner = self._print(base)
            if not isinstance(base, sp.Symbol | sp.Indexed):
                inner = f"({inner})"
            return f"{inner}.powi({int(exp)})"
        return str(super()._print_Pow(expr))

    def _print_Indexed(self, expr: sp.Indexed) -> str:
        i, j = (int(k) for k in expr.indices)
        return f"t[{4 * i + j}]"

    def _print_SafeSqrt(self, expr: sp.Expr) -> str:
        return f"safe_sqrt({self._print(expr.args[0])}, stretch)"

    def _print_Coulomb(self, expr: sp.Expr) -> str:
        v, up, down = (self._print(a) for a in expr.args)
        return f"(if {v} > 0.0 {{ {up} }} else if {v} < 0.0 {{ {down} }} else {{ 0.0 }})"

    def _print_Clamp(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"{t}.max(0.0).min({tf})"

    def _print_Inside(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"(if {t} >= 0.0 && {t} <= {tf} {{ 1.0 }} else {{ 0.0 }})"

    def _print_Pick(self, expr: sp.Expr) -> str:
        c, a, b = (self._print(x) for x in expr.args)
        return f"(if {c} {{ {a} }} else {{ {b} }})"

    def _print_NaN(self, expr: sp.Expr) -> str:
        return "f64::NAN"


LANGUAGE = Language(
    name="rust",
    printer=RustPrinter,
    files=(("rust_module.rs.j2", "{prefix}.rs", None),),
    comment="//",
    note="mod {prefix}; (no crates)",
)
