"""dhsym check and dhsym grade from the command line (exit codes, JSON)."""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path

import pytest

from dhsym.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
HW = ROOT / "examples" / "homework"
RIGHT = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]"


def run_check(monkeypatch, capsys, answer: str, *extra: str) -> tuple[int, str, str]:
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(answer.encode())))
    code = main(["check", "--key", "planar2r", "--question", "T0_2", "--answer", "-", *extra])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_exit_codes_correct_incorrect_unreadable(monkeypatch, capsys):
    assert run_check(monkeypatch, capsys, RIGHT)[0] == 0
    code, out, _ = run_check(monkeypatch, capsys, RIGHT.replace("+ a2*S12", "- a2*S12"))
    assert code == 1 and "wrong sign" in out
    code, out, err = run_check(monkeypatch, capsys, "[[1, 2], [3")
    assert code == 2 and "unreadable answer" in err


def test_json_output(monkeypatch, capsys):
    code, out, _ = run_check(monkeypatch, capsys, RIGHT.replace("C12, -S12", "S12, -S12"), "--json")
    data = json.loads(out)
    assert code == 1 and data["verdict"] == "incorrect" and data["schema"] == 1
    assert data["diagnosis"][0]["kind"] == "sin_cos_swapped"


def test_answer_from_a_file_and_a_table_key_file(tmp_path, capsys):
    f = tmp_path / "a.tex"
    lines = (
        (ROOT / "tests" / "data" / "seeds" / "002_8d4894e47f2048cf.txt")
        .read_text(encoding="utf-8")
        .splitlines()
    )
    f.write_text(lines[166], encoding="utf-8")
    code = main(
        [
            "check",
            "--key",
            str(HW / "generic_modified_link.yaml"),
            "--question",
            "A1",
            "--answer",
            str(f),
            "--json",
        ]
    )
    data = json.loads(capsys.readouterr().out)
    assert code == 1 and data["diagnosis"][0]["entries"] == [[2, 4]]


def test_unknown_key_is_an_error(capsys):
    assert main(["check", "--key", "nosuchrobot", "--question", "T0_1", "--answer", "-"]) == 2
    assert "dhsym: error" in capsys.readouterr().err


def test_grade_command(tmp_path, capsys):
    out = tmp_path / "report"
    code = main(
        [
            "grade",
            str(HW / "assignment.yaml"),
            str(HW / "class.csv"),
            "-o",
            str(out),
            "--workers",
            "0",
            "--quiet",
        ]
    )
    assert code == 0 and "graded 3 submission(s)" in capsys.readouterr().out
    assert (out / "gradebook.csv").is_file() and (out / "summary.html").is_file()


def test_rounding_option_both_ways(monkeypatch, capsys):
    answer = RIGHT.replace(
        "[S12, C12, 0, a1*S1 + a2*S12]", "[S12, C12*sin(1.5708), 0, a1*S1 + a2*S12]"
    )
    code, out, _ = run_check(monkeypatch, capsys, answer)
    assert code == 0 and "to 5 significant digits" in out
    assert run_check(monkeypatch, capsys, answer, "--rounding", "off")[0] == 1
    short = answer.replace("1.5708", "1.6")
    assert run_check(monkeypatch, capsys, short)[0] == 1
    assert run_check(monkeypatch, capsys, short, "--rounding", "digits=2")[0] == 0
    code, _, err = run_check(monkeypatch, capsys, answer, "--rounding", "roughly")
    assert code == 2 and "unknown rounding 'roughly'" in err


def _one_error_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.startswith("dhsym: error: ") and err.count("\n") == 1, err
    return err


def test_a_question_with_a_huge_frame_number_is_a_clean_error(capsys):
    question = "T0_" + "9" * 5000
    assert main(["check", "--key", "planar2r", "--question", question, "--answer", "-"]) == 2
    assert "unknown question" in _one_error_line(capsys)


