"""Trajectory and gain answers judged: right answers in every written form, decimals at the
rounding rule, each catalogued mistake named, wrong answers never right, hostile answers
refused with a reason."""

from __future__ import annotations

import pytest

from dhsym.checking.comparing.verdict import Verdict
from dhsym.checking.judging.checker import check_answer
from dhsym.checking.judging.key import PreparedKeys
from dhsym.checking.judging.trajectory_key import TrajectoryKey
from dhsym.checking.reading.limits import AnswerLimits


def check(spec: str, question: str, answer: str, **kw: object) -> tuple[str, tuple[str, ...]]:
    r = check_answer(TrajectoryKey.load(spec, question, **kw), answer)  # type: ignore[arg-type]
    return r.verdict.value, r.kinds


SYMBOLIC_CUBIC = "cubic(q0=q0, qf=qf, tf=tf)"
SYMBOLIC_QUINTIC = "quintic(q0=q0, qf=qf, tf=tf)"


@pytest.mark.parametrize(
    "answer",
    [
        "3*(qf-q0)/tf**2",
        "3*(-q0+qf)/tf^2",
        "3 (q_f - q_0)/t_f^2",
        "(3*qf - 3*q0)*tf**(-2)",
        r"\frac{3(q_f-q_0)}{t_f^2}",
        r"\dfrac{3\left(q_{f}-q_{0}\right)}{t_{f}^{2}}",
        "3*qf/tf^2 - 3*q0/tf^2",
    ],
)
def test_a_symbolic_coefficient_in_every_written_form(answer: str) -> None:
    r = check_answer(TrajectoryKey.load(SYMBOLIC_CUBIC, "traj a2"), answer)
    assert r.verdict is Verdict.CORRECT, r.message
    assert r.entries[0].proof == "exact"


def test_quintic_coefficients_and_the_lowered_power() -> None:
    for k, answer in ((3, "10*(qf - q0)/tf^3"), (4, "-15 (qf-q0)/tf^4"), (5, "6(qf-q0)/tf^5")):
        assert check(SYMBOLIC_QUINTIC, f"traj a{k}", answer) == ("correct", ())
    assert check(SYMBOLIC_QUINTIC, "traj a3", "10*(qf - q0)/tf^2") == (
        "incorrect",
        ("tf_for_tf_squared",),
    )
    assert check(SYMBOLIC_QUINTIC, "traj a3", "10*(qf - q0)/tf^4") == ("incorrect", ())
    assert check(SYMBOLIC_QUINTIC, "traj a0", "q0") == ("correct", ())
    assert check(SYMBOLIC_QUINTIC, "traj a1", "0") == ("correct", ())


def test_numeric_keys_and_decimals_at_the_rounding_rule() -> None:
    spec = "cubic(q0=0, qf=1, tf=3)"  # a2 = 1/3
    for answer in ("1/3", "0.333", "0.3333", "0.33333", "2/6"):
        assert check(spec, "traj a2", answer)[0] == "correct", answer
    for answer in ("0.33", "0.334", "0.3", "1/3 + 1e-12", "0.3334"):
        assert check(spec, "traj a2", answer)[0] == "incorrect", answer
    assert check(spec, "traj a2", "0.33", rounding="abs=0.01")[0] == "correct"
    assert check(spec, "traj a2", "0.333", rounding="off")[0] == "incorrect"
    r = check_answer(TrajectoryKey.load(spec, "traj a2"), "0.333")
    assert r.entries[0].proof == "rounding" and "3 significant digits" in r.message


