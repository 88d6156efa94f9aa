"""Templates: golden key lines of the 2R and PUMA 560 output, escaping, overrides and the CLI."""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest

import dhsym
from dhsym.cli.main import main
from dhsym.errors import DHError
from dhsym.explain.documents import (
    render_derivation,
    render_handout,
    write_handout,
)
from dhsym.notation.escape import escape_markdown
from dhsym.notation.templates import builtin_dir

ROW_2R = r"C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12} \\"
PX_PUMA = r"p_{x} &= C_{1}(a_{2} C_{2} + a_{3} C_{23} - d_{4} S_{23}) + d_{3} S_{1}"
PX_CRAIG = r"p_{x} &= C_{1}(a_{2} C_{2} + a_{3} C_{23} - d_{4} S_{23}) - d_{3} S_{1}"


def _render(name: str, fmt: str, **options: object) -> str:
    return render_derivation(dhsym.load(name), fmt=fmt, **options)


def _lines(text: str) -> list[str]:
    return [line.strip() for line in text.splitlines()]


# --- golden key lines ---------------------------------------------------------------------


@pytest.mark.parametrize("fmt", ["markdown", "latex"])
def test_golden_planar_2r(fmt):
    lines = _lines(_render("planar2r", fmt))
    assert ROW_2R in lines
    assert r"S_{12} & C_{12} & 0 & a_{1} S_{1} + a_{2} S_{12} \\" in lines
    assert r"C_{1} & -S_{1} & 0 & a_{1} C_{1} \\" in lines  # ^0T_1 of seed 001
    assert r"$C_{1} C_{2} - S_{1} S_{2} = C_{12}$, $S_{1} C_{2} + C_{1} S_{2} = S_{12}$." in lines
    assert (
        r"i & \theta_i & d_i & a_i & \alpha_i & \text{joint} \\ \hline" in lines
        or fmt == "markdown"
    )


@pytest.mark.parametrize("fmt", ["markdown", "latex"])
def test_golden_puma_560(fmt):
    text = _render("puma560", fmt)
    lines = _lines(text)
    assert PX_PUMA in lines
    assert r"p_{z} &= a_{2} S_{2} + a_{3} S_{23} + d_{4} C_{23}" in lines
    assert r"r_{33} &= C_{23} C_{5} - S_{23} C_{4} S_{5}" in lines
    assert r"$C_{2} C_{3} - S_{2} S_{3} = C_{23}$, $S_{2} C_{3} + C_{2} S_{3} = S_{23}$." in lines
    if fmt == "latex":
        assert (
            r"$C_{23}$ & $\cos{\left(\theta_{2} + \theta_{3} \right)}$ & "
            r"$S_{23}$ & $\sin{\left(\theta_{2} + \theta_{3} \right)}$ \\" in lines
        )
        assert r"\boxed{\theta_{1}}" in text
    else:
        assert r"$C_{23} = \cos{\left(\theta_{2} + \theta_{3} \right)}$" in text
        assert r"| 1 | $\boldsymbol{\theta_{1}}$ | $0$ | $0$ | $\frac{\pi}{2}$ | R |" in lines


@pytest.mark.parametrize("fmt", ["markdown", "latex"])
def test_golden_puma_560_modified(fmt):
    text = _render("puma560_modified", fmt)
    lines = _lines(text)
    assert PX_CRAIG in lines  # Craig (3.14): p_x = c1[a2 c2 + a3 c23 - d4 s23] - d3 s1
    assert (
        r"S_{i} c_{\alpha_{i-1}} & C_{i} c_{\alpha_{i-1}} & -s_{\alpha_{i-1}} & "
        r"-d_{i} s_{\alpha_{i-1}} \\" in lines
    )
    assert "one slide of Mohan's" in text and "Lecture 9" in text
    if fmt == "latex":
        assert r"i & \alpha_{i-1} & a_{i-1} & d_i & \theta_i & \text{joint} \\ \hline" in lines
    else:
        assert r"| $i$ | $\alpha_{i-1}$ | $a_{i-1}$ | $d_i$ | $\theta_i$ | joint |" in lines


