"""Lecture notation in text, LaTeX and Markdown."""

from __future__ import annotations

import re

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings

import dhsym
from dhsym.errors import DHError
from dhsym.notation.layout import pieces
from dhsym.notation.printers import Notation, TrigStyle, angle_label, format_angle
from dhsym.notation.tables import table_latex

from ..strategies import dh_tables
from .rules import nontrivial, violations

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


# --- the term-order policy (issue 11) ------------------------------------------------------

# Every arm-matrix entry, in the policy's order (text; read back against the engine below).
GOLDEN = {
    "puma560_modified": (
        (
            "C1*(C23*(C4*C5*C6 - S4*S6) - S23*S5*C6) + S1*(S4*C5*C6 + C4*S6)",
            "C1*(S23*S5*S6 - C23*(C4*C5*S6 + S4*C6)) + S1*(C4*C6 - S4*C5*S6)",
            "-C1*(C23*C4*S5 + S23*C5) - S1*S4*S5",
            "C1*(a2*C2 + a3*C23 - d4*S23) - d3*S1",
        ),
        (
            "S1*(C23*(C4*C5*C6 - S4*S6) - S23*S5*C6) - C1*(S4*C5*C6 + C4*S6)",
            "S1*(S23*S5*S6 - C23*(C4*C5*S6 + S4*C6)) - C1*(C4*C6 - S4*C5*S6)",
            "C1*S4*S5 - S1*(C23*C4*S5 + S23*C5)",
            "S1*(a2*C2 + a3*C23 - d4*S23) + d3*C1",
        ),
        (
            "-S23*(C4*C5*C6 - S4*S6) - C23*S5*C6",
            "S23*(C4*C5*S6 + S4*C6) + C23*S5*S6",
            "S23*C4*S5 - C23*C5",
            "-a2*S2 - a3*S23 - d4*C23",
        ),
    ),
    "puma560": (
        (
            "C1*(C23*(C4*C5*C6 - S4*S6) - S23*S5*C6) - S1*(S4*C5*C6 + C4*S6)",
            "C1*(S23*S5*S6 - C23*(C4*C5*S6 + S4*C6)) - S1*(C4*C6 - S4*C5*S6)",
            "S1*S4*S5 - C1*(C23*C4*S5 + S23*C5)",
            "C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1",
        ),
        (
            "S1*(C23*(C4*C5*C6 - S4*S6) - S23*S5*C6) + C1*(S4*C5*C6 + C4*S6)",
            "S1*(S23*S5*S6 - C23*(C4*C5*S6 + S4*C6)) + C1*(C4*C6 - S4*C5*S6)",
            "-S1*(C23*C4*S5 + S23*C5) - C1*S4*S5",
            "S1*(a2*C2 + a3*C23 - d4*S23) - d3*C1",
        ),
        (
            "S23*(C4*C5*C6 - S4*S6) + C23*S5*C6",
            "-S23*(C4*C5*S6 + S4*C6) - C23*S5*S6",
            "C23*C5 - S23*C4*S5",
            "a2*S2 + a3*S23 + d4*C23",
        ),
    ),
    "stanford": (
        (
            "C1*(C2*(C4*C5*C6 - S4*S6) - S2*S5*C6) - S1*(S4*C5*C6 + C4*S6)",
            "C1*(S2*S5*S6 - C2*(C4*C5*S6 + S4*C6)) - S1*(C4*C6 - S4*C5*S6)",
            "C1*(C2*C4*S5 + S2*C5) - S1*S4*S5",
            "C1*(S2*(d3 + d6*C5) + d6*C2*C4*S5) - S1*(d2 + d6*S4*S5)",
        ),
        (
            "S1*(C2*(C4*C5*C6 - S4*S6) - S2*S5*C6) + C1*(S4*C5*C6 + C4*S6)",
            "S1*(S2*S5*S6 - C2*(C4*C5*S6 + S4*C6)) + C1*(C4*C6 - S4*C5*S6)",
            "S1*(C2*C4*S5 + S2*C5) + C1*S4*S5",
            "C1*(d2 + d6*S4*S5) + S1*(S2*(d3 + d6*C5) + d6*C2*C4*S5)",
        ),
        (
            "-S2*(C4*C5*C6 - S4*S6) - C2*S5*C6",
            "S2*(C4*C5*S6 + S4*C6) + C2*S5*S6",
            "C2*C5 - S2*C4*S5",
            "C2*(d3 + d6*C5) - d6*S2*C4*S5",
        ),
    ),
    "scara": (
        ("C[12-4]", "S[12-4]", "0", "a1*C1 + a2*C12"),
        ("S[12-4]", "-C[12-4]", "0", "a1*S1 + a2*S12"),
        ("0", "0", "-1", "-d3 - d4"),
    ),
    "planar2r": (
        ("C12", "-S12", "0", "a1*C1 + a2*C12"),
        ("S12", "C12", "0", "a1*S1 + a2*S12"),
        ("0", "0", "1", "0"),
    ),
    "planar4r": (
        ("C1234", "-S1234", "0", "a1*C1 + a2*C12 + a3*C123 + a4*C1234"),
        ("S1234", "C1234", "0", "a1*S1 + a2*S12 + a3*S123 + a4*S1234"),
        ("0", "0", "1", "0"),
    ),
}

