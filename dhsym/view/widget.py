"""The view as a Jupyter widget (anywidget): JupyterLab, Jupyter Notebook, VS Code.

:class:`ArmView` runs the same bundled view as the page (``static/viewer.js``, three.js from
npm, shipped in the wheel: nothing is fetched), with the robot's generated JavaScript
appended. ``q`` is shared both ways: moving a slider sets ``view.q`` in Python, and setting
``view.q`` moves the arm. Where widgets do not run (a notebook exported by nbconvert
without the widget state, a terminal), the display falls back to a picture of the arm at
the first ``q`` (PNG, from :mod:`dhsym.plot`) and a line of text.

Needs the ``widgets`` extra (``pip install 'dhsym[widgets]'``: anywidget).
"""

from __future__ import annotations

import base64
import io
from collections.abc import Callable, Sequence
from functools import cache, partial
from typing import TYPE_CHECKING, Any

import numpy as np

from dhsym.errors import DHError

from .javascript import robot_script
from .page import bundle
from .scene import WORKSPACE_POINTS, scene

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["arm_view"]


def _png(robot: KinematicChain, q: Sequence[float] | np.ndarray) -> str:
    """The arm at ``q`` as a PNG (base64), the static picture of the view."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from dhsym.plot.figures import plot_robot

    fig = plot_robot(robot, list(q))
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=80)
    import matplotlib.pyplot as plt

    plt.close(fig)
    return base64.b64encode(buffer.getvalue()).decode("ascii")


def solve_target(robot: KinematicChain, target: np.ndarray) -> tuple[list[dict[str, Any]], str]:
    """The branches of ``robot.ik`` for ``target`` (16 numbers, or 4×4) as the view shows
    them, and the reason when there is none.

    >>> import dhsym, numpy as np
    >>> arm = dhsym.load("puma560")
    >>> found, why = solve_target(arm, arm.fk([0.1, -0.5, 0.3, 0.2, 0.4, 0.1]))
    >>> len(found), found[0]["branch"], why
    (8, 'right arm, elbow down, wrist not flipped', '')
    >>> far = np.eye(4)
    >>> far[0, 3] = 5.0
    >>> solve_target(arm, far)[1][:44]
    'no branch of the closed form reproduces the '
    """
    T = np.asarray(target, dtype=float).reshape(4, 4)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        return [], "the target must be 16 finite numbers"
    ik = getattr(robot, "ik", None)
    if ik is None:
        return [], "this chain has no inverse kinematics (load it as a robot: dhsym.load)"
    try:
        found = ik(T)
    except DHError as exc:
        return [], str(exc)
    rows = [
        {"branch": branch, "q": [float(x) for x in q]}
        for branch, q in zip(found.branches, np.asarray(found.q))
    ]
    return rows, "" if rows else (found.reason or "no solution")


@cache
def _widget_class() -> type:
    """The widget class, made once (anywidget is imported only when a view is shown)."""
    try:
        import anywidget
        import traitlets
    except ImportError as exc:  # pragma: no cover - the widgets extra is installed in CI
        raise DHError(
            "robot.view() needs anywidget: pip install 'dhsym[widgets]'; or write a page "
            "that needs nothing: dhsym view NAME -o arm.html"
        ) from exc

    class ArmView(anywidget.AnyWidget):
        """The arm with one slider per joint; ``q`` is shared with the page."""

        _esm = traitlets.Unicode().tag(sync=True)
        scene = traitlets.Dict().tag(sync=True)
        q = traitlets.List(traitlets.Float()).tag(sync=True)
        #: the pose the student asks for (16 numbers row by row), set by the page
        target = traitlets.List(traitlets.Float()).tag(sync=True)
        #: what the IK gave for it: ``{"branch": name, "q": [...]}`` each, and why none
        solutions = traitlets.List(traitlets.Dict()).tag(sync=True)
        reason = traitlets.Unicode("").tag(sync=True)
        #: counts the answers, so that the page hears each one (even a repeated one)
        solved = traitlets.Int(0).tag(sync=True)

        def __init__(
            self, *, static: tuple[str, str], solve: Callable[[np.ndarray], Any], **kw: Any
        ) -> None:
            super().__init__(**kw)
            self._static = static
            self._solve = solve

        @traitlets.observe("target")
        def _target_moved(self, change: dict[str, Any]) -> None:
            self.solutions, self.reason = self._solve(np.array(change["new"], dtype=float))
            self.solved += 1

        def _repr_mimebundle_(self, **kwargs: Any) -> tuple[dict[str, Any], dict[str, Any]]:
            bundle = super()._repr_mimebundle_(**kwargs)
            data: dict[str, Any] = dict(bundle[0]) if bundle else {}
            meta: dict[str, Any] = dict(bundle[1]) if bundle else {}
            data["image/png"], data["text/plain"] = self._static
            return data, meta

    return ArmView


def arm_view(
    robot: KinematicChain, q: Sequence[float] | None = None, *, workspace: int = WORKSPACE_POINTS
) -> Any:
    """An ``ArmView`` widget of ``robot`` at ``q`` (radians and length units).

    >>> import dhsym
    >>> view = arm_view(dhsym.load("planar2r").table.with_values({"a1": 1, "a2": 0.8}))
    >>> view.q, sorted(view._repr_mimebundle_()[0])[1:]
    ([0.0, 0.0], ['image/png', 'text/plain'])
    """
    from dhsym.kinematics.chain import KinematicChain

    chain = robot if isinstance(robot, KinematicChain) else KinematicChain(robot)
    shown = scene(chain, q, workspace=workspace)
    esm = (
        bundle() + "\n" + robot_script(chain) + "export default DhsymViewer.widget(DHSYM_ROBOT);\n"
    )
    text = f"{shown.name}: a 3D view with a slider per joint (q = {[float(x) for x in shown.q]})"
    return _widget_class()(
        solve=partial(solve_target, chain),
        _esm=esm,
        scene=shown.data(),
        q=[float(x) for x in shown.q],
        static=(_png(chain, shown.q), text),
    )