def test_golden_text():
    text = _render("puma560", "text")
    lines = _lines(text)
    assert lines[0] == "PUMA 560: forward kinematics (standard DH convention)"
    assert "p_x = C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1" in lines
    assert "C2*C3 - S2*S3 = C23" in lines
    assert "= [ C1  0   S1  0 ]" in lines  # ^0T_1, aligned under its label
    assert "1 | [theta1] | 0   | 0   | pi/2    | R" in lines
    assert re.search(r"C23 = cos\(theta2 \+ theta3\)", text)
    two = _lines(_render("planar2r", "text"))
    assert "T0_2 = [ C12  -S12  0  a1*C1 + a2*C12 ]" in two


@pytest.mark.parametrize("name", [*dhsym.builtin_names(), "planar8r"])
@pytest.mark.parametrize("full", [False, True])
def test_text_fits_a_terminal(name, full):
    out = render_derivation(dhsym.load(name, compact=not full), fmt="text")
    assert max(len(line) for line in out.splitlines()) <= 100
    assert "\x1b" not in out and "\t" not in out


# --- Markdown that renders in JupyterLab and GitHub ------------------------------------------


@pytest.mark.parametrize("name", ["planar2r", "puma560", "puma560_modified", "stanford"])
def test_markdown_math_is_well_formed(name):
    md = _render(name, "markdown", check=name != "stanford")
    lines = md.splitlines()
    opens = [k for k, line in enumerate(lines) if line == "$$"]
    assert opens and len(opens) % 2 == 0
    assert md.count("$$") == len(opens)  # display delimiters sit on lines of their own
    for start, end in zip(opens[::2], opens[1::2], strict=True):
        assert all(lines[k].strip() for k in range(start + 1, end)), "blank line inside $$"
        assert start == 0 or not lines[start - 1].strip()
        assert end + 1 == len(lines) or not lines[end + 1].strip()
    for line in lines:
        if line == "$$" or line.startswith("|"):
            continue
        spans = re.findall(r"\$([^$]+)\$", line)
        assert line.count("$") % 2 == 0, line
        for span in spans:
            assert span == span.strip(), f"inline math must not start/end with a space: {span!r}"


def _mathjax_html(md: str, tmp_path: Path) -> Path:
    from nbconvert.filters.markdown_mistune import markdown2html_mistune

    page = tmp_path / "page.html"
    page.write_text(
        "<!DOCTYPE html><html><head><meta charset='utf-8'>"
        "<script type='text/x-mathjax-config'>MathJax.Hub.Config({tex2jax: {inlineMath: "
        "[['$','$']], displayMath: [['$$','$$']]}, TeX: {noErrors: {disabled: true}, "
        "noUndefined: {disabled: true}}, messageStyle: 'none'}); MathJax.Hub.Queue(function() "
        "{document.body.setAttribute('data-done', 'yes');});</script>"
        "<script src='file:///usr/share/javascript/mathjax/MathJax.js?config=TeX-AMS_HTML'>"
        "</script></head><body>" + markdown2html_mistune(md) + "</body></html>",
        encoding="utf-8",
    )
    return page


