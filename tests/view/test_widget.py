"""``robot.view()``: the widget's module in Chromium with a stand-in for the Jupyter model,
and its Python side (q both ways, inverse kinematics for a target, the static picture).

The stand-in model keeps the state anywidget would sync (``get``, ``set``, ``on``,
``save_changes``); the test plays the kernel's part by handing the page's target to the
widget in Python and the widget's answer back to the page.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import dhsym
from dhsym.view.widget import arm_view

from .test_page import ROBOTS

pytest.importorskip("anywidget")

HARNESS = """<!DOCTYPE html><html><body><div id="w"></div>
<script type="application/json" id="esm">{esm}</script>
<script type="application/json" id="state">{state}</script>
<script type="module">
const esm = JSON.parse(document.getElementById("esm").textContent);
const url = URL.createObjectURL(new Blob([esm], {{ type: "text/javascript" }}));
const widget = (await import(url)).default;
class Model {{
  constructor(state) {{ this.state = state; this.handlers = {{}}; this.saves = 0; }}
  get(k) {{ return this.state[k]; }}
  set(k, v) {{ this.state[k] = v; }}
  save_changes() {{ this.saves += 1; }}
  on(ev, f) {{ (this.handlers[ev] ||= []).push(f); }}
  off(ev, f) {{ this.handlers[ev] = (this.handlers[ev] || []).filter((g) => g !== f); }}
  kernel(k, v) {{ this.state[k] = v; (this.handlers["change:" + k] || []).forEach((f) => f()); }}
}}
window.model = new Model(JSON.parse(document.getElementById("state").textContent));
widget.render({{ model: window.model, el: document.getElementById("w") }});
window.rendered = true;
</script></body></html>"""


def _json(data: object) -> str:
    from dhsym.view.page import script_json

    return script_json(data)


def _open(guarded: Any, view: Any, tmp_path: Path) -> Any:
    state = {"scene": view.scene, "q": view.q, "solutions": [], "reason": "", "solved": 0}
    path = tmp_path / "widget.html"
    path.write_text(HARNESS.format(esm=_json(view._esm), state=_json(state)), encoding="utf-8")
    page = guarded.page
    page.goto(path.as_uri())
    page.wait_for_function("() => window.rendered === true")
    return page


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_sliders_set_q_and_q_moves_the_sliders(name: str, guarded: Any, tmp_path: Path) -> None:
    robot = ROBOTS[name]()
    n = len(robot.variables)
    start = [0.1 * (k % 3) for k in range(n)]  # within every robot's limits
    view = robot.view(start, workspace=0)
    start = list(view.q)  # clipped into the limits (the Panda's joint 4 stays below 0)
    page = _open(guarded, view, tmp_path)
    sliders = page.locator("input[type=range]")
    assert sliders.count() == n
    hi = float(sliders.nth(1).get_attribute("max"))
    lo = float(sliders.nth(1).get_attribute("min"))
    value = lo + 0.3 * (hi - lo)
    page.evaluate(
        """(v) => { const s = document.querySelector("input[data-joint='2']");
                   s.value = String(v); s.dispatchEvent(new Event("input")); }""",
        value,
    )
    q = page.evaluate("() => window.model.state.q")
    scale = view.scene["joints"][1]["scale"]
    assert q == pytest.approx([*start[:1], value * scale, *start[2:]])
    assert page.evaluate("() => window.model.saves") == 1
    # the kernel moves the arm: the sliders and the readout follow
    moved = [*start[:-1], start[-1] + 0.05 * scale]
    page.evaluate("(q) => window.model.kernel('q', q)", moved)
    last = view.scene["joints"][-1]
    assert float(page.input_value(f"input[data-joint='{n}']")) == pytest.approx(
        moved[-1] / last["scale"]
    )
    shown = json.loads(page.get_attribute("[data-name=position]", "data-xyz"))
    np.testing.assert_allclose(shown, robot.fk(moved)[:3, 3], atol=1e-12)
    assert guarded.errors == [] and guarded.outside == []


def test_a_typed_target_gives_branches_to_choose(guarded: Any, tmp_path: Path) -> None:
    robot = dhsym.load("puma560")
    view = robot.view([0.1, -0.5, 0.3, 0.2, 0.4, 0.1], workspace=0)
    page = _open(guarded, view, tmp_path)
    page.fill("input[data-target=z]", "0.2")
    page.fill("input[data-target=rz]", "30")
    page.click("button[data-name=solve]")
    target = page.evaluate("() => window.model.state.target")
    T = np.array(target).reshape(4, 4)
    assert T[2, 3] == pytest.approx(0.2)
    R0 = robot.fk([0.1, -0.5, 0.3, 0.2, 0.4, 0.1])[:3, :3]
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    np.testing.assert_allclose(
        T[:3, :3], np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ R0, atol=1e-9
    )
    view.target = target  # the kernel solves ...
    assert len(view.solutions) == 8 and view.reason == ""
    for key in ("solutions", "reason", "solved"):  # ... and the page hears it
        page.evaluate("([k, v]) => window.model.kernel(k, v)", [key, getattr(view, key)])
    options = page.locator("select[data-name=branches] option").all_inner_texts()
    assert options == [s["branch"] for s in view.solutions]
    page.select_option("select[data-name=branches]", "3")
    q = page.evaluate("() => window.model.state.q")
    np.testing.assert_allclose(robot.fk(q), T, atol=1e-9)
    assert guarded.errors == [] and guarded.outside == []


def test_an_unreachable_target_says_why() -> None:
    view = dhsym.load("puma560").view(workspace=0)
    far = np.eye(4)
    far[0, 3] = 5.0
    view.target = list(far.ravel())
    assert view.solutions == [] and "theta3" in view.reason and view.solved == 1
    view.target = list(far.ravel())  # the same target: no new answer (the page keeps it)
    assert view.solved == 1


def test_where_widgets_do_not_run_a_picture_shows() -> None:
    view = arm_view(dhsym.load("stanford"), workspace=0)
    data, _ = view._repr_mimebundle_()
    assert data["image/png"][:8] == "iVBORw0K"  # a PNG, base64
    assert "application/vnd.jupyter.widget-view+json" in data
    assert data["text/plain"].startswith("Stanford")


def test_degrees_are_read_as_the_robot_says() -> None:
    view = dhsym.load("stanford").view([90, 0, 0.2, 0, 0, 0], deg=True, workspace=0)
    assert view.q[0] == pytest.approx(np.pi / 2) and view.q[2] == pytest.approx(0.2)
