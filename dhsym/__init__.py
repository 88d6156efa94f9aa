"""dhsym: Denavit–Hartenberg tables to lecture-style closed-form kinematics.

>>> import dhsym
>>> robot = dhsym.load("planar2r")
>>> robot.arm_matrix()[0, 3]
a1*cos(theta1) + a2*cos(theta1 + theta2)
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from .chains import FrameChain
from .derivation import Derivation, derive
from .errors import ChainError, DHError, GeometryError, ParseError, TableError
from .library import builtin_names, builtin_table, load, load_table, planar_chain
from .notation import Notation
from .pose import Pose
from .robot import Robot
from .table import AngleUnit, Convention, DHRow, DHTable, Elementary, JointType
from .tablefile import dump_table, read_table, read_table_text

# Names whose modules import numpy or matplotlib load on first use (PEP 562), so that
# `import dhsym` costs little more than `import sympy`.
_LAZY = {
    "animate_path": "animation",
    "joint_path": "animation",
    "frame_origins": "plotting",
    "plot_robot": "plotting",
    "plot_workspace": "plotting",
    "Key": "checking",
    "check": "checking",
    "check_answer": "checking",
    "grade": "checking",
    "JointAxis": "axes",
    "Tool": "axes",
    "common_normal": "axes",
    "assign_frames": "frames",
    "FrameAssignment": "frames",
    "convert": "conversion",
    "to_modified": "conversion",
    "to_standard": "conversion",
    "check_conversion": "conversion",
    "Joint": "joints",
    "Mechanism": "joints",
    "PAIRS": "joints",
    "mobility": "joints",
}


def __getattr__(name: str) -> object:
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module 'dhsym' has no attribute {name!r}")


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
    "joint_path",
    "load",
    "load_table",
    "mobility",
    "planar_chain",
    "plot_robot",
    "plot_workspace",
    "read_table",
    "read_table_text",
    "to_modified",
    "to_standard",
    "__version__",
]
