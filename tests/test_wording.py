"""Words for students: nothing a student or teacher reads calls a lecture "seed 00x".

The lectures are cited by title and author (docs/explanations/lectures.md). This test makes every
artefact dhsym produces — handouts, derivations in every format, frame-assignment steps,
feedback pages and the class summary, the command line's output, help and errors — and
reads the notebooks and the sources (docstrings, templates, examples, README) from disk.
"""

from __future__ import annotations

import contextlib
import io
import json
import re
import sys
from pathlib import Path

import pytest

import dhsym
from dhsym.cli.main import build_parser, main
from dhsym.cli.robots import derive_json
from dhsym.explain.documents import render_handout
from dhsym.explain.rendering import render

ROOT = Path(__file__).resolve().parent.parent
HW = ROOT / "examples" / "homework"
# "seed 002", "Seed_001", "seeds 000 and 004", also broken across a line ("seed\n002")
INTERNAL = re.compile(r"seeds?[\s_-]*0\d", re.IGNORECASE)
ROBOTS = [*dhsym.builtin_names(), "planar3r"]


def internal_words(text: str) -> list[str]:
    """The places in ``text`` that speak of seeds (a little context around each)."""
    return [
        " ".join(text[max(m.start() - 30, 0) : m.end() + 10].split())
        for m in INTERNAL.finditer(text)
    ]


def test_the_pattern_finds_what_it_must():
    assert internal_words("one slide of Seed 002 prints\nfine\nseeds 000 and 004, SEED001")
    assert len(internal_words("Seed 001 (x)\nseed_002\nseeds 003")) == 3
    assert not internal_words("the lectures (Ghosal, Lecture 5; Mohan, Lecture 9), seedling")
    assert internal_words("one slide of seed\n002 prints")


@pytest.fixture(scope="module")
def derivations():
    return {name: dhsym.derive(name) for name in ROBOTS}


@pytest.mark.parametrize("fmt", ["text", "markdown", "latex"])
def test_derivations_of_every_built_in_robot(derivations, fmt):
    for name, d in derivations.items():
        assert internal_words(render(d, fmt)) == [], name


def test_json_derivations_and_tables(derivations):
    for name in ROBOTS:
        robot = dhsym.load(name)
        assert internal_words(json.dumps(derive_json(robot), ensure_ascii=False)) == [], name
        assert internal_words(dhsym.dump_table(robot.table)) == [], name
        assert internal_words(robot.table.name + robot.table.source + robot.table.notes) == []


def test_handouts_answers_problems_and_the_convention_note(derivations):
    ds = list(derivations.values())
    for mode in ("answers", "problems"):
        tex = render_handout(ds, mode=mode, convention_note=True, title="All robots")
        assert internal_words(tex) == [], mode


def test_frame_assignment_steps_and_task_chains():
    from dhsym.geometry.frames import assign_frames

    scara = [
        ((0, 0, 0), (0, 0, 1), "R"),
        ((0.4, 0, 0), (0, 0, 1), "R"),
        ((0.7, 0, 0), (0, 0, -1), "P"),
        ((0.7, 0, 0), (0, 0, -1), "R"),
    ]
    tool = ((0.7, 0, -0.05), (0, 0, -1), (0, -1, 0))
    for convention in ("standard", "modified"):
        fa = assign_frames(scara, tool=tool, convention=convention)
        text = "\n".join(s.text + "\n" + s.markdown for s in fa.steps) + fa._repr_markdown_()
        assert internal_words(text) == [], convention
        assert internal_words(dhsym.derive(dhsym.Robot(fa.table)).to_text()) == []


@pytest.mark.slow
def test_feedback_pages_and_summary_of_the_example_class(tmp_path):
    report = dhsym.grade(
        HW / "assignment.yaml", HW / "submissions", tmp_path, workers=0, progress=False
    )
    pages = sorted((tmp_path / "feedback").iterdir())
    assert len(pages) >= 2 * report.students
    for page in [*pages, tmp_path / "summary.html", tmp_path / "gradebook.csv"]:
        assert internal_words(page.read_text(encoding="utf-8")) == [], page.name


def _run(argv: list[str], stdin: str = "") -> str:
    out, err = io.StringIO(), io.StringIO()
    saved = sys.stdin
    sys.stdin = io.TextIOWrapper(io.BytesIO(stdin.encode()))
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            with contextlib.suppress(SystemExit):
                main(argv)
    finally:
        sys.stdin = saved
    return out.getvalue() + err.getvalue()


def test_command_line_output_help_and_errors(tmp_path):
    wrong = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 - a2*S12], [0, 0, 1, 0]]"
    runs = [["list"], ["--help"], ["derive", "nosuchrobot"], ["show", "puma56"]]
    runs += [["show", name] for name in ROBOTS]
    runs += [["show", name, "--format", "yaml"] for name in ROBOTS]
    runs += [
        ["fk", "puma560", "--q", "0,0,0,0,0,0"],
        ["fk", str(HW / "generic_modified_link.yaml"), "--q", "0"],
        ["convert", "example1_rrp", "--to", "modified", "--samples", "2"],
        ["handout", "example4_6dof", "-o", "-"],
        ["handout", "puma560_modified", "-o", "-", "--mode", "problems", "--convention-note"],
    ]
    checks = [
        ["check", "--key", "planar2r", "--question", "T0_2", "--answer", "-", *fmt]
        for fmt in ([], ["--format", "markdown"], ["--json"])
    ]
    text = "".join(_run(argv) for argv in runs)
    text += "".join(_run(argv, wrong) for argv in checks)
    key, answer = HW / "generic_modified_link.yaml", HW / "submissions" / "carol" / "q4.md"
    text += _run(["check", "--key", str(key), "--question", "A1", "--answer", str(answer)])
    parser = build_parser()
    for sub in parser._subparsers._group_actions[0].choices.values():
        text += sub.format_help()
    assert "Example 4" in text and "usage: dhsym" in text
    assert internal_words(text) == []


def test_sources_docstrings_templates_examples_and_readme():
    files = [ROOT / "README.md"]
    for folder, patterns in (
        ("dhsym", ("*.py", "*.yaml")),
        ("templates", ("*.j2",)),
        ("examples", ("*.py", "*.yaml", "*.csv", "*.md", "*.txt")),
        ("docs", ("*.md",)),
    ):
        for pattern in patterns:
            files += sorted((ROOT / folder).rglob(pattern))
    found = {str(f.relative_to(ROOT)): internal_words(f.read_text(encoding="utf-8")) for f in files}
    assert len(found) > 100
    assert {k: v for k, v in found.items() if v} == {}


def test_notebooks_read_from_disk():
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    assert notebooks
    found = {nb.name: internal_words(nb.read_text(encoding="utf-8")) for nb in notebooks}
    assert {k: v for k, v in found.items() if v} == {}
