"""The screws room: screw axes, twists, the matrix exponential and logarithm, the adjoint
(Lynch and Park, *Modern Robotics*), a robot as a product of exponentials, DH ↔ PoE.

May import model, cache, notation, kinematics and geometry.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "Exponential": "algebra",
        "MatrixLog": "algebra",
        "ScrewAxis": "algebra",
        "adjoint": "algebra",
        "bracket": "algebra",
        "matrix_exp": "algebra",
        "matrix_log": "algebra",
        "skew": "algebra",
    },
)

__all__ = [
    "Exponential",
    "MatrixLog",
    "ScrewAxis",
    "adjoint",
    "bracket",
    "matrix_exp",
    "matrix_log",
    "skew",
]
