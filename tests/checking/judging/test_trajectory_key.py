"""The key of a trajectory or gain question: the profile read from text (never sympify),
its expected value from the trajectory and control rooms, each mistake's value derived
once, and the clear errors of a key that cannot answer its question."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.checking.judging.key import Key, load_key
from dhsym.checking.judging.trajectory_key import (
    SYMBOLS,
    Motion,
    TrajectoryKey,
    is_profile_spec,
    prepare_trajectory,
    spec_names,
)
from dhsym.control import gains
from dhsym.errors import DHError
from dhsym.trajectory import cubic, lspb, minimum_time, quintic

q0, qf, tf = SYMBOLS["q0"], SYMBOLS["qf"], SYMBOLS["tf"]


def expected(spec: str, question: str) -> sp.Expr:
    return prepare_trajectory(TrajectoryKey.load(spec, question)).part.expected


def test_the_expected_values_are_the_rooms_own() -> None:
    assert expected("cubic(q0=q0, qf=qf, tf=tf)", "traj a2") == cubic(q0, qf, tf).coefficients[2]
    assert (
        expected("quintic(q0=0, qf=pi/2, tf=2)", "traj a5")
        == (quintic(0, sp.pi / 2, 2).coefficients[5])
    )
    assert expected("lspb(q0=0, qf=1, tf=2, a=2)", "tb") == lspb(0, 1, 2, a=2).joints[0][0].end
    assert expected("trapezoidal(q0=0, qf=1, tf=2, v=0.75)", "tb") == sp.Rational(2, 3)
    assert expected("minimum_time(q0=0, qf=2, vmax=1, amax=1)", "tb") == (
        minimum_time(0, 2, 1, 1).joints[0][0].end
    )
    assert expected("gains(omega=10, zeta=0.5)", "kd") == gains(10, sp.Rational(1, 2))[1]
    assert expected("quintic(q0=0, qf=1, tf=1)", "q@1/4") == quintic(0, 1, 1).at("1/4")[0]


def test_each_mistake_is_derived_once_where_it_applies() -> None:
    def wrong(spec: str, question: str) -> dict[str, sp.Expr]:
        return dict(prepare_trajectory(TrajectoryKey.load(spec, question)).part.wrong)

    (kind, value), *more = wrong("cubic(q0=q0, qf=qf, tf=tf)", "traj a2").items()
    assert kind == "tf_for_tf_squared" and sp.simplify(value - 3 * (qf - q0) / tf) == 0
    assert not more
    assert set(wrong("cubic(q0=0, qf=1, tf=2, v0=1/2)", "traj a2")) == {
        "tf_for_tf_squared",
        "boundary_velocity_left_out",
    }
    assert wrong("cubic(q0=0, qf=1, tf=1)", "traj a2") == {}  # t_f = 1: the mistake is invisible
    assert wrong("gains(omega=10)", "kp") == {"kp_not_squared": 10}
    assert wrong("gains(omega=10)", "kd") == {"kd_without_two": 10}
    assert wrong("lspb(q0=0, qf=1, tf=2, a=2)", "tb") == {
        "blend_time_wrong_limit": 1 + sp.sqrt(2) / 2
    }
    assert wrong("quintic(q0=0, qf=1, tf=2)", "vmax") == {}


def test_the_profile_text_and_its_names() -> None:
    m = Motion.parse("cubic(q_0 = 0, q_f = pi/2, t_f = 2, v_0 = 0.1)")
    assert m.params == (("q0", 0), ("qf", sp.pi / 2), ("tf", 2), ("v0", sp.Rational(1, 10)))
    assert m.text == "cubic(q0=0, qf=pi/2, tf=2, v0=1/10)"
    assert Motion.parse("lspb(q0=0, qf=1, tf=2, v=3/4)").values["V"] == sp.Rational(3, 4)
    assert (
        Motion.parse("minimum_time(q0=0, qf=1, vmax=vmax, amax=2)").values["vmax"]
        == (SYMBOLS["vmax"])
    )
    assert Motion.parse("cubic(q0=0, qf=1, tf=T)", {"T": sp.Integer(3)}).values["tf"] == 3
    assert spec_names("cubic(q0=Q0, qf=pi/2, tf=sqrt(T))") == {"Q0", "T"}
    assert is_profile_spec("gains(omega=10)") and is_profile_spec("Cubic(q0=0, qf=1, tf=1)")
    assert not is_profile_spec("puma560") and not is_profile_spec("spline(1, 2)")
    assert not is_profile_spec("cubic(" + "x" * 1000 + ")")


@pytest.mark.parametrize(
    "spec, message",
    [
        ("cubic(q0=0, tf=2)", "cubic needs qf"),
        ("cubic(q0=0, qf=1, tf=2, V=1)", "cubic takes no 'V'"),
        ("cubic(q0=0, qf=1, qf=2, tf=1)", "qf is given twice"),
        ("cubic(q0=0, qf=1, tf=X)", "unknown name X"),
        ("cubic(q0=0, qf=__import__('os'), tf=1)", "double underscores"),
        ("cubic(q0=0, qf=1, tf=-1)", "a duration must be positive"),
        ("lspb(q0=0, qf=1, tf=2, V=1, a=2)", "not both"),
        ("lspb(q0=0, qf=1, tf=2, V=5)", "too large"),
        ("lspb(q0=0, qf=1, tf=2, a=0.1)", "too small"),
        ("cubic(q0 0, qf=1, tf=1)", "expected name=value"),
        ("spline(q0=0)", "expected a profile like cubic"),
    ],
)
def test_a_bad_profile_is_a_clear_error(spec: str, message: str) -> None:
    with pytest.raises(DHError, match=message) as err:
        TrajectoryKey.load(spec, "traj a2" if spec.startswith("cubic") else "tb")
    assert err.value.field is not None and err.value.field.startswith("key")


@pytest.mark.parametrize(
    "spec, question, message",
    [
        ("cubic(q0=0, qf=1, tf=2)", "tb", "blend time belongs to an lspb or minimum_time"),
        ("cubic(q0=0, qf=1, tf=2)", "traj a4", "a cubic has a0 … a3"),
        ("cubic(q0=0, qf=1, tf=2)", "kp", "asked of a gains"),
        ("cubic(q0=0, qf=1, tf=2, v0=1)", "vmax", "rest-to-rest"),
        ("cubic(q0=0, qf=1, tf=2)", "q@3", "outside the motion"),
        ("lspb(q0=0, qf=1, tf=2)", "traj a2", "coefficients belong to a cubic or quintic"),
        ("gains(omega=10)", "traj a2", "a gains key answers kp and kd"),
        ("cubic(q0=0, qf=1, tf=2)", "T0_2", "not one a profile answers"),
    ],
)
def test_a_question_the_profile_cannot_answer(spec: str, question: str, message: str) -> None:
    with pytest.raises(DHError, match=message) as err:
        TrajectoryKey.load(spec, question)
    assert err.value.field == "ask"


def test_load_key_reads_either_kind() -> None:
    assert isinstance(load_key("cubic(q0=0, qf=1, tf=2)", "traj a2"), TrajectoryKey)
    assert isinstance(load_key("planar2r", "px"), Key)
    with pytest.raises(DHError, match="asks about a profile"):
        load_key("planar2r", "traj a2")
    with pytest.raises(DHError, match="no real value"):
        TrajectoryKey.load("cubic(q0=q0, qf=sqrt(-1 - q0^2), tf=1)", "traj a2")


def test_a_drawn_value_gives_the_students_key() -> None:
    key = TrajectoryKey.load("cubic(q0=0, qf=1, tf=T)", "traj a2", drawn={"T": sp.Integer(2)})
    mine = key.with_drawn({"T": sp.Integer(4)})
    assert prepare_trajectory(mine).part.expected == sp.Rational(3, 16)
    assert mine.spec == key.spec and mine != key
