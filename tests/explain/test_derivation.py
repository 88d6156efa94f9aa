"""The derivation model: sections, sum-angle steps, entry splitting and options."""

from __future__ import annotations

import re

import pytest
import sympy as sp

import dhsym
from dhsym.errors import DHError
from dhsym.explain.derivation import Derivation, derive, general_link
from dhsym.kinematics.transforms import Rx, Rz, Tx, Tz
from dhsym.model.parsing import parse_expression
from dhsym.notation.layout import LATEX_WIDTH, TEXT_WIDTH, math_width
from dhsym.notation.layout import pieces as _pieces
from dhsym.notation.tables import table_latex

S = lambda n: sp.Symbol(n, real=True)  # noqa: E731


def _texts(block):
    return [[c.text for c in row] for row in block.rows]


# --- the 2R example of seed 001 -----------------------------------------------------------


def test_planar_2r_follows_seed_001():
    d = derive("planar2r")
    assert isinstance(d, Derivation) and d.n == 2 and d.convention == "standard"
    assert [b.label.latex for b in d.links] == ["{}^{0}T_{1}", "{}^{1}T_{2}"]
    assert _texts(d.links[0])[0] == ["C1", "-S1", "0", "a1*C1"]
    assert d.links[0].prefix[0].text == "R_z(theta1)*T_x(a1)"
    assert [c.latex for c in d.result.rows[0]] == [
        "C_{12}",
        "-S_{12}",
        "0",
        "a_{1} C_{1} + a_{2} C_{12}",
    ]
    assert _texts(d.result)[1] == ["S12", "C12", "0", "a1*S1 + a2*S12"]
    assert not d.result.wide and d.result.entries == ()


def test_the_sum_angle_step_is_named_where_joints_combine():
    (step,) = derive("planar2r").products
    assert step.final and step.block.prefix[0].latex == r"{}^{0}T_{1}\,{}^{1}T_{2}"
    cos, sin = step.identities
    assert [(t.sign, t.math.latex) for t in cos.terms] == [
        ("+", "C_{1} C_{2}"),
        ("-", "S_{1} S_{2}"),
    ]
    assert cos.result.latex == "C_{12}"
    assert [(t.sign, t.math.text) for t in sin.terms] == [("+", "S1*C2"), ("+", "C1*S2")]
    assert sin.result.text == "S12"


def test_puma_560_names_c23_at_the_third_product_only():
    d = derive("puma560")
    named = {s.block.label.text: [i.result.text for i in s.identities] for s in d.products}
    assert named == {"T0_2": [], "T0_3": ["C23", "S23"], "T0_4": [], "T0_5": [], "T0_6": []}
    assert [s.final for s in d.products] == [False] * 4 + [True]


def test_a_flip_gives_a_difference_identity():
    # SCARA: alpha = 180 deg on joint 2 turns theta4 into a difference angle
    d = derive("scara")
    results = [i.result.text for s in d.products for i in s.identities]
    assert "C[12-4]" in results and "S[12-4]" in results
    for s in d.products:
        for i in s.identities:
            lhs = sum((1 if t.sign == "+" else -1) * _value(t.math.text) for t in i.terms)
            assert sp.simplify(sp.expand_trig(lhs - _value(i.result.text))) == 0


def _value(text: str) -> sp.Expr:
    """Read C12 and C[12-4] style abbreviations back into cos/sin of theta sums."""
    text = re.sub(r"\b([CS])\[(\d+)-(\d+)\]", r"\1\2m\3", text)

    def resolve(name: str) -> sp.Expr | None:
        m = re.fullmatch(r"([CS])(\d+)(?:m(\d+))?", name)
        if not m:
            return None
        arg = sum(S(f"theta{k}") for k in m.group(2)) - (
            S(f"theta{m.group(3)}") if m.group(3) else 0
        )
        return (sp.cos if m.group(1) == "C" else sp.sin)(arg)

    return parse_expression(text, resolve=resolve)


# --- the PUMA 560: per-entry equations ---------------------------------------------------------


