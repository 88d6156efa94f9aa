"""The manipulability ellipse: singular values of J_v, drawn at the tool, flat at a singularity."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

from dhsym.plot.ellipses import plot_manipulability, velocity_ellipse  # noqa: E402


def test_the_2r_ellipse_is_the_singular_values_of_its_jacobian():
    robot = dhsym.load("planar2r")
    a1, a2 = 1.0, 0.8
    for t2 in (0.4, 1.2, 2.5):
        e = velocity_ellipse(robot, [0.3, t2])
        assert e.dim == 2
        assert e.w == pytest.approx(a1 * a2 * abs(np.sin(t2)))  # |det J_v| = a1 a2 |S2|
        assert np.prod(e.axes) == pytest.approx(e.w)
        J = robot.jacob0([0.3, t2])[:2]
        for k in range(2):  # J Jᵀ u = σ² u along each semi-axis
            u = e.directions[:, k]
            assert np.allclose(J @ J.T @ u, e.axes[k] ** 2 * u)
        assert np.allclose(e.centre, robot.fk([0.3, t2])[:3, 3])


def test_the_ellipse_collapses_at_the_singularity():
    e = velocity_ellipse(dhsym.load("planar2r"), [0.7, 0.0])
    assert e.w == pytest.approx(0.0, abs=1e-12) and e.axes[1] == pytest.approx(0.0, abs=1e-12)
    assert e.axes[0] == pytest.approx(np.hypot(1.8, 0.8))  # |J_v q̇| for q̇ along (1.8, 0.8)
    tangent = np.array([-np.sin(0.7), np.cos(0.7)])  # the only direction the tool can move
    assert abs(e.directions[:, 0] @ tangent) == pytest.approx(1.0)


def test_the_drawn_ellipse_has_the_computed_axes():
    robot = dhsym.load("planar2r")
    fig = plot_manipulability(robot, [[30, 90], [30, 20]], deg=True, scale=0.5)
    ax = fig.axes[0]
    for k, q in enumerate([[30, 90], [30, 20]]):
        e = velocity_ellipse(robot, q, deg=True)
        (line,) = [ln for ln in ax.get_lines() if ln.get_gid() == f"ellipse:{k}"]
        pts = np.column_stack(line.get_data()) - e.centre[:2]
        coords = pts @ e.directions / (0.5 * e.axes)  # in units of the drawn semi-axes
        assert np.allclose((coords**2).sum(axis=1), 1.0)
        assert np.abs(coords).max(axis=0) == pytest.approx([1.0, 1.0], abs=2e-3)
        assert line.get_label() == f"w = {e.w:.3g}"


def test_a_spatial_arm_gets_an_ellipsoid_in_3d():
    robot = dhsym.load("puma560")
    e = velocity_ellipse(robot, [0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert e.dim == 3 and e.axes.shape == (3,)
    fig = plot_manipulability(robot, [0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert fig.axes[0].name == "3d"
    with pytest.raises(DHError, match="needs a 3D axes"):
        plot_manipulability(robot, [0] * 6, ax=matplotlib.figure.Figure().add_subplot())
