"""The log checker, safe compilation, and the compiled handouts (CI: TeX)."""

from __future__ import annotations

import os
import shutil
import subprocess
import time
import unicodedata
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
import sympy as sp

import dhsym
from dhsym.errors import DHError
from dhsym.explain.documents import write_handout
from dhsym.explain.latex import check_log, compile_pdf, run_latex
from dhsym.notation.layout import math_width

ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts"

# --- layout ---------------------------------------------------------------------------


def test_math_width_grows_with_content():
    assert (
        math_width("C_{1}") < math_width("C_{123}") < math_width(r"\cos{\left(\theta_{1}\right)}")
    )
    assert math_width("a + b") > math_width("ab")


# --- the log ----------------------------------------------------------------------------


def test_check_log_reports_errors_overfull_and_missing_characters():
    log = "\n".join(
        [
            "Overfull \\hbox (4.9pt too wide) in paragraph at lines 3--4",
            "Overfull \\hbox (5.1pt too wide) in alignment at lines 10--12",
            "Overfull \\vbox (50pt too high) has occurred while \\output is active",
            "./doc.tex:17: Undefined control sequence.",
            "! Undefined control sequence.",
            "l.17 \\foo",
            "Missing character: There is no ^^A in font cmr10!",
        ]
    )
    issues = check_log(log)
    assert [(i.kind, i.line) for i in issues] == [
        ("overfull", 10),
        ("error", 17),
        ("missing", None),
    ]
    assert issues[0].width_pt == pytest.approx(5.1)
    assert check_log(log, max_overfull_pt=6.0)[0].kind == "error"
    assert check_log("This is pdfTeX\nOutput written on doc.pdf (1 page).") == []


def test_check_log_reads_a_path(tmp_path):
    log = tmp_path / "x.log"
    log.write_text("Overfull \\hbox (9.0pt too wide) detected at line 3\n")
    assert [i.line for i in check_log(log)] == [3]


# --- compiling (no TeX needed for the failure paths) --------------------------------------


def test_missing_tex_names_the_debian_packages(tmp_path, monkeypatch):
    tex = tmp_path / "a.tex"
    tex.write_text("\\documentclass{article}\\begin{document}x\\end{document}\n")
    monkeypatch.setattr(shutil, "which", lambda name: None)
    with pytest.raises(DHError, match="texlive-latex-extra latexmk"):
        compile_pdf(tex)


def test_compile_refuses_a_missing_file(tmp_path):
    with pytest.raises(DHError, match="no such file"):
        compile_pdf(tmp_path / "nothing.tex")


def _doc(body: str) -> str:
    return "\\documentclass{article}\n\\begin{document}\n" + body + "\n\\end{document}\n"


@pytest.mark.tex
def test_compile_reports_the_latex_error_with_its_line(tmp_path, need_tex):
    tex = tmp_path / "bad.tex"
    tex.write_text(_doc("fine\n\\undefinedcommand"))
    with pytest.raises(DHError, match=r"line 4: Undefined control sequence"):
        compile_pdf(tex)


@pytest.mark.tex
def test_shell_escape_is_off_and_absolute_reads_are_refused(tmp_path, need_tex):
    tex = tmp_path / "evil.tex"
    tex.write_text(_doc("\\immediate\\write18{touch pwned}x"))
    compile_pdf(tex)  # \write18 without shell escape just writes to the log
    assert not (tmp_path / "pwned").exists()
    tex.write_text(_doc("\\input{/etc/passwd}"))
    with pytest.raises(DHError, match="LaTeX failed"):
        compile_pdf(tex)


@pytest.mark.tex
def test_a_runaway_document_is_killed_after_the_timeout(tmp_path, need_tex):
    tex = tmp_path / "loop.tex"
    tex.write_text(_doc("\\def\\a{\\a}\\a"))
    # the loop never ends by itself: the call returns only because the run is killed at its
    # time limit, which the error names (no clock in the test: a loaded machine passes too)
    with pytest.raises(DHError, match=r"did not finish within 2 s on .*loop\.tex"):
        compile_pdf(tex, timeout=2)


# --- the handouts, compiled ------------------------------------------------------------------


def _compile(path: Path, robots: list[str], **options: object) -> tuple[Path, list, float]:
    start = time.monotonic()
    run = run_latex(write_handout(robots, path, **options))
    return run.pdf, list(run.issues), time.monotonic() - start


