"""The pictures room: the arm with its DH frames (matplotlib, imported when drawing),
the workspace, animations along a joint path, the manipulability ellipse and every
inverse-kinematics solution side by side.

May import model, notation and kinematics.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "animate_path": "animation",
        "frame_origins": "figures",
        "joint_path": "animation",
        "plot_manipulability": "ellipses",
        "plot_robot": "figures",
        "plot_solutions": "solutions",
        "plot_workspace": "figures",
        "velocity_ellipse": "ellipses",
    },
)

__all__ = [
    "animate_path",
    "frame_origins",
    "joint_path",
    "plot_manipulability",
    "plot_robot",
    "plot_solutions",
    "plot_workspace",
    "velocity_ellipse",
]
