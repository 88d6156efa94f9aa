"""Names in answers: key symbols, aliases and the lecture abbreviations."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym import load_table
from dhsym.checking.reading.answer_names import NameContext
from dhsym.errors import ParseError
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


def test_glued_factors_are_split_by_the_keys_symbols():
    ctx = NameContext.from_table(load_table("puma560"))
    t4 = S("theta4")
    assert ctx.resolve("s_23c_4") == sp.sin(t2 + t3) * sp.cos(t4)
    assert ctx.resolve("a_2c_2") == S("a2") * sp.cos(t2)
    assert ctx.resolve("d3S1") == S("d3") * sp.sin(t1)
    assert ctx.resolve("C_1C_23") == sp.cos(t1) * sp.cos(t2 + t3)
    assert ctx.resolve("costheta1sintheta2") == sp.cos(t1) * sp.sin(t2)
    assert ctx.resolve("c_theta1c_theta2") == sp.cos(t1) * sp.cos(t2)
    assert ctx.resolve("a12") is None and ctx.resolve("x_1y_2") is None  # no known factors


def test_whole_name_first_and_ambiguous_splits_refused():
    table = read_table_text(
        "joints: [{type: R, theta: theta1, d: 0, a: l, alpha: 0},"
        " {type: R, theta: theta2, d: 0, a: lc1, alpha: 0}]"
    )
    ctx = NameContext.from_table(table)
    assert ctx.resolve("lc1") == S("lc1")  # the whole name, not l·c1
    assert ctx.resolve("lC1") == S("l") * sp.cos(t1)
    with pytest.raises(ParseError, match="ambiguous name 'lc1C12'.*'l c1 C12'.*'lc1 C12'"):
        ctx.resolve("lc1C12")


# --- what `derive --format text` prints, `check` reads ------------------------------------


def test_printed_angle_differences_read_back() -> None:
    ctx = NameContext.from_table(load_table("scara"))
    t1, t2, t4 = (sp.Symbol(f"theta{k}", real=True) for k in (1, 2, 4))
    assert ctx.resolve("C_angle_12_minus_4") == sp.cos(t1 + t2 - t4)
    assert ctx.resolve("s_angle_2_minus_1_minus_4") == sp.sin(t2 - t1 - t4)
    assert ctx.resolve("C_angle_12_minus_9") is None  # no joint 9: not an abbreviation


ARMS = ["scara", "planar2r", "planar4r", "puma560", "puma560_modified", "ur5", "stanford"]
ARMS += ["cartesian", "cylindrical", "example1_rrp", "example4_6dof"]


@pytest.mark.parametrize("robot", ARMS)
def test_every_printed_entry_of_the_arm_matrix_is_correct(robot: str) -> None:
    # each entry of ^0T_n as `dhsym derive --format text` prints it (C[12-4] included),
    # fed to check as the answer to its own question
    import dhsym

    chain = dhsym.Robot(load_table(robot))
    n = chain.n
    T = chain.transform(0, n).matrix
    printed_all = [chain.notation.text(T[r, c]) for r in range(3) for c in range(4)]
    assert robot != "scara" or "C[12-4]" in printed_all  # the notation this test is about
    for r in range(3):
        for c in range(4):
            printed = chain.notation.text(T[r, c])
            result = dhsym.check(printed, key=robot, question=f"T0_{n}[{r},{c}]").result
            assert result.verdict.value == "correct", (robot, r, c, printed, result)
