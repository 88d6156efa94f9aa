"""URDF files on the command line: convert both ways, show/derive/fk/plot with --tip."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.cli.main import main
from dhsym.formats.urdf import chain_from_urdf
from dhsym.model.tablefile import read_table

UR5 = str(Path(__file__).resolve().parents[1] / "data" / "urdf" / "ur5_robot.urdf")


def test_convert_urdf_to_a_table_file_with_its_origin(tmp_path: Path, capsys) -> None:
    out = tmp_path / "ur5.yaml"
    assert main(["convert", UR5, "--to", "modified", "--tip", "tool0", "-o", str(out)]) == 0
    text = out.read_text()
    assert text.startswith("# DH table (modified convention) of the URDF chain world -> tool0")
    assert "# Frame assignment:" in text
    table = read_table(out)
    q = np.linspace(-1, 1, 6)
    reference = chain_from_urdf(UR5, tip="tool0").fk(q)
    from dhsym.robot import Robot

    assert np.abs(Robot(table).fk(q) - reference).max() < 1e-9
    assert "fk agrees with the URDF chain" in capsys.readouterr().err


def test_convert_a_table_to_urdf_and_back(tmp_path: Path) -> None:
    arm = tmp_path / "puma.urdf"
    assert main(["convert", "stanford", "--to", "urdf", "-o", str(arm)]) == 0
    assert arm.read_text().startswith('<?xml version="1.0"?>')
    assert main(["show", str(arm), "--tip", "tool"]) == 0


def test_show_derive_fk_plot_take_urdf_files(tmp_path: Path, capsys) -> None:
    assert main(["show", UR5, "--tip", "tool0"]) == 0
    assert "| 1 | $\\theta_{1}$ | $0.089159$ |" in capsys.readouterr().out
    assert main(["derive", UR5, "--tip", "wrist_1_link", "--to", "1"]) == 0
    assert "0.089159" in capsys.readouterr().out
    assert main(["fk", UR5, "--tip", "tool0", "--q", "0,0,0,0,0,0", "--json"]) == 0
    assert '"matrix"' in capsys.readouterr().out
    picture = tmp_path / "ur5.svg"
    assert main(["plot", UR5, "--tip", "tool0", "-o", str(picture)]) == 0
    assert picture.stat().st_size > 1000


def test_errors_are_one_line(capsys) -> None:
    assert main(["show", UR5]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") <= 2 and "give the tip link" in err and "tool0" in err
    assert main(["show", "puma560", "--tip", "x"]) == 2
    assert "--tip and --base choose a chain in a URDF file" in capsys.readouterr().err


def test_export_lang_urdf_writes_one_file(tmp_path: Path) -> None:
    assert main(["export", "puma560", "--lang", "urdf", "-o", str(tmp_path / "gen")]) == 0
    text = (tmp_path / "gen" / "puma560.urdf").read_text()
    assert text.count("<inertial>") == 6
    q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
    back = chain_from_urdf(text, tip="tool")
    np.testing.assert_allclose(back.fk(q), dhsym.load("puma560").fk(q), atol=1e-12)
    arm = tmp_path / "arm.urdf"
    argv = ["export", "planar2r", "--lang", "urdf", "--values", "a1=1,a2=0.5", "-o", str(arm)]
    assert main(argv) == 0
    assert chain_from_urdf(arm.read_text(), tip="tool").n == 2
    argv = ["export", "puma560", "--lang", "urdf", "--prefix", "puma", "-o", str(tmp_path)]
    assert main(argv) == 0 and (tmp_path / "puma.urdf").is_file()
    assert main(["export", "puma560", "--lang", "urdf", "--what", "fk", "-o", str(tmp_path)]) == 2


_HOSTILE_NAMES = """<robot name="&lt;script&gt;alert(1)&lt;/script&gt;&#10;# Injected *title*">
<link name="base&#10;## x"/><link name="&lt;img src=x onerror=alert(1)&gt;"/>
<joint name="j" type="revolute"><parent link="base&#10;## x"/>
<child link="&lt;img src=x onerror=alert(1)&gt;"/><axis xyz="0 0 1"/></joint></robot>"""


def test_show_escapes_names_from_the_file(tmp_path: Path, capsys) -> None:
    path = tmp_path / "names.urdf"
    path.write_text(_HOSTILE_NAMES)
    assert main(["show", str(path)]) == 0
    out = capsys.readouterr().out
    assert "<script>" not in out and "<img" not in out
    assert out.startswith("# &lt;script&gt;alert(1)&lt;/script&gt; \\# Injected \\*title\\*\n")
    assert "\n## x" not in out  # a newline in a link name starts no heading
    assert main(["show", str(path), "--format", "yaml"]) == 0  # YAML quotes them
    assert 'name: "<script>alert(1)</script>\\n# Injected *title*"' in capsys.readouterr().out


# --- round trips: convert, then every command on the written file -----------------------------

_DATA = Path(UR5).parent
_TIPS = {
    "ur5_robot.urdf": "tool0",
    "panda.urdf": "panda_hand_tcp",
    "kinova.urdf": "j2s6s200_end_effector",
    "so100.urdf": "gripper",
}
_CASES = [
    pytest.param(
        file, to, marks=() if (file, to) == ("ur5_robot.urdf", "standard") else pytest.mark.slow
    )
    for file in _TIPS
    for to in ("standard", "modified", "urdf")
]


@pytest.mark.parametrize(("file", "to"), _CASES)
def test_converted_files_are_read_by_every_command(file: str, to: str, tmp_path: Path) -> None:
    source = _DATA / file
    out = tmp_path / f"arm.{'urdf' if to == 'urdf' else 'yaml'}"
    assert main(["convert", str(source), "--tip", _TIPS[file], "--to", to, "-o", str(out)]) == 0
    if to != "urdf":  # limits: numbers in the file's unit (once -565486677/(500000*pi))
        limits = re.findall(r"limits: \[([^\]]*)\]", out.read_text())
        assert limits and not any("pi" in pair for pair in limits)
    tip = ["--tip", "tool"] if to == "urdf" else []
    table = chain_from_urdf(source, tip=_TIPS[file]).table
    q = ",".join(["0.1"] * table.n)
    assert main(["show", str(out), *tip]) == 0
    assert main(["derive", str(out), *tip, "--format", "text"]) == 0
    assert main(["fk", str(out), *tip, "--q", q, "--rad"]) == 0
    assert main(["ik", str(out), *tip, "--pose-of", q, "--rad", "--numeric"]) == 0
    written = dhsym.Robot(read_table(out)) if to != "urdf" else chain_from_urdf(out, tip="tool")
    qs = np.full(table.n, 0.1)
    assert np.abs(written.fk(qs) - chain_from_urdf(source, tip=_TIPS[file]).fk(qs)).max() < 1e-9


def test_convert_like_a_reference_matches_it_or_lists_the_rows_that_cannot(tmp_path, capsys):
    # issue 32, item 5: dhsym convert x.urdf --like ur5
    out = tmp_path / "ur5.yaml"
    argv = ["convert", UR5, "--tip", "tool0", "--to", "standard", "-o", str(out)]
    assert main([*argv, "--like", "ur5"]) == 0
    err = capsys.readouterr().err
    assert "no equivalent choice" not in err and "fk agrees with the URDF chain" in err
    table = read_table(out)
    ur5 = dhsym.load("ur5").table
    for mine, theirs in zip(table.rows, ur5.rows, strict=True):
        assert float(mine.a) == pytest.approx(float(theirs.a.xreplace(ur5.value_map)))
        assert mine.alpha == theirs.alpha and mine.theta == theirs.theta
    assert main([*argv, "--like", "puma560"]) == 0
    err = capsys.readouterr().err
    assert "no equivalent choice of frames matches puma560 in every row:" in err
    assert "row 2: a = -0.425 here, 0.4318 in the reference: a length no frame choice" in err
    # a table, not only a URDF: the Panda's own modified table stays as it is
    assert main(["convert", "panda", "--to", "modified", "--like", "panda", "-o", "-"]) == 0
    assert "no equivalent choice" not in capsys.readouterr().err
    assert main(["convert", "panda", "--to", "urdf", "--like", "ur5"]) == 2
    assert main([*argv, "--like", "planar2r"]) == 2  # another number of rows: refused
    assert "no frame choice matches them" in capsys.readouterr().err


def test_show_prints_the_base_and_tool_transforms_with_the_table(capsys):
    assert main(["show", UR5, "--tip", "tool0"]) == 0
    out = capsys.readouterr().out
    assert "| 2 | $\\theta_{2}$ | $0$ | $-0.425$ | $0$ | R |" in out
    assert "base transform: $R_z(180^{\\circ})$" in out and "tool transform" not in out
    assert main(["show", "kuka_lwr4"]) == 0
    assert "tool transform: $T_z(dt)\\,R_z(-45^{\\circ})$" in capsys.readouterr().out


def test_a_huge_tip_is_not_echoed_in_full(capsys):
    # issue 34's leftover: a 100 kB --tip was echoed whole in the error
    tip = "x" * 100_000
    assert main(["show", UR5, "--tip", tip]) == 2
    err = capsys.readouterr().err
    assert "no link named 'xxxx" in err and "(100000 characters)" in err and len(err) < 2_000
    assert main(["show", "ur5", "--tip", "tool0"]) == 2
    assert "'ur5' is not one" in capsys.readouterr().err
