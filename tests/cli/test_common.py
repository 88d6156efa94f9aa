"""The shell's conventions: -o -, closed pipes, plain help with defaults, --values, paths."""

from __future__ import annotations

import argparse
import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

from dhsym.cli.common import EXIT_BROKEN_PIPE, parse_values, run_quietly
from dhsym.cli.main import build_parser, main
from dhsym.errors import DHError

ROOT = Path(__file__).resolve().parents[2]
WRONG = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 - a2*S12], [0, 0, 1, 0]]"


def _dhsym(*args: str, **kw: object) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "COLUMNS"}
    return subprocess.run(
        [sys.executable, "-m", "dhsym", *args], capture_output=True, env=env, **kw
    )


# --- -o - ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv",
    [
        ["derive", "planar2r", "--format", "json", "-o", "-"],
        ["convert", "planar2r", "--to", "modified", "-o", "-", "--samples", "3"],
        ["handout", "planar2r", "-o", "-"],
        ["plot", "planar2r", "-o", "-"],
    ],
)
def test_dash_writes_to_standard_output(argv, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert out.strip() and "wrote" not in err
    assert list(tmp_path.iterdir()) == []  # no file named "-"
    start = {"derive": "{", "convert": "name:", "handout": "\\documentclass", "plot": "<?xml"}
    assert out.startswith(start[argv[0]])


def test_binary_picture_to_a_pipe_but_not_to_a_terminal(capsysbinary, monkeypatch):
    assert main(["plot", "planar2r", "-o", "-", "--format", "png"]) == 0
    assert capsysbinary.readouterr().out.startswith(b"\x89PNG")
    monkeypatch.setattr(sys.stdout, "isatty", lambda: True)
    assert main(["plot", "planar2r", "-o", "-", "--format", "pdf"]) == 2
    assert b"would print a PDF picture on the terminal" in capsysbinary.readouterr().err


def test_handout_to_stdout_refuses_what_needs_a_file(capsys):
    assert main(["handout", "planar2r", "-o", "-", "--pdf"]) == 2
    assert "--pdf needs a file" in capsys.readouterr().err


# --- closed pipes ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv",
    [
        ["derive", "puma560"],  # long output: the error comes at a write in the command
        ["fk", "planar2r", "--q", "0,0"],  # short output: at the final flush
        ["--help"],
    ],
)
def test_a_closed_pipe_ends_quietly(argv):
    proc = subprocess.Popen(
        [sys.executable, "-m", "dhsym", *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    proc.stdout.close()  # the reader is gone before anything is written: `| head -c0`
    err = proc.stderr.read()
    proc.stderr.close()
    assert proc.wait(timeout=120) in (0, EXIT_BROKEN_PIPE)
    assert err == b""


def test_head_of_a_derivation_in_a_shell():
    out = subprocess.run(
        f"{sys.executable} -m dhsym derive puma560 --format json | head -c1",
        shell=True,
        capture_output=True,
        text=True,
    )
    assert out.stdout == "{" and out.stderr == ""


def test_run_quietly_turns_a_broken_pipe_into_141():
    def writes_to_a_closed_pipe() -> int:
        raise BrokenPipeError(32, "Broken pipe")

    saved = os.dup(sys.stdout.fileno()) if hasattr(sys.stdout, "fileno") else None
    try:
        assert run_quietly(writes_to_a_closed_pipe) == EXIT_BROKEN_PIPE
    finally:
        if saved is not None:
            os.dup2(saved, sys.stdout.fileno())
            os.close(saved)
    assert run_quietly(lambda: 0) == 0


# --- help ------------------------------------------------------------------------------------


def _parsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    out = {"dhsym": parser}
    for name, sub in parser._subparsers._group_actions[0].choices.items():
        out[name] = sub
        for action in sub._actions:
            if isinstance(action, argparse._SubParsersAction):
                out.update({f"{name} {k}": v for k, v in action.choices.items()})
    return out


@pytest.mark.parametrize("name", sorted(_parsers()))
def test_help_is_plain_and_shows_defaults_and_choices(name):
    parser = _parsers()[name]
    text = parser.format_help()
    for markup in ("``", ":func:", ":class:", ":mod:", "\n.. "):
        assert markup not in text, f"{name} --help has reST markup {markup!r}"
    for action in parser._actions:
        if not action.option_strings or action.help == argparse.SUPPRESS:
            continue
        assert action.help, f"{name} {action.option_strings[0]} has no help"
        if action.default not in (None, False, True, argparse.SUPPRESS) and action.nargs != 0:
            assert "default" in (parser._get_formatter()._get_help_string(action)), action
        if action.choices:
            assert "{" + ",".join(action.choices) + "}" in text


def test_help_shows_the_default_and_the_choices_of_format():
    text = _parsers()["derive"].format_help()
    assert "--format {text,markdown,latex,json}" in text and "(default: text)" in text


@pytest.mark.parametrize("name", ["check", "grade"])
def test_exit_codes_are_in_the_help(name):
    text = " ".join(_parsers()[name].format_help().split())
    assert "Exit status: 0" in text and "2 the" in text
    if name == "check":
        assert "1 the answer is incorrect" in text


def test_help_and_version_from_the_shell():
    out = _dhsym("--help", text=True)
    assert out.returncode == 0 and "COMMAND" in out.stdout and out.stderr == ""
    out = _dhsym("--version", text=True)
    assert out.returncode == 0 and out.stdout.startswith("dhsym ")


# --- check on a terminal ---------------------------------------------------------------------


def test_check_prints_plain_text_markdown_only_when_asked(monkeypatch, capsys):
    def check(*extra: str) -> str:
        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(WRONG.encode())))
        argv = ["check", "--key", "planar2r", "--question", "T0_2", "--answer", "-", *extra]
        assert main(argv) == 1
        return capsys.readouterr().out

    text = check()
    assert "a2*S12" in text and "INCORRECT" in text
    for escape in ("\\_", "\\*", "\\[", "**", "$"):
        assert escape not in text
    assert "T0\\_2" in check("--format", "markdown") and "$a_{1} S_{1}" in check(
        "--format", "markdown"
    )
    assert check("--json").startswith("{") and check("--format", "json").startswith("{")