# Craig, Introduction to Robotics, eq. 3.14, as printed (c/s in lower case, * added).
CRAIG_314 = {
    (0, 0): "c1*(c23*(c4*c5*c6 - s4*s6) - s23*s5*c6) + s1*(s4*c5*c6 + c4*s6)",
    (1, 0): "s1*(c23*(c4*c5*c6 - s4*s6) - s23*s5*c6) - c1*(s4*c5*c6 + c4*s6)",
    (2, 0): "-s23*(c4*c5*c6 - s4*s6) - c23*s5*c6",
    (0, 1): "c1*(c23*(-c4*c5*s6 - s4*c6) + s23*s5*s6) + s1*(c4*c6 - s4*c5*s6)",
    (1, 1): "s1*(c23*(-c4*c5*s6 - s4*c6) + s23*s5*s6) - c1*(c4*c6 - s4*c5*s6)",
    (2, 1): "-s23*(-c4*c5*s6 - s4*c6) + c23*s5*s6",
    (0, 2): "-c1*(c23*c4*s5 + s23*c5) - s1*s4*s5",
    (1, 2): "-s1*(c23*c4*s5 + s23*c5) + c1*s4*s5",
    (2, 2): "s23*c4*s5 - c23*c5",
    (0, 3): "c1*(a2*c2 + a3*c23 - d4*s23) - d3*s1",
    (1, 3): "s1*(a2*c2 + a3*c23 - d4*s23) + d3*c1",
    (2, 3): "-a3*s23 - a2*s2 - d4*c23",
}
# Where the policy departs from the book: a minus before its bracket, not in all its
# terms (r12, r22, r32: c23(-c4c5s6 - s4c6)); a sum led by a positive term (r23, and
# r12/r22 inside the bracket); terms in joint order (pz: Craig writes a3s23 first).
CRAIG_DIFFERS = {(0, 1), (1, 1), (2, 1), (1, 2), (2, 3)}


def _reads_back(text: str, table: dhsym.DHTable) -> sp.Expr:
    """Parse printed text as the checker reads an answer; C[12-4] names a difference angle."""
    from dhsym.checking.reading.answer_names import NameContext
    from dhsym.model.parsing import parse_expression

    ctx = NameContext.from_table(table)
    angles = {str(k): r.variable for k, r in enumerate(table.rows, 1)}

    def difference(m: re.Match[str]) -> str:
        return f"{m.group(1)}diff{m.group(2).replace('-', 'm').replace(',', 'x')}"

    text = re.sub(r"\b([CScs])\[([0-9,\-]+)\]", difference, text)

    def resolve(name: str) -> sp.Expr | None:
        m = re.fullmatch(r"([CScs])diff([0-9x]+)m([0-9xm]+)", name)
        if m is None:
            return ctx.resolve(name)
        split = lambda s: s.split("x") if "x" in s else list(s)  # noqa: E731
        arg = sum(angles[k] for k in split(m.group(2))) - sum(
            angles[k] for part in m.group(3).split("m") for k in split(part)
        )
        return (sp.cos if m.group(1) in "Cc" else sp.sin)(arg)

    return parse_expression(text, resolve=resolve)