def test_puma_560_arm_matrix_is_given_entry_by_entry():
    d = derive("puma560")
    assert d.result.wide and d.result.wide_text
    names = [e.name.latex for e in d.result.entries]
    assert names == [
        "r_{11}",
        "r_{12}",
        "r_{13}",
        "r_{21}",
        "r_{22}",
        "r_{23}",
        "r_{31}",
        "r_{32}",
        "r_{33}",
        "p_{x}",
        "p_{y}",
        "p_{z}",
    ]
    px = d.result.entries[9]
    assert px.latex_lines == (r"C_{1}(a_{2} C_{2} + a_{3} C_{23} - d_{4} S_{23}) + d_{3} S_{1}",)
    assert px.text_lines == ("C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1",)
    assert d.result.entries[11].text_lines == ("a2*S2 + a3*S23 + d4*C23",)


def test_every_entry_equals_the_arm_matrix():
    r = dhsym.load("puma560")
    d = derive(r)
    abbreviations = {
        f"{c}{k}": f(S(f"theta{k}")) for k in range(1, 7) for c, f in (("C", sp.cos), ("S", sp.sin))
    }
    abbreviations |= {
        "C23": sp.cos(S("theta2") + S("theta3")),
        "S23": sp.sin(S("theta2") + S("theta3")),
    }
    entries = [r.arm_matrix()[i, j] for i in range(3) for j in range(3)] + [
        r.arm_matrix()[i, 3] for i in range(3)
    ]
    for eq, expected in zip(d.result.entries, entries, strict=True):
        got = parse_expression(" ".join(eq.text_lines), resolve=abbreviations.get)
        assert sp.expand(got - expected) == 0, eq.name.text


@pytest.mark.parametrize("name", ["puma560", "stanford", "example4_6dof", "planar8r"])
def test_long_entries_are_split_at_signs_and_fit(name):
    d = derive(name, compact=False)
    entries = [e for s in (*[p.block for p in d.products], d.result) for e in s.entries]
    assert entries
    anchor = math_width("{}={}")  # continuations are measured from the = sign
    for e in entries:
        assert math_width(e.latex_lines[0]) <= LATEX_WIDTH
        assert all(math_width(x) <= LATEX_WIDTH + anchor for x in e.latex_lines[1:])
    split = [e for e in d.result.entries if len(e.latex_lines) > 1]
    assert split, "full notation of a 6-DOF arm needs split entries"
    for e in split:  # each continuation: an indent, then its sign
        assert all(re.match(r"(\\quad |\\phantom\{.*\})\{\}[-+] ", x) for x in e.latex_lines[1:])
    text = [x for e in d.result.entries for x in e.text_lines]
    assert max(map(len, text)) <= TEXT_WIDTH - 12


@pytest.mark.parametrize("name", [*dhsym.builtin_names(), "planar8r"])
@pytest.mark.parametrize("compact", [True, False])
def test_pieces_print_exactly_what_the_printer_prints(name, compact):
    """Splitting never changes a formula: the pieces rejoin to the printer's own output."""
    r = dhsym.load(name, compact=compact)
    norm = lambda s: re.sub(r"\\(?:left|right)|\s", "", s)  # noqa: E731
    for e in r.arm_matrix().matrix:
        ps = _pieces(e, r.notation)
        assert norm("".join(p.latex for p in ps)) == norm(r.notation.latex(e))
        assert "".join(p.text for p in ps).replace(" ", "") == r.notation.text(e).replace(" ", "")


# --- the general link matrix (seed 002) ------------------------------------------------------


def test_general_link_modified_has_the_correct_sign_in_entry_2_4():
    g = general_link("modified")
    assert [(f.kind, f.axis) for f in g.factors] == [("R", "x"), ("T", "x"), ("R", "z"), ("T", "z")]
    assert g.word.text == "R_x(alpha_{i-1})*T_x(a_{i-1})*R_z(theta_i)*T_z(d_i)"
    assert g.result.rows[1][3].latex == r"-d_{i} s_{\alpha_{i-1}}"  # seed 002's slide says +
    assert g.result.rows[2][3].latex == r"d_{i} c_{\alpha_{i-1}}"
    assert [p.latex for p in g.parameters] == [r"\alpha_{i-1}", "a_{i-1}", "d_{i}", r"\theta_{i}"]


