"""The inertial model of a chain: each link's parameters, the joint rates and gravity.

A link *i* is the body that carries DH frame *i*; joint *j* moves the links ``i ≥ j``.
Rows without inertial parameters get the textbook symbolic set
(:meth:`~dhsym.model.inertia.LinkInertia.textbook`) when ``textbook=True``; fixed
rows without parameters carry no mass.

A joint variable ``q`` enters its cell as ``k q + c`` (``theta: -theta1`` of the Jaco,
``theta: 2*theta2``, ``d: -d3``): the joint turns (slides) at ``k q̇``, and the torque
(force) of the equations of motion is the generalized force of ``q``, ``k`` times the
moment (force) along the joint's axis. ``cell_rates`` keeps each ``k``, read once from
:func:`~dhsym.kinematics.jacobian.joint_rows`; Lagrange–Euler, Newton–Euler, the numeric
recursion and the exported ``rne`` all read it here. Motor inertia ``Jm G²`` and
friction stay defined on ``q`` itself.

Examples
--------
>>> import dhsym
>>> dm = dynamic_model(dhsym.load("planar2r"))
>>> dm.rates, dm.accelerations, dm.cell_rates
((thetadot1, thetadot2), (thetaddot1, thetaddot2), (1, 1))
>>> dm.links[0].m, dm.gravity
(m1, (0, 0, -981/100))
>>> dynamic_model(dhsym.load("jaco")).cell_rates
(-1, 1, 1, 1, 1, 1)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.jacobian import joint_rows
from dhsym.model.inertia import LinkInertia
from dhsym.model.parsing import rate_symbols
from dhsym.model.table import JointType

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["DynamicModel", "dynamic_model", "rate_symbols"]

Matrix: TypeAlias = sp.ImmutableMatrix
_ZERO_LINK = LinkInertia(0, (0, 0, 0), sp.zeros(3, 3))


@dataclass(frozen=True)
class DynamicModel:
    """A robot with the inertial parameters of every link (one per DH row).

    ``joints[k]`` is the 1-based row of the k-th joint variable and ``cell_rates[k]`` the
    rate ``∂ cell / ∂ q_k`` of its variable in its cell (a nonzero constant: the joint
    moves at ``cell_rates[k] · q̇_k``); ``gravity`` is the gravitational acceleration
    written in DH frame 0.
    """

    robot: KinematicChain = field(compare=False, repr=False)
    links: tuple[LinkInertia, ...]
    variables: tuple[sp.Symbol, ...]
    rates: tuple[sp.Symbol, ...]
    accelerations: tuple[sp.Symbol, ...]
    joints: tuple[int, ...]
    kinds: tuple[JointType, ...]
    cell_rates: tuple[sp.Expr, ...]
    gravity: tuple[sp.Expr, sp.Expr, sp.Expr]

    @property
    def n(self) -> int:
        """Number of joint variables."""
        return len(self.variables)

    @property
    def parameters(self) -> tuple[sp.Symbol, ...]:
        """The constant symbols of the inertial parameters and gravity, sorted by name."""
        syms = set().union(*(L.free_symbols for L in self.links))
        syms |= set().union(*(g.free_symbols for g in self.gravity))
        return tuple(sorted(syms, key=lambda s: s.name))

    @property
    def masses(self) -> tuple[sp.Symbol, ...]:
        """The symbols of the link masses (what printed results are collected by)."""
        syms = set().union(*(L.m.free_symbols for L in self.links))
        return tuple(sorted(syms, key=lambda s: s.name))

    @property
    def has_drive(self) -> bool:
        """Whether any joint has motor inertia or friction."""
        return any(self.links[r - 1].has_drive for r in self.joints)

    def armature(self) -> tuple[sp.Expr, ...]:
        """``Jm G²`` per joint (the motor inertia seen at the joint)."""
        return tuple(self.links[r - 1].Jm * self.links[r - 1].G ** 2 for r in self.joints)


def dynamic_model(robot: KinematicChain, *, textbook: bool = True) -> DynamicModel:
    """The inertial model of ``robot``; rows without parameters get the textbook set.

    With ``textbook=False`` a joint row without parameters is an error.
    """
    table = robot.table
    # the rate of each joint's variable in its cell (joint_rows refuses a cell that is
    # not linear in its variable, naming the row and field)
    cell_rates = tuple(rate for _, _, _, rate in joint_rows(robot))
    links = []
    for i, row in enumerate(table.rows, start=1):
        if row.inertia is not None:
            links.append(row.inertia)
        elif row.joint is JointType.FIXED:
            links.append(_ZERO_LINK)
        elif textbook:
            links.append(LinkInertia.textbook(i))
        else:
            raise DHError(f"row {i} has no inertial parameters (m, r, I)")
    gravity = Matrix(table.gravity)
    if table.base:  # gravity is given in the world frame: write it in frame 0
        gravity = Matrix(robot.transform(0, -1).matrix[:3, :3] * gravity)
    variables = table.variables
    return DynamicModel(
        robot,
        tuple(links),
        variables,
        rate_symbols(variables),
        rate_symbols(variables, 2),
        table.joint_rows,
        tuple(table.rows[r - 1].joint for r in table.joint_rows),
        cell_rates,
        tuple(sp.expand(g) for g in gravity),
    )