@pytest.fixture(scope="module")
def handouts(tmp_path_factory):
    """Compile, once per module and in parallel, one document with every built-in robot and
    the two PUMA 560 handouts (each in its own convention). Call it after ``need_tex``."""
    folder = tmp_path_factory.mktemp("handouts")
    jobs = {
        "all": (folder / "all.tex", dhsym.builtin_names(), {"check": True}),
        "puma560": (folder / "puma560.tex", ["puma560"], {"check": True}),
        "puma560_modified": (
            folder / "puma560_modified.tex",
            ["puma560_modified"],
            {"convention_note": True},
        ),
        "sections": (
            folder / "sections.tex",
            SECTION_ROBOTS,
            {"check": True, "sections": "fk,jacobian,singularities,ik"},
        ),
    }
    done: dict[str, tuple[Path, list, float]] = {}

    def compiled() -> dict[str, tuple[Path, list, float]]:
        if not done:
            with ThreadPoolExecutor(max_workers=4) as pool:
                futures = {k: pool.submit(_compile, *j[:2], **j[2]) for k, j in jobs.items()}
                done.update({k: f.result() for k, f in futures.items()})
        return done

    return compiled


@pytest.mark.tex
def test_every_builtin_robot_compiles_without_errors_or_overfull_boxes(handouts, need_tex):
    results = handouts()
    for name, (pdf, issues, seconds) in results.items():
        assert pdf.exists()
        assert issues == [], f"{name}: {[str(i) for i in issues]}"
        print(f"{name}: compiled in {seconds:.1f} s")
    text = subprocess.run(
        ["pdftotext", str(results["all"][0]), "-"], capture_output=True, text=True, check=True
    ).stdout
    for name in dhsym.builtin_names():
        assert dhsym.load(name).name in text
    assert "0.4521" in text  # the numeric check of the PUMA 560 at zero (seed 001)
    modified = subprocess.run(
        ["pdftotext", str(results["puma560_modified"][0]), "-"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert "The two DH conventions" in modified and "αi−1" in modified


#: the robots whose Jacobian, singularities and inverse kinematics the suite compiles
SECTION_ROBOTS = ["puma560", "puma560_modified", "stanford", "planar2r", "scara"]


@pytest.mark.tex
def test_jacobian_singularity_and_ik_sections_compile_and_print(handouts, need_tex):
    pdf, issues, _ = handouts()["sections"]
    assert issues == [], [str(i) for i in issues]
    text = subprocess.run(
        ["pdftotext", str(pdf), "-"], capture_output=True, text=True, check=True
    ).stdout
    for heading in ("Forward kinematics", "The Jacobian", "Singular configurations"):
        assert text.count(heading) >= len(SECTION_ROBOTS)
    assert text.count("Inverse kinematics") >= len(SECTION_ROBOTS)
    assert "wrist singularity" in text and "elbow singularity" in text
    assert "right arm, elbow down, wrist not flipped" in text  # the PUMA 560's 8 solutions
    assert "elbow up" in text and "wrist flipped" in text
    assert "atan2" in text


@pytest.mark.tex
def test_full_notation_and_numeric_lengths_also_fit_the_page(tmp_path, need_tex):
    pdf, issues, _ = _compile(
        tmp_path / "full.tex", ["puma560", "stanford", "planar8r"], compact=False, numeric=True
    )
    assert issues == [], [str(i) for i in issues]


@pytest.mark.tex
def test_a_fragment_fits_a_default_article_with_a_narrower_width(tmp_path, need_tex):
    from dhsym.explain.documents import render_derivation

    robot = dhsym.load("puma560", compact=False)
    (tmp_path / "frag.tex").write_text(render_derivation(robot, fmt="latex", width=40))
    main = tmp_path / "main.tex"
    main.write_text(
        "\\documentclass{article}\n\\usepackage{amsmath}\n\\allowdisplaybreaks\n"
        "\\begin{document}\n\\input{frag}\n\\end{document}\n"
    )
    run = run_latex(main)
    assert run.pdf.exists() and run.issues == ()


@pytest.mark.tex
def test_hostile_strings_compile_and_print_literally(tmp_path, need_tex):
    title = r"\input{/etc/passwd} }\end{document} 100% $x$ #&_~^"
    course = r"\write18{rm -rf /} Übung α"
    rows = [dhsym.DHRow.revolute("theta1", a="a1")]
    table = dhsym.DHTable.from_rows(rows, name=r"Arm_{1} \write18{touch pwned} 50%")
    pdf, issues, _ = _compile(
        tmp_path / "hostile.tex",
        [dhsym.Robot(table), "planar2r"],
        title=title,
        course=course,
        author="O'Brien <o@b.c>",
        date="2024-05-01",
        mode="problems",
        convention_note=True,
    )
    assert [i for i in issues if i.kind != "overfull"] == []
    assert not (tmp_path / "pwned").exists()
    text = subprocess.run(
        ["pdftotext", str(pdf), "-"], capture_output=True, text=True, check=True
    ).stdout
    text = unicodedata.normalize("NFC", text).replace("’", "'")
    for literal in (
        r"\input{/etc/passwd} }\end{document} 100% $x$ #&_~^",
        r"\write18{rm -rf /} Übung α",
        r"Arm_{1} \write18{touch pwned} 50%",
        "O'Brien <o@b.c>",
    ):
        assert literal in text, literal
    assert "root:" not in text


@pytest.mark.tex
def test_page_one_of_the_puma_handout_is_not_blank(handouts, tmp_path, need_tex):
    import matplotlib.image as mpimg

    pdf = handouts()["puma560"][0]
    subprocess.run(
        [
            "pdftoppm",
            "-png",
            "-r",
            "110",
            "-f",
            "1",
            "-l",
            "1",
            "-singlefile",
            str(pdf),
            str(tmp_path / "page1"),
        ],
        check=True,
        timeout=60,
    )
    png = tmp_path / "page1.png"
    pixels = mpimg.imread(png)
    dark = (pixels[..., :3].mean(axis=-1) < 0.5).mean()
    assert 0.005 < dark < 0.25, dark  # text and a table, not an empty or black page
    ARTIFACTS.mkdir(exist_ok=True)
    shutil.copy(png, ARTIFACTS / "handout-puma560-page1.png")


def _plotting_available() -> bool:
    try:
        import dhsym.plot.figures  # noqa: F401
    except ImportError:
        return False
    return True


@pytest.mark.tex
@pytest.mark.skipif(not _plotting_available(), reason="dhsym.plot.figures is not available")
def test_handout_with_home_configuration_figure_compiles(tmp_path, need_tex):
    pdf, issues, _ = _compile(tmp_path / "fig.tex", ["planar2r"], figure=True)
    assert (tmp_path / "fig-planar-2r-home.pdf").exists()
    assert "\\includegraphics" in (tmp_path / "fig.tex").read_text()
    assert issues == [], [str(i) for i in issues]


def test_environment_of_the_compiler_is_locked_down(tmp_path, monkeypatch):
    """Without running TeX: the command and environment that compile_pdf would use."""
    import dhsym.explain.latex as L

    calls = []

    def run(cmd, cwd, env, timeout):
        calls.append((cmd, env))
        out = Path(env["TEXMFOUTPUT"])
        (out / "a.pdf").write_bytes(b"%PDF")
        (out / "a.log").write_text("ok")

    monkeypatch.setattr(L, "_run", run)
    monkeypatch.setattr(shutil, "which", lambda name: "/usr/bin/" + name)
    tex = tmp_path / "a.tex"
    tex.write_text(_doc("x"))
    assert compile_pdf(tex) == tex.with_suffix(".pdf")
    cmd, env = calls[0]
    assert cmd[0] == "latexmk" and "-norc" in cmd and cmd[-1] == "a.tex"
    assert cmd[-2] == f"-outdir={env['TEXMFOUTPUT']}" and Path(cmd[-2][8:]) != tmp_path
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.pdf", "a.tex"]
    for flag in ("-no-shell-escape", "-halt-on-error", "-interaction=nonstopmode"):
        assert flag in cmd
    assert env["openin_any"] == env["openout_any"] == "p" and env["shell_escape"] == "f"
    assert "openin_any" not in os.environ  # set for TeX only, not in our own process


@pytest.mark.tex
def test_auxiliary_files_stay_in_a_temporary_folder_unless_kept(tmp_path, need_tex):
    tex = tmp_path / "doc.tex"
    tex.write_text(_doc("x \\label{a}\\ref{a}"))
    assert compile_pdf(tex) == tex.with_suffix(".pdf")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["doc.pdf", "doc.tex"]
    compile_pdf(tex, keep_aux=True)
    assert {"doc.aux", "doc.log", "doc.pdf", "doc.tex"} <= {p.name for p in tmp_path.iterdir()}


@pytest.mark.tex
def test_a_failed_compilation_leaves_its_log_beside_the_source(tmp_path, need_tex):
    tex = tmp_path / "bad.tex"
    tex.write_text(_doc("\\undefinedcommand"))
    with pytest.raises(DHError, match="see .*bad.log"):
        compile_pdf(tex)
    assert "Undefined control sequence" in (tmp_path / "bad.log").read_text(encoding="latin-1")
    assert not (tmp_path / "bad.aux").exists()


@pytest.mark.tex
def test_symbol_names_with_sympy_modifiers_compile(tmp_path, need_tex):
    """sympy prints thetascr as \\mathscr{\\theta}, qfrak as \\mathfrak{q}, …: all compile."""
    from sympy.printing.latex import modifier_dict

    mods = sorted(modifier_dict)
    rows = [dhsym.DHRow.revolute(f"theta{m}", a=f"a{m}") for m in mods[:12]]
    rows += [dhsym.DHRow.prismatic(f"d{m}", alpha=sp.pi / 2) for m in mods[12:]]
    table = dhsym.DHTable.from_rows(rows, name="modifiers")
    pdf, issues, _ = _compile(tmp_path / "mods.tex", [dhsym.Robot(table)], mode="problems")
    assert pdf.exists() and [i for i in issues if i.kind != "overfull"] == []
    assert r"\mathscr{\theta}" in (tmp_path / "mods.tex").read_text()
