"""The kinematics room: the one transform kernel (elementary matrices, words, ^iT_j, rigid
inverse), the compact closed form and its proof, compiled numbers, ``Pose`` and ``Chain``,
and kinematic decoupling (:mod:`.decoupling`), on which the Jacobian's factors and the
inverse kinematics (:mod:`dhsym.ik`) both rest.

May import :mod:`dhsym.model` and :mod:`dhsym.notation` (``Robot.plot`` reaches the plot
room and ``Robot.inverse``/``Robot.ik`` the :mod:`dhsym.ik` room at call time: conveniences).
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "Chain": "chain",
        "chain_word": "transforms",
        "compile_exprs": "numeric",
        "compile_pose": "numeric",
        "compile_word": "numeric",
        "compose": "simplification",
        "link_word": "transforms",
        "numeric_equal": "simplification",
        "plain_product": "transforms",
        "Pose": "pose",
        "Jacobian": "jacobian",
        "analytic_jacobian": "jacobian",
        "geometric_jacobian": "jacobian",
        "prove_equal": "simplification",
        "rigid_inverse": "transforms",
        "to_float": "numeric",
        "Rx": "transforms",
        "Ry": "transforms",
        "Rz": "transforms",
        "Tx": "transforms",
        "Ty": "transforms",
        "Tz": "transforms",
    },
)

__all__ = [
    "Jacobian",
    "Chain",
    "Pose",
    "Rx",
    "Ry",
    "Rz",
    "Tx",
    "Ty",
    "Tz",
    "analytic_jacobian",
    "chain_word",
    "compile_exprs",
    "compile_pose",
    "compile_word",
    "compose",
    "geometric_jacobian",
    "link_word",
    "numeric_equal",
    "plain_product",
    "prove_equal",
    "rigid_inverse",
    "to_float",
]
