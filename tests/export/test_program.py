"""The exporters' programs: every name a generated function reads is declared in it.

The campaign's case: a planar 3R whose second row has a length ``d2`` that only the pose's
z (the fk) reads; with ``--symbolic-lengths`` the IK's fk check read ``p_d2``, which the
IK never declared (the check's expressions were not among those searched for parameters).
"""

from __future__ import annotations

import shutil

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.export.program import IKProgram, Program, fk_program, ik_program, jacobian_program
from dhsym.model.tablefile import read_table_text

from ..conftest import _need
from . import _harness as h

PLANAR_3R_D2 = """
name: planar 3R with d2
joints:
  - {type: R, theta: q1, d: 0, a: a1, alpha: 0}
  - {type: R, theta: q2, d: d2, a: a2, alpha: 0}
  - {type: R, theta: q3, d: 0, a: a3, alpha: 0}
values: {a1: 1, a2: 0.8, a3: 0.5, d2: 0.1}
"""

#: a length called x: its parameter p_x is also the name of the pose's x
LENGTH_X = """
name: planar 2R with x
joints:
  - {type: R, theta: q1, d: 0, a: x, alpha: 0}
  - {type: R, theta: q2, d: d2, a: a2, alpha: 0}
values: {x: 1, a2: 0.8, d2: 0.2}
"""


def _robot(text: str) -> dhsym.Robot:
    return dhsym.Robot(read_table_text(text))


def _read(program: Program | IKProgram) -> set[str]:
    """The names the function's expressions read."""
    return {
        s.name for e in program.expressions() for s in e.free_symbols if isinstance(s, sp.Symbol)
    }


def _declared(program: Program | IKProgram) -> set[str]:
    """The names the function has: its inputs, its parameters and its assignments."""
    names = {p.name for p in program.parameters} | {a.name for a in program.body}
    if isinstance(program, IKProgram):
        return names | {"T"} | {a.name for a in program.pose} | set(program.signs)
    return names | set(program.joints)


@pytest.mark.parametrize("text", [PLANAR_3R_D2, LENGTH_X])
@pytest.mark.parametrize("symbolic", [False, True])
def test_every_name_a_function_reads_is_declared(text, symbolic):
    robot = _robot(text)
    fk = fk_program(robot, symbolic_lengths=symbolic)
    programs = [fk, jacobian_program(robot, symbolic_lengths=symbolic)]
    programs.append(ik_program(robot, symbolic_lengths=symbolic))
    for program in programs:
        assert _read(program) <= _declared(program)
        assert program.parameters == fk.parameters  # the functions share one p
    if symbolic:
        ik = programs[-1]
        assert isinstance(ik, IKProgram)
        assert "p_d2" in _read(ik)  # only the check reads it, and it is declared


@pytest.mark.parametrize("lang", ["c", "cpp", "rust", "python", "matlab"])
def test_the_ik_declares_a_length_only_its_check_reads(lang):
    files = dhsym.export(_robot(PLANAR_3R_D2), lang, prefix="arm", symbolic_lengths=True)
    text = "\n".join(files.values())
    ik = text[text.index("ik(") :]
    declared = {
        "c": "const double p_d2 = p[3];",
        "cpp": "const double p_d2 = p[3];",
        "rust": "let p_d2 = p[3];",
        "python": "p_d2 = p[3]",
        "matlab": "p_d2 = p(4);",
    }[lang]
    assert declared in ik


def _points(robot: dhsym.Robot) -> tuple[np.ndarray, np.ndarray]:
    q = np.random.default_rng(3).uniform(-2.5, 2.5, (4, len(robot.variables)))
    return q, robot.fk(q)


def _params(robot: dhsym.Robot) -> list[float]:
    """The table's values in the order of ``p`` (its constants, sorted by name)."""
    values = robot.table.value_map
    return [float(values[c]) for c in robot.table.constants]


def _compare(robot: dhsym.Robot, q, poses, result) -> None:
    fks, jacs, iks = result
    for row, F, J in zip(q, fks, jacs):
        assert np.abs(F - robot.fk(row)).max() <= 1e-12
        assert np.abs(J - robot.jacobian(row)).max() <= 1e-12
    for T, Q in zip(poses, iks):
        want = robot.ik(T).q
        assert Q.shape == want.shape and len(Q) >= 1
        assert np.abs(np.angle(np.exp(1j * (Q - want)))).max() <= 1e-9


@pytest.mark.parametrize("text", [PLANAR_3R_D2, LENGTH_X])
def test_symbolic_lengths_run_in_python(text, tmp_path):
    robot = _robot(text)
    params = _params(robot)
    files = dhsym.export(robot, "python", prefix="arm", symbolic_lengths=True)
    q, poses = _points(robot)
    n = len(robot.variables)
    _compare(robot, q, poses, h.run_python(files, "arm", q, poses, n, True, True, tmp_path, params))


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["c", "cpp", "rust"])
@pytest.mark.parametrize("text", [PLANAR_3R_D2, LENGTH_X])
def test_symbolic_lengths_build_and_run(lang, text, tmp_path):
    if lang == "rust":
        _need("rustc", h.rustc() is not None, "apt-get install rustc (or rustup)")
    else:
        compiler = "gcc" if lang == "c" else "g++"
        _need(compiler, shutil.which(compiler) is not None, f"apt-get install {compiler}")
    robot = _robot(text)
    params = _params(robot)
    files = dhsym.export(robot, lang, prefix="arm", symbolic_lengths=True)
    q, poses = _points(robot)
    n = len(robot.variables)
    if lang == "rust":
        result = h.run_rust(files, "arm", q, poses, n, True, True, tmp_path, params=params)
    else:
        result = h.run_c(files, "arm", q, poses, n, True, True, tmp_path, lang == "cpp", params)
    _compare(robot, q, poses, result)
