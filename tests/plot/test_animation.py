"""Animations along a joint-space path: GIF where Pillow is, else a strip of PNG frames."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.plot.animation import animate_path, joint_path

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")


def test_joint_path_is_straight_and_includes_both_ends():
    path = joint_path([0, 10, 0.1], [90, -10, 0.3], 5)
    assert path.shape == (5, 3)
    np.testing.assert_allclose(path[0], [0, 10, 0.1])
    np.testing.assert_allclose(path[-1], [90, -10, 0.3])
    np.testing.assert_allclose(np.diff(path, axis=0), np.tile([22.5, -5, 0.05], (4, 1)))
    with pytest.raises(DHError):
        joint_path([0, 0], [1, 2, 3], 4)
    with pytest.raises(DHError):
        joint_path([0, 0], [1, 2], 1)


def test_gif_has_one_frame_per_configuration(tmp_path):
    pytest.importorskip("PIL")
    from PIL import Image

    out = animate_path(
        dhsym.load("planar2r"),
        joint_path([0, 0], [90, 60], 6),
        tmp_path / "a.gif",
        deg=True,
        view="2d",
        dpi=40,
    )
    assert out == tmp_path / "a.gif"
    with Image.open(out) as im:
        assert im.format == "GIF" and im.n_frames == 6


def test_frame_strip_when_no_writer(tmp_path):
    robot = dhsym.load("example1_rrp")
    qs = joint_path([0, 0, 0], [1.0, -0.5, 0.2], 3)
    out = animate_path(robot, qs, tmp_path / "strip", dpi=40)
    assert out == tmp_path / "strip" and out.is_dir()
    frames = sorted(out.iterdir())
    assert [f.name for f in frames] == ["frame_000.png", "frame_001.png", "frame_002.png"]
    assert all(f.read_bytes().startswith(b"\x89PNG") for f in frames)
    assert frames[0].read_bytes() != frames[-1].read_bytes()


def test_mp4_or_strip(tmp_path):
    from matplotlib import animation

    out = animate_path(
        dhsym.load("planar2r"), joint_path([0, 0], [1, 1], 2), tmp_path / "m.mp4", dpi=40
    )
    if animation.writers.is_available("ffmpeg"):
        assert out.suffix == ".mp4" and out.stat().st_size > 0
    else:
        assert out == tmp_path / "m" and len(list(out.glob("frame_*.png"))) == 2


def test_bad_configuration_is_refused(tmp_path):
    with pytest.raises(DHError):
        animate_path(dhsym.load("planar2r"), [[0, 0, 0]], tmp_path / "x.gif")
