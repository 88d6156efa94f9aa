"""The screws room: screw axes, twists, the matrix exponential and logarithm, the adjoint
(Lynch and Park, *Modern Robotics*), a robot as a product of exponentials, DH ↔ PoE.

May import model, cache, notation, kinematics and geometry.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "AxisStep": "product",
        "Exponential": "algebra",
        "MatrixLog": "algebra",
        "ProductOfExponentials": "product",
        "ScrewAxis": "algebra",
        "ScrewJacobian": "product",
        "adjoint": "algebra",
        "body_from_geometric": "product",
        "bracket": "algebra",
        "from_chain": "product",
        "matrix_exp": "algebra",
        "matrix_log": "algebra",
        "prove_same_fk": "product",
        "read_poe": "poefile",
        "read_poe_text": "poefile",
        "skew": "algebra",
        "space_from_geometric": "product",
        "to_dh": "poe_to_dh",
    },
)

__all__ = [
    "AxisStep",
    "Exponential",
    "MatrixLog",
    "ProductOfExponentials",
    "ScrewAxis",
    "ScrewJacobian",
    "adjoint",
    "body_from_geometric",
    "bracket",
    "from_chain",
    "matrix_exp",
    "matrix_log",
    "prove_same_fk",
    "read_poe",
    "read_poe_text",
    "skew",
    "space_from_geometric",
    "to_dh",
]
