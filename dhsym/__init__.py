"""dhsym: Denavit–Hartenberg tables to lecture-style closed-form kinematics.

>>> import dhsym
>>> robot = dhsym.load("planar2r")
>>> robot.arm_matrix()[0, 3]
a1*cos(theta1) + a2*cos(theta1 + theta2)
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from dhsym.explain.derivation import Derivation, derive
from dhsym.geometry.chains import FrameChain
from dhsym.kinematics.pose import Pose
from dhsym.kinematics.robot import Robot, load
from dhsym.model.kinds import AngleUnit, Convention, JointType
from dhsym.model.library import builtin_names, builtin_table, load_table, planar_chain
from dhsym.model.table import DHRow, DHTable, Elementary
from dhsym.model.tablefile import dump_table, read_table, read_table_text
from dhsym.notation.printers import Notation

from ._lazy import lazy_exports
from .errors import ChainError, DHError, GeometryError, ParseError, TableError

# Names whose modules import numpy, matplotlib or the checker load on first use (PEP 562),
# so that `import dhsym` costs little more than `import sympy`.
__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "animate_path": "dhsym.plot.animation",
        "joint_path": "dhsym.plot.animation",
        "frame_origins": "dhsym.plot.figures",
        "plot_manipulability": "dhsym.plot.ellipses",
        "plot_robot": "dhsym.plot.figures",
        "plot_solutions": "dhsym.plot.solutions",
        "plot_workspace": "dhsym.plot.figures",
        "Key": "dhsym.checking",
        "check_answer": "dhsym.checking",
        "grade": "dhsym.checking",
        "JointAxis": "dhsym.geometry.axes",
        "Tool": "dhsym.geometry.axes",
        "common_normal": "dhsym.geometry.axes",
        "assign_frames": "dhsym.geometry.frames",
        "FrameAssignment": "dhsym.geometry.frames",
        "convert": "dhsym.geometry.conversion",
        "to_modified": "dhsym.geometry.conversion",
        "to_standard": "dhsym.geometry.conversion",
        "check_conversion": "dhsym.geometry.conversion",
        "Joint": "dhsym.geometry.joints",
        "Mechanism": "dhsym.geometry.joints",
        "PAIRS": "dhsym.geometry.joints",
        "mobility": "dhsym.geometry.joints",
        "inverse": "dhsym.kinematics.robot",
        "singularities": "dhsym.kinematics.singularities",
    },
)


try:
    __version__ = version("dhsym")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0"

__all__ = [
    "AngleUnit",
    "ChainError",
    "Convention",
    "DHError",
    "DHRow",
    "DHTable",
    "Derivation",
    "Elementary",
    "FrameAssignment",
    "FrameChain",
    "GeometryError",
    "Joint",
    "JointAxis",
    "JointType",
    "Key",
    "Mechanism",
    "Notation",
    "PAIRS",
    "ParseError",
    "Pose",
    "Robot",
    "TableError",
    "Tool",
    "animate_path",
    "assign_frames",
    "builtin_names",
    "builtin_table",
    "check_answer",
    "check_conversion",
    "common_normal",
    "convert",
    "derive",
    "dump_table",
    "frame_origins",
    "grade",
    "inverse",
    "joint_path",
    "load",
    "load_table",
    "mobility",
    "planar_chain",
    "plot_manipulability",
    "plot_robot",
    "plot_solutions",
    "plot_workspace",
    "read_table",
    "read_table_text",
    "to_modified",
    "to_standard",
    "__version__",
]
