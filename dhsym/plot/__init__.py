"""The pictures room: the arm with its DH frames (matplotlib, imported when drawing),
the workspace, and animations along a joint path.

May import model, notation and kinematics.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "animate_path": "animation",
        "frame_origins": "figures",
        "joint_path": "animation",
        "plot_robot": "figures",
        "plot_workspace": "figures",
    },
)

__all__ = [
    "animate_path",
    "frame_origins",
    "joint_path",
    "plot_robot",
    "plot_workspace",
]
