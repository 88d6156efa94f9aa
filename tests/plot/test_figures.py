"""Pictures: triads where the kinematics puts the frames, equal axes, files written."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.cli.main import main
from dhsym.errors import DHError, GeometryError

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

from dhsym.plot.figures import (  # noqa: E402
    frame_origins,
    is_planar,
    joint_values,
    plot_robot,
    plot_workspace,
    plotted_frames,
    skeleton,
    view_limits,
    workspace_points,
)

ROOT = Path(__file__).resolve().parents[2]

BASE_TOOL = """
name: 2R on a pedestal with a tool
angles: deg
joints:
  - {type: R, theta: theta1, d: 0, a: a1, alpha: 0}
  - {type: R, theta: theta2, d: 0, a: a2, alpha: 0}
values: {a1: 1.0, a2: 0.8}
base: [{Tz: 0.5}, {Rx: 90}]
tool: [{Tx: 0.2}, {Rz: 30}]
"""


def _exact_pose(robot, i: int, j: int, q: np.ndarray) -> np.ndarray:
    """^iT_j from the plain product of elementary matrices, evaluated with sympy (independent
    of the compiled fk functions the plot uses)."""
    subs = dict(robot.table.value_map)
    subs.update(zip(robot.variables, (sp.Float(v, 30) for v in q), strict=True))
    return np.array(robot.plain_transform(i, j).evalf(subs=subs), dtype=float)


ROBOTS = [
    "planar2r",
    "puma560",
    "puma560_modified",
    "example1_rrp",
    "stanford",
    "scara",
    "cartesian",
]


@pytest.mark.parametrize("name", ROBOTS)
def test_plotted_triads_are_the_frames_of_the_kinematics(name):
    robot = dhsym.load(name)
    q = np.random.default_rng(7).uniform(-1.2, 1.2, len(robot.variables))
    q = np.where(
        [robot.table.rows[i - 1].joint.value == "P" for i in robot.table.joint_rows],
        np.abs(q) * 0.3,
        q,
    )
    fig = plot_robot(robot, q)
    drawn = plotted_frames(fig)
    assert sorted(drawn, key=int) == [str(k) for k in range(robot.n + 1)]
    for k in range(robot.n + 1):
        T = _exact_pose(robot, 0, k, q)
        rows = drawn[str(k)]
        np.testing.assert_allclose(rows[0], T[:3, 3], atol=1e-9)
        for j in range(3):
            axis = rows[1 + j] - rows[0]
            np.testing.assert_allclose(axis / np.linalg.norm(axis), T[:3, j], atol=1e-9)
    np.testing.assert_allclose(
        frame_origins(robot, q), [drawn[str(k)][0] for k in range(robot.n + 1)]
    )


def test_base_and_tool_frames_are_drawn_in_world_coordinates():
    robot = dhsym.Robot(dhsym.read_table_text(BASE_TOOL))
    q = np.radians([30, -50])
    drawn = plotted_frames(plot_robot(robot, q))
    assert set(drawn) == {"W", "0", "1", "2", "tool"}
    np.testing.assert_allclose(drawn["W"][0], [0, 0, 0], atol=1e-12)
    np.testing.assert_allclose(drawn["0"][0], [0, 0, 0.5], atol=1e-12)
    for label, k in (("1", 1), ("2", 2), ("tool", 3)):
        np.testing.assert_allclose(drawn[label][0], _exact_pose(robot, -1, k, q)[:3, 3], atol=1e-9)
    np.testing.assert_allclose(drawn["tool"][0], robot.fk(q)[:3, 3], atol=1e-9)
    assert frame_origins(robot, q).shape == (3, 3)


def test_frames_land_where_each_convention_puts_them():
    """Standard: d along z_{i-1}, then a along x_i. Modified: a along x_{i-1}, then d along z_i."""
    q = np.radians([30, -30, 45, 10, 45, 20])
    for name, d_axis, a_axis in (
        ("puma560", "prev_z", "cur_x"),
        ("puma560_modified", "cur_z", "prev_x"),
    ):
        robot = dhsym.load(name)
        sk = skeleton(robot, q)
        poses = {lab: T for lab, T in zip(sk.labels, sk.poses, strict=True)}
        # the link segments form one unbroken path from frame 0 to frame n
        path = [sk.segments[0].start] + [s.end for s in sk.segments]
        np.testing.assert_allclose(path[0], poses["0"][:3, 3], atol=1e-12)
        np.testing.assert_allclose(path[-1], poses["6"][:3, 3], atol=1e-12)
        for s, t in zip(sk.segments[:-1], sk.segments[1:], strict=True):
            np.testing.assert_allclose(s.end, t.start, atol=1e-12)
        lengths = {"a": [], "d": []}
        for s in sk.segments:
            lengths[s.kind].append(np.linalg.norm(s.end - s.start))
        assert sorted(np.round(lengths["a"], 6)) == [0.0203, 0.4318]
        assert sorted(np.round(lengths["d"], 6)) == [0.15005, 0.4318]
        # each segment runs along the axis its convention says
        for i in range(1, 7):
            prev, cur = poses[str(i - 1)], poses[str(i)]
            axes = {
                "prev_z": prev[:3, 2],
                "cur_z": cur[:3, 2],
                "prev_x": prev[:3, 0],
                "cur_x": cur[:3, 0],
            }
            step = cur[:3, 3] - prev[:3, 3]
            row = robot.table.rows[i - 1]
            d = float(row.d.subs(robot.table.value_map))
            a_val = float(row.a.subs(robot.table.value_map))
            np.testing.assert_allclose(step, d * axes[d_axis] + a_val * axes[a_axis], atol=1e-12)
    std, mod = frame_origins(dhsym.load("puma560")), frame_origins(dhsym.load("puma560_modified"))
    assert not np.allclose(std, mod)  # the two conventions put the frames in different places


def test_modified_labels_use_the_previous_index():
    texts = [t.get_text() for t in plot_robot(dhsym.load("puma560_modified")).axes[0].texts]
    assert "$a_{2} = 0.432$" in texts and "$d_{3} = 0.15$" in texts
    texts = [t.get_text() for t in plot_robot(dhsym.load("puma560")).axes[0].texts]
    assert "$a_{2} = 0.432$" in texts and "$a_{3} = 0.0203$" in texts
    assert "{0} {1}" in texts and "{4} {5} {6}" in texts  # coincident origins share a label


def test_axes_have_equal_scaling():
    fig = plot_robot(dhsym.load("puma560"), np.radians([0, 30, -60, 0, 20, 0]))
    ax = fig.axes[0]
    spans = [np.ptp(lim) for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim())]
    assert spans[0] == pytest.approx(spans[1]) == pytest.approx(spans[2])
    aspect = ax.get_box_aspect()
    assert aspect[0] == pytest.approx(aspect[1]) == pytest.approx(aspect[2])
    origins = frame_origins(dhsym.load("puma560"), np.radians([0, 30, -60, 0, 20, 0]))
    for lim, c in zip((ax.get_xlim(), ax.get_ylim(), ax.get_zlim()), origins.T, strict=True):
        assert lim[0] < c.min() and c.max() < lim[1]


def test_planar_robot_in_2d():
    robot = dhsym.load("planar2r")
    fig = plot_robot(robot, [30, 45], deg=True, view="2d", scale=0.3)
    ax = fig.axes[0]
    assert ax.name != "3d"
    assert ax.get_aspect() == 1.0
    assert np.ptp(ax.get_xlim()) == pytest.approx(np.ptp(ax.get_ylim()))
    drawn = plotted_frames(fig)
    T = robot.fk([30, 45], deg=True)
    np.testing.assert_allclose(drawn["2"][0], T[:2, 3], atol=1e-12)
    np.testing.assert_allclose(drawn["2"][1] - drawn["2"][0], 0.3 * T[:2, 0], atol=1e-9)
    assert is_planar(robot) and not is_planar(dhsym.load("puma560"))
    with pytest.raises(GeometryError, match="not planar"):
        plot_robot(dhsym.load("puma560"), view="2d")


def test_scara_top_view_marks_z_down():
    fig = plot_robot(dhsym.load("scara"), [30, 45, 0.1, 0], deg=True, view="2d")
    markers = {line.get_gid(): line.get_marker() for line in fig.axes[0].get_lines()}
    assert markers["frame:0:z"] == "o" and markers["frame:2:z"] == "o"
    inner = [
        ln.get_marker()
        for ln in fig.axes[0].get_lines()
        if ln.get_gid() is None and ln.get_marker() in (".", "x")
    ]
    assert inner.count(".") == 2 and inner.count("x") == 3  # z0, z1 up; z2, z3, z4 down


def test_png_pdf_svg_written(tmp_path):
    fig = plot_robot(dhsym.load("puma560"))
    for suffix, magic in ((".png", b"\x89PNG"), (".pdf", b"%PDF"), (".svg", b"<?xml")):
        out = tmp_path / f"puma{suffix}"
        fig.savefig(out)
        data = out.read_bytes()
        assert data.startswith(magic) and len(data) > 10_000


def test_cli_plot(tmp_path, capsys):
    out = tmp_path / "2r.png"
    assert main(["plot", "planar2r", "--q", "30, pi/4", "--view", "2d", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"\x89PNG") and out.stat().st_size > 10_000
    assert "wrote" in capsys.readouterr().err
    ws = tmp_path / "ws.svg"
    assert main(["plot", "planar2r", "--workspace", "--samples", "300", "-o", str(ws)]) == 0
    assert ws.read_text().count("<use") + ws.read_text().count("<path") > 300
    assert (
        main(["plot", "puma560", "--q", "0,30,-60,0,20,0", "--deg", "-o", str(tmp_path / "p.pdf")])
        == 0
    )
    assert main(["plot", "planar2r", "-o", str(tmp_path / "x.gif")]) == 2
    assert main(["plot", "planar2r", "--q", "1,2,3", "-o", str(tmp_path / "x.png")]) == 2
    assert main(["plot", "puma560", "--view", "2d", "-o", str(tmp_path / "x.png")]) == 2
    assert "dhsym: error:" in capsys.readouterr().err


def test_workspace_of_2r_is_inside_the_annulus():
    robot = dhsym.load("planar2r")
    a1, a2 = 1.0, 0.8
    pts = workspace_points(robot, 3000)
    r = np.linalg.norm(pts[:, :2], axis=1)
    assert np.all(r >= abs(a1 - a2) - 1e-12) and np.all(r <= a1 + a2 + 1e-12)
    assert r.max() > 0.99 * (a1 + a2)
    fold = np.sqrt(a1**2 + a2**2 + 2 * a1 * a2 * np.cos(np.radians(150)))  # joint 2 stops at 150°
    assert r.min() >= fold - 1e-9 and r.min() < fold + 0.05
    np.testing.assert_allclose(pts[:, 2], 0.0, atol=1e-12)
    fig = plot_workspace(robot, 500)
    scatter = [c for c in fig.axes[0].collections if c.get_gid() == "workspace"]
    assert len(scatter) == 1 and len(scatter[0].get_offsets()) == 500
    assert fig.axes[0].get_aspect() == 1.0


def test_workspace_default_limits_for_prismatic_and_unlimited_joints():
    robot = dhsym.Robot(
        dhsym.read_table_text(
            "joints: [{type: R, theta: q1, d: 0, a: 1, alpha: 0},"
            " {type: P, theta: 0, d: d2, a: 0, alpha: 0}]"
        )
    )
    pts = workspace_points(robot, 400)
    assert pts[:, 2].min() >= 0.0 and pts[:, 2].max() <= 1.0 and pts[:, 2].max() > 0.9
    assert plot_workspace(robot, 100).axes[0].name == "3d"
    with pytest.raises(DHError):
        workspace_points(robot, 0)


def test_joint_values():
    robot = dhsym.load("example1_rrp")
    np.testing.assert_allclose(
        joint_values(robot, [180, 90, 0.2], deg=True), [np.pi, np.pi / 2, 0.2]
    )
    np.testing.assert_allclose(joint_values(robot), [0, 0, 0])
    with pytest.raises(DHError, match="needs 3"):
        joint_values(robot, [1, 2])
    with pytest.raises(DHError):
        plot_robot(robot, [0, 0, 0], view="top")


def test_view_limits_hold_every_configuration():
    robot = dhsym.load("planar2r")
    qs = np.radians([[0, 0], [90, 0], [180, 90]])
    centre, half = view_limits(robot, qs, dim=2)
    for q in qs:
        o = frame_origins(robot, q)[:, :2]
        assert np.all(np.abs(o - centre) <= half)


def test_importing_dhsym_does_not_import_matplotlib():
    code = (
        "import sys, dhsym, dhsym.plot.figures, dhsym.plot.animation\n"
        "import dhsym.explain.notebooks, dhsym.cli\n"
        "dhsym.cli.build_parser()\n"
        "heavy = [m for m in ('matplotlib', 'nbconvert', 'nbclient') if m in sys.modules]\n"
        "assert not heavy, heavy\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    subprocess.run([sys.executable, "-c", code], check=True, env=env, cwd=ROOT)


@pytest.mark.parametrize("name", ["ur5", "puma560", "panda"])
def test_frame_labels_never_sit_on_one_another(name):
    # issue 32, item 5: the UR5's {4}, {5}, {6}, {tool} were drawn on top of each other
    robot = dhsym.load(name)
    q = np.zeros(len(robot.variables))
    fig = plot_robot(robot, q)
    ax = fig.axes[0]
    texts = [t for t in ax.texts if t.get_gid() == "frame label"]
    where = np.array([t.get_position_3d() for t in texts])
    sk = skeleton(robot, q)
    gaps = np.linalg.norm(where[:, None] - where[None], axis=-1) + np.eye(len(where)) * 1e9
    assert gaps.min() >= 0.5 * sk.scale  # no two labels within half a triad
    shown = " ".join(t.get_text() for t in texts)
    assert sorted(shown.split()) == sorted("{" + lab + "}" for lab in sk.labels)  # each once