def test_general_link_matrices_are_the_products_of_their_factors():
    t, d, a, al = (S(n) for n in ("t", "d", "a", "al"))
    for conv, word in (
        ("standard", Rz(t) * Tz(d) * Tx(a) * Rx(al)),
        ("modified", Rx(al) * Tx(a) * Rz(t) * Tz(d)),
    ):
        g = general_link(conv)
        names = {"Ci": sp.cos(t), "Si": sp.sin(t), "d_i": d, "a_i": a, "a_{i-1}": a}
        for r in range(4):
            for c in range(4):
                text = g.result.rows[r][c].text
                text = re.sub(r"[cs]_alpha_(?:i|\{i-1\})", lambda m: f"{m.group(0)[0]}AL", text)
                text = text.replace("a_{i-1}", "a_im1")
                got = parse_expression(
                    text, resolve={**names, "a_im1": a, "cAL": sp.cos(al), "sAL": sp.sin(al)}.get
                )
                assert sp.simplify(got - word[r, c]) == 0, (conv, r, c)


def test_factors_can_be_left_out():
    assert derive("planar2r", factors=False).general is None
    assert derive("planar2r").general.result.label.latex == "{}^{i-1}T_{i}"


# --- the table --------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["puma560", "puma560_modified", "stanford", "example1_rrp"])
def test_table_cells_are_those_of_table_latex(name):
    t = dhsym.load(name).table
    data = derive(name).table
    lines = table_latex(t).splitlines()
    assert " & ".join(h.latex for h in data.heads) + r" \\ \hline" == lines[1]
    for row, line in zip(data.rows, lines[2:-1], strict=True):
        cells = [rf"\boxed{{{c.math.latex}}}" if c.variable else c.math.latex for c in row]
        assert " & ".join(cells) == line.removesuffix(r" \\")


def test_table_headers_follow_the_convention():
    assert [h.text for h in derive("puma560_modified").table.heads] == [
        "i",
        "alpha_{i-1}",
        "a_{i-1}",
        "d_i",
        "theta_i",
        "joint",
    ]
    assert [h.text for h in derive("puma560").table.heads] == [
        "i",
        "theta_i",
        "d_i",
        "a_i",
        "alpha_i",
        "joint",
    ]
    stanford = derive("stanford").table
    assert [c.variable for c in stanford.rows[2]] == [False, False, True, False, False, False]
    assert stanford.degrees and [v.text for v in stanford.variables][2] == "d3"


def test_values_print_as_the_decimals_they_were_written_as():
    assert [(s.text, v.text) for s, v in derive("planar2r").table.values] == [
        ("a1", "1"),
        ("a2", "0.8"),
    ]


# --- options ----------------------------------------------------------------------------


def test_any_pair_of_frames():
    d = derive("puma560", frm=1, to=3)
    assert [b.label.text for b in d.links] == ["T1_2", "T2_3"]
    assert [s.block.label.text for s in d.products] == ["T1_3"]
    assert d.result.label.text == "T1_3" and not d.inverse


def test_inverse_pair_uses_the_rigid_inverse():
    r = dhsym.load("planar2r")
    d = derive(r, frm=2, to=0)
    assert d.inverse and d.result.label.text == "T2_0"
    assert d.result.prefix[0].latex == r"\left({}^{0}T_{2}\right)^{-1}"
    assert d.result.rows[0][3].text == r.notation.text(r.transform(2, 0)[0, 3])
    assert not any(s.final for s in d.products)


def test_bad_frames_are_refused():
    with pytest.raises(DHError, match="identity"):
        derive("planar2r", frm=1, to=1)
    with pytest.raises(DHError, match="frames of Planar 2R"):
        derive("planar2r", to=7)
    with pytest.raises(DHError, match="expected a robot name"):
        derive(42)  # type: ignore[arg-type]


