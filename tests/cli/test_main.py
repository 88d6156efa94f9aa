"""The command line: list, show, derive, fk; errors exit 2 with one line."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from dhsym.cli.main import main


def test_list(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "puma560" in out and "RRRRRR" in out and "planarNr" in out


def test_show_markdown_and_yaml(capsys):
    assert main(["show", "scara"]) == 0
    assert "| 3 | $0$ | $d_{3}$ |" in capsys.readouterr().out
    assert main(["show", "scara", "--format", "yaml"]) == 0
    assert "- {type: P, theta: 0, d: d3" in capsys.readouterr().out


def test_derive_json_is_stable(capsys):
    assert main(["derive", "planar2r", "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["schema"] == 1
    assert d["compact"][0] == ["C12", "-S12", "0", "a1*C1 + a2*C12"]
    assert d["latex"][0][3] == "a_{1} C_{1} + a_{2} C_{12}"
    assert d["legend"][0] == {"abbrev": "C1", "meaning": "cos(theta1)"}
    assert [x["label"] for x in d["links"]] == ["T0_1", "T1_2"]


def test_derive_any_pair(capsys):
    assert main(["derive", "puma560", "--format", "json", "--from", "2", "--to", "5"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["label"] == "T2_5" and len(d["links"]) == 3


def test_fk(capsys):
    assert main(["fk", "puma560", "--q", "0,0,0,0,0,0", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["matrix"][0][3] == pytest.approx(0.4521)
    assert d["matrix"][1][3] == pytest.approx(-0.15005)
    assert main(["fk", "planar2r", "--q", "90,0", "--deg"]) == 0
    assert "1.8" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["fk", "puma560", "--q", "0,0"], "--q needs 6 values (one per joint), got 2"),
        (["fk", "puma560", "--q", "0,0,0,0,0,__import__('os')"], "names with double underscores"),
        (["fk", "planar2r", "--q", "1,x"], "--q value 2 (x) must be a real number"),
        (["fk", "planar2r", "--q", "0e99999999999,0"], "exponent 99999999999"),
        (["show", "nothing-here"], "no built-in robot or table file 'nothing-here'"),
        (["derive", "planar2r", "--to", "9"], "frames of Planar 2R are 0"),
    ],
)
def test_bad_input_exits_2_with_one_line(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("dhsym: error: ") and message in err
    assert err.count("\n") == 1


def test_bad_table_file_names_file_row_field(tmp_path, capsys):
    p = tmp_path / "bad.yaml"
    p.write_text("joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 90}]\n")
    assert main(["show", str(p)]) == 2
    err = capsys.readouterr().err
    assert "bad.yaml: row 1, field alpha: angle 90 is larger than 2*pi radians" in err


def test_console_script_runs_without_traceback(tmp_path):
    out = subprocess.run(
        [sys.executable, "-m", "dhsym", "fk", "planar2r", "--q", "1"],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 2 and "Traceback" not in out.stderr


def test_complex_joint_value_is_a_clean_error(capsys):
    assert main(["fk", "planar2r", "--q", "sqrt(-1),0"]) == 2
    assert "--q value 1 (sqrt(-1)) must be a real number" in capsys.readouterr().err


def test_show_prints_lengths_as_the_decimals_written(capsys):
    assert main(["show", "puma560"]) == 0
    out = capsys.readouterr().out
    assert "values: a2 = 0.4318, a3 = 0.0203, d3 = 0.15005, d4 = 0.4318" in out
    assert "2159/5000" not in out


def test_decimal_angles_read_as_exact_are_noted_on_stderr(tmp_path, capsys):
    from pathlib import Path

    import dhsym

    puma = (Path(dhsym.__file__).parent / "model" / "robots" / "puma560.yaml").read_text()
    path = tmp_path / "puma.yaml"
    path.write_text(puma.replace("alpha: pi/2", "alpha: 1.5708").replace("pi/2", "1.5708"))
    note = "dhsym: note: Decimal angles read as exact: alpha ±1.5708 in rows 1, 3, 4, 5 as ±π/2"
    for argv in (
        ["show", str(path)],
        ["derive", str(path)],
        ["convert", str(path), "--to", "modified"],
    ):
        assert main(argv) == 0
        captured = capsys.readouterr()
        assert captured.err.count(note) == 1 and "cos(3927" not in captured.out
    assert main(["derive", str(path), "--format", "markdown"]) == 0
    assert "*Note:* Decimal angles read as exact" in capsys.readouterr().out
    assert main(["show", "puma560"]) == 0
    assert "note" not in capsys.readouterr().err


def _dhsym(*argv: str, timeout: float = 120) -> subprocess.CompletedProcess:
    """The console command in a fresh process; a hang fails the test instead of the suite."""
    return subprocess.run(
        [sys.executable, "-m", "dhsym", *argv], capture_output=True, text=True, timeout=timeout
    )


def test_show_refuses_devices_and_fifos_at_once(tmp_path):
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    for path in ("/dev/zero", str(fifo)):
        out = _dhsym("show", path)
        assert out.returncode == 2 and "Traceback" not in out.stderr
        assert out.stderr == f"dhsym: error: {path}: table file is not a regular file " + (
            "(a device, FIFO, socket or folder)\n"
        )


def _long_table(tmp_path, n: int, twisted: bool) -> str:
    rows = [
        f"  - {{type: R, theta: q{k}, d: 0.1, a: 0.2, alpha: {(-1) ** k * 90 if twisted else 0}}}"
        for k in range(1, n + 1)
    ]
    p = tmp_path / f"{'twisted' if twisted else 'planar'}{n}.yaml"
    p.write_text("angles: deg\njoints:\n" + "\n".join(rows) + "\n")
    return str(p)


def test_derive_of_a_long_or_exploding_chain_is_a_one_line_refusal(tmp_path, capsys):
    assert main(["derive", _long_table(tmp_path, 250, twisted=False)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "spans 250 links; a derivation shows at most 60" in err
    assert main(["derive", _long_table(tmp_path, 24, twisted=True)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "too large to write out in closed form" in err and "--from/--to" in err


def test_every_command_answers_on_a_sixty_row_twisted_table(tmp_path, capsys):
    """Every command, in this process (one derivation of the table, not one per command);
    the last one also from the shell."""
    table = _long_table(tmp_path, 60, twisted=True)
    q = ",".join(["0.1"] * 60)
    answer = tmp_path / "answer.txt"
    answer.write_text("[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]\n")
    runs = [
        ("list",),
        ("show", table),
        ("show", table, "--format", "yaml"),
        ("derive", table),
        ("derive", table, "--from", "55", "--to", "60", "--format", "json"),
        ("fk", table, "--q", q),
        ("convert", table, "--to", "modified"),
        ("check", "--key", table, "--question", "T0_60", "--answer", str(answer)),
        ("check", "--key", table, "--question", "T3_5", "--answer", str(answer)),
        ("handout", table, "-o", str(tmp_path / "h.tex")),
        ("plot", table, "--view", "2d", "-o", str(tmp_path / "p.png")),
    ]
    for argv in runs:
        code = main(list(argv))  # an exception, not an exit code, fails the test
        err = capsys.readouterr().err
        assert "Traceback" not in err, argv
        assert code in (0, 1, 2), (argv, err)
        if code == 2:
            assert err.startswith("dhsym: error: ") and err.count("\n") == 1, argv
    assert _dhsym("fk", table, "--q", q).returncode == 0


_FIVE = """name: five joints
joints:
  - {theta: theta1, d: 0.3, a: 0, alpha: pi/2}
  - {theta: theta2, d: 0, a: 0.4, alpha: 0}
  - {theta: theta3, d: 0, a: 0.3, alpha: pi/2}
  - {theta: theta4, d: 0.2, a: 0.1, alpha: pi/2}
  - {theta: theta5, d: 0.1, a: 0, alpha: 0}
