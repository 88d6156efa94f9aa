"""The inverse kinematics room: derivations family by family, their solvers, one solution type.

:mod:`.structure` classifies an arm by its joint axes; one module per family derives its
closed form as lecture steps (:mod:`.decoupled`: spherical wrist and planar arms;
:mod:`.parallel`: three parallel axes; :mod:`.inverted`: the chain read backwards), each a
:class:`~.closed_form.ClosedForm` made of the pieces of :mod:`.steps`; :mod:`.general6r`
solves the general 6R by Raghavan–Roth elimination (an :class:`~.general6r.Elimination`);
:mod:`.families` chooses. Both derivations follow :class:`~.protocols.InverseKinematics`;
their solvers (:class:`~.closed_form_solver.ClosedFormSolver`: the steps rewritten by
:mod:`.rewriting` and compiled; :class:`~.general6r.EliminationSolver`) follow
:class:`~.protocols.IKSolver` and return the one :class:`~.solution.IKSolution`, as the
numeric solver (:mod:`.levenberg_marquardt`) does; :mod:`.choices` applies joint limits, a
given joint and the nearest solution, and keeps what was derived
(:class:`~.choices.IKCache`).

May import :mod:`dhsym.model`, :mod:`dhsym.notation` and :mod:`dhsym.kinematics`.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "ClosedForm": "closed_form",
        "Elimination": "general6r",
        "IKCache": "choices",
        "IKSolution": "solution",
        "IKSolver": "protocols",
        "InverseKinematics": "protocols",
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
    "ClosedForm",
    "Elimination",
    "IKCache",
    "IKSolution",
    "IKSolver",
    "InverseKinematics",
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
