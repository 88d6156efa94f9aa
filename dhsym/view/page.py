"""One self-contained HTML page of the view: three.js, the view and the robot inlined.

:func:`view_page` renders ``templates/view.html.j2``: the bundled view
(``static/viewer.js``, three.js from npm), the robot's generated JavaScript
(:func:`dhsym.view.javascript.robot_script`) and its scene as JSON. The page fetches
nothing: it opens offline from a file, in a docs site or an LMS page.

Examples
--------
>>> import dhsym
>>> html = view_page(dhsym.load("planar2r").table.with_values({"a1": 1, "a2": 0.8}))
>>> html.startswith("<!DOCTYPE html>"), "http://" in html.split("<script>")[0], len(html) < 10**6
(True, False, True)
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from importlib import resources
from typing import TYPE_CHECKING

from dhsym.notation.templates import PAGE, environment

from .javascript import robot_script
from .scene import WORKSPACE_POINTS, Scene, scene

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain
    from dhsym.model.table import DHTable

__all__ = ["bundle", "script_json", "view_page"]


def bundle() -> str:
    """The bundled view (three.js and ``js/src/viewer.js``), as shipped in the wheel."""
    return (resources.files("dhsym.view") / "static" / "viewer.js").read_text(encoding="utf-8")


def script_json(data: object) -> str:
    """JSON that can sit inside a ``<script>`` element: ``<``, ``>``, ``&`` and the line
    separators written as escapes, so no text can close the element.

    >>> script_json({"name": "</script><b>"})
    '{"name": "\\\\u003c/script\\\\u003e\\\\u003cb\\\\u003e"}'
    """
    text = json.dumps(data, ensure_ascii=False, allow_nan=False)
    for ch in "<>&\u2028\u2029":
        text = text.replace(ch, f"\\u{ord(ch):04x}")
    return text


def view_page(
    robot: KinematicChain | DHTable,
    q: Sequence[float] | None = None,
    *,
    workspace: int = WORKSPACE_POINTS,
    footer: str = "",
) -> str:
    """The page of ``robot`` (a chain, or a table with values) at ``q``.

    ``workspace`` tool positions are sampled for the workspace cloud (0: none).
    """
    from markupsafe import Markup

    from dhsym._version import __version__
    from dhsym.kinematics.chain import KinematicChain

    chain = robot if isinstance(robot, KinematicChain) else KinematicChain(robot)
    shown: Scene = scene(chain, q, workspace=workspace)
    script = bundle() + "\n" + robot_script(chain)
    return (
        environment("html", PAGE)
        .get_template("view.html.j2")
        .render(
            title=f"{shown.name}: dhsym view",
            version=__version__,
            scene_json=Markup(script_json(shown.data())),  # noqa: S704 - escaped above
            script=Markup(script.replace("</script", "<\\/script")),  # noqa: S704
            footer=footer or f"{shown.name}, {shown.convention} DH table; drawn by dhsym.",
        )
    )
