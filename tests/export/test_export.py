"""The API and CLI of the export room: names, determinism, hostile input, errors."""

from __future__ import annotations

import shutil
import subprocess

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.model.table import DHRow, DHTable

from ..conftest import _need
from . import _harness as h

HOSTILE = '*/ #include <stdlib.h>\n%{ system("rm -rf /") %} ??/ \\'


def _hostile_robot() -> dhsym.Robot:
    rows = [DHRow.revolute("theta1", a="a1"), DHRow.revolute("theta2", a="a2")]
    table = DHTable.from_rows(rows, name=HOSTILE, values={"a1": 1, "a2": 0.5})
    return dhsym.Robot(table)


def test_same_bytes_twice():
    r = dhsym.load("puma560")
    for lang in dhsym.export.LANGUAGES:
        assert dhsym.export(r, lang) == dhsym.export(dhsym.load("puma560"), lang)


@pytest.mark.parametrize("lang", ["c", "cpp", "matlab", "rust", "python"])
def test_hostile_names_stay_in_comments(lang):
    files = dhsym.export(_hostile_robot(), lang)  # the prefix is the name made an identifier
    for name, text in files.items():
        assert name.startswith("include_stdlib_h_system_rm_rf")
        assert "??/" not in text and "*/ #" not in text and "%{" not in text
        for line in text.splitlines():
            if "rm -rf" in line or "<stdlib" in line:  # the name stays inside one comment line
                assert line.lstrip().startswith(("* ", "// ", "% ", "# ", "/* "))
                assert "*/" not in line or line.rstrip().endswith("*/")


def test_hostile_c_compiles_and_runs(tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    robot = _hostile_robot()
    files = dhsym.export(robot, "c")
    q = np.array([[0.3, 0.4]])
    name = "include_stdlib_h_system_rm_rf"
    fks, jacs, iks = h.run_c(files, name, q, robot.fk(q), 2, True, True, tmp_path)
    assert np.abs(fks[0] - robot.fk(q[0])).max() <= 1e-12 and len(iks[0]) == 1


def test_python_module_runs_for_hostile_names(tmp_path):
    robot = _hostile_robot()
    mod = h.load_python(dhsym.export(robot, "python", prefix="class"), "class_", tmp_path)
    assert np.abs(mod.fk([0.1, 0.2]) - robot.fk([0.1, 0.2])).max() <= 1e-12


@pytest.mark.parametrize(
    "prefix", ["int main(){ */", "*/ x", "../../escaped", "/tmp/abs", "2r", ""]
)
def test_a_prefix_that_is_not_a_name_is_refused(prefix):
    with pytest.raises(DHError, match="is not a name"):
        dhsym.export(_hostile_robot(), "c", what="fk", prefix=prefix)


def test_dynamics_needs_numeric_inertial_parameters():
    with pytest.raises(DHError, match="needs numeric inertial parameters"):
        dhsym.export(dhsym.load("planar2r"), "c", what="fk,dynamics")


def test_unknown_language_and_missing_values():
    with pytest.raises(DHError, match="unknown language"):
        dhsym.export(dhsym.load("planar2r"), "fortran")
    table = DHTable.from_rows([DHRow.revolute("theta1", a="a1")], name="no values")
    with pytest.raises(DHError, match="symbolic-lengths"):
        dhsym.export(dhsym.Robot(table), "c", what="fk")
    files = dhsym.export(dhsym.Robot(table), "c", what="fk", symbolic_lengths=True)
    assert "NPARAMS 1" in files["no_values.h"]


def test_ik_comments_name_steps_and_branches():
    files = dhsym.export(dhsym.load("puma560"), "c", prefix="puma")
    text = files["puma.c"]
    r = dhsym.load("puma560")
    q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
    names = r.ik(r.fk(q)).branches
    for k, name in enumerate(names):
        assert f" *   {k}: {name}" in text
    assert "/* Step 4 (position):" in text and "PUMA_MAX_IK_SOLUTIONS 8" in files["puma.h"]


def test_cli_writes_the_files(tmp_path):
    from dhsym.cli.main import main

    assert main(["export", "planar2r", "--lang", "c", "--prefix", "arm", "-o", str(tmp_path)]) == 0
    text = (tmp_path / "arm.c").read_text()
    assert "made by: dhsym export planar2r --lang c --what fk,jacobian,ik --prefix arm" in text
    assert main(["export", "planar2r", "--lang", "urdf", "-o", str(tmp_path)]) == 0
    assert '<robot name="planar2r">' in (tmp_path / "planar2r.urdf").read_text()
    assert (
        main(["export", "planar2r", "--lang", "c", "--what", "dynamics", "-o", str(tmp_path)]) == 2
    )


def test_gcc_is_warning_free_for_puma(tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    for name, text in dhsym.export(dhsym.load("puma560"), "c", prefix="puma").items():
        (tmp_path / name).write_text(text)
    flags = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-c", "puma.c"]
    done = subprocess.run(["gcc", *flags], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0 and done.stderr == ""
