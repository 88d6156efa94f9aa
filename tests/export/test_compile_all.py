"""Every built-in robot, with its numbers and with ``--symbolic-lengths``, exported in every
language and built: C (``gcc -std=c99 -Wall -Wextra -Werror -pedantic``), C++ (``g++
-std=c++17``, all headers in one translation unit), Rust (one crate, warnings denied),
NumPy (imported and called) and MATLAB (run by Octave), each language in one compiler or
interpreter run. Python and Octave are also checked against ``robot.fk``, ``robot.jacobian``
and ``robot.ik`` at one configuration.

The parts are fk, Jacobian, the closed-form IK where the robot has one, and the inverse
dynamics where its inertial parameters are numbers; plus the campaign's planar 3R with a
length ``d2`` that only the IK's fk check reads. The exports are made once (one derivation
per robot, the programs shared by the languages: :func:`dhsym.export.export_languages`).
"""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.ik.choices import IKCache
from dhsym.model.library import builtin_names

from ..conftest import _need
from . import _harness as h
from .test_program import PLANAR_3R_D2, _robot

pytestmark = pytest.mark.slow


@dataclass(frozen=True)
class Case:
    """One robot in one mode, exported in every language under ``prefix``."""

    prefix: str
    robot: dhsym.Robot
    params: tuple[float, ...] | None
    ik: bool
    rne: bool
    files: dict[str, dict[str, str]]


def _robots() -> list[tuple[str, dhsym.Robot]]:
    return [(n, dhsym.load(n)) for n in builtin_names()] + [("planar3r_d2", _robot(PLANAR_3R_D2))]


def _export(robot: dhsym.Robot, symbolic: bool, cache: IKCache, prefix: str) -> tuple:
    def files(what: tuple[str, ...]) -> dict[str, dict[str, str]]:
        return dhsym.export.export_languages(
            robot, dhsym.export.LANGUAGES, what, prefix, symbolic, cache=cache
        )

    base: tuple[str, ...] = ("fk", "jacobian", "ik")
    try:
        out = files(base)
    except DHError as err:
        assert "IK" in str(err) or "6R" in str(err), err  # no closed form: fk and Jacobian
        base = ("fk", "jacobian")
        out = files(base)
    rne = False
    if not symbolic:
        try:
            out, rne = files((*base, "dynamics")), True
        except DHError as err:  # no numbers for the inertias (the Jaco's rne: test_rne)
            assert "numeric inertial parameters" in str(err), err
    return out, "ik" in base, rne


@pytest.fixture(scope="module")
def cases() -> list[Case]:
    out = []
    for name, robot in _robots():
        cache = robot.ik_cache()  # robot.ik below reads the same derivation
        for symbolic in (False, True):
            prefix = f"{name}_{'s' if symbolic else 'n'}"
            files, ik, rne = _export(robot, symbolic, cache, prefix)
            values = robot.table.value_map
            constants = robot.table.constants if symbolic else ()
            params = tuple(float(values[c]) for c in constants) if constants else None
            out.append(Case(prefix, robot, params, ik, rne, files))
    return out


def _write(cases: list[Case], lang: str, folder: Path) -> list[str]:
    folder.mkdir()
    names = []
    for case in cases:
        for name, text in case.files[lang].items():
            (folder / name).write_text(text)
            names.append(name)
    return names


def _run(cmd: list[str], folder: Path) -> str:
    done = subprocess.run(cmd, cwd=folder, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-4000:] + done.stdout[-2000:]
    return done.stdout


def test_every_robot_is_exported(cases):
    assert len(cases) == 2 * (len(builtin_names()) + 1) >= 36
    assert sum(c.ik for c in cases) >= 2 * 12  # all but the redundant arms and the Jaco
    assert all(c.files["c"][f"{c.prefix}.c"] for c in cases)


