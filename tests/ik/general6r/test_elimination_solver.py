"""The general 6R behind ``Robot.ik`` and ``derive --what ik``: every six-joint DH model of
roboticstoolbox solved (8/8), a joint given, limits, near, batches, the refusal without
numbers, and the derivation document."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.cli.main import main
from dhsym.errors import DHError
from dhsym.explain.inverse_kinematics import derive_inverse
from dhsym.ik import IKSolution
from dhsym.ik.general6r import Elimination
from dhsym.model.tablefile import read_table

DATA = Path(__file__).parents[2] / "data" / "rtb"
GENERAL = ("jaco", "mico")
CLOSED = ("irb140", "kr5", "puma560", "ur3", "ur5", "ur10")


def _random_q(n: int, joints: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, joints))


def _distance(batch_q: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``(N,)`` the smallest distance (angles modulo 2π) from ``q[i]`` to a solution of pose i."""
    d = np.abs(np.angle(np.exp(1j * (batch_q - q[:, None, :]))))
    return np.nan_to_num(d, nan=np.inf).max(axis=-1).min(axis=-1)  # type: ignore[no-any-return]


@pytest.mark.parametrize(
    "name", [*CLOSED, *(pytest.param(n, marks=pytest.mark.slow) for n in GENERAL)]
)
def test_every_six_joint_model_of_roboticstoolbox_is_solved(name: str) -> None:
    robot = dhsym.Robot(read_table(DATA / f"{name}.yaml"))
    q = _random_q(100, 6, seed=len(name))
    batch = robot.ik(robot.fk(q))
    assert isinstance(batch, IKSolution) and batch.batch
    assert (_distance(batch.q, q) < 1e-8).all()
    assert (batch.residual[batch.valid] <= 1e-9).all()
    family = robot.inverse().family
    assert (family == "general 6R") == (name in GENERAL)
    if name in GENERAL:  # the real roots of a real polynomial of degree 16: an even number
        assert (batch.count % 2 == 0).all()


@pytest.mark.slow
def test_a_jaco_solution_that_needs_more_than_six_newton_steps_is_kept() -> None:
    robot = dhsym.Robot(read_table(DATA / "jaco.yaml"))
    q = np.random.default_rng(1).uniform(-np.pi, np.pi, (100, 6))[97]
    sol = robot.ik(robot.fk(q))
    assert len(sol) == 8  # a multi-start search finds 8; one needs more than six Newton steps
    assert sol.residual.max() < 1e-12


@pytest.mark.slow
def test_the_built_in_jaco_one_pose_batch_limits_and_near() -> None:
    robot = dhsym.load("jaco")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T = robot.fk(q)
    sol = robot.ik(T)
    assert isinstance(sol, IKSolution) and sol.method == "general 6R"
    assert 2 <= len(sol) <= 16
    assert sol.branches == tuple(f"solution {k}" for k in range(1, len(sol) + 1))
    assert np.abs(robot.fk(sol.q) - T).max() < 1e-9
    nearest = robot.ik(T, near=q + 0.01)
    assert np.abs(nearest.q[0] - q).max() < 1e-9
    assert set(nearest.branches) == set(sol.branches)  # the names follow the solutions
    # the same pose in a batch gives the same solutions
    batch = robot.ik(np.stack([T, T]))
    assert batch.count.tolist() == [len(sol)] * 2
    assert np.allclose(batch.solution(1).q, sol.q)
    assert batch.solution(0).branches == sol.branches
    # limits: a table with ±1.2 rad on every joint keeps exactly the solutions inside
    bound = sp.Rational(6, 5)
    rows = tuple(replace(r, limits=(-bound, bound)) for r in robot.table.rows)
    limited = dhsym.Robot(replace(robot.table, rows=rows))
    kept = limited.ik(T, limits=True)
    inside = (np.abs(sol.q) <= 1.2).all(axis=1)
    assert len(kept) == int(inside.sum()) >= 1
    # the elimination compiled while deriving is the solver's, kept in the robot's cache
    ik = robot.inverse()
    assert isinstance(ik, Elimination) and robot.ik_cache().solver().core is ik.core


@pytest.mark.slow
def test_the_panda_with_joint_1_given_is_a_general_6r() -> None:
    robot = dhsym.load("panda")
    q = np.random.default_rng(3).uniform(-2.5, 2.5, (8, 7))
    for row in q:
        sol = robot.ik(robot.fk(row), free={1: row[0]})
        assert sol.method == "general 6R"
        d = np.abs(np.angle(np.exp(1j * (sol.q - row)))).max(axis=1)
        assert d.min() < 1e-8


@pytest.mark.slow
def test_symbolic_lengths_need_values() -> None:
    table = read_table(DATA / "mico.yaml")
    values = table.value_map
    robot = dhsym.Robot(replace(table, values=()))
    assert robot.inverse().family == "general 6R"  # derived without numbers
    q = np.array([0.2, 0.4, -0.6, 1.0, 0.5, -0.3])
    T = dhsym.Robot(table).fk(q)
    with pytest.raises(DHError, match="general 6R is solved in numbers: give values for D1, D2"):
        robot.ik(T)
    sol = robot.ik(T, values=values)
    assert np.abs(np.angle(np.exp(1j * (sol.q - q)))).max(axis=1).min() < 1e-8


def test_a_position_alone_is_refused() -> None:
    robot = dhsym.load("jaco")
    with pytest.raises(DHError, match="give a full 4×4 pose"):
        robot.ik([0.1, 0.2, 0.3])


@pytest.mark.slow
def test_the_derivation_names_the_method_and_every_format_renders(capsys) -> None:
    ik = dhsym.load("jaco").inverse()
    assert ik.structure == "no three consecutive axes parallel or meeting: general 6R"
    assert ik.count == 16 and ik.branches == ()
    text = " ".join(s.text for s in ik.steps)
    for words in ("Raghavan and Roth", "Manocha and Canny", "14×9", "16×16", "Newton"):
        assert words in text
    d = derive_inverse("jaco", check=True)
    assert [p.title for p in d.parts] == [
        "The Raghavan–Roth elimination",
        "The eigenproblem: joint 3",
    ]
    names = ["".join(r.words for r in name) for name, _ in d.check.solutions]
    assert names[0] == "solution 1" and len(names) >= 2
    for fmt in ("text", "markdown", "latex"):
        assert main(["derive", "jaco", "--what", "ik", "--format", fmt]) == 0
        out = capsys.readouterr().out
        assert "general 6R" in out and "Manocha and Canny" in out
    assert main(["derive", "jaco", "--what", "ik", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["count"] == 16 and data["steps"][0]["lhs"] == "E_1"
