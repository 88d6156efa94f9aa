"""Statics, the bridge from the Jacobian lecture: the joint torques τ = Jᵀ F that balance
a wrench ``F = [f; n]`` at the tip (Spong, Hutchinson and Vidyasagar, §4.10).

Examples
--------
>>> import dhsym
>>> s = statics(dhsym.load("planar2r"))
>>> print(s.notation.text(s.tau))
Matrix([
[nz + fy*(a1*C1 + a2*C12) - fx*(a1*S1 + a2*S12)],
[                    nz + fy*a2*C12 - fx*a2*S12]])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.jacobian import compact, geometric_jacobian
from dhsym.model.parsing import REAL
from dhsym.notation.printers import Notation

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["Statics", "WRENCH", "static_torques", "statics"]

Matrix: TypeAlias = sp.ImmutableMatrix

#: The symbols of a tip wrench in the base frame: force ``fx, fy, fz``, moment ``nx, ny, nz``.
WRENCH = tuple(sp.Symbol(s, **REAL) for s in ("fx", "fy", "fz", "nx", "ny", "nz"))


@dataclass(frozen=True)
class Statics:
    """``tau = Jᵀ F`` with ``F = (fx, fy, fz, nx, ny, nz)`` in the base frame."""

    tau: Matrix
    wrench: tuple[sp.Symbol, ...]
    jacobian: Matrix
    robot: KinematicChain = field(repr=False, compare=False)

    @property
    def notation(self) -> Notation:
        """The robot's lecture notation."""
        return self.robot.notation


def statics(robot: KinematicChain) -> Statics:
    """The exact ``τ = Jᵀ F`` of ``robot`` (geometric Jacobian at the tool, base frame);
    its numbers at a configuration are :func:`static_torques`."""
    J = geometric_jacobian(robot).matrix
    tau = (J.T * Matrix(WRENCH)).applyfunc(
        lambda e: sp.collect(sp.expand(e), WRENCH, evaluate=True, func=compact)
    )
    return Statics(Matrix(tau), WRENCH, Matrix(J), robot)


def static_torques(
    robot: KinematicChain,
    q: object,
    wrench: object,
    *,
    values: Mapping[object, object] | None = None,
) -> np.ndarray:
    """The numbers of :func:`statics`: τ = J(q)ᵀ F for one state ``(n,)`` or a batch
    ``(..., n)``, ``wrench`` ``(..., 6)`` in the base frame (the Jacobian of
    :meth:`~dhsym.kinematics.chain.KinematicChain.jacob0`).

    >>> import dhsym
    >>> static_torques(dhsym.load("planar2r"), [0.0, 0.0], [0, 1, 0, 0, 0, 0])
    array([1.8, 0.8])
    """
    F = np.asarray(wrench, dtype=float)
    if F.shape[-1:] != (6,):
        raise DHError(f"a wrench has 6 entries [fx, fy, fz, nx, ny, nz], got shape {F.shape}")
    J = robot.jacob0(np.asarray(q, dtype=float), values=values)
    tau: np.ndarray = np.einsum("...ij,...i->...j", J, F)
    return tau
