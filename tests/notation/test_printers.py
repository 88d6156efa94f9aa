"""Lecture notation in text, LaTeX and Markdown."""

from __future__ import annotations

import sympy as sp

import dhsym
from dhsym.notation.printers import Notation, angle_label, format_angle
from dhsym.notation.tables import table_latex

S = lambda n: sp.Symbol(n, real=True)  # noqa: E731
t = [S(f"theta{i}") for i in range(1, 11)]
nota = Notation.from_variables(t)


def test_sum_and_difference_labels():
    assert nota.text(sp.cos(t[0] + t[1])) == "C12"
    assert nota.text(sp.sin(t[1] + t[2])) == "S23"
    assert nota.text(sp.cos(t[0] + t[1] - t[3])) == "C[12-4]"
    assert nota.latex(sp.cos(t[0] - t[1])) == "C_{1-2}"
    assert nota.latex(sp.sin(t[0]) ** 2) == "S_{1}^{2}"


def test_labels_above_nine_are_comma_separated():
    assert nota.text(sp.cos(t[8] + t[9])) == "C9,10"
    assert nota.latex(sp.cos(sum(t))) == "C_{1,2,3,4,5,6,7,8,9,10}"


def test_twist_and_other_symbols_use_small_c_s():
    al = S("alpha1")
    assert nota.latex(sp.cos(al)) == r"c_{\alpha_{1}}"
    assert nota.text(sp.sin(al)) == "s_alpha1"


def test_non_joint_arguments_print_in_full():
    assert nota.text(sp.cos(t[0] + sp.pi / 5)) == "cos(theta1 + pi/5)"
    assert nota.latex(sp.cos(2 * t[0])) == r"\cos{\left(2 \theta_{1} \right)}"


def test_lowercase_craig_style_and_full_form():
    craig = Notation.from_variables(t, style="c1")
    assert craig.text(sp.cos(t[1] + t[2])) == "c23"
    full = Notation.from_variables(t, compact=False)
    assert full.text(sp.cos(t[0] + t[1])) == "cos(theta1 + theta2)"
    assert full.legend([sp.cos(t[0])]) == []


def test_exact_decimals_print_as_decimals():
    assert nota.text(sp.Rational("0.15005") * t[0]) == "0.15005*theta1"
    assert nota.latex(sp.Rational(1, 3)) == r"\frac{1}{3}"
    assert nota.latex(sp.Rational(4, 5)) == "0.8"
    assert nota.text(sp.Rational(1, 2) * t[0]) == "theta1/2"


def test_legend_lists_each_abbreviation_once():
    e = sp.cos(t[0]) * sp.cos(t[0] + t[1]) + sp.sin(t[0] + t[1]) + sp.cos(S("alpha2"))
    entries = nota.legend([e, e])
    assert [x.text for x in entries] == ["C1", "C12", "S12", "c_alpha2"]
    assert entries[1].meaning_latex == r"\cos{\left(\theta_{1} + \theta_{2} \right)}"


def test_angle_label_rejects_non_unit_coefficients():
    labels = {t[0]: "1", t[1]: "2"}
    assert angle_label(2 * t[0], labels) is None
    assert angle_label(t[0] + 1, labels) is None


def test_format_angle_in_degrees():
    assert format_angle(t[2] + sp.pi / 2, degrees=True) == r"\theta_{3} + 90^{\circ}"
    assert format_angle(-sp.pi / 2, degrees=True, latex=False) == "-90°"
    assert format_angle(sp.Integer(0), degrees=True) == "0"


def test_table_latex_uses_the_conventions_own_headers():
    std = table_latex(dhsym.builtin_table("puma560"))
    assert r"i & \theta_i & d_i & a_i & \alpha_i" in std
    mod = table_latex(dhsym.builtin_table("puma560_modified"))
    assert r"i & \alpha_{i-1} & a_{i-1} & d_i & \theta_i" in mod
    assert r"2 & -90^{\circ} & 0 & 0 & \boxed{\theta_{2}}" in mod


def test_pose_and_table_display_in_notebooks():
    r = dhsym.load("planar2r")
    html = r.arm_matrix()._repr_latex_()
    assert html.startswith("$${}^{0}T_{2} = \\left[\\begin{matrix}") or "bmatrix" in html
    assert "a_{1} C_{1} + a_{2} C_{12}" in html
    assert r.table._repr_latex_().startswith("$$\\begin{array}")
    assert "| 1 | $\\theta_{1}$ |" in r.table._repr_markdown_()
