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


_ROUNDED_MAIN = """
#include <stdio.h>
#include "arm.{h}"
int main(void)
{
    double T[16], S[ARM_MAX][ARM_N], R[ARM_MAX];
    int i, j, c;
    while (1) {
        for (j = 0; j < 16; ++j) if (scanf("%lf", &T[j]) != 1) return 0;
        c = CALL;
        printf("%d\\n", c);
        for (i = 0; i < c; ++i) {
            for (j = 0; j < ARM_N; ++j) printf("%.17g ", S[i][j]);
            printf("%.17g\\n", R[i]);
        }
    }
}
"""


def _same_solutions(robot, got, residual, want):
    """The exported solutions are robot.ik's (angles modulo 2π, residuals to rounding);
    robot.ik may list one solution twice where the stretched arm makes two branches meet."""
    assert len(got) <= len(want) and (len(got) == 0) == (len(want) == 0)
    for row, res in zip(got, residual):
        d = row - want.q
        d = np.abs(np.remainder(d + np.pi, 2 * np.pi) - np.pi).max(axis=1)
        k = int(d.argmin())
        assert d[k] <= 1e-8 and abs(res - want.residual[k]) <= 1e-12
    for row in want.q:
        d = row - got
        assert np.abs(np.remainder(d + np.pi, 2 * np.pi) - np.pi).max(axis=1).min() <= 1e-8


@pytest.mark.parametrize("lang", ["c", "cpp"])
@pytest.mark.parametrize("name", ["puma560", "ur5", "stanford"])
def test_exported_ik_takes_rounded_poses(name, lang, tmp_path):
    """The exported IK keeps robot.ik's tolerance rule (dhsym.ik.accuracy): on poses rounded
    to 6 and 3 decimals it finds robot.ik's solutions, with their residuals; a pose that
    is no rotation has none."""
    cc = "g++" if lang == "cpp" else "gcc"
    _need(cc, shutil.which(cc), f"apt-get install {cc}")
    robot = dhsym.load(name)
    files = dhsym.export(robot, lang, what=("fk", "ik"), prefix="arm")
    for file, text in files.items():
        (tmp_path / file).write_text(text)
    if lang == "c":
        call, head, defs = "arm_ik(T, 0.0, S, R)", "h", "-DARM_MAX=ARM_MAX_IK_SOLUTIONS"
        defs2, build = "-DARM_N=ARM_NJOINTS", ["gcc", "-std=c99", "main.c", "arm.c", "-lm"]
    else:
        call, head, defs = "arm::ik(T, S, R)", "hpp", "-DARM_MAX=arm::MAX_IK_SOLUTIONS"
        defs2, build = "-DARM_N=arm::NJOINTS", ["g++", "-std=c++17", "main.c"]
    (tmp_path / "main.c").write_text(_ROUNDED_MAIN.replace("CALL", call).replace("{h}", head))
    flags = ["-Wall", "-Wextra", "-Werror", "-O2", defs, defs2, "-o", "prog"]
    subprocess.run([*build[:2], *flags, *build[2:]], cwd=tmp_path, check=True)
    rng = np.random.default_rng(11)
    poses = []
    for q in rng.uniform(-3.0, 3.0, (8, len(robot.variables))):
        T = robot.fk(q)
        poses += [T, np.round(T, 6), np.round(T, 3)]
    mirrored = np.diag([1.0, 1.0, -1.0, 1.0])  # det -1: no rotation, no solution
    poses.append(mirrored)
    text = "\n".join(" ".join(repr(float(v)) for v in T.ravel()) for T in poses) + "\n"
    out = subprocess.run(
        [str(tmp_path / "prog")], input=text, capture_output=True, text=True, check=True
    ).stdout.split("\n")
    n = len(robot.variables)
    at = 0
    for T in poses:
        c = int(out[at])
        rows = np.array([[float(x) for x in line.split()] for line in out[at + 1 : at + 1 + c]])
        at += 1 + c
        if T is mirrored:
            assert c == 0
            continue
        rows = rows.reshape(c, n + 1)
        _same_solutions(robot, rows[:, :n], rows[:, n], robot.ik(T))


def _rounded_poses(robot):
    rng = np.random.default_rng(5)
    poses = []
    for q in rng.uniform(-3.0, 3.0, (6, len(robot.variables))):
        T = robot.fk(q)
        poses += [np.round(T, 6), np.round(T, 3)]
    return poses


@pytest.mark.parametrize("name", ["puma560", "ur5"])
def test_exported_python_ik_takes_rounded_poses(name, tmp_path):
    robot = dhsym.load(name)
    mod = h.load_python(
        dhsym.export(robot, "python", what=("fk", "ik"), prefix="arm"), "arm", tmp_path
    )
    for T in _rounded_poses(robot):
        q, residual = mod.ik_with_residual(T)
        _same_solutions(robot, q, residual, robot.ik(T))
        assert np.array_equal(mod.ik(T), q)
    assert len(mod.ik(np.diag([1.0, 1.0, -1.0, 1.0]))) == 0  # no rotation: none


def test_exported_octave_ik_takes_rounded_poses(tmp_path):
    _need("octave", shutil.which("octave"), "apt-get install octave")
    robot = dhsym.load("ur5")
    for file, text in dhsym.export(robot, "matlab", what=("fk", "ik"), prefix="arm").items():
        (tmp_path / file).write_text(text)
    poses = _rounded_poses(robot)
    np.savetxt(tmp_path / "t.txt", np.array(poses).reshape(len(poses), 16), fmt="%.17g")
    script = (
        "Ts = dlmread('t.txt');\n"
        "for i = 1:size(Ts, 1)\n"
        "  [Q, c, r] = arm_ik(reshape(Ts(i, :), 4, 4).');\n"
        "  fprintf('%d\\n', c); fprintf('%.17g\\n', [Q, r].');\n"
        "end\n"
    )
    (tmp_path / "drive.m").write_text(script)
    out = subprocess.run(
        ["octave", "--no-gui", "--quiet", "--no-window-system", "drive.m"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.split()
    n, at = len(robot.variables), 0
    for T in poses:
        c = int(out[at])
        rows = np.array([float(x) for x in out[at + 1 : at + 1 + c * (n + 1)]]).reshape(c, n + 1)
        at += 1 + c * (n + 1)
        _same_solutions(robot, rows[:, :n], rows[:, n], robot.ik(T))
