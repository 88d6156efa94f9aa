"""``dhsym derive --what`` (text, Markdown, LaTeX, JSON) and ``dhsym handout --sections``."""

from __future__ import annotations

import json

import pytest

import dhsym
from dhsym.cli.main import main
from dhsym.model.parsing import parse_expression


@pytest.mark.parametrize("what", ["jacobian", "singularities", "ik"])
@pytest.mark.parametrize("fmt", ["text", "markdown", "latex"])
def test_derive_what_in_every_format(what, fmt, capsys):
    assert main(["derive", "planar2r", "--what", what, "--format", fmt]) == 0
    out = capsys.readouterr().out
    key = {
        ("jacobian", "text"): "J2 = [z_1 x (o_2 - o_1); z_1] = [-a2*S12; a2*C12; 0; 0; 0; 1]",
        ("jacobian", "markdown"): r"-a_{1} S_{1} - a_{2} S_{12} & -a_{2} S_{12} \\",
        ("jacobian", "latex"): r"-a_{1} S_{1} - a_{2} S_{12} & -a_{2} S_{12} \\",
        ("singularities", "text"): "det J_v = a1*a2*S2",
        ("singularities", "markdown"): r"\det J_{v} &= a_{1} a_{2} S_{2}",
        ("singularities", "latex"): r"\det J_{v} &= a_{1} a_{2} S_{2}",
        ("ik", "text"): "theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)",
        ("ik", "markdown"): r"\theta_{1} &= \operatorname{atan2}\left(p_{y}, p_{x}\right)",
        ("ik", "latex"): r"\theta_{1} &= \operatorname{atan2}\left(p_{y}, p_{x}\right)",
    }[what, fmt]
    assert key in out