def test_time_limits_from_the_command_line_are_validated(tmp_path, capsys):
    for bad in ("inf", "nan", "-1", "0", "1e300"):
        argv = ["check", "--key", "planar2r", "--question", "T0_2", "--answer", "-"]
        assert main([*argv, "--timeout", bad]) == 2
        assert "--timeout: expected a time limit in seconds above 0" in _one_error_line(capsys)
        argv = ["grade", str(HW / "assignment.yaml"), str(HW / "submissions")]
        assert main([*argv, "-o", str(tmp_path / "o"), "--timeout", bad, "--quiet"]) == 2
        assert "--timeout: expected a time limit in seconds above 0" in _one_error_line(capsys)


def test_an_answer_that_is_a_fifo_is_unreadable_at_once(tmp_path):
    import os
    import subprocess

    fifo = tmp_path / "answer.txt"
    os.mkfifo(fifo)
    out = subprocess.run(
        [sys.executable, "-m", "dhsym", "check", "--key", "planar2r", "--question", "T0_2"]
        + ["--answer", str(fifo)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 2 and "not a regular file" in out.stderr


def test_help_lists_every_question_kind(capsys):
    from dhsym.cli.main import build_parser

    for cmd in ("check", "grade"):
        with pytest.raises(SystemExit):
            build_parser().parse_args([cmd, "--help"])
        text = capsys.readouterr().out
        for kind in ("table", "T<i>_<j>", "A<k>", "arm", "px", "J[row,col]", "det J", "ik all"):
            assert kind in text, (cmd, kind)
        assert "ik@q1,...,qn" in text
        for kind in ("M[row,col]", "c_ijk", "tau_static"):
            assert kind in text, (cmd, kind)


def test_new_assignment_writes_an_example_that_grades(tmp_path, capsys):
    from dhsym.checking import Assignment
    from dhsym.cli.main import main

    out = tmp_path / "hw"
    assert main(["new-assignment", str(out)]) == 0
    text = (out / "assignment.yaml").read_text(encoding="utf-8")
    assert "# rounding:" in text and "ask: det J" in text
    a = Assignment.load(out / "assignment.yaml")
    assert [q.id for q in a.questions] == ["q1", "q2", "q3", "q4", "q5"]
    assert (out / "submissions" / "alice" / "q1.md").is_file()
    assert main(["new-assignment", str(out)]) == 2  # not an empty folder


def test_the_example_homework_is_package_data():
    text = (Path(__file__).parents[2] / "pyproject.toml").read_text(encoding="utf-8")
    assert '    "dhsym.examples",\n' in text  # a package of the wheel
    assert '"dhsym.examples" = "examples/homework"' in text
    assert (
        '"dhsym.examples" = ["*.yaml", "*.csv", "submissions/*/*.md", "submissions/*/*.txt"]'
        in text
    )


def test_a_missing_answer_file_is_named(tmp_path, capsys):
    missing = tmp_path / "q1.txt"
    argv = ["check", "--key", "planar2r", "--question", "T0_2", "--answer", str(missing)]
    assert main(argv) == 2
    assert str(missing) in capsys.readouterr().out


def test_check_a_profile_key(monkeypatch, capsys):
    def run(answer: str, *args: str) -> tuple[int, str]:
        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(answer.encode())))
        code = main(["check", "--answer", "-", *args])
        return code, capsys.readouterr().out

    key = ["--key", "cubic(q0=q0, qf=qf, tf=tf)", "--question", "traj a2"]
    assert run("3*(qf - q0)/tf^2", *key)[0] == 0
    code, out = run("3*(qf - q0)/tf", *key, "--json")
    data = json.loads(out)
    assert code == 1 and data["diagnosis"][0]["kind"] == "tf_for_tf_squared"
    assert data["key"] == "cubic(q0=q0, qf=qf, tf=tf)"
    assert run("0.3", "--key", "cubic(q0=0, qf=1, tf=3)", "--question", "traj a2")[0] == 1
    assert (
        run(
            "0.3",
            "--key",
            "cubic(q0=0, qf=1, tf=3)",
            "--question",
            "traj a2",
            "--rounding",
            "abs=0.05",
        )[0]
        == 0
    )
    assert (
        main(["check", "--key", "cubic(q0=0, qf=1)", "--question", "traj a2", "--answer", "-"]) == 2
    )
    assert "cubic needs tf" in capsys.readouterr().err