@pytest.mark.browser
def test_markdown_renders_with_mathjax_without_errors(tmp_path, need_chromium):
    """The Markdown as Jupyter shows it: mistune keeps the math, MathJax typesets it."""
    if not Path("/usr/share/javascript/mathjax/MathJax.js").exists():
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail("libjs-mathjax is required in CI: apt-get install libjs-mathjax")
        pytest.skip("libjs-mathjax is not installed (apt-get install libjs-mathjax)")
    md = (
        _render("planar2r", "markdown", check=True) + "\n" + _render("puma560_modified", "markdown")
    )
    control = "\n\nA control with an error: $\\undefinedmacro x$\n"  # proves errors are seen
    page = _mathjax_html(md + control, tmp_path)
    dom = subprocess.run(
        [
            "chromium",
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--virtual-time-budget=30000",
            "--dump-dom",
            page.as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    ).stdout
    assert 'data-done="yes"' in dom
    assert dom.count('class="MathJax_Display"') == md.count("$$") // 2
    assert dom.count("&lt;merror") == 1 and "undefinedmacro" in dom  # only the control


# --- escaping -----------------------------------------------------------------------------


def _hostile_robot(name: str) -> dhsym.Robot:
    rows = [dhsym.DHRow.revolute("theta1", a="a1")]
    return dhsym.Robot(dhsym.DHTable.from_rows(rows, name=name, source=name))


@pytest.mark.parametrize(
    "name", [r"\input{/etc/passwd}", r"\write18{rm -rf /}", r"}\end{document}", "50% $x$ #&_~^"]
)
def test_user_strings_are_escaped_in_latex(name):
    tex = render_handout([_hostile_robot(name)], title=name, course=name, author=name, date=name)
    for live in (r"\input{", r"\write18{", r"}\end{document}", "50% ", "#&"):
        assert live not in tex
    assert tex.count(r"\end{document}") == 1 and tex.rstrip().endswith(r"\end{document}")


def test_user_strings_are_escaped_in_markdown_and_cleaned_in_text():
    robot = _hostile_robot("*bold* <script>alert(1)</script> $x$ [a](b)\x1b[31m")
    md = render_derivation(robot, fmt="markdown")
    assert md.splitlines()[0] == (
        r"## \*bold\* &lt;script&gt;alert(1)&lt;/script&gt; \$x\$ \[a\](b)\[31m: "
        "forward kinematics (standard DH convention)"
    )
    text = render_derivation(robot, fmt="text")
    assert "\x1b" not in text and text.startswith("*bold* <script>")
    assert escape_markdown("a|b") == r"a\|b"


# --- templates ------------------------------------------------------------------------------


def test_a_user_template_folder_overrides_blocks(tmp_path):
    (tmp_path / "derivation.tex.j2").write_text(
        '((* extends "base/derivation.tex.j2" *))\n'
        "((* block legend *))MY OWN LEGEND((* endblock *))\n"
    )
    (tmp_path / "derivation.md.j2").write_text(
        '{% extends "base/derivation.md.j2" %}{% block heading %}# Custom {{ d.name }}\n'
        "{% endblock %}"
    )
    tex = render_derivation(dhsym.load("planar2r"), fmt="latex", template_dir=tmp_path)
    assert "MY OWN LEGEND" in tex and "Abbreviations" not in tex and ROW_2R in tex
    handout = render_handout(["planar2r"], template_dir=tmp_path)
    assert "MY OWN LEGEND" in handout
    md = render_derivation(dhsym.load("planar2r"), fmt="markdown", template_dir=tmp_path)
    assert md.startswith("# Custom Planar 2R")


def test_template_mistakes_are_reported_as_dherror(tmp_path):
    (tmp_path / "derivation.txt.j2").write_text("{{ d.no_such_field }}")
    with pytest.raises(DHError, match="no_such_field"):
        render_derivation(dhsym.load("planar2r"), fmt="text", template_dir=tmp_path)
    with pytest.raises(DHError, match="does not exist"):
        render_derivation(dhsym.load("planar2r"), template_dir=tmp_path / "missing")
    with pytest.raises(DHError, match="unknown format"):
        render_derivation(dhsym.load("planar2r"), fmt="html")


def test_built_in_templates_exist():
    names = {p.name for p in builtin_dir().iterdir()}
    assert {
        "handout.tex.j2",
        "fragment.tex.j2",
        "derivation.tex.j2",
        "derivation.md.j2",
        "derivation.txt.j2",
        "macros.tex.j2",
        "problems.tex.j2",
    } <= names


# --- handouts ---------------------------------------------------------------------------------


def test_handout_answers_mode_with_several_robots():
    tex = render_handout(
        ["planar2r", "puma560_modified"],
        title="Lecture 5",
        course="ME 101",
        author="A. Teacher",
        date="May 2024",
    )
    assert tex.startswith(r"\documentclass") and tex.count(r"\section{") == 2
    assert r"\section{PUMA 560 (modified DH, Craig)}" in tex
    assert "Lecture 5" in tex and "ME 101" in tex and "A. Teacher" in tex and "May 2024" in tex
    assert tex.count(r"\clearpage") == 1 and ROW_2R in tex and PX_CRAIG in tex


def test_handout_problems_mode_asks_questions_without_answers():
    tex = render_handout(["puma560"], mode="problems", check=True)
    assert r"\item Derive ${}^{0}T_{2} = {}^{0}T_{1}\,{}^{1}T_{2}$" in tex
    assert r"\item Evaluate ${}^{0}T_{6}$ at" in tex and r"\vspace{14cm}" in tex
    assert r"\boxed{\theta_{1}}" in tex  # the table is given
    assert "p_{x} &=" not in tex and "Abbreviations" not in tex  # the answers are not


def test_convention_note_shows_both_general_matrices():
    tex = render_handout(["planar2r"], convention_note=True)
    assert r"\section*{The two DH conventions}" in tex
    assert (
        r"-d_{i} s_{\alpha_{i-1}} \\" in tex and r"s_{\alpha_{i}} & c_{\alpha_{i}} & d_{i}" in tex
    )


def test_handout_option_errors():
    with pytest.raises(DHError, match="unknown mode"):
        render_handout(["planar2r"], mode="exam")
    with pytest.raises(DHError, match="unknown handout option"):
        render_handout(["planar2r"], colour="red")
    with pytest.raises(DHError, match=r"must end in \.tex"):
        write_handout(["planar2r"], "out.pdf")


def test_figure_names_are_checked(tmp_path):
    with pytest.raises(DHError, match="figure file names"):
        render_handout(["planar2r"], figures={"planar-2r": "../x}.pdf"})
    tex = render_handout(["planar2r"], figures={"planar-2r": "hw-planar-2r-home.pdf"})
    assert r"\includegraphics[width=0.5\textwidth]{hw-planar-2r-home.pdf}" in tex


def test_fragment_is_for_inclusion():
    tex = _render("planar2r", "latex")
    assert r"\documentclass" not in tex and r"\begin{document}" not in tex
    assert tex.startswith("%% dhsym derivation of Planar 2R; needs \\usepackage{amsmath}")
    assert r"\subsection*{The result}" in tex


# --- command line ---------------------------------------------------------------------------


def test_cli_derive_formats(capsys):
    assert main(["derive", "planar2r", "--format", "markdown"]) == 0
    assert ROW_2R in capsys.readouterr().out
    assert main(["derive", "puma560", "--format", "text"]) == 0
    assert "p_x = C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1" in capsys.readouterr().out
    assert main(["derive", "planar2r", "--format", "latex", "--full"]) == 0
    assert r"\cos{\left(\theta_{1} + \theta_{2} \right)}" in capsys.readouterr().out


def test_cli_notation_option_for_derive_and_handout(tmp_path, capsys):
    assert main(["derive", "puma560_modified", "--notation", "c1", "--format", "text"]) == 0
    assert "p_x = c1*(a2*c2 + a3*c23 - d4*s23) - d3*s1" in capsys.readouterr().out
    assert main(["derive", "planar2r", "--notation", "c_theta", "--format", "markdown"]) == 0
    assert r"a_{1} c_{\theta_{1}} + a_{2} c_{\theta_{12}}" in capsys.readouterr().out
    out = tmp_path / "craig.tex"
    assert main(["handout", "puma560_modified", "--notation", "c1", "-o", str(out)]) == 0
    tex = out.read_text()
    assert r"p_{x} &= c_{1}(a_{2} c_{2} + a_{3} c_{23} - d_{4} s_{23}) - d_{3} s_{1}" in tex
    assert r"$c_{i} = \cos\theta_i$" in tex and "C_{1}" not in tex
    with pytest.raises(SystemExit):
        main(["derive", "planar2r", "--notation", "fancy"])


def test_cli_derive_markdown_to_a_file(tmp_path, capsys):
    out = tmp_path / "build" / "puma560.md"
    assert main(["derive", "puma560", "--format", "markdown", "-o", str(out)]) == 0
    assert PX_PUMA in out.read_text()


def test_cli_handout_writes_the_tex(tmp_path, capsys):
    out = tmp_path / "hw.tex"
    code = main(
        [
            "handout",
            "planar2r",
            "puma560",
            "-o",
            str(out),
            "--title",
            r"\input{x}",
            "--mode",
            "problems",
            "--check",
            "--convention-note",
            "--numeric",
        ]
    )
    assert code == 0 and "wrote" in capsys.readouterr().err
    tex = out.read_text()
    assert r"\textbackslash{}input\{x\}" in tex and tex.count(r"\section{") == 2
    assert r"\item Evaluate" in tex


def test_cli_handout_errors(tmp_path, capsys):
    assert main(["handout", "planar2r", "-o", str(tmp_path / "x.tex"), "--check", "1,2,3"]) == 2
    assert "needs 2 joint values" in capsys.readouterr().err
    assert (
        main(
            [
                "handout",
                "planar2r",
                "-o",
                str(tmp_path / "x.tex"),
                "--template-dir",
                str(tmp_path / "none"),
            ]
        )
        == 2
    )
    assert "does not exist" in capsys.readouterr().err
    assert main(["handout", "nosuchrobot", "-o", str(tmp_path / "x.tex")]) == 2
