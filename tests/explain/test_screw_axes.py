"""``derive --what screws``: the screw axes step by step in text, Markdown, LaTeX and JSON."""

from __future__ import annotations

import json

import pytest

from dhsym.cli.main import main
from dhsym.explain.documents import render_derivation
from dhsym.explain.screw_axes import derive_screws


def test_the_steps_and_results_of_a_scara() -> None:
    d = derive_screws("scara")
    assert d.n == 4 and [s.revolute for s in d.steps] == [True, True, False, True]
    assert d.steps[2].point is None
    assert d.product_body.text.startswith("M e^([B1]*theta1)")


@pytest.mark.parametrize(
    ("fmt", "key"),
    [
        ("text", "v2 = -omega2 x q2 = [0; -a1; 0]"),
        ("markdown", r"\mathcal{B}_{i} = [\mathrm{Ad}_{M^{-1}}]\,\mathcal{S}_{i}"),
        ("latex", r"\subsection*{The screw axes at home}"),
    ],
)
def test_each_format_holds_its_key_line(fmt: str, key: str) -> None:
    out = render_derivation("planar2r", fmt, what="screws")
    assert key in out
    assert "Lynch and Park" in out
    assert "$i-1$" in out or fmt == "text"


def test_cli_derive_screws_json(capsys) -> None:
    assert main(["derive", "planar2r", "--what", "screws", "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["what"] == "screws"
    assert d["space"]["compact"] == [["0", "0"], ["0", "0"], ["1", "1"], ["0", "0"],
                                     ["0", "-a1"], ["0", "0"]]  # fmt: skip
    assert d["body"]["latex"][4] == ["a_{1} + a_{2}", "a_{2}"]
    assert d["formula"]["space"] == "T(theta) = e^([S1]*theta1) e^([S2]*theta2) M"


def test_cli_derive_screws_text(capsys) -> None:
    assert main(["derive", "stanford", "--what", "screws"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("Stanford")
    assert "Joint 3 (prismatic, d3), z of frame 2:" in out


@pytest.mark.tex
@pytest.mark.slow
def test_handout_screws_section_compiles_without_overfull_boxes(tmp_path, need_tex) -> None:
    from importlib import resources

    from dhsym.explain.documents import write_handout
    from dhsym.explain.latex import run_latex
    from dhsym.robot import from_poe

    with resources.as_file(resources.files("dhsym.screws") / "robots") as folder:
        ur5 = from_poe(folder / "lynch_park_ur5.poe.yaml")
    tex = write_handout(["puma560", ur5, "stanford"], tmp_path / "s.tex", sections="fk,screws")
    source = tex.read_text()
    assert r"\subsection{Screw axes and the product of exponentials}" in source
    run = run_latex(tex)
    assert run.pdf.exists()
    assert list(run.issues) == [], [str(i) for i in run.issues]
