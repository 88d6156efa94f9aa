"""Homework on trajectories and gains: coefficients, blend time, peak velocity, position
at a time, gains for critical damping, and the typical mistakes named."""

from __future__ import annotations

import pytest

from dhsym.checking.comparing.verdict import Verdict
from dhsym.checking.judging.trajectory_judge import TrajectoryKey, check_trajectory_answer
from dhsym.errors import DHError


def check(key: TrajectoryKey, question: str, answer: str) -> tuple[str, tuple[str, ...]]:
    r = check_trajectory_answer(key, question, answer)
    return r.verdict.value, r.kinds


def test_symbolic_coefficients_in_every_written_form() -> None:
    key = TrajectoryKey.of("quintic", q0="q0", qf="qf", tf="tf")
    for answer in ("10*(qf - q0)/tf^3", "10 (q_f - q_0)/t_f**3", r"\frac{10(q_f-q_0)}{t_f^3}"):
        assert check(key, "traj a3", answer) == ("correct", ())
    assert check(key, "traj a3", "10*(qf - q0)/tf^2") == ("incorrect", ("tf_for_tf_squared",))
    assert check(key, "traj a3", "10*(qf - q0)/tf^4")[1] == ()


def test_boundary_velocity_left_out() -> None:
    key = TrajectoryKey.of("cubic", q0=0, qf=1, tf=2, v0=0.5, vf=0)
    # a2 = 3/4 − (2·0.5 + 0)/2 = 1/4; from rest it would be 3/4
    assert check(key, "traj a2", "0.25") == ("correct", ())
    assert check(key, "traj a2", "3/4") == ("incorrect", ("boundary_velocity_left_out",))


def test_blend_time_and_the_wrong_limit() -> None:
    key = TrajectoryKey.of("minimum_time", q0=0, qf=0.5, vmax=1, amax=1)  # never cruises
    assert check(key, "tb", "sqrt(0.5)") == ("correct", ())
    assert check(key, "tb", "0.7071") == ("correct", ())
    assert check(key, "t_b", "1") == ("incorrect", ("blend_time_wrong_limit",))
    key = TrajectoryKey.of("lspb", q0=0, qf=1, tf=2, a=2)
    assert check(key, "tb", "1 - sqrt(2)/2") == ("correct", ())
    assert check(key, "tb", "1 + sqrt(2)/2") == ("incorrect", ("blend_time_wrong_limit",))


def test_peak_velocity_and_position_at_a_time() -> None:
    assert check(TrajectoryKey.of("cubic", q0=0, qf=1, tf=2), "vmax", "3/4") == ("correct", ())
    assert check(TrajectoryKey.of("quintic", q0=0, qf=1, tf=2), "peak", "15/16") == ("correct", ())
    assert check(TrajectoryKey.of("lspb", q0=1, qf=3, tf=2, V=1.8), "vmax", "1.8") == (
        "correct",
        (),
    )
    key = TrajectoryKey.of("quintic", q0=0, qf=1, tf=1)
    assert check(key, "q@0.5", "1/2") == ("correct", ())
    assert check(key, "q@0.25", "0.1035") == ("correct", ())  # 53/512 to 3 digits
    assert check(key, "q@0.25", "0.2")[0] == "incorrect"


def test_gains_for_critical_damping() -> None:
    key = TrajectoryKey.of("gains", omega=10)
    assert check(key, "kp", "100") == ("correct", ())
    assert check(key, "kd", "20") == ("correct", ())
    assert check(key, "kd", "10") == ("incorrect", ("kd_without_two",))
    assert check(key, "kp", "10") == ("incorrect", ("kp_not_squared",))
    sym = TrajectoryKey.of("gains", omega="omega", zeta="zeta")
    assert check(sym, "kd", "2 zeta omega") == ("correct", ())


def test_unreadable_and_bad_questions() -> None:
    key = TrajectoryKey.of("cubic", q0=0, qf=1, tf=2)
    r = check_trajectory_answer(key, "traj a2", "__import__('os')")
    assert r.verdict is Verdict.UNREADABLE
    with pytest.raises(DHError, match="unknown trajectory question"):
        check_trajectory_answer(key, "traj b2", "1")
    with pytest.raises(DHError, match="a cubic has a0 … a3"):
        check_trajectory_answer(key, "traj a4", "1")
    with pytest.raises(DHError, match="takes no V"):
        TrajectoryKey.of("cubic", q0=0, qf=1, tf=2, V=1)
