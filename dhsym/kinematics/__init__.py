"""The kinematics room: the one transform kernel (elementary matrices, words, ^iT_j, rigid
inverse), the compact closed form and its proof, compiled numbers, ``Pose``,
``KinematicChain`` (the typed core every room above takes: table, notation, cached ``^iT_j``,
compiled fk and Jacobian functions), Jacobians, singularities and kinematic decoupling
(:mod:`.decoupling`), on which the Jacobian's factors and the inverse kinematics
(:mod:`dhsym.ik`) both rest.

May import :mod:`dhsym.model` and :mod:`dhsym.notation`, nothing else: the conveniences
that reach the rooms above (``ik``, ``dynamics``, ``plot``, …) are
:class:`dhsym.robot.Robot`'s.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "KinematicChain": "chain",
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
        "to_float": "constants",
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
    "KinematicChain",
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
