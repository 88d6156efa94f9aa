# ruff: noqa: E501
"""The exported inverse dynamics ``rne(q, qd, qdd)`` in every language, built and run,
against ``robot.rne`` at random states (some joints at rest, where Coulomb friction is 0):
≤ 1e-9 relative, for the PUMA 560 (published parameters, motor inertia, friction),
numeric 2R (standard DH) and 3R (modified DH, friction; and with its variables at rates
−1, 2, −1/2 in their cells) arms and the Jaco (its first joint's
variable enters as ``theta: -theta1``: the joint turns at −q̇1 and τ1 is the generalized
force of q1; illustrative inertias, friction at that joint). The program's operation count
(issue 33: the PUMA's under 400), and the recursion it is made from against the dynamics
room's, also on the Stanford arm (a prismatic joint) and the UR5 with numbers for every
inertial parameter."""

from __future__ import annotations

import shutil
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.dynamics.compiled_dynamics import numeric_model
from dhsym.dynamics.model import dynamic_model
from dhsym.dynamics.recursive_newton_euler import rne_expressions
from dhsym.errors import DHError
from dhsym.export.program import _rne_recursion, rne_program
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


# the 3R arm with its variables at rates -1, 2 and -1/2 in their cells (friction at the
# flipped joint and at the doubled one, whose gear is reversed)
ARM_3R_RATES = (
    ARM_3R.replace("theta: q1,", "theta: -q1,")
    .replace("theta: q2,", "theta: 2*q2 + pi/2,")
    .replace("theta: q3,", "theta: pi/3 - q3/2,")
)

#: the built-in Jaco's table with inertias (``theta: -theta1``)
JACO = Path(__file__).resolve().parents[1] / "data" / "dynamics" / "jaco_inertial.yaml"


def _robots():
    return {
        "puma560": dhsym.load("puma560"),
        "arm2r": dhsym.Robot(read_table_text(ARM_2R)),
        "arm3r_modified": dhsym.Robot(read_table_text(ARM_3R)),
        "arm3r_rates": dhsym.Robot(read_table_text(ARM_3R_RATES)),
        "jaco": dhsym.load(str(JACO)),
    }


NAMES = ["puma560", "arm2r", "arm3r_modified", "arm3r_rates", "jaco"]


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


def _generic_values(robot: dhsym.Robot) -> dict[str, sp.Expr]:
    """A number for every inertial symbol of a table without them: every centre-of-mass
    component and every product of inertia nonzero (nothing for the program to drop)."""
    values: dict[str, sp.Expr] = {}
    for s in dynamic_model(robot).parameters:
        name, k = s.name, int("".join(c for c in s.name if c.isdigit()) or 1)
        if name.startswith("m"):
            values[name] = sp.Rational(10 + k, 4)
        elif name[:3] in ("Ixx", "Iyy", "Izz"):
            values[name] = sp.Rational(20 + k + 3 * "xyz".index(name[1]), 100)
        elif name.startswith("I"):
            values[name] = sp.Rational(k, 1000)
        elif name.startswith("r"):
            values[name] = (-1) ** k * sp.Rational(k + 2 * "xyz".index(name[1]), 50)
        else:
            raise AssertionError(f"no value for {name}")
    return values


def _model(name: str):
    if name in NAMES:
        robot = _robots()[name]
        return robot, None
    robot = dhsym.load(name)
    return robot, _generic_values(robot)


def _at(point: dict) -> Callable[[sp.Expr], sp.Expr]:
    """Each step of a recursion evaluated at ``point`` as it is made."""
    return lambda e: e.xreplace(point)


# mul, add of the exported rne (sympy.count_ops: MUL + DIV, ADD + SUB); before the
# arrangement of export.program._rne_recursion: PUMA 560 258 + 217, Stanford 335 + 285,
# UR5 378 + 336 (the last two with _generic_values)
COUNTS = {"puma560": (210, 188), "stanford": (275, 270), "ur5": (309, 309)}


@pytest.mark.parametrize("name", sorted(COUNTS))
def test_the_rne_program_is_short_and_makes_no_trivial_products(name):
    robot, values = _model(name)
    prog = rne_program(robot, values=values)
    exprs = prog.expressions()
    total = sp.Add(*(sp.count_ops(e, visual=True) for e in exprs))
    ops = {str(s): int(total.coeff(s)) for s in total.free_symbols}
    mul = ops.get("MUL", 0) + ops.get("DIV", 0)
    add = ops.get("ADD", 0) + ops.get("SUB", 0)
    assert mul <= COUNTS[name][0] and add <= COUNTS[name][1], (mul, add)
    if name == "puma560":  # issue 33: at most 400 operations
        assert mul + add < 400 and ops.get("POW", 0) <= 10, ops
    for e in exprs:  # no product by 0 or ±1.0 (-1: a minus sign), no line that renames
        for m in sp.preorder_traversal(e):
            if m.is_Mul:
                assert all(a == -1 or abs(a) not in (0, 1) for a in m.args if a.is_Number), e
    assert not any(a.expr.is_Symbol for a in prog.body)


# the Jaco left out: its exact twists (sqrt(3) in cos and sin of pi/3) keep the exact
# recursion at float points from collapsing (twenty minutes); its program is checked
# against robot.rne in every language, and the recursion's rate in tests/dynamics
@pytest.mark.parametrize("name", [*(n for n in NAMES if n != "jaco"), "stanford", "ur5"])
def test_the_arranged_recursion_is_the_recursion_of_the_dynamics_room(name):
    """_rne_recursion (U matrices, moments about the joints' points, the wrist's last link
    carried) against rne_expressions on the same numbers: both conventions, a prismatic
    joint (Stanford), products of inertia and full centres of mass (Stanford, UR5)."""
    robot, values = _model(name)
    dm = numeric_model(robot, values)
    inputs = (*dm.variables, *dm.rates, *dm.accelerations)
    q, qd, qdd = _states(dm.n, 3)
    for state in zip(q, qd, qdd):
        at = _at(dict(zip(inputs, map(sp.Float, np.concatenate(state)))))
        a = np.array([float(e) for e in _rne_recursion(dm, at)])
        b = np.array([float(at(e)) for e in rne_expressions(dm, clean=at)])
        assert np.allclose(a, b, rtol=1e-12, atol=1e-12), (a, b)


def test_the_program_computes_the_recursion():
    """The straight-line program of a robot without friction, run line by line, gives the
    recursion's torques: what the printers write is what was proven."""
    robot, values = _model("stanford")
    prog = rne_program(robot, values=values)
    dm = numeric_model(robot, values)
    q, qd, qdd = _states(dm.n, 2)
    for state in zip(q, qd, qdd):
        known = {
            sp.Symbol(name, real=True): state[("q", "qd", "qdd").index(arr)][k]
            for name, arr, k in prog.inputs
        }
        for a in prog.body:
            known[sp.Symbol(a.name, real=True)] = float(a.expr.xreplace(known))
        got = np.array([float(o.expr.xreplace(known)) for o in prog.outputs])
        inputs = (*dm.variables, *dm.rates, *dm.accelerations)
        at = _at(dict(zip(inputs, map(sp.Float, np.concatenate(state)))))
        want = np.array([float(e) for e in rne_expressions(dm, clean=at)])
        assert np.allclose(got, want, rtol=1e-9, atol=1e-9), (got, want)