def _equal(a: sp.Expr, b: sp.Expr) -> bool:
    return a == b or sp.expand(a - b) == 0


@pytest.mark.parametrize("name", GOLDEN)
def test_golden_arm_matrix_entries_read_back_to_the_engine(name):
    r = dhsym.load(name)
    A = r.arm_matrix().matrix
    got = tuple(tuple(r.notation.text(A[i, j]) for j in range(4)) for i in range(3))
    assert got == GOLDEN[name]
    for i in range(3):
        for j in range(4):
            assert _equal(_reads_back(GOLDEN[name][i][j], r.table), A[i, j]), (name, i, j)


def test_the_craig_table_reads_as_craig_prints_it():
    r = dhsym.load("puma560_modified", style="c1")
    A = r.arm_matrix().matrix
    for (i, j), craig in CRAIG_314.items():
        ours = r.notation.text(A[i, j])
        assert (ours == craig) is ((i, j) not in CRAIG_DIFFERS), (i, j, ours)
        assert _equal(_reads_back(craig, r.table), A[i, j])  # the book and dhsym agree
    assert (
        r.notation.text(A[0, 1])
        == "c1*(s23*s5*s6 - c23*(c4*c5*s6 + s4*c6)) + s1*(c4*c6 - s4*c5*s6)"
    )
    assert r.notation.text(A[1, 2]) == "c1*s4*s5 - s1*(c23*c4*s5 + s23*c5)"


SIX = ["puma560", "puma560_modified", "stanford", "planar4r", "example4_6dof", "scara"]


@pytest.mark.parametrize("name", SIX)
def test_every_entry_of_the_six_robots_follows_the_three_rules(name):
    r = dhsym.load(name)
    texts = [r.notation.text(e) for e in r.arm_matrix().matrix]
    assert [t for t in texts if violations(t)] == []


def test_the_rule_reader_catches_sympys_order():
    # the PUMA r11 as sympy ordered it before the printers did
    old = "((-S4*S6 + C4*C5*C6)*C23 - S5*S23*C6)*C1 + (S4*C5*C6 + S6*C4)*S1"
    assert set(violations(old)) == {"factor", "lead", "order"}
    assert violations("d3*S1 + C1*(a2*C2 + a3*C23 - d4*S23)") == []
    assert violations("S1*C1") == ["order"] and violations("C4*C1") == ["order"]
    assert violations("-S4*S6 + C4*C5*C6") == ["lead"]
    assert nontrivial("a1*C1") and not nontrivial("-S12") and not nontrivial("0")


def test_products_put_numbers_then_lengths_then_joints_then_brackets():
    a2, d4, a3 = S("a2"), S("d4"), S("a3")
    c, s = [sp.cos(x) for x in t], [sp.sin(x) for x in t]
    assert nota.text(c[1] * a2 * 2) == "2*a2*C2"
    assert nota.text(c[5] * s[4] * sp.sin(t[1] + t[2])) == "S23*S5*C6"
    assert nota.text(s[0] * c[0]) == "C1*S1"  # C before S on the same joint
    assert nota.text((a2 * c[1] + a3 * c[2]) * c[0]) == "C1*(a2*C2 + a3*C3)"
    assert nota.text(sp.cos(S("alpha1")) * s[0] * d4) == "d4*S1*c_alpha1"  # twists last
    assert nota.text(sp.Rational(3001, 20000) * s[0]) == "0.15005*S1"


