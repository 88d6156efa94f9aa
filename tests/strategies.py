"""Hypothesis strategies: random DH tables in both conventions."""

from __future__ import annotations

import sympy as sp
from hypothesis import strategies as st

from dhsym.model.table import Convention, DHRow, DHTable

_TWISTS = [sp.Integer(0), sp.pi, sp.pi / 2, -sp.pi / 2, sp.pi / 3, -sp.pi / 4]
_OFFSETS = [sp.Integer(0), sp.pi / 2, -sp.pi / 2, sp.pi, sp.pi / 6]
_LENGTHS = [sp.Integer(0), sp.Integer(1), sp.Rational(1, 2), sp.Rational(-3, 10)]


@st.composite
def dh_rows(draw: st.DrawFn, k: int) -> DHRow:
    """Row ``k`` (1-based): revolute, prismatic or fixed, with symbolic or numeric entries."""
    kind = draw(st.sampled_from("RRRPF"))
    alpha = draw(st.sampled_from([*_TWISTS, sp.Symbol(f"alpha{k}", real=True)]))
    a = draw(st.sampled_from([*_LENGTHS, sp.Symbol(f"a{k}", real=True)]))
    theta_c = draw(st.sampled_from(_OFFSETS))
    d_c = draw(st.sampled_from([*_LENGTHS, sp.Symbol(f"b{k}", real=True)]))
    if kind == "R":
        return DHRow.revolute(sp.Symbol(f"theta{k}", real=True) + theta_c, d=d_c, a=a, alpha=alpha)
    if kind == "P":
        return DHRow.prismatic(
            sp.Symbol(f"d{k}", real=True) + d_c,
            theta=theta_c,
            a=a,
            alpha=alpha,
            variable=sp.Symbol(f"d{k}", real=True),
        )
    return DHRow.fixed(theta=theta_c, d=d_c, a=a, alpha=alpha)


@st.composite
def dh_tables(draw: st.DrawFn, min_rows: int = 1, max_rows: int = 5) -> DHTable:
    """A random valid table in a random convention."""
    n = draw(st.integers(min_rows, max_rows))
    rows = [draw(dh_rows(k)) for k in range(1, n + 1)]
    convention = draw(st.sampled_from(list(Convention)))
    return DHTable(tuple(rows), convention)