def test_numeric_lengths_are_substituted():
    d = derive("puma560", numeric=True)
    assert d.numeric and d.table.values == ()
    assert d.result.entries[11].text_lines == ("0.4318*S2 + 0.4318*C23 + 0.0203*S23",)


def test_full_notation():
    d = derive("planar2r", compact=False)
    assert d.result.rows[0][0].text == "cos(theta1 + theta2)"
    assert d.legend == ()  # nothing abbreviated
    assert (
        d.products[0].identities[0].result.latex == r"\cos{\left(\theta_{1} + \theta_{2} \right)}"
    )


def test_legend_lists_every_abbreviation_shown():
    d = derive("puma560")
    legend = {e.abbrev.latex: e.meaning.latex for e in d.legend}
    assert legend["C_{23}"] == r"\cos{\left(\theta_{2} + \theta_{3} \right)}"
    assert set(legend) == {f"{c}_{{{k}}}" for c in "CS" for k in (1, 2, 3, 4, 5, 6, 23)}
    assert derive("planar8r").legend_columns < d.legend_columns == 3


def test_numeric_check_reproduces_the_toolbox_value_of_seed_001():
    d = derive("puma560", check=True)
    rows = [[c.text for c in row] for row in d.check.rows]
    assert rows == [
        ["1", "0", "0", "0.4521"],
        ["0", "1", "0", "-0.15"],
        ["0", "0", "1", "0.4318"],
        ["0", "0", "0", "1"],
    ]
    assert [x.text for _, x in derive("planar2r", check=[sp.pi / 2, 0]).check.q] == ["1.5708", "0"]
    with pytest.raises(DHError, match="needs 2 joint values"):
        derive("planar2r", check=[0.0])
    with pytest.raises(DHError, match="needs values for a1, a2, a3"):
        derive("planar3r", check=True)


def test_repr_methods_render_the_derivation():
    d = derive("planar2r")
    md = d._repr_markdown_()
    assert md.startswith("## Planar 2R") and "$$" in md
    assert r"C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12} \\" in md
    assert r"\begin{bmatrix}" in d._repr_latex_()
    assert str(d).splitlines()[0] == "Planar 2R: forward kinematics (standard DH convention)"


def test_derivation_is_frozen_plain_data():
    d = derive("planar2r")
    with pytest.raises(AttributeError):
        d.name = "x"  # type: ignore[misc]
    assert d.key == "planar-2r" and d.source.startswith("IRob2305 Introduction to Robotics")


def test_a_notebook_shows_the_derivation_as_markdown():
    formatters = pytest.importorskip("IPython.core.formatters")
    data, _ = formatters.DisplayFormatter().format(derive("planar2r"))
    assert {"text/markdown", "text/latex", "text/plain"} <= set(data)
    assert "### The result" in data["text/markdown"]
    assert r"C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12} \\" in data["text/markdown"]


# --- chains whose closed form would explode -----------------------------------------------


def _snake(n: int) -> dhsym.DHTable:
    """n revolute joints with alternating ±90° twists: no two axes parallel, no planar runs."""
    rows = [
        dhsym.DHRow.revolute(f"q{k}", d=f"d{k}", a=f"a{k}", alpha=(-1) ** k * sp.pi / 2)
        for k in range(1, n + 1)
    ]
    return dhsym.DHTable.from_rows(rows, name=f"snake {n}")


def test_spatial_chain_too_large_in_closed_form_is_refused_with_the_parts_that_fit():
    with pytest.raises(DHError, match=r"--from/--to") as info:
        derive(_snake(16))
    message = str(info.value)
    assert "^0T_16 of snake 16 is too large" in message and "^0T_10 ^10T_16" in message
    d = derive(_snake(16), frm=10, to=16)  # the part it suggests is derived
    assert d.result.rows[0][0].text


def test_a_derivation_shows_at_most_sixty_links():
    rows = [dhsym.DHRow.prismatic(f"d{k}") for k in range(1, 251)]
    with pytest.raises(DHError, match=r"spans 250 links; a derivation shows at most 60"):
        derive(dhsym.DHTable.from_rows(rows, name="long"))
