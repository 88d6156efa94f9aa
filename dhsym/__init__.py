"""dhsym: Denavit–Hartenberg tables to lecture-style closed-form kinematics.

>>> import dhsym
>>> robot = dhsym.load("planar2r")
>>> robot.arm_matrix()[0, 3]
a1*cos(theta1) + a2*cos(theta1 + theta2)
"""

from __future__ import annotations

from ._lazy import lazy_exports

# Every name loads on first use (PEP 562): `import dhsym` costs almost nothing, so that
# `dhsym --help` starts fast, and the names a program uses import only what they need.
__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        # the rooms themselves
        "checking": "checking",
        "cli": "cli",
        "explain": "explain",
        "export": "export",
        "geometry": "geometry",
        "kinematics": "kinematics",
        "model": "model",
        "notation": "notation",
        "plot": "plot",
        # model
        "AngleUnit": "dhsym.model.kinds",
        "Convention": "dhsym.model.kinds",
        "JointType": "dhsym.model.kinds",
        "DHRow": "dhsym.model.table",
        "DHTable": "dhsym.model.table",
        "Elementary": "dhsym.model.table",
        "builtin_names": "dhsym.model.library",
        "builtin_table": "dhsym.model.library",
        "load_table": "dhsym.model.library",
        "planar_chain": "dhsym.model.library",
        "dump_table": "dhsym.model.tablefile",
        "read_table": "dhsym.model.tablefile",
        "read_table_text": "dhsym.model.tablefile",
        # notation, kinematics
        "Notation": "dhsym.notation.printers",
        "Pose": "dhsym.kinematics.pose",
        "Robot": "dhsym.kinematics.robot",
        "load": "dhsym.kinematics.robot",
        # explain
        "Derivation": "dhsym.explain.derivation",
        "derive": "dhsym.explain.derivation",
        # plot
        "animate_path": "dhsym.plot.animation",
        "joint_path": "dhsym.plot.animation",
        "frame_origins": "dhsym.plot.figures",
        "plot_manipulability": "dhsym.plot.ellipses",
        "plot_robot": "dhsym.plot.figures",
        "plot_solutions": "dhsym.plot.solutions",
        "plot_workspace": "dhsym.plot.figures",
        # checking
        "Key": "dhsym.checking",
        "check": "dhsym.checking",
        "check_answer": "dhsym.checking",
        "grade": "dhsym.checking",
        # geometry
        "FrameChain": "dhsym.geometry.chains",
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
        # errors, version
        "ChainError": "dhsym.errors",
        "DHError": "dhsym.errors",
        "GeometryError": "dhsym.errors",
        "ParseError": "dhsym.errors",
        "TableError": "dhsym.errors",
        "__version__": "dhsym._version",
    },
)

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
    "check",
    "check_answer",
    "check_conversion",
    "common_normal",
    "convert",
    "derive",
    "dump_table",
    "export",
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
    "singularities",
    "to_modified",
    "to_standard",
    "__version__",
]
