"""The equations-of-motion derivation: the dynamics room's results, printed in each format."""

from __future__ import annotations

import json

import pytest

import dhsym
from dhsym.cli.main import main
from dhsym.explain.documents import document, render_derivation
from dhsym.explain.equations_of_motion import derive_dynamics
from dhsym.model.tablefile import read_table_text
from dhsym.robot import Robot

# Spong, Hutchinson and Vidyasagar, Robot Modeling and Control, §7.3: the two-link planar
# elbow arm, hanging in the x-y plane (frame i at the far end of link i, standard DH).
SPONG = """
name: Two-link planar elbow arm
convention: standard
gravity: [0, -g, 0]
joints:
  - {type: R, theta: q1, d: 0, a: l1, alpha: 0, m: m1, r: [lc1 - l1, 0, 0], I: [Ix1, Iy1, I1]}
  - {type: R, theta: q2, d: 0, a: l2, alpha: 0, m: m2, r: [lc2 - l2, 0, 0], I: [Ix2, Iy2, I2]}
"""


@pytest.fixture(scope="module")
def planar2r():
    return derive_dynamics("planar2r")


@pytest.fixture(scope="module")
def spong():
    return derive_dynamics(Robot(read_table_text(SPONG)))


def test_entries_are_the_cores_results_in_lecture_notation(planar2r):
    robot = dhsym.load("planar2r")
    eom = robot.dynamics()
    nota = robot.notation
    assert [e.name.text for e in planar2r.inertia] == ["M11", "M12", "M22"]
    for e, (i, j) in zip(planar2r.inertia, [(0, 0), (0, 1), (1, 1)], strict=True):
        whole = nota.text(eom.M[i, j])
        assert "".join(line.strip() + " " for line in e.text_lines).split() == whole.split()
    assert [e.text_lines[0] for e in planar2r.gravity_vector] == ["0", "0"]
    nonzero = [
        (i, j, k)
        for i in range(2)
        for j in range(i, 2)
        for k in range(2)
        if eom.christoffel[i][j][k] != 0
    ]
    assert [e.name.text for e in planar2r.christoffel] == [
        f"c{i + 1}{j + 1}{k + 1}" for i, j, k in nonzero
    ]
    assert len(planar2r.energies) == 2 and planar2r.energies[1].potential.text_lines == (
        "9.81*m2*rz2",
    )


def test_newton_euler_table_has_both_passes(planar2r):
    assert [(s.name, s.link) for s in planar2r.outward][:6] == [
        (n, 1) for n in ("omega", "omegadot", "a", "ac", "F", "N")
    ]
    assert [(s.name, s.link) for s in planar2r.inward] == [
        ("f", 2),
        ("n", 2),
        ("tau", 2),
        ("f", 1),
        ("n", 1),
        ("tau", 1),
    ]
    omega2 = next(s for s in planar2r.outward if (s.name, s.link) == ("omega", 2))
    assert [r[0].text for r in omega2.value.rows] == ["0", "0", "thetadot1 + thetadot2"]
    # the inward pass ends in the Lagrange torques
    robot = dhsym.load("planar2r")
    tau1 = next(s for s in planar2r.inward if (s.name, s.link) == ("tau", 1))
    assert tau1.value.rows[0][0].text == robot.notation.text(robot.dynamics().tau[0])


def test_planar2r_key_lines_in_every_format(planar2r):
    text = planar2r.to_text()
    assert "     M11 = Izz1 + m1*(a1**2 + rx1**2 + ry1**2 + 2*a1*rx1) + Izz2" in text
    assert "     M22 = Izz2 + m2*(a2**2 + rx2**2 + ry2**2 + 2*a2*rx2)" in text
    assert "     g1 = 0\n     g2 = 0" in text
    assert "     c112 = m2*(a1*ry2*C2 + a1*a2*S2 + a1*rx2*S2)" in text
    assert "   omega_1 = [0; 0; thetadot1]" in text
    assert "Inward pass, i = 2 .. 1 (f_3 = n_3 = 0):" in text
    md = planar2r.to_markdown()
    assert r"M_{22} &= Izz_{2} + m_{2}(a_{2}^{2} + rx_{2}^{2} + ry_{2}^{2} + 2 a_{2} rx_{2})" in md
    assert (
        r"M_{11} &= Izz_{1} + m_{1}(a_{1}^{2} + rx_{1}^{2} + ry_{1}^{2} + 2 a_{1} rx_{1}) + Izz_{2}"
        in md
    )
    assert "g_{1} &= 0" in md and "### Newton–Euler, the same torques recursively" in md
    tex = planar2r.to_latex()
    assert r"M_{22} &= Izz_{2} + m_{2}(a_{2}^{2} + rx_{2}^{2} + ry_{2}^{2} + 2 a_{2} rx_{2})" in tex
    assert r"\subsection*{The Christoffel symbols}" in tex and "g_{2} &= 0" in tex
    assert r"\omega_{1} = \begin{bmatrix}" in tex.replace("\n", " ").replace("  ", " ")
    assert tex.isascii()
    for out in (text, md, tex):
        assert "Spong, Hutchinson and Vidyasagar" in out and "Craig" in out


