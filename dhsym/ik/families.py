"""The family classifier's choice: which derivation solves an arm, tried in order.

:func:`inverse` reads the structure of the table (:func:`~dhsym.ik.structure.classify`)
and derives the closed form with the family that fits:

* :data:`~dhsym.ik.structure.SPHERICAL_WRIST` and :data:`~dhsym.ik.structure.DECOUPLED`
  (fewer joints, prismatic joints): kinematic decoupling, :mod:`dhsym.ik.decoupled`;
* :data:`~dhsym.ik.structure.PARALLEL` (axes 2, 3, 4 parallel): :mod:`dhsym.ik.parallel`;
* :data:`~dhsym.ik.structure.INVERTED` (the first three axes meet, or axes 3, 4, 5 are
  parallel): the chain read backwards, :mod:`dhsym.ik.inverted`;
* :data:`~dhsym.ik.structure.GENERAL_6R`: the Raghavan–Roth elimination
  (:func:`dhsym.ik.general6r.derive_general`, an :class:`~dhsym.ik.general6r.Elimination`).

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

from .closed_form import ClosedForm
from .decoupled import derive_decoupled
from .general6r import Elimination, derive_general
from .inverted import derive_inverted
from .parallel import derive_parallel
from .structure import DECOUPLED, GENERAL_6R, INVERTED, PARALLEL, SPHERICAL_WRIST, classify

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["derivations", "inverse"]

#: A family's derivation: the closed form, or the general 6R's elimination.
Derive = Callable[["KinematicChain"], ClosedForm | Elimination]


def derivations(family: str) -> tuple[Derive, ...]:
    """The derivations to try, in order, for an arm of ``family``.

    >>> [f.__name__ for f in derivations("three parallel axes")]
    ['derive_parallel']
    >>> [f.__name__ for f in derivations("general 6R")]
    ['derive_decoupled', 'derive_general']
    """
    table: dict[str, tuple[Derive, ...]] = {
        SPHERICAL_WRIST: (derive_decoupled,),
        DECOUPLED: (derive_decoupled,),
        PARALLEL: (derive_parallel,),
        INVERTED: (derive_inverted,),
        GENERAL_6R: (derive_decoupled, derive_general),
    }
    return table[family]


def inverse(robot: KinematicChain) -> ClosedForm | Elimination:
    """Derive the inverse kinematics of ``robot`` from the structure of its table: a
    :class:`~dhsym.ik.closed_form.ClosedForm`, or for the general 6R an
    :class:`~dhsym.ik.general6r.Elimination`.

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
