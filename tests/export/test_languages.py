"""Generated code in every language, built and run, against robot.fk, robot.jacobian and
robot.ik at random points: ≤ 1e-12 for fk and Jacobians, ≤ 1e-9 for IK solutions (same
number, same order as robot.ik)."""

from __future__ import annotations

import re
import shutil

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.export.ik_source import derivation

from ..conftest import _need
from . import _harness as h

#: built-in robots, and some converted to the other convention (both conventions)
ROBOTS = [
    "planar2r",
    "planar4r",
    "scara",
    "stanford",
    "puma560",
    "puma560_modified",
    "puma260",
    "example4_6dof",
    "example1_rrp",
    "cylindrical",
    "cartesian",
]
CONVERTED = ["planar2r", "scara", "stanford"]
#: the built-ins of the ik room: three parallel axes (UR), redundant arms (fk and Jacobian
#: only), the general 6R (its IK is not exported: fk and Jacobian only)
NEW = ["ur3", "ur5", "ur10", "panda", "kuka_lwr4", "jaco"]
#: chains read backwards (the inverted-chain family): the reversed PUMA and UR5
REVERSED = ["puma560@reversed", "ur5@reversed"]
#: the UR family and one inverted chain in every language
EVERY_LANGUAGE = ["ur5", "ur10", "ur5@reversed"]


def _robot(name: str) -> dhsym.Robot:
    if name.endswith("@reversed"):
        from dhsym.ik.inverted import reversed_table

        return dhsym.Robot(reversed_table(dhsym.load_table(name.split("@")[0])))
    if name.endswith("@modified"):
        table = dhsym.to_modified(dhsym.load_table(name.split("@")[0]))
        return dhsym.Robot(table)
    return dhsym.load(name)


ALL = ROBOTS + [f"{n}@modified" for n in CONVERTED]
C_AND_PYTHON = ALL + NEW + REVERSED
OTHERS = ALL + EVERY_LANGUAGE


def _has_ik(robot: dhsym.Robot) -> bool:
    try:
        derivation(robot)
    except DHError:
        return False
    return True


def _points(robot: dhsym.Robot, m: int = 6):
    rng = np.random.default_rng(7)
    n = len(robot.variables)
    q = rng.uniform(-2.5, 2.5, (m, n))
    for k, r in enumerate(r for r in robot.table.rows if r.variable is not None):
        if r.joint.value != "R":
            q[:, k] = rng.uniform(0.2, 0.8, m)
    return q, robot.fk(q)


def _wrapped(a: np.ndarray, b: np.ndarray, revolute: np.ndarray) -> float:
    d = a - b
    d[..., revolute] = np.remainder(d[..., revolute] + np.pi, 2 * np.pi) - np.pi
    return float(np.abs(d).max()) if d.size else 0.0


def _compare(robot, q, poses, result, ik: bool) -> None:
    fks, jacs, iks = result
    for row, F in zip(q, fks):
        assert np.abs(F - robot.fk(row)).max() <= 1e-12
    for row, J in zip(q, jacs):
        assert np.abs(J - robot.jacob0(row)).max() <= 1e-12
    if ik:
        revolute = np.array([r.joint.value == "R" for r in robot.table.rows if r.variable])
        for T, Q in zip(poses, iks):
            want = robot.ik(T)
            assert Q.shape == want.q.shape
            assert _wrapped(Q, want.q, revolute) <= 1e-9


def _run(lang: str, name: str, tmp_path) -> None:
    robot = _robot(name)
    ik = _has_ik(robot)
    what = ("fk", "jacobian", "ik") if ik else ("fk", "jacobian")
    files = dhsym.export(robot, lang, what=what, prefix="arm")
    q, poses = _points(robot)
    n = len(robot.variables)
    runner = {
        "c": h.run_c,
        "cpp": lambda *a: h.run_c(*a, cpp=True),
        "rust": h.run_rust,
        "matlab": h.run_octave,
        "python": h.run_python,
    }[lang]
    result = runner(files, "arm", q, poses, n, True, ik, tmp_path)
    _compare(robot, q, poses, result, ik)


@pytest.mark.parametrize("name", C_AND_PYTHON)
def test_python(name, tmp_path):
    _run("python", name, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("name", C_AND_PYTHON)
def test_c(name, tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    _run("c", name, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("name", OTHERS)
def test_cpp(name, tmp_path):
    _need("g++", shutil.which("g++") is not None, "apt-get install g++")
    _run("cpp", name, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("name", OTHERS)
def test_rust(name, tmp_path):
    _need("rustc", h.rustc() is not None, "apt-get install rustc (or rustup)")
    _run("rust", name, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("name", OTHERS)
def test_octave(name, tmp_path):
    _need("octave", shutil.which("octave") is not None, "apt-get install octave")
    _run("matlab", name, tmp_path)


@pytest.mark.slow
def test_symbolic_lengths_c_and_python(tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    robot = dhsym.load("puma560")
    files = dhsym.export(robot, "c", prefix="arm", symbolic_lengths=True)
    assert "ARM_NPARAMS 4" in files["arm.h"] and "0.4318" not in files["arm.c"]
    params = [float(v) for _, v in robot.table.values]  # a2, a3, d3, d4 (sorted by name)
    q, poses = _points(robot)
    result = h.run_c(files, "arm", q, poses, 6, True, True, tmp_path, params=params)
    _compare(robot, q, poses, result, True)
    py = dhsym.export(robot, "python", prefix="arm", symbolic_lengths=True)
    (tmp_path / "py").mkdir()
    result = h.run_python(py, "arm", q, poses, 6, True, True, tmp_path / "py", params=params)
    _compare(robot, q, poses, result, True)


@pytest.mark.parametrize("name", ["ur5", "ur3", "ur5@reversed"])
def test_ik_of_the_new_families_has_every_branch(name):
    """The UR and the inverted chain export their eight branches, in robot.ik's order."""
    robot = _robot(name)
    files = dhsym.export(robot, "c", what="ik", prefix="arm")
    assert "#define ARM_MAX_IK_SOLUTIONS 8" in files["arm.h"]
    family = robot.inverse().family
    assert family in ("three parallel axes", "inverted chain")
    assert len(re.findall(r"for \(i\d = 0; i\d < 2;", files["arm.c"])) == 3  # the sign loops


@pytest.mark.slow
@pytest.mark.parametrize("name", ["ur5", "ur3"])
def test_ur_ik_from_c_and_python_at_many_poses(name, tmp_path):
    """More random poses than :func:`_run`: the same branches, same order, ≤ 1e-9."""
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    robot = _robot(name)
    rng = np.random.default_rng(11)
    q = rng.uniform(-np.pi, np.pi, (40, 6))
    poses = robot.fk(q)
    for lang, runner in (("c", h.run_c), ("python", h.run_python)):
        files = dhsym.export(robot, lang, prefix="arm")
        (tmp_path / lang).mkdir()
        result = runner(files, "arm", q[:0], poses, 6, True, True, tmp_path / lang)
        counts = [len(Q) for Q in result[2]]
        assert counts == [len(robot.ik(T)) for T in poses] and max(counts) == 8
        _compare(robot, q[:0], poses, result, True)


@pytest.mark.parametrize("name", ["jaco", "planar4r", "panda"])
def test_ik_refused_clearly(name):
    robot = _robot(name)
    with pytest.raises(DHError) as err:
        dhsym.export(robot, "c", what="ik")
    if name == "jaco":
        assert "general 6R: the eigenvalue solver is not exported" in str(err.value)
    else:
        assert "no closed-form IK to export" in str(err.value)
