"""The page of ``dhsym view``: self-contained, offline, and the arm it shows is ``robot.fk``.

Each robot's page is opened from a file in headless Chromium; a slider is moved as a
student would (its value set and an ``input`` event sent); the tool position the page
prints, every frame the page draws and its readout of ^0T_n are compared with dhsym's
fk; the canvas must change; no request may leave the machine.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import dhsym
from dhsym.cli.main import main
from dhsym.errors import DHError
from dhsym.view import view_page
from dhsym.view.page import script_json

URDF = Path(__file__).resolve().parents[1] / "data" / "urdf"

ROBOTS = {
    "puma560": lambda: dhsym.load("puma560"),
    "ur5": lambda: dhsym.load("ur5"),
    "panda": lambda: dhsym.load("panda"),
    "stanford": lambda: dhsym.load("stanford"),  # a prismatic joint
    "puma560_modified": lambda: dhsym.load("puma560_modified"),
    "so100_urdf": lambda: dhsym.from_urdf(URDF / "so100.urdf"),
}

MOVE = """([joint, value]) => {
  const input = document.querySelector(`input[data-joint="${joint}"]`);
  input.value = String(value);
  input.dispatchEvent(new Event("input"));
  return window.dhsymView.q.slice();
}"""

FRAMES = """() => {
  const v = window.dhsymView;
  return v.frames.map((f) => Array.from(f.matrix.elements));
}"""


def _open(guarded: Any, path: Path) -> Any:
    page = guarded.page
    page.goto(path.as_uri())
    page.wait_for_function("() => window.dhsymView && window.dhsymView.redraws > 0")
    return page


def _pixels(page: Any) -> bytes:
    return page.locator(".stage canvas").screenshot()


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_a_moved_slider_moves_the_arm_where_fk_puts_it(
    name: str, guarded: Any, tmp_path: Path
) -> None:
    robot = ROBOTS[name]()
    path = tmp_path / f"{name}.html"
    path.write_text(view_page(robot, workspace=500), encoding="utf-8")
    page = _open(guarded, path)
    before = _pixels(page)
    rng = np.random.default_rng(7)
    sliders = page.locator("input[type=range]")
    assert sliders.count() == len(robot.variables)
    q = None
    for joint in range(1, len(robot.variables) + 1):
        lo = float(sliders.nth(joint - 1).get_attribute("min"))
        hi = float(sliders.nth(joint - 1).get_attribute("max"))
        q = page.evaluate(MOVE, [joint, lo + (hi - lo) * rng.random()])
    T = robot.fk(np.array(q))
    shown = json.loads(page.get_attribute("[data-name=position]", "data-xyz"))
    np.testing.assert_allclose(shown, T[:3, 3], atol=1e-12)
    cells = page.locator("table[data-name=fk] td").all_inner_texts()
    np.testing.assert_allclose(np.array(cells, dtype=float).reshape(4, 4), T, atol=6e-5)
    # every frame the page draws is dhsym's ^0T_k (three.js keeps column-major elements)
    drawn = np.array(page.evaluate(FRAMES)).reshape(-1, 4, 4).transpose(0, 2, 1)
    base_first = -1 if robot.table.base else 0
    for k in range(robot.n + 1):
        want = robot.fk_function(base_first, k)(np.array(q))
        np.testing.assert_allclose(drawn[k], want, atol=1e-9, err_msg=f"frame {k}")
    np.testing.assert_allclose(drawn[robot.n + 1], T, atol=1e-9)
    assert _pixels(page) != before
    assert guarded.errors == [] and guarded.outside == []


def test_the_page_is_whole_and_small(tmp_path: Path) -> None:
    html = view_page(dhsym.load("puma560"))
    assert len(html.encode()) <= 1_000_000
    head = html.split("<script>")[0]
    assert "src=" not in html.replace("\\", "") or 'src="http' not in html
    assert "<link" not in head and "http://" not in head and "https://" not in head
    assert html.count("<script") == 2  # the scene as JSON, then the code


def test_text_in_the_scene_cannot_close_the_script(guarded: Any, tmp_path: Path) -> None:
    table = dhsym.load("planar2r").table
    hostile = type(table)(**{**table.__dict__, "name": "</script><img src=x onerror=alert(1)>"})
    path = tmp_path / "hostile.html"
    path.write_text(view_page(hostile.with_values({"a1": 1, "a2": 0.8})), encoding="utf-8")
    page = _open(guarded, path)
    assert page.inner_text("h3.title") == "</script><img src=x onerror=alert(1)>"
    assert page.locator("img").count() == 0
    assert guarded.errors == [] and guarded.outside == []
    assert "<\\u002f" not in script_json("</")  # escaped as \\u003c, nothing else changed


def test_closed_form_and_link_matrices_show_on_request(guarded: Any, tmp_path: Path) -> None:
    robot = dhsym.load("puma560")
    path = tmp_path / "puma.html"
    path.write_text(view_page(robot, workspace=0), encoding="utf-8")
    page = _open(guarded, path)
    assert page.locator(".closed").is_hidden()
    page.get_by_role("button", name="closed form").click()
    assert page.locator(".closed").is_visible()
    assert robot.notation.text(robot.tool_pose().matrix[0, 3]) in page.inner_text(".closed")
    page.get_by_role("button", name="link matrices").click()
    page.evaluate(MOVE, [3, 0.4])
    assert page.locator(".links .active").get_attribute("data-link") == "3"
    A3 = robot.link_matrix(3).matrix.xreplace(robot.table.value_map).subs(robot.variables[2], 0.4)
    shown = page.locator(".links .active td").all_inner_texts()
    np.testing.assert_allclose(
        np.array(shown, dtype=float), np.array(A3[:3, :], float).ravel(), atol=6e-5
    )
    assert guarded.errors == []


def test_coincident_frames_share_one_label(guarded: Any, tmp_path: Path) -> None:
    path = tmp_path / "puma.html"
    path.write_text(view_page(dhsym.load("puma560"), workspace=0), encoding="utf-8")
    page = _open(guarded, path)
    labels = [t for t in page.locator(".frame-label").all_inner_texts() if t]
    assert "4, 5, 6, tool" in labels  # the spherical wrist: four frames at one point
    assert len(labels) == len(set(labels))


def test_symbolic_lengths_need_values() -> None:
    from dhsym.model.table import DHRow, DHTable

    bare = DHTable.from_rows([DHRow.revolute("q1", a="a1"), DHRow.revolute("q2", a="a2")])
    with pytest.raises(DHError, match="needs a value for a1, a2"):
        view_page(bare)


def test_cli_writes_the_page(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "arm.html"
    assert main(["view", "stanford", "--q", "10,20,0.3,0,0,0", "--deg", "-o", str(out)]) == 0
    html = out.read_text(encoding="utf-8")
    scene = json.loads(html.split('id="dhsym-scene">')[1].split("</script>")[0])
    assert [j["value"] for j in scene["joints"]][:3] == [10.0, 20.0, 0.3]
    assert main(["view", "puma560", "--q", "1,2", "-o", str(tmp_path / "p.html")]) == 2
    assert "6" in capsys.readouterr().err
    assert not (tmp_path / "p.html").exists()


def test_the_tool_path_and_the_workspace(guarded: Any, tmp_path: Path) -> None:
    robot = dhsym.load("ur5")
    path = tmp_path / "ur5.html"
    path.write_text(view_page(robot, workspace=300), encoding="utf-8")
    page = _open(guarded, path)
    page.get_by_role("button", name="tool path").click()
    page.get_by_role("button", name="workspace").click()
    qs = [page.evaluate(MOVE, [1, v]) for v in (0.2, 0.4, 0.6)]
    traced = page.evaluate(
        """() => { const v = window.dhsymView, g = v.traceLine.geometry;
                   const a = g.getAttribute("position").array;
                   const n = g.drawRange.count;
                   return { n, last: Array.from(a.slice(3 * (n - 3), 3 * n)),
                            shown: v.traceLine.visible, cloud: v.cloud.visible,
                            points: v.cloud.geometry.getAttribute("position").count }; }"""
    )
    assert traced["shown"] and traced["cloud"] and traced["points"] == 300
    assert traced["n"] == 4  # the first pose, then three moves
    want = np.array([robot.fk(q)[:3, 3] for q in qs]).ravel()
    np.testing.assert_allclose(traced["last"], want, atol=1e-6)  # float32 in the buffer
    cloud = view_page(robot, workspace=300).split('"cloud": [')[1].split("]")[0]
    sampled = np.array(cloud.split(","), dtype=float).reshape(-1, 3)
    reach = np.linalg.norm(sampled, axis=1)
    lengths = sum(
        abs(float(x))
        for r in robot.table.rows
        for x in (r.a.xreplace(robot.table.value_map), r.d.xreplace(robot.table.value_map))
    )
    assert 0.5 < reach.max() <= lengths  # within the summed DH lengths (1.19 m)


@pytest.mark.parametrize("name", ["puma560", "panda"])
def test_the_manipulability_ellipsoid_is_the_jacobians(
    name: str, guarded: Any, tmp_path: Path
) -> None:
    robot = dhsym.load(name)
    path = tmp_path / f"{name}.html"
    path.write_text(view_page(robot, workspace=0), encoding="utf-8")
    page = _open(guarded, path)
    page.get_by_role("button", name="manipulability").click()
    q = [page.evaluate(MOVE, [k, 0.3 + 0.1 * k]) for k in (1, 2, 4)][-1]
    Jv = robot.jacob0(np.array(q))[:3]
    want = np.sqrt(np.sort(np.linalg.eigvalsh(Jv @ Jv.T)))
    got = page.evaluate("() => window.dhsymView.axes")
    np.testing.assert_allclose(np.sort(got), want, atol=1e-9)
    shown = float(page.get_attribute("[data-name=manipulability]", "data-value"))
    assert shown == pytest.approx(np.sqrt(np.linalg.det(Jv @ Jv.T)), abs=1e-12)
    assert page.locator("[data-name=manipulability]").is_visible()
    assert guarded.errors == []