def test_sums_lead_with_a_positive_term_in_joint_order():
    c, s = [sp.cos(x) for x in t], [sp.sin(x) for x in t]
    assert nota.text(-s[3] * s[5] + c[3] * c[4] * c[5]) == "C4*C5*C6 - S4*S6"
    assert nota.text(-S("d4") * s[1] + S("a3") * c[1] + S("a2")) == "a2 + a3*C2 - d4*S2"
    assert nota.text(-S("a2") * s[1] - S("a3") * s[2]) == "-a2*S2 - a3*S3"
    assert nota.text(3 - c[0]) == "3 - C1"  # a number comes last, unless it leads


def test_a_minus_stands_before_its_bracket():
    c, s = [sp.cos(x) for x in t], [sp.sin(x) for x in t]
    inner = -s[4] * c[3] * c[1] - s[1] * c[4]  # all terms negative
    assert nota.text(inner * c[0]) == "-C1*(C2*C4*S5 + S2*C5)"
    # a leaf bracket reads like a sum-angle identity: the all-cosine term positive
    assert nota.text((s[3] * s[5] - c[3] * c[5]) * s[1]) == "-S2*(C4*C6 - S4*S6)"
    # an outer bracket shows the fewest minus signs
    outer = (-(c[3] + s[3]) * c[1] + s[1]) * c[0]
    assert nota.text(outer) == "C1*(S2 - C2*(C4 + S4))"


def test_brackets_alternate_by_level_in_latex():
    r = dhsym.load("puma560_modified")
    A = r.arm_matrix().matrix
    assert r.notation.latex(A[0, 0]) == (
        r"C_{1}[C_{23}(C_{4} C_{5} C_{6} - S_{4} S_{6}) - S_{23} S_{5} C_{6}]"
        r" + S_{1}(S_{4} C_{5} C_{6} + C_{4} S_{6})"
    )
    c = [sp.cos(x) for x in t]
    three = c[0] * (c[1] * (c[2] * (c[3] + 1) + 1) + 1)
    assert nota.latex(three) == r"C_{1}\{C_{2}[C_{3}(C_{4} + 1) + 1] + 1\}"
    assert nota.text(three) == "C1*(C2*(C3*(C4 + 1) + 1) + 1)"  # text reads back: ( ) only
    tall = c[0] * (c[1] + sp.sqrt(2) / 2)
    assert nota.latex(tall) == r"C_{1}\left(C_{2} + \frac{\sqrt{2}}{2}\right)"


def test_fractions_keep_the_order_inside():
    c, s = [sp.cos(x) for x in t], [sp.sin(x) for x in t]
    e = sp.sqrt(3) / 2 * S("a1") * s[1] * c[0]
    assert nota.text(e) == "sqrt(3)*a1*C1*S2/2"
    assert nota.latex(e) == r"\frac{\sqrt{3} a_{1} C_{1} S_{2}}{2}"
    assert nota.text(-t[0] / 2) == "-theta1/2"


@pytest.mark.parametrize(
    ("style", "latex", "text"),
    [
        ("C1", r"C_{1}(a_{2} C_{2} + a_{3} C_{23} - d_{4} S_{23}) - d_{3} S_{1}", "C1*("),
        ("c1", r"c_{1}(a_{2} c_{2} + a_{3} c_{23} - d_{4} s_{23}) - d_{3} s_{1}", "c1*("),
        (
            "c_theta",
            r"c_{\theta_{1}}(a_{2} c_{\theta_{2}} + a_{3} c_{\theta_{23}} - d_{4} s_{\theta_{23}})"
            r" - d_{3} s_{\theta_{1}}",
            "c1*(",
        ),
    ],
)
def test_the_three_styles(style, latex, text):
    r = dhsym.load("puma560_modified", style=style)
    px = r.arm_matrix().matrix[0, 3]
    assert r.notation.latex(px) == latex and r.notation.text(px).startswith(text)
    assert _equal(_reads_back(r.notation.text(px), r.table), px)


