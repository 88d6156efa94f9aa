"""The pictures of a closed loop: the tracking error and the torques of simulated runs on
Spong's two-link arm, each line the run's own data, labelled by run and joint."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.control import PD, ComputedTorque, plot_torques, plot_tracking_error, simulate
from dhsym.errors import DHError
from dhsym.trajectory import quintic

VALUES = {"m1": 1, "m2": 1, "l1": 1, "l2": 1, "lc1": 0.5, "lc2": 0.5, "I1": 0.1, "I2": 0.1}


@pytest.fixture(scope="module")
def runs() -> dict[str, object]:
    arm = dhsym.load("spong2r")
    values = {**VALUES, "g": 9.81}
    model = arm.dynamics_functions(values)
    ref = quintic([0.0, 0.0], [1.0, -0.8], 0.5)
    return {
        "PD": simulate(arm, PD(64.0, 16.0, ref), 0.6, values=values, dt=1e-2),
        "computed torque": simulate(
            arm, ComputedTorque(64.0, 16.0, ref, model=model), 0.6, values=values, dt=1e-2
        ),
    }


def _lines(fig):
    (ax,) = fig.axes
    return ax, ax.get_lines()


def test_tracking_error_one_line_per_run_and_joint(runs) -> None:
    ax, lines = _lines(plot_tracking_error(runs))
    assert [ln.get_label() for ln in lines] == [
        "PD, joint 1",
        "PD, joint 2",
        "computed torque, joint 1",
        "computed torque, joint 2",
    ]
    for ln, (name, j) in zip(
        lines, [("PD", 0), ("PD", 1), ("computed torque", 0), ("computed torque", 1)]
    ):
        np.testing.assert_array_equal(ln.get_xdata(), runs[name].t)
        np.testing.assert_array_equal(ln.get_ydata(), runs[name].error[:, j])
    assert ax.get_xlabel() == "t (s)" and ax.get_yscale() == "linear"
    assert [t.get_text() for t in ax.get_legend().get_texts()][0] == "PD, joint 1"


def test_largest_error_on_a_log_axis(runs) -> None:
    ax, lines = _lines(plot_tracking_error(runs, largest=True, log=True))
    assert [ln.get_label() for ln in lines] == ["PD", "computed torque"]
    for ln, name in zip(lines, runs):
        np.testing.assert_array_equal(ln.get_ydata(), np.abs(runs[name].error).max(axis=1))
    assert ax.get_yscale() == "log"
    # PD lags the motion, computed torque follows it (to the RK4 step of 1e-2 s)
    assert lines[0].get_ydata().max() > 1e-3 > 1e-5 > lines[1].get_ydata().max()


def test_torques_of_one_joint_into_given_axes(runs) -> None:
    from matplotlib.figure import Figure

    fig = Figure()
    left, right = fig.subplots(1, 2)
    assert plot_torques(runs, joints=[1], ax=right) is fig
    assert left.get_lines() == [] and right.get_title() == "torque of joint 1"
    lines = right.get_lines()
    assert [ln.get_label() for ln in lines] == ["PD", "computed torque"]
    for ln, name in zip(lines, runs):
        np.testing.assert_array_equal(ln.get_ydata(), runs[name].tau[:, 0])
    one = plot_torques(runs["PD"])
    assert [ln.get_label() for ln in one.axes[0].get_lines()] == ["joint 1", "joint 2"]


def test_bad_joints_and_runs(runs) -> None:
    with pytest.raises(DHError, match=r"joints are numbered 1 … 2, got \[3\]"):
        plot_torques(runs, joints=[3])
    with pytest.raises(DHError, match="give a ClosedLoop"):
        plot_tracking_error({"x": np.zeros(3)})
