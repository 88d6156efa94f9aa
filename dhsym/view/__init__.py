"""The arm in 3D: one slider per joint, its DH frames, the arm matrix read out live.

A room of its own above the export room: :mod:`.scene` is what the view shows (the joints'
sliders in the table's units and limits, the base and tool, sizes from the DH lengths, the
closed-form entries, the workspace), :mod:`.javascript` the robot's generated JavaScript
(the link matrices and the fk, printed from the export room's programs, as the C is),
:mod:`.page` one self-contained HTML page (three.js, the view and the robot inlined: it
opens offline, from a file, in a docs site or an LMS page) and :mod:`.widget` the
JupyterLab widget (anywidget) with its static picture where widgets do not run. The
JavaScript of the view is bundled with three.js from npm (``js/``) into
``dhsym/view/static/viewer.js``, shipped in the wheel: nothing is fetched.

May import model, notation, kinematics, ik, export, plot.
"""

from __future__ import annotations

from .page import view_page
from .scene import JointSlider, Scene, scene

__all__ = ["JointSlider", "Scene", "scene", "view_page"]
