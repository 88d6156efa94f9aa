"""All inverse-kinematics solutions side by side: one panel each, every panel reaches the pose."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

from dhsym.plot.solutions import plot_solutions  # noqa: E402


def _tool_origin(ax) -> np.ndarray:
    (line,) = [ln for ln in ax.get_lines() if ln.get_gid() == "tool:x"]
    data = line.get_data_3d() if hasattr(line, "get_data_3d") else line.get_data()
    return np.column_stack(data)[0]


def test_eight_puma_solutions_in_eight_panels_reaching_one_pose():
    robot = dhsym.load("puma560")
    T = robot.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    sol = robot.ik(T)
    fig = plot_solutions(robot, sol)
    assert [ax.get_title() for ax in fig.axes] == list(sol.branches)
    assert len(fig.axes) == 8 and all(ax.name == "3d" for ax in fig.axes)
    for ax in fig.axes:
        assert np.allclose(_tool_origin(ax), T[:3, 3])
    limits = {tuple(np.round(ax.get_xlim(), 9)) for ax in fig.axes}
    assert len(limits) == 1  # one view for every panel


def test_planar_solutions_are_drawn_from_above_with_names_given():
    robot = dhsym.load("planar2r")
    q = np.array([[0.2, 0.9], [1.1, -0.9]])
    fig = plot_solutions(robot, q, names=["a", "b"], columns=1)
    assert [ax.get_title() for ax in fig.axes] == ["a", "b"]
    assert all(ax.name != "3d" for ax in fig.axes)


def test_wrong_shapes_are_refused():
    robot = dhsym.load("planar2r")
    with pytest.raises(DHError, match="needs solutions of 2 joint values"):
        plot_solutions(robot, np.zeros((2, 3)))
    with pytest.raises(DHError, match="2 solutions need 2 names"):
        plot_solutions(robot, np.zeros((2, 2)), names=["one"])
