"""The family classifier: relations of consecutive axes, in either convention."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import dhsym
from dhsym.ik import classify

DATA = Path(__file__).parents[1] / "data" / "rtb"


def _random_q(robot: dhsym.Robot, n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(-np.pi, np.pi, (n, len(robot.variables)))


def _recovered(robot: dhsym.Robot, q: np.ndarray, **kw: object) -> np.ndarray:
    """For each row of q: True when a solution of ik(fk(q)) equals it modulo 2π."""
    batch = robot.ik(robot.fk(q), **kw)
    d = batch.q - q[:, None, :]
    d = np.abs(np.angle(np.exp(1j * d)))  # angle differences modulo 2π
    return np.nan_to_num(d, nan=np.inf).max(axis=-1).min(axis=-1) < 1e-7


def test_the_classification_is_printed_from_the_axes_in_either_convention() -> None:
    ur5 = dhsym.load("ur5")
    assert str(classify(ur5)) == "axes 2, 3, 4 parallel"
    assert classify(ur5).family == "three parallel axes"
    modified = dhsym.Robot(dhsym.to_modified(ur5.table))
    assert str(classify(modified)) == "axes 2, 3, 4 parallel"
    assert str(classify(dhsym.load("puma560"))) == "axes 4, 5, 6 meet in a point"
    assert classify(dhsym.load("panda")).sentences == ("axes 1, 2, 3 meet in a point",)


def test_a_general_6r_is_solved_by_the_elimination() -> None:
    table = dhsym.load("puma560").table
    rows = list(table.rows)
    from dataclasses import replace

    rows[4] = replace(rows[4], a=0.05)
    rows[1] = replace(rows[1], alpha=0.3)
    r = dhsym.Robot(replace(table, rows=tuple(rows)))
    assert classify(r).family == "general 6R"
    assert r.inverse().family == "general 6R"
    assert _recovered(r, _random_q(r, 10)).all()
