"""The geometry room: joint axes as lines, the DH frame-assignment algorithm with its
sentences, standard <-> modified conversion, joint pairs and mobility, task-frame chains.

May import model, notation and kinematics.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "assign_frames": "frames",
        "check_conversion": "conversion",
        "common_normal": "axes",
        "CommonNormal": "axes",
        "convert": "conversion",
        "FrameAssignment": "frames",
        "FrameChain": "chains",
        "Joint": "joints",
        "JointAxis": "axes",
        "Mechanism": "joints",
        "mobility": "joints",
        "PAIRS": "joints",
        "to_modified": "conversion",
        "to_standard": "conversion",
        "Tool": "axes",
    },
)

__all__ = [
    "CommonNormal",
    "FrameAssignment",
    "FrameChain",
    "Joint",
    "JointAxis",
    "Mechanism",
    "PAIRS",
    "Tool",
    "assign_frames",
    "check_conversion",
    "common_normal",
    "convert",
    "mobility",
    "to_modified",
    "to_standard",
]
