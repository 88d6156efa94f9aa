"""What the IK tests share: roboticstoolbox's models as data, random configurations, and
the round trip q → fk → ik that must contain q."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import dhsym

DATA = Path(__file__).parents[1] / "data" / "rtb"


def random_q(robot: dhsym.Robot, n: int, seed: int = 0) -> np.ndarray:
    """``n`` configurations drawn uniformly from (-π, π) for every joint."""
    rng = np.random.default_rng(seed)
    return rng.uniform(-np.pi, np.pi, (n, len(robot.variables)))


def recovered(robot: dhsym.Robot, q: np.ndarray, **kw: object) -> np.ndarray:
    """For each row of q: True when a solution of ik(fk(q)) equals it modulo 2π."""
    batch = robot.ik(robot.fk(q), **kw)
    d = batch.q - q[:, None, :]
    d = np.abs(np.angle(np.exp(1j * d)))  # angle differences modulo 2π
    return np.nan_to_num(d, nan=np.inf).max(axis=-1).min(axis=-1) < 1e-7
