"""Robotics Toolbox for Python (``roboticstoolbox``) DH robots both ways.

:func:`table_from_rtb` reads a ``DHRobot`` into a DH table through its documented attributes only
(``robot.links``, ``robot.mdh``, ``robot.base``, ``robot.tool``, ``robot.name``; each
link's ``sigma``, ``theta``, ``d``, ``a``, ``alpha``, ``offset``, ``qlim`` and
``isflip``), so it needs no import of the toolbox. The toolbox's link transform is
``θ = q + offset`` (``θ = −q + offset`` for a flipped joint; ``d`` likewise for a
prismatic one, ``DHLink.A``); a flipped joint becomes the entry ``offset − q``, so q
means the same in both. Floats are read as their exact decimals, and angles that are a
multiple of π/12 to the digits of a double are snapped as the table reader does.

:func:`to_rtb` builds a ``DHRobot`` (``RevoluteDH``/``PrismaticDH`` or the ``MDH``
classes) with offsets, flips, limits, base and tool; it imports ``roboticstoolbox``,
which is not a dependency of dhsym (``pip install roboticstoolbox-python``).
Dynamics parameters are not carried over either way yet.

Examples
--------
>>> from types import SimpleNamespace as Obj
>>> link = Obj(sigma=0, theta=0.0, d=0.5, a=0.0, alpha=1.5707963267948966, offset=0.0,
...            qlim=None, isflip=True)
>>> table = table_from_rtb(Obj(links=[link], mdh=False, base=None, tool=None, name="one"))
>>> table.rows[0], table.rows[0].offset
(DHRow(R: theta=-theta1, d=1/2, a=0, alpha=pi/2), 0)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import FormatError
from dhsym.geometry.axes import exact_matrix
from dhsym.geometry.conversion import transform_word
from dhsym.kinematics.numeric import to_float
from dhsym.model.entries import as_expr
from dhsym.model.kinds import Convention, JointType
from dhsym.model.parsing import symbol
from dhsym.model.table import DHRow, DHTable, Elementary

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["table_from_rtb", "to_rtb"]


def _number(value: object, where: str) -> sp.Expr:
    try:
        number = float(value)  # type: ignore[arg-type]  # anything: float() refuses it below
    except (TypeError, ValueError):
        raise FormatError(f"expected a number, got {value!r}", field=where) from None
    try:
        return as_expr(number, field=where)
    except Exception as err:  # noqa: BLE001 - re-raised as a format error
        raise FormatError(str(err), field=where) from None


def _transform(value: object, where: str) -> tuple[Elementary, ...]:
    """An SE3 (its ``.A``), a 4×4 array or None as a word of elementary transforms."""
    if value is None:
        return ()
    M = np.asarray(getattr(value, "A", value), dtype=float)
    if M.shape != (4, 4) or not np.all(np.isfinite(M)):
        raise FormatError(f"expected a 4×4 transform, got shape {M.shape}", field=where)
    if np.allclose(M, np.eye(4), atol=1e-15):
        return ()
    return transform_word(exact_matrix(M.tolist()))


def table_from_rtb(robot: object, *, name: str | None = None) -> DHTable:
    """A :class:`~dhsym.model.table.DHTable` from a roboticstoolbox ``DHRobot`` (``dhsym.from_rtb``
    makes it a :class:`~dhsym.robot.Robot`).

    >>> from types import SimpleNamespace as Obj
    >>> links = [Obj(sigma=0, theta=0.0, d=0.0, a=0.4318, alpha=0.0, offset=0.0,
    ...              qlim=[-0.7853981633974483, 3.9269908169872414], isflip=False),
    ...          Obj(sigma=1, theta=0.0, d=0.0, a=0.0, alpha=0.0, offset=0.1,
    ...              qlim=[0.0, 0.5], isflip=False)]
    >>> table = table_from_rtb(Obj(links=links, mdh=False, base=None, tool=None, name="RP"))
    >>> table.rows[0], table.rows[1]
    (DHRow(R: theta=theta1, d=0, a=2159/5000, alpha=0), DHRow(P: theta=0, d=d2 + 1/10, ...))
    >>> table.rows[0].limits
    (-pi/4, 5*pi/4)
    """
    links: Sequence[object] = list(getattr(robot, "links", None) or [])
    if not links:
        raise FormatError("expected a roboticstoolbox DHRobot with links", field="links")
    rows = []
    for k, link in enumerate(links, start=1):
        where = f"links[{k - 1}]"
        prismatic = bool(getattr(link, "sigma", 0))
        flip = bool(getattr(link, "isflip", getattr(link, "flip", False)))
        p = {
            key: _number(getattr(link, key, 0.0), f"{where}.{key}")
            for key in ("theta", "d", "a", "alpha", "offset")
        }
        var = symbol(f"d{k}" if prismatic else f"theta{k}")
        entry = (-var if flip else var) + p["offset"]
        qlim = getattr(link, "qlim", None)
        limits = None
        if qlim is not None and len(qlim) == 2 and all(np.isfinite(np.asarray(qlim, float))):
            limits = tuple(_number(v, f"{where}.qlim") for v in qlim)
            limits = _snapped_limits(limits) if not prismatic else limits
        kw = dict(a=p["a"], alpha=p["alpha"], variable=var, limits=limits)
        if prismatic:
            rows.append(DHRow.prismatic(entry, theta=p["theta"], **kw))
        else:
            rows.append(DHRow.revolute(entry, d=p["d"], **kw))
    title = name or str(getattr(robot, "name", "") or "roboticstoolbox robot")
    table = DHTable.from_rows(
        rows,
        convention=Convention.MODIFIED if getattr(robot, "mdh", False) else Convention.STANDARD,
        name=title,
        source=f"roboticstoolbox DHRobot {title}",
        base=_transform(getattr(robot, "base", None), "base"),
        tool=_transform(getattr(robot, "tool", None), "tool"),
    )
    return table


def _snapped_limits(limits: tuple[sp.Expr, ...]) -> tuple[sp.Expr, ...]:
    from dhsym.model.angles import AngleSnap, snap_angle

    out = []
    for v in limits:
        found = snap_angle(v, AngleSnap())
        out.append(found[0] if found else v)
    return tuple(out)


def to_rtb(robot: KinematicChain | DHTable) -> object:
    """A roboticstoolbox ``DHRobot`` with the table's offsets, flips, limits, base and tool.

    Needs ``roboticstoolbox`` (``pip install roboticstoolbox-python``) and numbers for
    every symbolic length (the table's ``values``).
    """
    try:
        import roboticstoolbox as rtb
        from spatialmath import SE3
    except ImportError:
        raise FormatError(
            "to_rtb needs the Robotics Toolbox for Python: pip install roboticstoolbox-python"
        ) from None
    from dhsym.kinematics.transforms import plain_product

    table = (robot if isinstance(robot, DHTable) else robot.table).substituted()
    if table.constants:
        missing = ", ".join(str(s) for s in table.constants)
        raise FormatError(f"give numbers for {missing} (table.with_values) before to_rtb")
    modified = table.convention is Convention.MODIFIED
    links = []
    for row in table.rows:
        var = row.variable
        if var is None:
            raise FormatError("fixed rows have no roboticstoolbox link", field="joints")
        field = row.variable_field
        assert field is not None  # var is not None: a joint row
        entry = getattr(row, field)
        slope = sp.expand(entry).coeff(var)
        if slope not in (1, -1):
            raise FormatError(f"{row.variable_field} = {entry}: the variable's factor must be ±1")
        offset = to_float(sp.expand(entry - slope * var))
        qlim = None if row.limits is None else [to_float(v) for v in row.limits]
        common = dict(a=to_float(row.a), alpha=to_float(row.alpha), offset=offset, flip=slope == -1)
        if qlim is not None:
            common["qlim"] = qlim
        if row.joint is JointType.PRISMATIC:
            prismatic = rtb.PrismaticMDH if modified else rtb.PrismaticDH
            links.append(prismatic(theta=to_float(row.theta), **common))
        else:
            revolute = rtb.RevoluteMDH if modified else rtb.RevoluteDH
            links.append(revolute(d=to_float(row.d), **common))

    def se3(word: tuple[Elementary, ...]) -> object:
        M = np.array(plain_product(word).evalf(30).tolist(), dtype=float)
        return SE3(M, check=False)

    return rtb.DHRobot(
        links, name=table.name or "dhsym robot", base=se3(table.base), tool=se3(table.tool)
    )