"""


def test_no_closed_form_names_the_numeric_command_and_it_works(tmp_path, capsys):
    import json

    path = tmp_path / "five.yaml"
    path.write_text(_FIVE, encoding="utf-8")
    assert main(["derive", str(path), "--what", "ik"]) == 2
    err = capsys.readouterr().err
    assert f"dhsym ik {path} --pose" in err and "--numeric" in err
    q = [0.3, 0.5, -0.4, 0.2, 0.1]
    argv = ["ik", str(path), "--pose-of", ",".join(map(str, q)), "--numeric", "--json"]
    assert main([*argv, "--q0", "0.2,0.4,-0.3,0.1,0"]) == 0
    sol = json.loads(capsys.readouterr().out.splitlines()[-1])
    assert sol["converged"] and list(sol["q"].values()) == pytest.approx(q, abs=1e-8)


def test_singularities_without_a_factored_measure_name_the_manipulability(tmp_path, capsys):
    import numpy as np

    path = tmp_path / "five.yaml"
    path.write_text(_FIVE, encoding="utf-8")
    assert main(["derive", str(path), "--what", "singularities"]) == 2
    assert "--manipulability" in capsys.readouterr().err
    assert main(["fk", str(path), "--q", "0.3,0.5,-0.4,0.2,0.1", "--manipulability"]) == 0
    w = float(capsys.readouterr().out.rsplit("=", 1)[1])
    from dhsym.model.tablefile import read_table
    from dhsym.robot import Robot

    J = Robot(read_table(path)).jacob0([0.3, 0.5, -0.4, 0.2, 0.1])
    assert w == pytest.approx(np.prod(np.linalg.svd(J)[1]), rel=1e-5)  # printed to 6 digits


def test_ik_closed_form_at_a_pose(capsys):
    assert main(["ik", "planar2r", "--pose-of", "30,45", "--values", "a1=1,a2=1", "--json"]) == 0
    import json
    import math

    out = json.loads(capsys.readouterr().out.splitlines()[-1])
    assert [math.radians(30), math.radians(45)] in [
        pytest.approx(row, abs=1e-9) for row in out["q"]
    ]


def test_ik_json_is_alone_on_stdout_and_takes_a_rounded_pose(capsys):
    import json

    import numpy as np

    import dhsym

    r = dhsym.load("ur5")
    T = np.round(r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1]), 6)
    pose = ",".join(repr(float(x)) for x in T[:3].ravel())
    assert main(["ik", "ur5", "--pose", pose, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)  # the whole of stdout is the JSON
    assert len(out["q"]) == 8 and max(out["residual"]) <= 1e-6
    # none within 1e-9 of a pose rounded to 6 decimals: exit status 1 (issue 32, item 3)
    assert main(["ik", "ur5", "--pose", pose, "--json", "--tol", "1e-9"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert out["q"] == [] and "rigid pose" in out["reason"]
    q = "0.3,-0.5,0.4,0.2,0.7,-1.1"
    assert main(["ik", "ur5", "--pose-of", q, "--json"]) == 0
    captured = capsys.readouterr()
    assert len(json.loads(captured.out)["q"]) == 8 and "pose of --pose-of" in captured.err
