"""The family classifier's choice: which derivation solves an arm, tried in order.

:func:`inverse` reads the structure of the table (:func:`~dhsym.ik.structure.classify`)
and derives the closed form with the family that fits:

* :data:`~dhsym.ik.structure.SPHERICAL_WRIST` and :data:`~dhsym.ik.structure.DECOUPLED`
  (fewer joints, prismatic joints): kinematic decoupling, :mod:`dhsym.ik.decoupled`;
* :data:`~dhsym.ik.structure.PARALLEL` (axes 2, 3, 4 parallel): :mod:`dhsym.ik.parallel`;
* :data:`~dhsym.ik.structure.INVERTED` (the first three axes meet, or axes 3, 4, 5 are
  parallel): the chain read backwards, :mod:`dhsym.ik.inverted`;
* :data:`~dhsym.ik.structure.GENERAL_6R`: :func:`general_6r`, the Raghavan–Roth
  elimination (:mod:`dhsym.ik.general`).

Examples
--------
>>> import dhsym
>>> inverse(dhsym.load("puma560")).family, inverse(dhsym.load("ur3")).family
('spherical wrist', 'three parallel axes')
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from dhsym.kinematics.decoupling import StructureError

from .closed_form import InverseKinematics
from .decoupled import derive_decoupled
from .inverted import derive_inverted
from .parallel import derive_parallel
from .structure import DECOUPLED, GENERAL_6R, INVERTED, PARALLEL, SPHERICAL_WRIST, classify

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["derivations", "general_6r", "inverse"]


def general_6r(robot: KinematicChain) -> InverseKinematics:
    """The general 6R (no three consecutive axes parallel or meeting): every solution by the
    Raghavan–Roth elimination (:func:`dhsym.ik.general.derive_general`).

    >>> import dhsym
    >>> ik = general_6r(dhsym.load("jaco"))
    >>> ik.family, ik.count
    ('general 6R', 16)
    """
    from .general import derive_general

    return derive_general(robot)


def derivations(family: str) -> tuple[Callable[[KinematicChain], InverseKinematics], ...]:
    """The derivations to try, in order, for an arm of ``family``.

    >>> [f.__name__ for f in derivations("three parallel axes")]
    ['derive_parallel']
    """
    table: dict[str, tuple[Callable[[KinematicChain], InverseKinematics], ...]] = {
        SPHERICAL_WRIST: (derive_decoupled,),
        DECOUPLED: (derive_decoupled,),
        PARALLEL: (derive_parallel,),
        INVERTED: (derive_inverted,),
        GENERAL_6R: (derive_decoupled, general_6r),
    }
    return table[family]


def inverse(robot: KinematicChain) -> InverseKinematics:
    """Derive the closed-form inverse kinematics of ``robot`` from the structure of its table.

    Raises
    ------
    StructureError
        When no family gives a closed form; the message names the structure found and
        what is missing.

    >>> import dhsym
    >>> ik = inverse(dhsym.load("puma560"))
    >>> print(ik.structure)
    spherical wrist: joints 1–3 place the wrist centre (origin of frame 4), joints 4–6 turn ...
    >>> [b.role for b in ik.branches], ik.count
    (['arm', 'elbow', 'wrist'], 8)
    >>> inverse(dhsym.load("planar4r"))
    Traceback (most recent call last):
    ...
    dhsym.kinematics.decoupling.StructureError: no closed-form inverse kinematics ...
    """
    structure = classify(robot)
    reasons = []
    for derive in derivations(structure.family):
        try:
            return derive(robot)
        except StructureError as err:
            reasons.append(err.message)
    found = f" ({structure})" if structure.sentences else ""
    raise StructureError(
        f"no closed-form inverse kinematics for {robot.name or 'this table'}{found}: "
        + "; ".join(reasons)
    )
