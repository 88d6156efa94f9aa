"""dhsym variants, dhsym check-assignment, grade --variants and handout --variants."""

from __future__ import annotations

import csv
import io
import json
import re
import shutil
from pathlib import Path

import pytest

from dhsym.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
HW = ROOT / "examples" / "homework"
ASSIGNMENT = """title: HW variants
key: planar2r
secret: hw.secret
variants:
  a1: {from: 0.30, to: 0.50, step: 0.01}
  a2: [0.2, 0.25]
questions:
  - {id: q1, ask: T0_2, points: 2}
"""


@pytest.fixture
def hw(tmp_path: Path) -> Path:
    (tmp_path / "hw.yaml").write_text(ASSIGNMENT)
    (tmp_path / "class.csv").write_text("student,name\nalice,Alice\nbob,Bob\nJosé,José\n")
    return tmp_path / "hw.yaml"


def test_new_secret_then_listing(hw: Path, capsys):
    # no secret yet: one clear line, status 2
    assert main(["variants", str(hw), "--roster", str(hw.parent / "class.csv")]) == 2
    assert "--new-secret" in capsys.readouterr().err
    assert main(["variants", str(hw), "--new-secret"]) == 0
    assert "keep it private" in capsys.readouterr().out
    assert (hw.parent / "hw.secret").stat().st_mode & 0o777 == 0o600
    roster = str(hw.parent / "class.csv")
    assert main(["variants", str(hw), "--roster", roster, "--format", "csv"]) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    assert [r["student"] for r in rows] == ["alice", "bob", "José"]
    assert len({(r["a1"], r["a2"]) for r in rows}) == 3  # no duplicate in the class
    assert main(["variants", str(hw), "--roster", roster, "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["variants"] == ["a1", "a2"]
    assert [s["values"] for s in data["students"]] == [{"a1": r["a1"], "a2": r["a2"]} for r in rows]
    # the same again: reproducible
    assert main(["variants", str(hw), "--roster", roster]) == 0
    text = capsys.readouterr().out
    assert all(r["a1"] in text for r in rows) and "3 students, 3 distinct variants of 42" in text


def test_check_assignment_exit_status(tmp_path: Path, capsys):
    assert main(["check-assignment", str(HW / "assignment.yaml")]) == 0
    out = capsys.readouterr().out
    assert out.endswith("16 passed, 0 failed\n") and "FAIL" not in out
    bad = tmp_path / "bad.yaml"
    bad.write_text("key: planar2r\nquestions:\n  - {id: q1, ask: px, tests: {right: [a1*C1]}}\n")
    assert main(["check-assignment", str(bad)]) == 1
    out = capsys.readouterr().out
    assert "FAIL" in out and out.endswith("1 passed, 1 failed\n")


def test_grade_and_sheets_with_variants(hw: Path, tmp_path: Path, capsys):
    (hw.parent / "hw.secret").write_text("a-secret-of-the-cli-tests-0123456789\n")
    roster = str(hw.parent / "class.csv")
    assert main(["variants", str(hw), "--roster", roster, "--format", "csv"]) == 0
    values = {r["student"]: r for r in csv.DictReader(io.StringIO(capsys.readouterr().out))}
    subs = tmp_path / "subs"
    for who in ("alice", "bob"):
        a1, a2 = values[who]["a1"], values[who]["a2"]
        (subs / who).mkdir(parents=True)
        (subs / who / "q1.txt").write_text(
            f"[[C12, -S12, 0, {a1}*C1 + {a2}*C12], [S12, C12, 0, {a1}*S1 + {a2}*S12], [0, 0, 1, 0]]"
        )
    out = tmp_path / "report"
    args = ["grade", str(hw), str(subs), "-o", str(out), "--workers", "0", "--quiet"]
    assert main(args) == 2
    assert "--variants CLASS.csv" in capsys.readouterr().err
    assert main([*args, "--variants", roster]) == 0
    book = list(csv.DictReader((out / "gradebook.csv").open()))
    assert [(r["student"], r["total"]) for r in book] == [("alice", "2"), ("bob", "2")]
    assert f"a1 = {values['bob']['a1']}" in (out / "feedback" / "bob.md").read_text()
    sheets = tmp_path / "sheets"
    assert main(["handout", str(hw), "--variants", roster, "-o", str(sheets)]) == 0
    assert sorted(p.suffix for p in sheets.iterdir()) == [".tex"] * 3
    alice = (sheets / "alice.tex").read_text()
    assert f"Your values: a1 = {values['alice']['a1']}, a2 = {values['alice']['a2']}" in alice
    assert f"$a_{{1}} = {values['alice']['a1']}$" in alice  # the table's lengths are hers
    assert main(["handout", str(hw), "--variants", roster, "-o", str(tmp_path / "x.tex")]) == 2
    assert "-o names a folder" in capsys.readouterr().err


@pytest.mark.slow
def test_sheets_compile_to_pdf(hw: Path, tmp_path: Path):
    (hw.parent / "hw.secret").write_text("a-secret-of-the-cli-tests-0123456789\n")
    sheets = tmp_path / "sheets"
    roster = str(hw.parent / "class.csv")
    assert main(["handout", str(hw), "--variants", roster, "-o", str(sheets), "--pdf"]) == 0
    pdfs = sorted(sheets.glob("*.pdf"))
    assert len(pdfs) == 3 and all(p.read_bytes().startswith(b"%PDF") for p in pdfs)


def test_merged_sheets_are_one_document_a_page_per_student(hw: Path, tmp_path: Path):
    """--merged: every student's sheet in one LaTeX document from the handout template,
    compiled: one page per student, no overfull box, each student's values on their page."""
    from dhsym.explain.latex import run_latex

    (hw.parent / "hw.secret").write_text("a-secret-of-the-cli-tests-0123456789\n")
    roster = str(hw.parent / "class.csv")
    merged = tmp_path / "class.tex"
    args = ["handout", str(hw), "--variants", roster, "-o", str(tmp_path / "sheets")]
    assert main([*args, "--merged", str(merged)]) == 0
    tex = merged.read_text(encoding="utf-8")
    assert tex.count(r"\documentclass") == 1 and tex.count(r"\setcounter{page}{1}") == 3
    for student in ("alice", "bob"):  # the same sheet as the student's own file
        own = (tmp_path / "sheets" / f"{student}.tex").read_text(encoding="utf-8")
        values = own.split("Your values: ", 1)[1].split("}", 1)[0]
        assert f"Your values: {values}" in tex
    if shutil.which("pdflatex") is None and shutil.which("latexmk") is None:
        pytest.skip("no TeX installed")
    run = run_latex(merged)
    assert run.pdf.read_bytes().startswith(b"%PDF")
    pages = re.search(r"Output written on .*?\((\d+) pages?", run.log)
    assert pages is not None and int(pages[1]) == 3  # one page per student of the class list
    assert not [i for i in run.issues if i.kind == "overfull"]
    assert "Overfull" not in run.log
    assert main([*args, "--merged", str(tmp_path / "class.txt")]) == 2


def test_merged_pdf_is_compiled_by_the_command(hw: Path, tmp_path: Path):
    (hw.parent / "hw.secret").write_text("a-secret-of-the-cli-tests-0123456789\n")
    if shutil.which("pdflatex") is None and shutil.which("latexmk") is None:
        pytest.skip("no TeX installed")
    roster = str(hw.parent / "class.csv")
    out = tmp_path / "print" / "class.pdf"
    args = ["handout", str(hw), "--variants", roster, "-o", str(tmp_path / "sheets")]
    assert main([*args, "--merged", str(out)]) == 0
    assert out.read_bytes().startswith(b"%PDF") and out.with_suffix(".tex").is_file()