def test_boundary_velocity_left_out() -> None:
    spec = "cubic(q0=0, qf=1, tf=2, v0=0.5, vf=0)"  # a2 = 3/4 − (2·0.5 + 0)/2 = 1/4
    assert check(spec, "traj a2", "0.25") == ("correct", ())
    assert check(spec, "traj a2", "3/4") == ("incorrect", ("boundary_velocity_left_out",))
    assert check(spec, "traj a1", "1/2") == ("correct", ())
    sym = "cubic(q0=q0, qf=qf, tf=tf, v0=v0, vf=vf)"
    assert check(sym, "traj a2", "3*(qf-q0)/tf^2 - (2*v0 + vf)/tf") == ("correct", ())
    assert check(sym, "traj a2", "3*(qf-q0)/tf^2") == (
        "incorrect",
        ("boundary_velocity_left_out",),
    )
    # both mistakes at once explain nothing catalogued: still wrong
    assert check(sym, "traj a2", "3*(qf-q0)/tf") == ("incorrect", ())


def test_blend_time_and_the_wrong_limit() -> None:
    never_cruises = "minimum_time(q0=0, qf=0.5, vmax=1, amax=1)"
    assert check(never_cruises, "tb", "sqrt(0.5)") == ("correct", ())
    assert check(never_cruises, "tb", "sqrt(2)/2") == ("correct", ())
    assert check(never_cruises, "tb", "0.7071") == ("correct", ())
    assert check(never_cruises, "t_b", "1") == ("incorrect", ("blend_time_wrong_limit",))
    cruises = "minimum_time(q0=0, qf=2, vmax=1, amax=1)"
    assert check(cruises, "tb", "1") == ("correct", ())
    assert check(cruises, "tb", "sqrt(2)") == ("incorrect", ("blend_time_wrong_limit",))
    assert check(cruises, "tb", "1.41") == ("incorrect", ("blend_time_wrong_limit",))
    roots = "lspb(q0=0, qf=1, tf=2, a=2)"
    assert check(roots, "tb", "1 - sqrt(2)/2") == ("correct", ())
    assert check(roots, "tb", "1 + sqrt(2)/2") == ("incorrect", ("blend_time_wrong_limit",))
    sym = "lspb(q0=q0, qf=qf, tf=tf, a=a)"
    assert check(sym, "tb", "tf/2 - sqrt(a^2 tf^2 - 4 a (qf - q0))/(2 a)") == ("correct", ())
    assert check(sym, "tb", "tf/2 + sqrt(a^2 tf^2 - 4 a (qf - q0))/(2 a)") == (
        "incorrect",
        ("blend_time_wrong_limit",),
    )
    assert check("lspb(q0=0, qf=1, tf=2, V=3/4)", "tb", "2/3") == ("correct", ())


def test_peak_velocity_and_position_at_a_time() -> None:
    assert check("cubic(q0=0, qf=1, tf=2)", "vmax", "3/4") == ("correct", ())
    assert check(SYMBOLIC_CUBIC, "vmax", "3*(qf - q0)/(2*tf)") == ("correct", ())
    assert check("quintic(q0=0, qf=1, tf=2)", "vmax", "15/16") == ("correct", ())
    assert check("lspb(q0=1, qf=3, tf=2, V=1.8)", "vmax", "1.8") == ("correct", ())
    assert check("minimum_time(q0=0, qf=2, vmax=1, amax=1)", "v_max", "1") == ("correct", ())
    quintic = "quintic(q0=0, qf=1, tf=1)"
    assert check(quintic, "q@0.5", "1/2") == ("correct", ())
    assert check(quintic, "q@0.25", "0.1035") == ("correct", ())  # 53/512 = 0.10351…
    assert check(quintic, "q@0.25", "0.2")[0] == "incorrect"
    assert check(SYMBOLIC_QUINTIC, "q@tf/2", "(q0 + qf)/2") == ("correct", ())


