"""MATLAB/Octave function files: ``<prefix>_fk.m``, ``<prefix>_jacobian.m``, ``<prefix>_ik.m``.

``T = <prefix>_fk(q)`` (4×4), ``J = <prefix>_jacobian(q)`` (6×n),
``[Q, count, residual] = <prefix>_ik(T, tol)`` (``count``×n, one solution per row;
``tol`` optional), and
``<prefix>_njoints()``, ``<prefix>_max_ik_solutions()`` for the constants.

Examples
--------
>>> import sympy as sp
>>> from dhsym.export.ik_source import pose_input
>>> x = sp.Symbol("x", real=True)
>>> MatlabPrinter().doprint(sp.atan2(pose_input()[0, 3], x) + x**2)
'x.^2 + atan2(T(1, 4), x)'
"""

from __future__ import annotations

import sympy as sp
from sympy.printing.octave import OctaveCodePrinter

from .languages import Language

__all__ = ["LANGUAGE", "MatlabPrinter"]


class MatlabPrinter(OctaveCodePrinter):
    """sympy's Octave printer; ``T[i, j]`` is ``T(i+1, j+1)``, ``SafeSqrt`` a subfunction."""

    def _print_Indexed(self, expr: sp.Indexed) -> str:
        i, j = (int(k) for k in expr.indices)
        return f"{expr.base.label}({i + 1}, {j + 1})"

    def _print_SafeSqrt(self, expr: sp.Expr) -> str:
        return f"safe_sqrt({self._print(expr.args[0])}, stretch)"

    def _print_Coulomb(self, expr: sp.Expr) -> str:
        v, up, down = (self._print(a) for a in expr.args)
        return f"({up}*({v} > 0) + {down}*({v} < 0))"

    def _print_Clamp(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"min(max({t}, 0), {tf})"

    def _print_Inside(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"double({t} >= 0 & {t} <= {tf})"

    def _print_Pick(self, expr: sp.Expr) -> str:
        # the file's local function pick: only the value chosen is used (a product with
        # the condition would carry the NaN of the other value along)
        c, a, b = (self._print(x) for x in expr.args)
        return f"pick({c}, {a}, {b})"


LANGUAGE = Language(
    name="matlab",
    printer=MatlabPrinter,
    files=(
        ("matlab_fk.m.j2", "{prefix}_fk.m", None),
        ("matlab_jacobian.m.j2", "{prefix}_jacobian.m", "jacobian"),
        ("matlab_ik.m.j2", "{prefix}_ik.m", "ik"),
        ("matlab_njoints.m.j2", "{prefix}_njoints.m", None),
        ("matlab_max_ik.m.j2", "{prefix}_max_ik_solutions.m", "ik"),
        ("matlab_rne.m.j2", "{prefix}_rne.m", "dynamics"),
        ("matlab_cubic.m.j2", "{prefix}_cubic.m", "trajectory"),
        ("matlab_quintic.m.j2", "{prefix}_quintic.m", "trajectory"),
        ("matlab_lspb.m.j2", "{prefix}_lspb.m", "trajectory"),
        ("matlab_spline.m.j2", "{prefix}_spline.m", "trajectory"),
        ("matlab_computed_torque.m.j2", "{prefix}_computed_torque.m", "control"),
        ("matlab_fk_space.m.j2", "{prefix}_fk_space.m", "screws"),
        ("matlab_jacobian_space.m.j2", "{prefix}_jacobian_space.m", "screws"),
        ("matlab_jacobian_body.m.j2", "{prefix}_jacobian_body.m", "screws"),
    ),
    comment="%",
    note="addpath the folder; T = {prefix}_fk(q)",
)
