"""The inverse kinematics room: closed forms derived family by family, their compiler, and
a numeric solver apart.

:mod:`.structure` classifies an arm by its joint axes; one module per family derives its
closed form as lecture steps (:mod:`.decoupled`: spherical wrist and planar arms;
:mod:`.parallel`: three parallel axes; :mod:`.inverted`: the chain read backwards;
:mod:`.general6r`: the general 6R by Raghavan–Roth elimination, :mod:`.general` its
derivation and solver behind ``Robot.ik``);
:mod:`.families` chooses; :mod:`.compiler` turns the steps into numbers and
:mod:`.results` holds what it returns; :mod:`.choices` applies joint limits, a given
joint and the nearest solution; :mod:`.levenberg_marquardt` is the numeric solver.

May import :mod:`dhsym.model`, :mod:`dhsym.notation` and :mod:`dhsym.kinematics`.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "IKBatch": "results",
        "IKCache": "choices",
        "IKSolution": "results",
        "InverseKinematics": "closed_form",
        "NumericSolution": "levenberg_marquardt",
        "Structure": "structure",
        "StructureError": "dhsym.kinematics.decoupling",
        "classify": "structure",
        "general_6r": "general6r",
        "inverse": "families",
        "numeric_ik": "levenberg_marquardt",
        "pose_symbols": "steps",
        "solve": "choices",
        "sweep_free_joint": "choices",
    },
)

__all__ = [
    "IKBatch",
    "IKCache",
    "IKSolution",
    "InverseKinematics",
    "NumericSolution",
    "Structure",
    "StructureError",
    "classify",
    "general_6r",
    "inverse",
    "numeric_ik",
    "pose_symbols",
    "solve",
    "sweep_free_joint",
]