def test_gains_for_a_frequency_and_damping() -> None:
    assert check("gains(omega=10)", "kp", "100") == ("correct", ())
    assert check("gains(omega=10)", "kd", "20") == ("correct", ())
    assert check("gains(omega=10)", "kd", "10") == ("incorrect", ("kd_without_two",))
    assert check("gains(omega=10)", "kp", "10") == ("incorrect", ("kp_not_squared",))
    assert check("gains(omega=4, zeta=0.5)", "K_d", "4") == ("correct", ())
    sym = "gains(omega=omega, zeta=zeta)"
    for answer in ("2 zeta omega", r"2\zeta\omega", "2*ω*ζ", "omega*zeta*2"):
        assert check(sym, "kd", answer) == ("correct", ()), answer
    assert check(sym, "kd", "zeta*omega") == ("incorrect", ("kd_without_two",))
    assert check(sym, "kp", "omega^2") == ("correct", ())
    assert check(sym, "kp", "omega") == ("incorrect", ("kp_not_squared",))


@pytest.mark.parametrize(
    "spec, question, wrong",
    [
        ("cubic(q0=q0, qf=qf, tf=tf)", "traj a2", ["3*(qf+q0)/tf^2", "3*qf/tf^2", "0", "qf"]),
        ("cubic(q0=0, qf=1, tf=2)", "traj a3", ["1/4", "-1/8", "0.25", "-0.26", "-0.3"]),
        ("gains(omega=omega)", "kd", ["2*omega^2", "omega^2", "2"]),
        ("quintic(q0=0, qf=1, tf=1)", "q@0.25", ["0.10", "0.11", "53/500"]),
    ],
)
def test_a_wrong_answer_is_never_right(spec: str, question: str, wrong: list[str]) -> None:
    for answer in wrong:
        r = check_answer(TrajectoryKey.load(spec, question), answer)
        assert r.verdict is Verdict.INCORRECT, answer
        assert not r.entries[0].correct


def test_unknown_names_are_named() -> None:
    r = check_answer(TrajectoryKey.load(SYMBOLIC_CUBIC, "traj a2"), "3*(qf-q0)/T^2")
    assert r.verdict is Verdict.INCORRECT and r.kinds[0] == "unknown_symbol"
    assert "T" in r.diagnoses[0].detail


@pytest.mark.parametrize(
    "answer",
    [
        "__import__('os').system('ls')",
        "9" * 5000,
        "(" * 300 + "1" + ")" * 300,
        "[[1, 2], [3, 4]]",
        r"\begin{bmatrix} 1 & 2 \end{bmatrix}",
        "",
        b"\xff\xfe\x00",
        "2**2**2**2**2**2**2**2",
    ],
)
def test_hostile_and_unreadable_answers_are_refused_with_a_reason(answer: str | bytes) -> None:
    key = TrajectoryKey.load("cubic(q0=0, qf=1, tf=2)", "traj a2")
    r = check_answer(key, answer, limits=AnswerLimits(seconds=2.0))
    assert r.verdict in (Verdict.UNREADABLE, Verdict.INCORRECT)
    if r.verdict is Verdict.UNREADABLE:
        assert r.reason


def test_prepared_once_per_worker() -> None:
    keys = PreparedKeys()
    key = TrajectoryKey.load("quintic(q0=0, qf=1, tf=2)", "traj a3")
    assert keys.get(key) is keys.get(TrajectoryKey.load("quintic(q0=0, qf=1, tf=2)", "traj a3"))
    assert check_answer(key, "10/8", keys=keys).correct and len(keys) == 1


def test_equal_answers_whose_doubles_cancel_and_a_difference_below_double_precision() -> None:
    key = TrajectoryKey.load(SYMBOLIC_CUBIC, "traj a2")
    padded = "3*(qf-q0)/tf^2 + ((q0+qf)^30 - (q0+qf)^29*q0 - (q0+qf)^29*qf)"
    r = check_answer(key, padded)
    assert r.correct and r.entries[0].proof == "exact"
    assert check_answer(key, "sin(qf)^2 + cos(qf)^2 - 1 + 3*(qf-q0)/tf^2").correct
    assert not check_answer(key, "3*(qf-q0)/tf^2 + 10^-30").correct