def test_spong_arm_reproduces_his_d_and_g_in_every_format(spong):
    text = spong.to_text()
    assert "     M11 = I1 + lc1**2*m1 + I2 + m2*(l1**2 + 2*l1*lc2*C2 + lc2**2)" in text
    assert "     M12 = I2 + m2*(l1*lc2*C2 + lc2**2)" in text
    assert "     g1 = g*lc1*m1*C1 + m2*(g*l1*C1 + g*lc2*C12)" in text
    assert "     g2 = g*lc2*m2*C12" in text
    assert "     c112 = l1*lc2*m2*S2" in text
    md, tex = spong.to_markdown(), spong.to_latex()
    for out in (md, tex):
        assert r"g_{2} &= g l_{c2} m_{2} C_{12}" in out
        assert r"M_{12} &= I_{2} + m_{2}(l_{1} l_{c2} C_{2} + l_{c2}^{2})" in out
        assert "lc_{" not in out  # Spong's l_{c2}, never lc_2 (l times c_2 beside c_1)
    assert "with gravity g = (0, -g, 0) in the base frame" in " ".join(text.split())


def test_a_modified_dh_arm_is_printed_in_its_frames():
    rows = SPONG.replace("convention: standard", "convention: modified")
    rows = rows.replace(
        "a: l1, alpha: 0, m: m1, r: [lc1 - l1, 0, 0]", "a: 0, alpha: 0, m: m1, r: [lc1, 0, 0]"
    )
    rows = rows.replace(
        "a: l2, alpha: 0, m: m2, r: [lc2 - l2, 0, 0]", "a: l1, alpha: 0, m: m2, r: [lc2, 0, 0]"
    )
    d = derive_dynamics(Robot(read_table_text(rows)))
    assert d.modified
    assert "M11 = I1 + lc1**2*m1 + I2 + m2*(l1**2 + 2*l1*lc2*C2 + lc2**2)" in d.to_text()


def test_document_and_render_know_dynamics():
    assert document("planar2r", "dynamics").kind == "dynamics"
    out = render_derivation("planar2r", fmt="text", what="dynamics")
    assert out.splitlines()[0] == "Planar 2R: the equations of motion (standard DH convention)"
    with pytest.raises(dhsym.DHError, match="do not apply to --what dynamics"):
        document("planar2r", "dynamics", check=True)


@pytest.mark.parametrize("fmt", ["text", "markdown", "latex"])
def test_cli_derive_dynamics(fmt, capsys):
    assert main(["derive", "planar2r", "--what", "dynamics", "--format", fmt]) == 0
    out = capsys.readouterr().out
    key = {
        "text": "M22 = Izz2 + m2*(a2**2 + rx2**2 + ry2**2 + 2*a2*rx2)",
        "markdown": r"M_{22} &= Izz_{2} + m_{2}(a_{2}^{2}",
        "latex": r"M_{22} &= Izz_{2} + m_{2}(a_{2}^{2}",
    }[fmt]
    assert key in out