def test_style_names_and_errors():
    assert TrigStyle.parse("Craig") is TrigStyle.LOWER and TrigStyle.parse("c1") is TrigStyle.LOWER
    assert (
        TrigStyle.parse("lecture") is TrigStyle.UPPER and TrigStyle.parse("C1") is TrigStyle.UPPER
    )
    assert Notation(style="theta").style is TrigStyle.THETA
    with pytest.raises(DHError, match="unknown notation 'Fancy'"):
        Notation(style="Fancy")
    q = sp.Symbol("q2", real=True)
    assert Notation.from_variables([q], ["2"], style="c_theta").latex(sp.sin(q)) == "s_{q_{2}}"


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(dh_tables(max_rows=4))
def test_random_tables_print_by_the_rules_and_read_back(table):
    r = dhsym.Robot(table)
    for e in r.arm_matrix().matrix:
        text = r.notation.text(e)
        assert violations(text) == [], text
        assert _equal(_reads_back(text, table), e), text
        ps = pieces(e, r.notation)  # the line breaker sees what the printers print
        assert render_tokens(ps) == (r.notation.latex(e), text)


def render_tokens(ps):
    """The pieces joined back: (LaTeX, text)."""
    return "".join(p.latex for p in ps).strip(), "".join(p.text for p in ps).strip()


# --- decimal lengths print as the decimals written (issue 24, item 4) ----------------------

_SCARA = """name: SCARA decimal
angles: deg
joints:
  - {type: R, theta: theta1, d: 0, a: 0.35, alpha: 0}
  - {type: R, theta: theta2, d: 0, a: 0.25, alpha: 180}
  - {type: P, theta: 0, d: d3, a: 0, alpha: 0}
  - {type: R, theta: theta4, d: 0, a: 0, alpha: 0}
"""
_RRR = """name: RRR decimal
joints:
  - {type: R, theta: theta1, d: 0, a: 0.5, alpha: 0}
  - {type: R, theta: theta2, d: 0, a: 0.35, alpha: 0}
  - {type: R, theta: theta3, d: 0, a: 0.1, alpha: 0}
"""


def _robot(text: str):
    from dhsym.model.tablefile import read_table_text
    from dhsym.robot import Robot

    return Robot(read_table_text(text))


def _ik_lines(robot) -> dict[str, str]:
    nota = robot.notation
    return {nota.text(st.lhs): nota.text(st.rhs) for st in robot.inverse().steps}


def test_scara_with_decimal_lengths_prints_decimals_everywhere():
    r = _robot(_SCARA)
    nota = r.notation
    assert nota.text(r.transform(0, 4).matrix[0, 3]) == "0.35*C1 + 0.25*C12"
    assert nota.text(r.transform(1, 2).matrix[0, 3]) == "0.25*C2"  # a lone 1/4 too
    assert nota.latex(r.transform(0, 4).matrix[1, 3]) == "0.35 S_{1} + 0.25 S_{12}"
    ik = _ik_lines(r)
    assert ik["D_2"] == "(c_x**2 + c_y**2 - 0.185)/0.175"  # (p² - 0.35² - 0.25²)/(2·0.35·0.25)
    assert ik["theta1"] == "atan2(c_y, c_x) - atan2(0.25*S2, 0.25*C2 + 0.35)"
    assert all("/4" not in v and "/20" not in v for v in ik.values())


def test_rrr_with_decimal_lengths_jacobian_singularities_and_ik():
    r = _robot(_RRR)
    nota = r.notation
    J = r.jacobian()
    assert nota.text(J[0, 0]) == "-0.5*S1 - 0.35*S12 - 0.1*S123"
    assert nota.text(J[1, 1]) == "0.35*C12 + 0.1*C123"
    ik = _ik_lines(r)
    assert ik["D_2"] == "(c_x**2 + c_y**2 - 0.3725)/0.35"  # 0.5² + 0.35², 2·0.5·0.35
    assert ik["theta1"] == "atan2(c_y, c_x) - atan2(0.35*S2, 0.35*C2 + 0.5)"


def test_fractions_stay_fractions_without_decimals():
    t1 = sp.Symbol("theta1", real=True)
    nota = Notation.from_variables([t1])
    assert nota.text(sp.cos(t1) / 4) == "C1/4"
    assert Notation.from_variables([t1], decimals=True).text(sp.cos(t1) / 4) == "0.25*C1"