# --- --values ----------------------------------------------------------------------------------


def test_parse_values():
    assert parse_values("a1=1, d3=pi/2") == {"a1": 1.0, "d3": pytest.approx(1.5707963)}
    for bad in ("a1", "a1=", "=3", "1a=2", "a1=__import__('os')"):
        with pytest.raises(DHError):
            parse_values(bad)


def test_fk_and_plot_take_values(tmp_path, capsys):
    table = tmp_path / "arm.yaml"
    table.write_text(
        "name: Two links\njoints:\n  - {type: R, theta: theta1, d: 0, a: a1, alpha: 0}\n"
        "  - {type: R, theta: theta2, d: 0, a: a2, alpha: 0}\n"
    )
    assert main(["fk", str(table), "--q", "0,0", "--json", "--values", "a1=1,a2=0.5"]) == 0
    assert '"matrix": [[1.0, 0.0, 0.0, 1.5]' in capsys.readouterr().out
    for argv in (["fk", str(table), "--q", "0,0"], ["plot", str(table), "-o", "-"]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert "no numbers for a1, a2" in err and "values:" in err and "--values a1=" in err
    assert main(["plot", str(table), "-o", "-", "--values", "a1=1,a2=0.5"]) == 0
    assert capsys.readouterr().out.startswith("<?xml")
    assert main(["fk", str(table), "--q", "0,0", "--values", "a1=1,b=2"]) == 2
    assert "has no symbol b (its symbolic lengths: a1, a2)" in capsys.readouterr().err


# --- names and paths ---------------------------------------------------------------------------


def test_a_mistyped_robot_gets_the_closest_name(capsys):
    assert main(["derive", "puma650"]) == 2
    assert "did you mean 'puma560'?" in capsys.readouterr().err


def test_wrote_lines_give_the_path_as_typed(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["derive", "planar2r", "-o", "build/x.md", "--format", "markdown"]) == 0
    assert main(["convert", "planar2r", "--to", "modified", "-o", "./m.yaml"]) == 0
    assert main(["plot", "planar2r", "-o", "pics/2r.svg"]) == 0
    assert main(["handout", "planar2r", "-o", "build/h.tex"]) == 0
    err = capsys.readouterr().err
    for path in ("build/x.md", "./m.yaml", "pics/2r.svg", "build/h.tex"):
        assert f"wrote {path}\n" in err
    assert str(tmp_path) not in err


@pytest.mark.tex
def test_handout_pdf_keeps_auxiliary_files_only_when_asked(tmp_path, monkeypatch, capsys, need_tex):
    monkeypatch.chdir(tmp_path)
    assert main(["handout", "planar2r", "-o", "build/x.tex", "--pdf"]) == 0
    assert sorted(p.name for p in (tmp_path / "build").iterdir()) == ["x.pdf", "x.tex"]
    assert capsys.readouterr().err == "wrote build/x.tex\nwrote build/x.pdf\n"
    assert main(["handout", "planar2r", "-o", "build/y.tex", "--pdf", "--keep-aux"]) == 0
    assert (tmp_path / "build" / "y.log").is_file() and (tmp_path / "build" / "y.aux").is_file()


_DEG_TABLE = """angles: deg
joints:
  - {type: R, theta: theta1, d: 0, a: 1, alpha: 0}
  - {type: R, theta: theta2, d: 0, a: 1, alpha: 0}
"""


@pytest.mark.parametrize(
    ("flags", "x", "unit"),
    [
        ([], 1.0, "degrees (the table's angles: deg; --rad to override)"),  # 90°, -90°
        (["--deg"], 1.0, "degrees (--deg)"),
        (["--rad"], None, "radians (--rad)"),
    ],
)
def test_fk_takes_the_tables_angle_unit_and_says_it(tmp_path, capsys, flags, x, unit):
    import json
    import math

    path = tmp_path / "rr.yaml"
    path.write_text(_DEG_TABLE, encoding="utf-8")
    assert main(["fk", str(path), "--q=90,-90", "--json", *flags]) == 0
    p = json.loads(capsys.readouterr().out)["matrix"]
    expected = 1.0 if x else math.cos(90) + math.cos(0)
    assert p[0][3] == pytest.approx(expected, abs=1e-9)
    assert main(["fk", str(path), "--q=90,-90", *flags]) == 0
    assert capsys.readouterr().out.startswith(f"--q read in {unit}:\n[[")


def test_fk_of_a_radian_table_stays_in_radians(capsys):
    assert main(["fk", "puma560", "--q", "0,0,0,0,0,0"]) == 0
    out = capsys.readouterr().out
    assert "--q read in radians (the table's angles: rad; --deg to override)" in out
