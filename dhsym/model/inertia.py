"""The inertial parameters of one link, with roboticstoolbox's ``Link`` names.

A link's mass ``m``, its centre of mass ``r`` in link frame *i*, its inertia ``I``
about the centre of mass in link frame *i* (symmetric 3×3), and optionally the
motor inertia ``Jm``, gear ratio ``G``, viscous friction ``B`` and Coulomb friction
``Tc`` (``[Tc+, Tc−]``), all exact sympy expressions. The textbook symbolic set
(Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, §7.2) is
:meth:`LinkInertia.textbook`.

Examples
--------
>>> L = LinkInertia.from_data({"m": 17.4, "r": [-0.3638, 0.006, 0.2275],
...                            "I": [0.13, 0.524, 0.539, 0, 0, 0]}, row=2)
>>> L.m, L.r, L.I[2, 2]
(87/5, (-1819/5000, 3/500, 91/400), 539/1000)
>>> LinkInertia.from_data({"m": -1}, row=3)
Traceback (most recent call last):
...
dhsym.errors.TableError: row 3, field m: a mass cannot be negative (got -1)
>>> LinkInertia.textbook(2).parameters()
(m2, rx2, ry2, rz2, Ixx2, Iyy2, Izz2, Ixy2, Iyz2, Ixz2)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TypeAlias

import sympy as sp

from dhsym.errors import TableError

from .entries import as_expr
from .parsing import reserved_symbols, symbol

__all__ = ["INERTIA_KEYS", "LinkInertia"]

#: The per-row keys of a table file that hold inertial parameters.
INERTIA_KEYS = ("m", "r", "I", "Jm", "G", "B", "Tc")

Expr: TypeAlias = sp.Expr
_ZERO = sp.Integer(0)


def _expr(value: object, field: str, row: int | None) -> Expr:
    return as_expr(value, field=field, row=row)  # numbers exact, text via the whitelist parser


def _vector(value: object, n: int, field: str, row: int | None) -> tuple[Expr, ...]:
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) or len(value) != n:
        raise TableError(
            f"{field} must be a list of {n} values, got {value!r}", row=row, field=field
        )
    return tuple(_expr(v, field, row) for v in value)


def _inertia_matrix(value: object, row: int | None) -> sp.ImmutableMatrix:
    """``[Ixx, Iyy, Izz, Ixy, Iyz, Ixz]`` (roboticstoolbox's order), 3 diagonal values or 3×3."""
    if isinstance(value, sp.MatrixBase):
        value = value.tolist()
    if isinstance(value, Sequence) and not isinstance(value, (str, bytes)):
        if len(value) == 3 and all(
            isinstance(v, Sequence) and not isinstance(v, (str, bytes)) for v in value
        ):
            rows = [_vector(v, 3, "I", row) for v in value]
            M = sp.ImmutableMatrix(rows)
            for i, j in ((0, 1), (1, 2), (0, 2)):
                if sp.expand(M[i, j] - M[j, i]) != 0:
                    raise TableError(
                        f"the inertia is not symmetric: I[{i + 1},{j + 1}] = {M[i, j]} but "
                        f"I[{j + 1},{i + 1}] = {M[j, i]}",
                        row=row,
                        field="I",
                    )
            return M
        if len(value) in (3, 6):
            v = _vector(value, len(value), "I", row) + (_ZERO,) * (6 - len(value))
            xx, yy, zz, xy, yz, xz = v
            return sp.ImmutableMatrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    raise TableError(
        f"I must be 6 values [Ixx, Iyy, Izz, Ixy, Iyz, Ixz], 3 diagonal values or a 3x3 "
        f"list, got {value!r}",
        row=row,
        field="I",
    )


@dataclass(frozen=True)
class LinkInertia:
    """Mass, centre of mass, inertia about the centre of mass and drive of one link.

    Parameters
    ----------
    m
        Mass.
    r
        Centre of mass in link frame *i*, 3 entries.
    I
        Inertia about the centre of mass, axes of link frame *i* (symmetric 3×3).
    Jm, G, B, Tc
        Motor inertia, gear ratio, viscous and Coulomb friction (motor side, as in
        roboticstoolbox): the joint sees ``Jm G²`` more inertia and the friction torque
        ``B G² q̇ + |G| Tc`` (``Tc[0]`` when ``q̇ > 0``, ``Tc[1]`` when ``q̇ < 0``).
    """

    m: Expr
    r: tuple[Expr, Expr, Expr]
    I: sp.ImmutableMatrix  # noqa: E741 (roboticstoolbox's name)
    Jm: Expr = _ZERO
    G: Expr = sp.Integer(1)
    B: Expr = _ZERO
    Tc: tuple[Expr, Expr] = (_ZERO, _ZERO)

    @classmethod
    def from_data(
        cls, data: Mapping[str, object], *, row: int | None = None, physical: bool = True
    ) -> LinkInertia:
        """Read the keys of :data:`INERTIA_KEYS` (missing ones are zero, ``G`` one) and check them
        (``physical=False``: without the triangle inequality, for published data that breaks it).

        >>> LinkInertia.from_data({"m": "m1", "r": ["lc1 - a1", 0, 0], "Tc": 0.4}).Tc
        (2/5, -2/5)
        """
        unknown = sorted(set(data) - set(INERTIA_KEYS))
        if unknown:
            raise TableError(
                f"unknown inertial key {unknown[0]!r}: expected {', '.join(INERTIA_KEYS)}",
                row=row,
                field=unknown[0],
            )
        m = _expr(data.get("m", 0), "m", row)
        r = _vector(data.get("r", [0, 0, 0]), 3, "r", row)
        inertia = _inertia_matrix(data.get("I", [0, 0, 0, 0, 0, 0]), row)
        tc = data.get("Tc", 0)
        if isinstance(tc, Sequence) and not isinstance(tc, (str, bytes)):
            pair = _vector(tc, 2, "Tc", row)
        else:
            c = _expr(tc, "Tc", row)
            pair = (c, -c)
        scalars = {k: _expr(data[k], k, row) for k in ("Jm", "G", "B") if k in data}
        out = cls(m, r, inertia, Tc=pair, **scalars)
        out.check(row=row, physical=physical)
        return out

    @classmethod
    def textbook(cls, i: int) -> LinkInertia:
        """The symbolic set of link ``i``: ``m_i``, ``(rx_i, ry_i, rz_i)``, a full symmetric I.

        >>> LinkInertia.textbook(1).I
        Matrix([
        [Ixx1, Ixy1, Ixz1],
        [Ixy1, Iyy1, Iyz1],
        [Ixz1, Iyz1, Izz1]])
        """
        s = {n: symbol(f"{n}{i}") for n in ("Ixx", "Iyy", "Izz", "Ixy", "Iyz", "Ixz")}
        inertia = sp.ImmutableMatrix(
            [
                [s["Ixx"], s["Ixy"], s["Ixz"]],
                [s["Ixy"], s["Iyy"], s["Iyz"]],
                [s["Ixz"], s["Iyz"], s["Izz"]],
            ]
        )
        return cls(symbol(f"m{i}"), tuple(symbol(f"{c}{i}") for c in ("rx", "ry", "rz")), inertia)

    def __post_init__(self) -> None:
        # every entry through as_expr: exact, real and finite (complex values are refused)
        for name in ("m", "Jm", "G", "B"):
            object.__setattr__(self, name, as_expr(getattr(self, name), field=name))
        object.__setattr__(self, "r", tuple(as_expr(v, field="r") for v in self.r))
        object.__setattr__(self, "Tc", tuple(as_expr(v, field="Tc") for v in self.Tc))
        inertia = sp.ImmutableMatrix(self.I)
        object.__setattr__(self, "I", inertia.applyfunc(lambda v: as_expr(v, field="I")))
        if len(self.r) != 3 or self.I.shape != (3, 3) or len(self.Tc) != 2:
            raise TableError("r has 3 entries, I is 3x3 and Tc has 2 entries", field="inertia")

    def check(self, *, row: int | None = None, physical: bool = True) -> None:
        """Refuse a negative mass, and a numeric inertia that is not symmetric positive
        semi-definite or breaks the triangle inequality ``Ixx + Iyy ≥ Izz`` (and cyclic).

        >>> LinkInertia(1, (0, 0, 0), sp.diag(1, 1, 3)).check(row=2)
        Traceback (most recent call last):
        ...
        dhsym.errors.TableError: row 2, field I: the principal moments break the triangle ...
        """
        if self.m.is_number and self.m.is_negative:
            raise TableError(f"a mass cannot be negative (got {self.m})", row=row, field="m")
        for name in ("Jm", "B"):
            v = getattr(self, name)
            if v.is_number and v.is_negative:
                raise TableError(f"{name} cannot be negative (got {v})", row=row, field=name)
        if self.I != self.I.T:
            raise TableError("the inertia is not symmetric", row=row, field="I")
        if self.I.free_symbols:
            return
        import numpy as np

        values = np.linalg.eigvalsh(np.array(self.I.evalf(30).tolist(), dtype=float))
        scale = max(1.0, float(np.max(np.abs(values))))
        if values[0] < -1e-12 * scale:
            raise TableError(
                "the inertia is not positive semi-definite "
                f"(a principal moment is {values[0]:.6g})",
                row=row,
                field="I",
            )
        a, b, c = sorted(values)
        if physical and a + b < c - 1e-12 * scale:
            raise TableError(
                f"the principal moments break the triangle inequality ({a:.6g} + {b:.6g} "
                f"< {c:.6g}): no rigid body has this inertia (published data that breaks it: "
                "physical: false at the top of the table)",
                row=row,
                field="I",
            )

    @classmethod
    def combine(cls, parts: Sequence[LinkInertia]) -> LinkInertia:
        """One rigid body of several parts given in the same frame.

        The masses add, the centre of mass is the mass-weighted mean of the parts' centres,
        and each part's inertia moves from its own centre of mass to the common one by the
        parallel-axis theorem (:meth:`inertia_about`); the moved inertias add.

        Parameters
        ----------
        parts
            The parts, each with its mass, centre of mass and inertia about it, all in the
            axes of one frame. A drive (``Jm``, ``B``, ``Tc``) belongs to a joint, not to a
            body: parts with one are refused.

        Returns
        -------
        LinkInertia
            The whole body, in the same frame, with no drive. Entries are exact and not
            simplified (expand them as needed); a massless whole has its centre of mass at
            the origin.

        Examples
        --------
        Two unit point masses one unit either side of the origin on the x axis: mass 2,
        centre of mass at the origin, inertia ``m d² = 1`` from each about the y and z axes.

        >>> point = sp.zeros(3)
        >>> both = LinkInertia.combine(
        ...     [LinkInertia(1, (1, 0, 0), point), LinkInertia(1, (-1, 0, 0), point)]
        ... )
        >>> both.m, both.r, both.I.diagonal()
        (2, (0, 0, 0), Matrix([[0, 2, 2]]))
        """
        for k, part in enumerate(parts, start=1):
            if part.has_drive:
                raise TableError(
                    f"part {k} has a drive (motor inertia or friction): a drive belongs to a "
                    "joint, combine the bodies without it",
                    field="inertia",
                )
        m = sum((part.m for part in parts), sp.Integer(0))
        if m == 0:
            c = sp.zeros(3, 1)
        else:
            c = sum((part.m * sp.Matrix(part.r) for part in parts), sp.zeros(3, 1)) / m
        total = sp.zeros(3)
        for part in parts:
            total += part.inertia_about(c)
        return cls(m, (c[0], c[1], c[2]), sp.ImmutableMatrix(total))

    def inertia_about(self, point: Sequence[object] | sp.MatrixBase) -> sp.ImmutableMatrix:
        """The inertia about ``point`` (in link frame *i*, its axes), by the parallel-axis
        theorem ``I + m (dᵀd E − d dᵀ)`` with ``d = r − point``.

        >>> LinkInertia(2, (1, 0, 0), sp.diag(1, 1, 1)).inertia_about((0, 0, 0))
        Matrix([
        [1, 0, 0],
        [0, 3, 0],
        [0, 0, 3]])
        """
        d = sp.Matrix(self.r) - sp.Matrix(point)
        return sp.ImmutableMatrix(self.I + self.m * ((d.T * d)[0, 0] * sp.eye(3) - d * d.T))

    def parameters(self) -> tuple[Expr, ...]:
        """The standard 10 parameters as given here: ``m, r, I`` (about the centre of mass).

        The linear-in-parameters form uses first moments ``m r`` and the inertia about
        the link origin instead (:mod:`dhsym.dynamics.inertial_parameters`).
        """
        I = self.I  # noqa: E741
        return (self.m, *self.r, I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[1, 2], I[0, 2])

    def entries(self) -> dict[str, tuple[Expr, ...]]:
        """The parameters by their key in a table file (:data:`INERTIA_KEYS`).

        >>> LinkInertia(2, (1, 0, 0), sp.zeros(3)).entries()["r"]
        (1, 0, 0)
        """
        return {
            "m": (self.m,),
            "r": self.r,
            "I": tuple(self.I),
            "Jm": (self.Jm,),
            "G": (self.G,),
            "B": (self.B,),
            "Tc": self.Tc,
        }

    def check_constant(self, variables: Sequence[sp.Symbol], *, row: int | None = None) -> None:
        """Refuse a joint variable, rate or acceleration in any parameter (they are constants).

        A mass ``2 + sin(q2)`` would make the inertia matrix depend on a joint it does
        not belong to, and Lagrange–Euler and Newton–Euler would disagree; a parameter
        named ``thetadot1`` would be read as a rate. The error names the field and the
        symbol.

        >>> LinkInertia("2 + sin(q2)", (0, 0, 0), sp.zeros(3)).check_constant(
        ...     sp.symbols("q1 q2", real=True), row=1)
        Traceback (most recent call last):
        ...
        dhsym.errors.TableError: row 1, field m: uses q2, the joint variable q2: inertial ...
        """
        reserved = reserved_symbols(variables)
        for key, values in self.entries().items():
            used = set().union(*(v.free_symbols for v in values)) & set(reserved)
            if used:
                s = min(used, key=str)
                raise TableError(
                    f"uses {s}, {reserved[s]}: inertial parameters are constants of the link "
                    "(a mass, a centre of mass, an inertia), free of joint variables, rates "
                    "and accelerations",
                    row=row,
                    field=key,
                )

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        """Every symbol in the parameters."""
        exprs = [self.m, *self.r, *self.I, self.Jm, self.G, self.B, *self.Tc]
        return set().union(*(e.free_symbols for e in exprs))

    @property
    def has_drive(self) -> bool:
        """Whether motor inertia or friction is given."""
        return any(v != 0 for v in (self.Jm, self.B, *self.Tc))

    def subs(self, mapping: Mapping[sp.Basic, object]) -> LinkInertia:
        """A copy with ``mapping`` substituted everywhere."""
        m = dict(mapping)
        return LinkInertia(
            self.m.subs(m),
            tuple(v.subs(m) for v in self.r),
            self.I.subs(m),
            self.Jm.subs(m),
            self.G.subs(m),
            self.B.subs(m),
            tuple(v.subs(m) for v in self.Tc),
        )

    def data(self) -> dict[str, object]:
        """The keys of a table file, as exact values (what the writer prints).

        >>> LinkInertia(2, (1, 0, 0), sp.diag(0, 0, 3)).data()
        {'m': 2, 'r': [1, 0, 0], 'I': [0, 0, 3, 0, 0, 0]}
        """
        I = self.I  # noqa: E741
        out: dict[str, object] = {
            "m": self.m,
            "r": list(self.r),
            "I": [I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[1, 2], I[0, 2]],
        }
        if self.Jm != 0:
            out["Jm"] = self.Jm
        if self.G != 1:
            out["G"] = self.G
        if self.B != 0:
            out["B"] = self.B
        if any(v != 0 for v in self.Tc):
            out["Tc"] = list(self.Tc)
        return out
