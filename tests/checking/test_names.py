"""Names in answers: key symbols, aliases and the lecture abbreviations."""

from __future__ import annotations

import sympy as sp

from dhsym import load_table
from dhsym.checking.names import NameContext
from dhsym.model.tablefile import read_table_text

S = lambda n: sp.Symbol(n, real=True)  # noqa: E731
t1, t2, t3 = S("theta1"), S("theta2"), S("theta3")


def test_abbreviations_of_the_lectures():
    ctx = NameContext.from_table(load_table("puma560"))
    assert ctx.resolve("C12") == sp.cos(t1 + t2)
    assert ctx.resolve("S23") == sp.sin(t2 + t3)
    assert ctx.resolve("c1") == sp.cos(t1) and ctx.resolve("s1") == sp.sin(t1)
    assert ctx.resolve("C_12") == sp.cos(t1 + t2)
    assert ctx.resolve("c_alpha") == sp.cos(S("alpha"))
    assert ctx.resolve("c_alpha1") == sp.cos(S("alpha1"))
    assert ctx.resolve("c1s2") == sp.cos(t1) * sp.sin(t2)


def test_aliases_map_to_key_symbols():
    ctx = NameContext.from_table(load_table("puma560"))
    assert (
        ctx.resolve("q3") == t3 and ctx.resolve("theta_3") == t3 and ctx.resolve("a_2") == S("a2")
    )
    assert ctx.resolve("d3") == S("d3")  # a constant of the PUMA, not a variable alias
    assert ctx.resolve("zebra") is None and ctx.resolve("C7") is None


def test_generic_labels_i():
    table = read_table_text(
        "convention: modified\njoints: [{type: R, theta: theta_i, d: d_i, "
        "a: a_im1, alpha: alpha_im1}]"
    )
    ctx = NameContext.from_table(table)
    assert ctx.resolve("C_i") == sp.cos(S("theta_i"))
    assert ctx.resolve("c_theta_i") == sp.cos(S("theta_i"))
    assert ctx.resolve("s_alpha_im1") == sp.sin(S("alpha_im1"))