def test_c_builds(cases, tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    sources = [n for n in _write(cases, "c", tmp_path / "c") if n.endswith(".c")]
    flags = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-c"]
    _run(["gcc", *flags, *sources], tmp_path / "c")


def test_cpp_builds(cases, tmp_path):
    _need("g++", shutil.which("g++") is not None, "apt-get install g++")
    headers = _write(cases, "cpp", tmp_path / "cpp")
    includes = ["<cstdio>", "<cstdlib>", "<cstring>", *(f'"{n}"' for n in headers)]
    main = "".join(f"#include {i}\n" for i in includes) + "int main() { return 0; }\n"
    (tmp_path / "cpp" / "main.cpp").write_text(main)
    flags = ["-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic", "-fsyntax-only"]
    _run(["g++", *flags, "main.cpp"], tmp_path / "cpp")


def test_rust_builds(cases, tmp_path):
    rustc = h.rustc()
    _need("rustc", rustc is not None, "apt-get install rustc (or rustup)")
    assert rustc is not None
    modules = _write(cases, "rust", tmp_path / "rust")
    lib = "".join(f"pub mod {n.removesuffix('.rs')};\n" for n in modules)
    (tmp_path / "rust" / "lib.rs").write_text(lib)
    cmd = [rustc, "--edition", "2021", "--crate-type", "lib", "--emit=metadata", "-D", "warnings"]
    _run([*cmd, "lib.rs"], tmp_path / "rust")


def _check(case: Case, q: np.ndarray, T, J, solutions) -> None:
    robot = case.robot
    assert np.abs(np.asarray(T) - robot.fk(q)).max() <= 1e-12, case.prefix
    assert np.abs(np.asarray(J) - robot.jacobian(q)).max() <= 1e-12, case.prefix
    if case.ik:
        want = robot.ik(robot.fk(q)).q
        assert np.asarray(solutions).shape == want.shape, case.prefix
        for sol in np.asarray(solutions):  # each solution reproduces the pose
            assert np.abs(robot.fk(sol) - robot.fk(q)).max() <= 1e-9, case.prefix


def _configuration(robot: dhsym.Robot) -> np.ndarray:
    q = np.random.default_rng(5).uniform(-2.0, 2.0, len(robot.variables))
    for k, r in enumerate(r for r in robot.table.rows if r.variable is not None):
        if r.joint.value != "R":
            q[k] = 0.4
    return q


def test_python_imports_and_runs(cases, tmp_path):
    _write(cases, "python", tmp_path / "python")
    for case in cases:
        mod = h.load_python({}, case.prefix, tmp_path / "python")
        extra = () if case.params is None else (np.array(case.params),)
        q = _configuration(case.robot)
        T = mod.fk(q, *extra)
        solutions = mod.ik(case.robot.fk(q), *extra) if case.ik else None
        _check(case, q, T, mod.jacobian(q, *extra), solutions)
        if case.rne:
            tau = mod.rne(q, 0.5 * q, -q)
            assert np.allclose(tau, case.robot.rne(q, 0.5 * q, -q), rtol=1e-9, atol=1e-9)


def test_octave_runs(cases, tmp_path):
    _need("octave", shutil.which("octave-cli") is not None, "apt-get install octave")
    _write(cases, "matlab", tmp_path / "matlab")
    lines = []
    for case in cases:
        q = _configuration(case.robot)
        qs = "[" + " ".join(repr(float(v)) for v in q) + "]"
        p = "" if case.params is None else ", [" + " ".join(repr(v) for v in case.params) + "]"
        rows = ("; ".join(" ".join(repr(float(v)) for v in r) for r in case.robot.fk(q)),)
        T = "[" + rows[0] + "]"
        lines.append(f"fprintf('%.17g\\n', {case.prefix}_fk({qs}{p}).');")
        lines.append(f"fprintf('%.17g\\n', {case.prefix}_jacobian({qs}{p}).');")
        if case.ik:
            lines.append(f"[Q, c] = {case.prefix}_ik({T}{p}); fprintf('%d\\n', c);")
            lines.append("fprintf('%.17g\\n', Q.');")
        if case.rne:
            lines.append(f"fprintf('%.17g\\n', {case.prefix}_rne({qs}, {qs}, {qs}));")
    (tmp_path / "matlab" / "drive.m").write_text("\n".join(lines) + "\n")
    out = _run(["octave-cli", "--no-gui", "--quiet", "drive.m"], tmp_path / "matlab")
    numbers = [float(t) for t in out.split()]
    at = 0
    for case in cases:
        n = len(case.robot.variables)
        q = _configuration(case.robot)
        T = np.reshape(numbers[at : at + 16], (4, 4))
        J = np.reshape(numbers[at + 16 : at + 16 + 6 * n], (6, n))
        at += 16 + 6 * n
        solutions = None
        if case.ik:
            count = int(numbers[at])
            solutions = np.reshape(numbers[at + 1 : at + 1 + count * n], (count, n))
            at += 1 + count * n
        _check(case, q, T, J, solutions)
        if case.rne:
            assert np.isfinite(numbers[at : at + n]).all()
            at += n
    assert at == len(numbers)
