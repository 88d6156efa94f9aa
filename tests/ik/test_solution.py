"""One solution type for every solver (issue 31): the closed form, the general 6R, the
numeric solver and the compiled C answer the same pose with the same fields."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.ik import IKSolution, numeric_ik
from dhsym.ik.closed_form import ClosedForm
from dhsym.ik.general6r import Elimination
from dhsym.ik.protocols import IKSolver, InverseKinematics

Q_PUMA = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])


def _wrapped(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The largest joint difference modulo 2π between rows of ``a`` and a row ``b``."""
    return np.abs(np.angle(np.exp(1j * (a - b)))).max(axis=-1)  # type: ignore[no-any-return]


def _fields(sol: IKSolution, method: str, n: int) -> None:
    """What every solver's answer for one pose holds."""
    assert isinstance(sol, IKSolution) and not sol.batch
    assert sol.method == method
    assert sol.q.shape == (len(sol), n)
    assert sol.valid.shape == sol.residual.shape == (len(sol),)
    assert len(sol.branches) == len(sol.singular) == len(sol)
    assert sol.valid.all() and sol.converged
    assert (sol.residual < 1e-9).all()
    assert sol.reason is None


def test_closed_form_numeric_and_compiled_answer_the_same_pose_alike() -> None:
    robot = dhsym.load("puma560")
    T = robot.fk(Q_PUMA)
    closed = robot.ik(T)
    numeric = numeric_ik(robot, T, Q_PUMA + 0.05)
    _fields(closed, "closed form", 6)
    _fields(numeric, "numeric", 6)
    assert len(closed) == 8 and len(numeric) == 1
    assert numeric.iterations is not None and numeric.iterations > 0
    # the numeric solution is one of the closed form's, the generating q among them
    assert _wrapped(closed.q, numeric.q[0]).min() < 1e-8
    assert _wrapped(closed.q, Q_PUMA).min() < 1e-9
    if shutil.which("cc") or shutil.which("gcc"):
        compiled = robot.compiled().ik(T)
        _fields(compiled, "compiled", 6)
        assert len(compiled) == len(closed)
        # each compiled row is a closed-form row, and named as robot.ik names it
        for row, name in zip(compiled.q, compiled.branches, strict=True):
            k = int(_wrapped(closed.q, row).argmin())
            assert _wrapped(closed.q[k], row) < 1e-9
            assert closed.branches[k] == name


@pytest.mark.slow
def test_the_general_6r_answers_with_the_same_fields() -> None:
    robot = dhsym.load("jaco")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    T = robot.fk(q)
    general = robot.ik(T)
    _fields(general, "general 6R", 6)
    assert general.branches[0] == "solution 1"
    numeric = numeric_ik(robot, T, q + 0.05)
    _fields(numeric, "numeric", 6)
    assert _wrapped(general.q, numeric.q[0]).min() < 1e-8
    assert _wrapped(general.q, q).min() < 1e-9


def test_a_batch_is_the_same_type_over_a_leading_axis() -> None:
    robot = dhsym.load("puma560")
    qs = np.stack([Q_PUMA, Q_PUMA[::-1]])
    batch = robot.ik(robot.fk(qs))
    assert isinstance(batch, IKSolution) and batch.batch and batch.method == "closed form"
    assert batch.q.shape == (2, 8, 6) and batch.valid.shape == batch.residual.shape == (2, 8)
    one = robot.ik(robot.fk(qs[1]))
    assert batch.solution(1).branches == one.branches
    assert np.allclose(batch.solution(1).q, one.q)
    with pytest.raises(DHError, match="solution\\(i\\)"):
        _ = batch.branches
    with pytest.raises(DHError, match="this is one pose"):
        one.solution(0)


def test_an_empty_answer_says_why() -> None:
    robot = dhsym.load("puma560")
    far = np.eye(4)
    far[:3, 3] = (10.0, 0.0, 0.0)  # out of reach
    sol = robot.ik(far)
    assert len(sol) == 0 and not sol.converged
    assert sol.reason.startswith("no branch of the closed form reproduces the pose within 1e-09")
    assert "no real value of theta" in sol.reason  # the step with no real value, named
    lost = numeric_ik(robot, far, max_iter=3)
    assert not lost.converged and lost.reason == "did not converge in 3 iterations"
    assert len(lost) == 1 and not lost.valid[0]  # the last iterate is kept, marked invalid


def test_derivations_and_solvers_are_told_apart_by_type() -> None:
    puma = dhsym.load("puma560")
    ik = puma.inverse()
    assert isinstance(ik, ClosedForm) and isinstance(ik, InverseKinematics)
    assert not isinstance(ik, Elimination)
    assert isinstance(puma.ik_cache().solver(), IKSolver)
    assert puma.ik_cache().solver() is puma.ik_cache().solver()
