# ruff: noqa: E501
"""The exported inverse dynamics ``rne(q, qd, qdd)`` in every language, built and run,
against ``robot.rne`` at random states (some joints at rest, where Coulomb friction is 0):
≤ 1e-9 relative, for the PUMA 560 (published parameters, motor inertia, friction) and
numeric 2R (standard DH) and 3R (modified DH, friction) arms."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.model.tablefile import read_table_text

from ..conftest import _need
from . import _harness as h

ARM_2R = """
name: two-link arm
convention: standard
gravity: [0, -9.81, 0]
joints:
  - {type: R, theta: q1, d: 0, a: 0.7, alpha: 0, m: 2.5, r: [-0.35, 0, 0], I: [0.01, 0.1, 0.1]}
  - {type: R, theta: q2, d: 0, a: 0.5, alpha: 0, m: 1.5, r: [-0.2, 0.01, 0], I: [0.01, 0.05, 0.05]}
"""

ARM_3R = """
name: three-link modified arm
convention: modified
joints:
  - {type: R, theta: q1, d: 0.3, a: 0, alpha: 0, m: 4, r: [0, 0, 0.1], I: [0.1, 0.1, 0.05], Jm: 0.0002, G: 50, B: 0.001, Tc: [0.3, -0.25]}
  - {type: R, theta: q2, d: 0, a: 0, alpha: pi/2, m: 3, r: [0.2, 0, 0.02], I: [0.02, 0.08, 0.08, 0.001, 0, 0.002], Jm: 0.0001, G: -40, B: 0.002, Tc: 0.2}
  - {type: R, theta: q3, d: 0.05, a: 0.4, alpha: 0, m: 2, r: [0.15, 0, 0], I: [0.01, 0.04, 0.04]}
"""


def _robots():
    return {
        "puma560": dhsym.load("puma560"),
        "arm2r": dhsym.Robot(read_table_text(ARM_2R)),
        "arm3r_modified": dhsym.Robot(read_table_text(ARM_3R)),
    }


NAMES = ["puma560", "arm2r", "arm3r_modified"]


def _states(n: int, m: int = 8) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(23)
    q = rng.uniform(-np.pi, np.pi, (m, n))
    qd = rng.uniform(-2, 2, (m, n))
    qdd = rng.uniform(-3, 3, (m, n))
    qd[0] = 0.0  # at rest: Coulomb friction is 0, as in robot.rne
    qd[1, ::2] = 0.0
    return q, qd, qdd


def _check(robot: dhsym.Robot, states, tau: np.ndarray) -> None:
    want = robot.rne(*states)
    scale = np.abs(want).max(axis=1, keepdims=True)
    assert tau.shape == want.shape
    assert np.all(np.abs(tau - want) <= 1e-9 * np.maximum(scale, 1.0))


def _stdin(states) -> str:
    q, qd, qdd = states
    rows = [str(len(q))]
    rows += [" ".join(repr(float(v)) for v in np.concatenate(s)) for s in zip(q, qd, qdd)]
    return "\n".join(rows) + "\n"


_C_MAIN = """
#include <stdio.h>
#include "arm.{ext}"
int main(void)
{{
    int m, i, j;
    double q[{N}], qd[{N}], qdd[{N}], tau[{N}];
    if (scanf("%d", &m) != 1) return 1;
    for (i = 0; i < m; ++i) {{
        for (j = 0; j < {N}; ++j) if (scanf("%lf", &q[j]) != 1) return 1;
        for (j = 0; j < {N}; ++j) if (scanf("%lf", &qd[j]) != 1) return 1;
        for (j = 0; j < {N}; ++j) if (scanf("%lf", &qdd[j]) != 1) return 1;
        {call}(q, qd, qdd, tau);
        for (j = 0; j < {N}; ++j) printf("%.17g\\n", tau[j]);
    }}
    return 0;
}}
"""

_RUST_MAIN = h.rust_main("""\
    let n = arm::NJOINTS;
    let m = v[0] as usize;
    for i in 0..m {
        let at = 1 + 3 * n * i;
        let mut q = [0.0; arm::NJOINTS];
        let mut qd = [0.0; arm::NJOINTS];
        let mut qdd = [0.0; arm::NJOINTS];
        for j in 0..n { q[j] = v[at + j]; qd[j] = v[at + n + j]; qdd[j] = v[at + 2 * n + j]; }
        for x in arm::rne(&q, &qd, &qdd).iter() { println!("{:e}", x); }
    }
