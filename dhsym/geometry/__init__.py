"""The geometry room: joint axes as lines, the DH frame-assignment algorithm with its
sentences, the senses of x a textbook (or a reference table) chooses, standard <->
modified conversion, joint pairs and mobility, task-frame chains.

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
        "FrameChoice": "frame_choices",
        "Joint": "joints",
        "JointAxis": "axes",
        "Mechanism": "joints",
        "match_frames": "frame_choices",
        "mobility": "joints",
        "PAIRS": "joints",
        "to_modified": "conversion",
        "textbook_frames": "frame_choices",
        "to_standard": "conversion",
        "Tool": "axes",
    },
)

__all__ = [
    "CommonNormal",
    "FrameAssignment",
    "FrameChain",
    "FrameChoice",
    "Joint",
    "JointAxis",
    "Mechanism",
    "PAIRS",
    "Tool",
    "assign_frames",
    "check_conversion",
    "common_normal",
    "convert",
    "match_frames",
    "mobility",
    "textbook_frames",
    "to_modified",
    "to_standard",
]
