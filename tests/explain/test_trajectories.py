"""The trajectory document: the profiles of a joint derived, in text, Markdown, LaTeX and
JSON (``dhsym derive NAME --what trajectory``), and the handout's trajectory section."""

from __future__ import annotations

import json

import pytest
import sympy as sp

from dhsym.cli import main
from dhsym.explain.documents import render_derivation
from dhsym.explain.trajectories import derive_trajectory


def test_sections_and_the_lecture_coefficients() -> None:
    d = derive_trajectory("planar2r")
    assert [s.key for s in d.sections] == ["cubic", "quintic", "lspb"]
    cubic, quintic, lspb = d.sections
    assert cubic.solution[2].text == "a2 = 3*(-q_0 + q_f)/t_f**2"
    assert quintic.solution[3].latex == r"a_{3} = \frac{10 \left(- q_{0} + q_{f}\right)}{t_{f}^{3}}"
    assert quintic.system is not None and lspb.system is None
    assert [a.text for a in lspb.assumptions][0] == "q_f > q_0"
    assert lspb.position.text.startswith("q(t) = Piecewise((a*t**2/2 + q_0, t <= t_b)")


@pytest.mark.parametrize("fmt", ["text", "markdown", "latex"])
def test_render_in_every_format(fmt: str) -> None:
    out = render_derivation("puma560", fmt=fmt, what="trajectory")
    assert "Quintic polynomial" in out and "Linear segment with parabolic blends" in out
    assert "Spong, Hutchinson and Vidyasagar, Robot Modeling and Control" in out
    if fmt == "latex":
        assert r"\subsection*{Cubic polynomial}" in out
        assert r"\frac{10 \left(- q_{0} + q_{f}\right)}{t_{f}^{3}}" in out


def test_cli_derive_trajectory_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["derive", "planar2r", "--what", "trajectory", "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["what"] == "trajectory" and d["robot"] == "Planar 2R"
    quintic = d["profiles"][1]
    assert quintic["key"] == "quintic"
    assert quintic["solution"][5]["text"] == "a5 = 6*(-q_0 + q_f)/t_f**5"
    assert d["profiles"][2]["system"] is None


def test_lspb_pieces_are_the_profile() -> None:
    """The printed pieces in t_b and a equal the profile's segments (checked when built;
    here at numbers, independently)."""
    from dhsym.trajectory import lspb

    text = derive_trajectory("planar2r").sections[2].position.text
    assert "(V*(t - t_b) + a*t_b**2/2 + q_0, t <= -t_b + t_f)" in text
    q0, qf, tf, V, t = sp.symbols("q_0 q_f t_f V", positive=True) + (
        sp.Symbol("t", nonnegative=True),
    )
    tb, a = sp.symbols("t_b a", real=True)
    num = {q0: 1, qf: 3, tf: 2, V: sp.Rational(9, 5)}
    p = lspb(1, 3, 2, v=sp.Rational(9, 5))
    tbv, av = p.derivation().solution
    for time in (sp.Rational(1, 5), 1, sp.Rational(19, 10)):
        want = p.at(time)[0]
        pieces = [
            (q0 + a * t**2 / 2, time <= tbv),
            (q0 + a * tb**2 / 2 + V * (t - tb), time <= tf.subs(num) - tbv),
            (qf - a * (tf - t) ** 2 / 2, True),
        ]
        got = next(e for e, c in pieces if c).subs({**num, tb: tbv, a: av, t: time})
        assert got == want


def test_control_document_in_every_format(capsys: pytest.CaptureFixture[str]) -> None:
    from dhsym.explain.trajectories import derive_control

    d = derive_control("puma560")
    assert [m.text for _, m in d.steps][-1] == "K_d*edot + K_p*e + eddot = 0"
    assert [g.latex for g in d.gains] == [r"K_{p} = \omega^{2}", r"K_{d} = 2 \omega \zeta"]
    out = render_derivation("puma560", fmt="latex", what="control")
    assert r"M \left(K_{d} \dot{e} + K_{p} e + \ddot{e}\right) = 0" in out
    assert main(["derive", "planar2r", "--what", "control", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["gains"][1]["text"] == "K_d = 2*omega*zeta"


@pytest.mark.tex
@pytest.mark.slow
@pytest.mark.parametrize(
    ("robot", "sections", "heading"),
    [
        ("puma560", "fk,trajectory", "Trajectories"),
        ("planar2r", "fk,trajectory,control", "Control"),
    ],
)
def test_handout_section_compiles_without_overfull_boxes(  # type: ignore[no-untyped-def]
    tmp_path, need_tex, robot: str, sections: str, heading: str
) -> None:
    from dhsym.explain.documents import write_handout
    from dhsym.explain.latex import run_latex

    tex = write_handout([robot], tmp_path / "section.tex", sections=sections)
    assert rf"\subsection{{{heading}}}" in tex.read_text()
    run = run_latex(tex)
    assert run.pdf.exists()
    assert list(run.issues) == [], [str(i) for i in run.issues]