def test_jacobian_json(capsys):
    assert main(["derive", "puma560", "--what", "jacobian", "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert (d["schema"], d["what"], d["frame"], d["point"]) == (1, "jacobian", 0, 6)
    assert len(d["compact"]) == 6 and len(d["compact"][0]) == 6
    assert d["columns"][0]["axis"] == ["0", "0", "1"] and d["columns"][4]["lever"] == ["0"] * 3
    robot = dhsym.load("puma560")
    J = robot.jacobian().matrix
    ctx = {str(s): s for s in (*robot.variables, *robot.table.constants)}
    for i in range(6):
        for j in range(6):
            back = parse_expression(d["matrix"][i][j], resolve=ctx.get)
            assert (back - J[i, j]).equals(0)


def test_singularities_json(capsys):
    assert main(["derive", "puma560", "--what", "singularities", "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["measure"] == "det J"
    assert d["determinant"]["compact"] == "a2*S5*(a2*C2 + a3*C23 - d4*S23)*(a3*S3 + d4*C3)"
    wrist = [f for f in d["factors"] if f["kind"] == "wrist"][0]
    assert wrist["factor"]["full"] == "sin(theta5)"
    assert [z["value"]["compact"] for z in wrist["zeros"]] == ["0", "pi"]
    assert [b["name"] for b in d["blocks"]] == ["J11", "J22"]


def test_ik_json(capsys):
    assert main(["derive", "puma560", "--what", "ik", "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["count"] == 8 and [b["role"] for b in d["branches"]] == ["arm", "elbow", "wrist"]
    steps = {s["lhs"]: s for s in d["steps"]}
    assert steps["theta1"]["rhs"]["full"] == "atan2(c_y, c_x) - atan2(-d3, r)"
    assert steps["r"]["branch"] == "sigma_1"
    assert steps["theta4"]["singular"]["compact"] == "0"
    assert d["pose"][0] == ["n_x", "s_x", "a_x", "p_x"]
    for s in d["steps"]:  # every right-hand side reads back through the whitelist parser
        parse_expression(s["rhs"]["full"])


def test_from_and_to_belong_to_fk(capsys):
    assert main(["derive", "planar2r", "--what", "ik", "--to", "1"]) == 2
    assert "--from and --to choose ^iT_j" in capsys.readouterr().err


def test_no_closed_form_exits_2_with_the_reason(capsys):
    assert main(["derive", "planar4r", "--what", "ik"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no closed-form inverse kinematics" in err


def test_handout_sections(tmp_path, capsys):
    out = tmp_path / "hw.tex"
    argv = ["handout", "planar2r", "stanford", "-o", str(out), "--sections", "ik,jacobian"]
    assert main([*argv, "--check"]) == 0
    tex = out.read_text()
    assert r"\subsection{The Jacobian}" in tex and r"\subsection{Inverse kinematics}" in tex
    assert tex.index(r"\subsection{The Jacobian}") < tex.index(r"\subsection{Inverse kinematics}")
    assert r"\subsection{Forward kinematics}" not in tex
    assert "The standard DH table of this robot" in tex  # the table opens each robot
    assert (
        "right arm, first root of the $d_{3}$ equation, wrist not flipped" in tex
    )  # the check of the Stanford arm
    assert (
        main(["handout", "planar2r", "-o", str(out), "--sections", "fk,ik", "--mode", "problems"])
        == 0
    )
    tex = out.read_text()
    assert "Solve the inverse kinematics of this robot step by step" in tex


def test_handout_unknown_section_exits_2(tmp_path, capsys):
    argv = ["handout", "planar2r", "-o", str(tmp_path / "x.tex"), "--sections", "fk,velocity"]
    assert main(argv) == 2
    assert "unknown derivation 'velocity'" in capsys.readouterr().err


def test_derive_names_the_tool_transform_convert_moved(tmp_path, capsys):
    table = tmp_path / "rrr.yaml"
    table.write_text(
        "joints:\n"
        "  - {theta: theta1, d: 0, a: a1, alpha: 0}\n"
        "  - {theta: theta2, d: 0, a: a2, alpha: 0}\n"
        "  - {theta: theta3, d: 0, a: a3, alpha: 0}\n",
        encoding="utf-8",
    )
    modified = tmp_path / "rrr_modified.yaml"
    assert main(["convert", str(table), "--to", "modified", "-o", str(modified)]) == 0
    capsys.readouterr()
    assert main(["derive", str(modified)]) == 0
    out = capsys.readouterr().out
    assert "tool transform Tx(a3) after frame 3" in " ".join(out.split())
    assert "derive --to 4" in out


def test_handout_figure_says_which_pictures_it_wrote(tmp_path, capsys):
    out = tmp_path / "h.tex"
    assert main(["handout", "planar2r", "-o", str(out), "--figure"]) == 0
    said = capsys.readouterr().err  # "wrote …" lines go to standard error
    assert "h-planar-2r-home.pdf" in said and (tmp_path / "h-planar-2r-home.pdf").is_file()


SYMBOLIC_2R = """name: Symbolic 2R
joints:
  - {type: R, theta: theta1, d: 0, a: l1, alpha: 0, m: m1}
  - {type: R, theta: theta2, d: 0, a: l2, alpha: 0, m: m2}
"""


def test_handout_figure_of_a_symbolic_table_names_the_symbols_it_needs(tmp_path, capsys):
    table = tmp_path / "arm.yaml"
    table.write_text(SYMBOLIC_2R, encoding="utf-8")
    out = tmp_path / "h.tex"
    assert main(["handout", str(table), "-o", str(out), "--figure"]) == 2
    err = capsys.readouterr().err
    assert "has none for l1, l2: give them with --values l1=…,l2=…" in err
    assert "internal error" not in err and not out.exists()


def test_handout_values_give_the_figure_its_numbers_and_keep_the_derivation_symbolic(
    tmp_path, capsys
):
    table = tmp_path / "arm.yaml"
    table.write_text(SYMBOLIC_2R, encoding="utf-8")
    out = tmp_path / "h.tex"
    argv = ["handout", str(table), "-o", str(out), "--figure", "--values", "l1=1,l2=0.8,m1=2"]
    assert main(argv) == 0
    assert (tmp_path / "h-symbolic-2r-home.pdf").is_file()
    assert "l_{1} C_{1} + l_{2} C_{12}" in out.read_text()  # the lengths stay symbols
    capsys.readouterr()
    assert main(["handout", str(table), "-o", str(out), "--values", "l3=1"]) == 2
    assert "--values: no robot of this handout has a symbol l3" in capsys.readouterr().err


def test_handout_figure_uses_the_table_values_when_it_has_them(tmp_path, capsys):
    out = tmp_path / "h.tex"
    assert main(["handout", "spong2r", "-o", str(out), "--figure"]) == 0
    assert (tmp_path / "h-spong-two-link-arm-home.pdf").is_file()