def test_cli_derive_dynamics_json(capsys):
    assert main(["derive", "planar2r", "--what", "dynamics", "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert (d["schema"], d["what"], d["robot"]) == (1, "dynamics", "Planar 2R")
    assert d["M"][0][1] == d["M"][1][0]
    assert d["M"][1][1]["compact"] == "Izz2 + m2*(a2**2 + rx2**2 + ry2**2 + 2*a2*rx2)"
    assert [x["compact"] for x in d["g"]] == ["0", "0"]
    assert [x["compact"] for x in d["gravity"]] == ["0", "0", "-9.81"]
    assert [(c["i"], c["j"], c["k"]) for c in d["christoffel"]] == [(1, 1, 2), (1, 2, 1), (2, 2, 1)]
    sweeps = [s["sweep"] for s in d["newton_euler"]]
    assert sweeps.count("outward") == 12 and sweeps.count("inward") == 6
    # the "full" formula reads back through the whitelist parser to the core's M11
    from dhsym.model.parsing import parse_expression

    m11 = dhsym.load("planar2r").dynamics().M[0, 0]
    back = parse_expression(d["M"][0][0]["full"])
    values = {s.name: 0.3 + 0.1 * k for k, s in enumerate(sorted(m11.free_symbols, key=str))}
    num = {s: values[s.name] for s in m11.free_symbols}
    assert {s.name for s in back.free_symbols} == set(values)
    assert float(back.subs({s: values[s.name] for s in back.free_symbols})) == pytest.approx(
        float(m11.subs(num))
    )


@pytest.mark.tex
@pytest.mark.slow
@pytest.mark.parametrize("mode", ["answers", "problems"])
def test_handout_dynamics_section_compiles_without_overfull_boxes(tmp_path, need_tex, mode):
    import subprocess

    from dhsym.explain.documents import write_handout
    from dhsym.explain.latex import run_latex

    robots = ["planar2r", Robot(read_table_text(SPONG))]
    tex = write_handout(robots, tmp_path / "dyn.tex", sections="fk,dynamics", mode=mode)
    source = tex.read_text()
    assert r"\subsection{Equations of motion}" in source
    run = run_latex(tex)
    assert run.pdf.exists()
    assert list(run.issues) == [], [str(i) for i in run.issues]
    text = subprocess.run(
        ["pdftotext", str(run.pdf), "-"], capture_output=True, text=True, check=True
    ).stdout
    if mode == "answers":
        assert "The Christoffel symbols" in text and "Inward pass" in text
        assert r"g_{2} &= g l_{c2} m_{2} C_{12}" in source
    else:
        assert "Christoffel symbols" in text and "Newton" in text


def test_cli_handout_accepts_the_dynamics_section(tmp_path, capsys):
    out = tmp_path / "h.tex"
    assert main(["handout", "planar2r", "--sections", "fk,dynamics", "-o", str(out)]) == 0
    source = out.read_text()
    assert r"\subsection{Equations of motion}" in source
    assert "Robot Modeling and" in source and "Newton--Euler" in source


def test_spong2r_prints_its_links_and_C_and_never_lc_beside_c1(capsys):
    d = derive_dynamics("spong2r")
    assert [L.mass.text_lines[0] for L in d.links] == ["m1", "m2"]
    C = dhsym.load("spong2r").dynamics().C
    assert d.coriolis is not None and len(d.coriolis.rows) == 2
    nota = dhsym.load("spong2r").notation
    assert [[x.text for x in row] for row in d.coriolis.rows] == [
        [nota.text(C[r, c]) for c in range(2)] for r in range(2)
    ]
    text = d.to_text()
    for line in (
        "1. The links: masses, centres of mass and inertias",
        "   Link 1: m_1 = m1",
        "   r_c1 = [lc1 - l1; 0; 0]",
        "   I_2 = [ 0   0   0 ]",
        "   C(q, qdot) = [ -l1*lc2*m2*thetadot2*S2  "
        "-m2*(l1*thetadot1*lc2*S2 + l1*lc2*thetadot2*S2) ]",
        "                [  l1*thetadot1*lc2*m2*S2  " + " " * 46 + "0 ]",
        "     g1 = g*lc1*m1*C1 + m2*(g*l1*C1 + g*lc2*C12)",
    ):
        assert line in text.splitlines(), line
    assert text.index("c221 = ") < text.index("C(q, qdot) = ") < text.index("g1 = ")
    assert (
        main(["derive", "spong2r", "--what", "dynamics", "--format", "latex", "--notation", "c1"])
        == 0
    )
    tex = capsys.readouterr().out
    assert r"g_{1} &= g l_{c1} m_{1} c_{1} + m_{2}(g l_{1} c_{1} + g l_{c2} c_{12})" in tex
    assert "lc_{" not in tex and r"\ell" not in tex
    flat = " ".join(tex.split())
    assert (
        r"\text{Link 1:} \quad m_{1} = m_{1}, \qquad "
        r"r_{c1} = \begin{bmatrix} l_{c1} - l_{1} \\ 0 \\ 0 \end{bmatrix}" in flat
    )
    assert r"C(q, \dot{q}) = \begin{bmatrix} -l_{1} l_{c2} m_{2} \dot{\theta}_{2} s_{2} &" in flat
    assert r"\subsection*{The links: masses, centres of mass and inertias}" in tex
    md = d.to_markdown()
    assert "### The links: masses, centres of mass and inertias" in md and r"C(q, \dot{q})" in md


@pytest.fixture(scope="module")
def puma_dynamics():
    return derive_dynamics("puma560")


@pytest.mark.slow
def test_puma_derivation_prints_grouped_constants_and_their_numbers(puma_dynamics):
    d = puma_dynamics
    names = [e.name.text for e in d.constants]
    assert names[:2] == ["I1", "I2"] and any(n.startswith("gamma") for n in names)
    assert "Jm1" in d.constants[0].text_lines[0]
    values = {e.name.text: e.text_lines[0] for e in d.parameter_values}
    assert values["m2"] == "17.4"
    m11 = d.inertia[0].text_lines
    assert "I1" in m11[0] and not any("m2" in line for line in m11)  # m2 inside constants
    assert {s.name for s in d.outward} == {"omega", "omegadot"}
    text = render_derivation(dhsym.load("puma560"), fmt="text", what="dynamics")
    assert "Armstrong, Khatib and Burdick" in text and "I1 = " in text


@pytest.mark.tex
@pytest.mark.slow
def test_puma_dynamics_handout_compiles_without_overfull_boxes(tmp_path, need_tex):
    from dhsym.explain.documents import write_handout
    from dhsym.explain.latex import run_latex

    tex = write_handout(["puma560"], tmp_path / "puma.tex", sections="dynamics", mode="answers")
    source = tex.read_text()
    assert r"I_{1} &=" in source and "Armstrong, Khatib and Burdick" in source
    run = run_latex(tex)
    assert run.pdf.exists()
    assert list(run.issues) == [], [str(i) for i in run.issues]