""")


def _export(name: str, lang: str) -> tuple[dhsym.Robot, dict[str, str]]:
    robot = _robots()[name]
    return robot, dhsym.export(robot, lang, what="rne", prefix="arm")


def _c_like(name: str, tmp_path: Path, cpp: bool) -> None:
    robot, files = _export(name, "cpp" if cpp else "c")
    n = len(robot.variables)
    main = _C_MAIN.format(ext="hpp" if cpp else "h", N=n, call="arm::rne" if cpp else "arm_rne")
    prog = h.build_c(files, tmp_path, main, cpp)
    states = _states(n)
    _check(robot, states, h.numbers([str(prog)], tmp_path, _stdin(states)).reshape(-1, n))


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_c(name, tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    _c_like(name, tmp_path, cpp=False)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_cpp(name, tmp_path):
    _need("g++", shutil.which("g++") is not None, "apt-get install g++")
    _c_like(name, tmp_path, cpp=True)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_rust(name, tmp_path):
    rustc = h.rustc()
    _need("rustc", rustc is not None, "apt-get install rustc (or rustup)")
    robot, files = _export(name, "rust")
    prog = h.build_rust(files, tmp_path, _RUST_MAIN)
    n = len(robot.variables)
    states = _states(n)
    _check(robot, states, h.numbers([str(prog)], tmp_path, _stdin(states)).reshape(-1, n))


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_octave(name, tmp_path):
    _need("octave", shutil.which("octave") is not None, "apt-get install octave")
    robot, files = _export(name, "matlab")
    n = len(robot.variables)
    states = _states(n)
    np.savetxt(tmp_path / "s.txt", np.hstack(states), fmt="%.17g")
    script = (
        "S = dlmread('s.txt');\n"
        f"for i = 1:rows(S)\n  tau = arm_rne(S(i, 1:{n})', S(i, {n + 1}:{2 * n})', S(i, {2 * n + 1}:{3 * n})');\n"
        "  printf('%.17g\\n', tau);\nend\n"
    )
    _check(robot, states, h.octave(files, tmp_path, script).reshape(-1, n))


@pytest.mark.parametrize("name", NAMES)
def test_python(name, tmp_path):
    robot, files = _export(name, "python")
    module = h.load_python(files, "arm", tmp_path)
    states = _states(len(robot.variables))
    _check(robot, states, module.rne(*states))  # a batch
    one = module.rne(states[0][1], states[1][1], states[2][1])  # one state
    _check(robot, tuple(s[1:2] for s in states), one[None, :])


def test_rne_is_another_name_and_files_are_deterministic():
    robot = _robots()["arm2r"]
    a = dhsym.export(robot, "c", what="dynamics", prefix="arm", command="x")
    b = dhsym.export(robot, "c", what=["rne", "fk"], prefix="arm", command="x")
    assert a == b
    assert "void arm_rne(const double q[ARM_NJOINTS], const double qd[ARM_NJOINTS]" in a["arm.h"]
    assert "Outward pass" in a["arm.c"] and "Inward pass" in a["arm.c"]
    assert sorted(dhsym.export(robot, "matlab", what="rne", prefix="arm")) == [
        "arm_fk.m",
        "arm_njoints.m",
        "arm_rne.m",
    ]


def test_refused_without_numbers_or_with_symbolic_lengths():
    with pytest.raises(DHError, match="numeric inertial parameters; no number for .*m1"):
        dhsym.export(dhsym.load("planar2r"), "c", what="dynamics")
    with pytest.raises(DHError, match="without --symbolic-lengths"):
        dhsym.export(_robots()["arm2r"], "c", what="rne", symbolic_lengths=True)


def test_cli_exports_the_puma_dynamics(tmp_path):
    from dhsym.cli.main import main

    args = ["export", "puma560", "--lang", "c", "--what", "rne", "--prefix", "puma"]
    assert main([*args, "-o", str(tmp_path)]) == 0
    assert "void puma_rne(const double q[PUMA_NJOINTS]" in (tmp_path / "puma.h").read_text()
    assert "friction B G^2 qd + |G| Tc" in (tmp_path / "puma.c").read_text()


@pytest.mark.slow
def test_compiled_rne_matches_robot(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    robot = _robots()["arm3r_modified"]
    fast = robot.compiled("c")
    assert fast.backend == "c"
    q, qd, qdd = _states(3)
    tau = np.array([fast.rne(*s) for s in zip(q, qd, qdd)])
    _check(robot, (q, qd, qdd), tau)
