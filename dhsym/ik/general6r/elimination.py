"""The general 6R's elimination, exact: the arm in standard form and the fourteen equations
of Raghavan and Roth, ``P(θ3) m45 = Q m12``.

The steps, in the standard DH form ``A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`` of the arm
(a modified table is rewritten into that form, its first twist and length going to the base):
split the loop as ``A3 A4 A5 = A2⁻¹ A1⁻¹ T A6⁻¹`` (the third and fourth columns of the
right side, a direction ``l`` and a point ``p``, do not depend on θ6); the fourteen
equations (Pieper's six plus Raghavan and Roth's eight) in ``p``, ``l``, ``p·p``, ``p·l``,
``p×l`` and ``(p·p) l − 2 (p·l) p`` are linear in the nine products ``m45`` of joints 4 and
5 (coefficients linear in ``c3, s3``) and in the eight products ``m12`` of joints 1 and 2
(:func:`elimination_matrices`). :mod:`dhsym.ik.general6r.eigenproblem` solves them in
numbers.

Examples
--------
>>> from dhsym.model.library import builtin_table
>>> links, base, tool = standard_chain(builtin_table("puma560"))
>>> len(links), links[0].joint
(6, 0)
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import TypeAlias

import sympy as sp
from sympy.polys.rings import PolyElement, ring

from dhsym.errors import DHError
from dhsym.kinematics.numeric import as_basic, to_float
from dhsym.kinematics.transforms import cos_sin
from dhsym.model.table import Convention, DHTable, Elementary, JointType

__all__ = [
    "EQUATIONS",
    "M12",
    "M45",
    "EliminationMatrices",
    "StandardLink",
    "elimination_matrices",
    "standard_chain",
]

#: The nine products of joints 4 and 5 the left sides are linear in (the columns of ``P``).
M45 = ("s4*s5", "s4*c5", "c4*s5", "c4*c5", "s4", "c4", "s5", "c5", "1")
#: The eight products of joints 1 and 2 the right sides are linear in (the columns of ``Q``).
M12 = ("s1*s2", "s1*c2", "c1*s2", "c1*c2", "s1", "c1", "s2", "c2")
#: The fourteen equations, in the order of the rows of ``P`` and ``Q``.
EQUATIONS = (
    "p_x",
    "p_y",
    "p_z",
    "l_x",
    "l_y",
    "l_z",
    "p·p",
    "p·l",
    "(p×l)_x",
    "(p×l)_y",
    "(p×l)_z",
    "((p·p)l − 2(p·l)p)_x",
    "((p·p)l − 2(p·l)p)_y",
    "((p·p)l − 2(p·l)p)_z",
)
_POSE = ("px", "py", "pz", "lx", "ly", "lz")


# --- the arm in standard form ----------------------------------------------------------------


@dataclass(frozen=True)
class StandardLink:
    """One link ``Rz(θ) Tz(d) Tx(a) Rx(α)`` of the arm in standard form, ``θ = sign·q + offset``.

    ``joint`` is the index (0-based) of the table's joint variable ``q`` that drives it.

    >>> StandardLink(0, 1, sp.pi / 2, sp.Rational(1, 10), 0, sp.pi / 2)
    StandardLink(joint=0, sign=1, offset=pi/2, d=1/10, a=0, alpha=pi/2)
    """

    joint: int
    sign: int
    offset: sp.Expr
    d: sp.Expr
    a: sp.Expr
    alpha: sp.Expr


# a rigid motion of polynomial entries: the rotation's rows and the translation
_Rigid: TypeAlias = tuple[list[list[PolyElement]], list[PolyElement]]


@dataclass(frozen=True)
class _Chain:
    """``T = base · A1 ⋯ A6 · tool`` with standard links: the form the elimination works on."""

    links: tuple[StandardLink, ...]
    base: tuple[Elementary, ...]
    tool: tuple[Elementary, ...]

    def reversed(self) -> _Chain:
        """The chain of ``T⁻¹``: ``A_i⁻¹ = Rx(−α_i) Tx(−a_i) Tz(−d_i) Rz(−θ_i)`` regrouped.

        Link k of the reversed chain is ``Rz(−θ_j) Tz(−d_j) Tx(−a_{j−1}) Rx(−α_{j−1})`` with
        ``j = 7 − k``; ``Rx(−α_6) Tx(−a_6)`` joins the base, the old base (inverted) the tool.
        """
        L = self.links
        links = []
        for k in range(6):
            j = 5 - k
            prev = L[j - 1] if j > 0 else None
            links.append(
                StandardLink(
                    L[j].joint,
                    -L[j].sign,
                    -L[j].offset,
                    -L[j].d,
                    -prev.a if prev else sp.Integer(0),
                    -prev.alpha if prev else sp.Integer(0),
                )
            )
        last = L[5]
        base = tuple(e.inverse() for e in reversed(self.tool))
        base += (Elementary("R", "x", -last.alpha), Elementary("T", "x", -last.a))
        tool = tuple(e.inverse() for e in reversed(self.base))
        return _Chain(tuple(links), base, tool)


def standard_chain(
    table: DHTable,
) -> tuple[tuple[StandardLink, ...], tuple[Elementary, ...], tuple[Elementary, ...]]:
    """The arm of a six-joint revolute table as ``base · A1 ⋯ A6 · tool`` in standard form.

    A modified row holds ``α_{i−1}, a_{i−1}``: since ``Rx`` and ``Tx`` commute, the product
    ``Rx(α0) Tx(a0) · Rz(θ1) Tz(d1) · Rx(α1) Tx(a1) · Rz(θ2) ⋯`` regroups into standard links
    with ``Rx(α0) Tx(a0)`` in the base and ``a6 = α6 = 0``. A joint entered as ``−q`` has sign
    −1. Returns the links, the base word and the tool word.

    >>> from dhsym.model.library import builtin_table
    >>> links, base, tool = standard_chain(builtin_table("puma560_modified").substituted())
    >>> links[2]
    StandardLink(joint=2, sign=1, offset=0, d=3001/20000, a=203/10000, alpha=-pi/2)
    >>> base
    (Rx(0), Tx(0))
    """
    chain = _standard(table)
    return chain.links, chain.base, chain.tool


def _standard(table: DHTable) -> _Chain:
    rows = table.rows
    if len(rows) != 6 or table.n != 6:
        raise DHError(
            f"the general 6R solver needs six joints; {table.name or 'this table'} "
            f"has {table.n} rows"
        )
    for i, r in enumerate(rows, start=1):
        if r.joint is not JointType.REVOLUTE:
            raise DHError(
                f"joint {i} is {r.joint.name.lower()}: the general 6R solver takes revolute "
                "joints only (prismatic arms have their own closed forms)",
                row=i,
                field="type",
            )
    table = table.substituted()
    rows = table.rows
    pieces = []
    for i, r in enumerate(rows, start=1):
        sign = sp.diff(r.theta, r.variable)
        offset = sp.expand(r.theta - sign * r.variable)
        if sign not in (1, -1) or offset.free_symbols:
            raise DHError(
                f"theta = {r.theta} is not ±{r.variable} + a constant", row=i, field="theta"
            )
        for name, e in r.params().items():
            free = as_basic(e).free_symbols
            if name != "theta" and free:
                raise DHError(
                    f"{name} = {e} has no numeric value: give values for "
                    f"{', '.join(sorted(map(str, free)))}",
                    row=i,
                    field=name,
                )
        pieces.append((int(sign), offset, r.d, r.a, r.alpha))
    zero = sp.Integer(0)
    if table.convention is Convention.STANDARD:
        links = tuple(StandardLink(i, s, o, d, a, al) for i, (s, o, d, a, al) in enumerate(pieces))
        return _Chain(links, tuple(table.base), tuple(table.tool))
    links = tuple(
        StandardLink(
            i, s, o, d, pieces[i + 1][3] if i < 5 else zero, pieces[i + 1][4] if i < 5 else zero
        )
        for i, (s, o, d, _, _) in enumerate(pieces)
    )
    base = tuple(table.base) + (
        Elementary("R", "x", pieces[0][4]),
        Elementary("T", "x", pieces[0][3]),
    )
    return _Chain(links, base, tuple(table.tool))


# --- the symbolic elimination ------------------------------------------------------------------


@dataclass(frozen=True)
class _Derivation:
    """The fourteen equations as polynomials over ℤ in generic link constants.

    Generators: ``s_i, c_i`` (joints 1–5), ``mu_i = sin α_i``, ``la_i = cos α_i``, ``a_i``,
    ``d_i`` (links 1–5) and the target ``l, p``; reduced modulo ``s² + c² = 1``,
    ``mu² + la² = 1`` and ``|l| = 1`` (a Gröbner basis in lex order: distinct leading
    variables), so each polynomial is in its unique normal form.
    """

    names: tuple[str, ...]
    left: tuple[PolyElement, ...]
    right: tuple[PolyElement, ...]


def _derive() -> _Derivation:
    names: list[str] = []
    for i in range(1, 6):
        names += [f"s{i}", f"c{i}"]
    names += [f"mu{i}" for i in range(1, 6)] + [f"la{i}" for i in range(1, 6)]
    for i in range(1, 6):
        names += [f"a{i}", f"d{i}"]
    names += ["lz", "lx", "ly", "px", "py", "pz"]
    R, *gens = ring(",".join(names), sp.ZZ)
    g = dict(zip(names, gens, strict=True))
    rel = [g[f"s{i}"] ** 2 + g[f"c{i}"] ** 2 - 1 for i in range(1, 6)]
    rel += [g[f"mu{i}"] ** 2 + g[f"la{i}"] ** 2 - 1 for i in range(1, 6)]
    rel += [g["lz"] ** 2 + g["lx"] ** 2 + g["ly"] ** 2 - 1]

    def red(p: PolyElement) -> PolyElement:
        return p.rem(rel)

    def link(i: int) -> _Rigid:
        c, s, la, mu, a, d = (g[f"{k}{i}"] for k in ("c", "s", "la", "mu", "a", "d"))
        return [[c, -s * la, s * mu], [s, c * la, -c * mu], [R(0), mu, la]], [a * c, a * s, d]

    def mul(X: _Rigid, Y: _Rigid) -> _Rigid:
        (R1, t1), (R2, t2) = X, Y
        Rm = [[sum(R1[i][k] * R2[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
        return Rm, [sum(R1[i][k] * t2[k] for k in range(3)) + t1[i] for i in range(3)]

    def inv(X: _Rigid) -> _Rigid:
        Rm, t = X
        RT = [[Rm[j][i] for j in range(3)] for i in range(3)]
        return RT, [-sum(RT[i][k] * t[k] for k in range(3)) for i in range(3)]

    def fourteen(p: list[PolyElement], u: list[PolyElement]) -> tuple[PolyElement, ...]:
        def dot(v: list[PolyElement], w: list[PolyElement]) -> PolyElement:
            return red(sum(x * y for x, y in zip(v, w, strict=True)))

        cross = (p[1] * u[2] - p[2] * u[1], p[2] * u[0] - p[0] * u[2], p[0] * u[1] - p[1] * u[0])
        pp, pu = dot(p, p), dot(p, u)
        tail = [red(pp * u[i] - 2 * pu * p[i]) for i in range(3)]
        return tuple([*p, *u, pp, pu, *(red(c) for c in cross), *tail])

    Rl, tl = mul(mul(link(3), link(4)), link(5))
    left = fourteen([red(tl[i]) for i in range(3)], [red(Rl[i][2]) for i in range(3)])
    Rm, tm = mul(inv(link(2)), inv(link(1)))
    lT = [g["lx"], g["ly"], g["lz"]]
    pT = [g["px"], g["py"], g["pz"]]
    lR = [red(sum(Rm[i][k] * lT[k] for k in range(3))) for i in range(3)]
    pR = [red(sum(Rm[i][k] * pT[k] for k in range(3)) + tm[i]) for i in range(3)]
    return _Derivation(tuple(names), left, fourteen(pR, lR))


def _terms(
    d: _Derivation, side: str
) -> Iterator[tuple[int, int, int, int, dict[str, int], tuple[int, ...]]]:
    """Each term of each equation as ``(row, joint part, product column, constants, pose)``.

    The joint part of the left side is 0, 1, 2 for ``1, c3, s3`` and the column indexes
    :data:`M45`; on the right the column indexes :data:`M12` (8 for the constant term).
    """
    idx = {n: k for k, n in enumerate(d.names)}
    first, second = ("4", "5") if side == "left" else ("1", "2")
    cols = M45 if side == "left" else (*M12, "1")
    col_of = {name: k for k, name in enumerate(cols)}
    consts = [n for n in d.names if n[:2] in ("mu", "la") or n[0] in "ad"]
    for row, poly in enumerate(d.left if side == "left" else d.right):
        for monom, coeff in poly.terms():
            part = 0
            if side == "left":
                part = 1 if monom[idx["c3"]] else 2 if monom[idx["s3"]] else 0
            word = [f"{t}{j}" for j in (first, second) for t in "sc" if monom[idx[f"{t}{j}"]]]
            key = "*".join(word) if word else "1"
            if key not in col_of:  # pragma: no cover - the theorem of Raghavan and Roth
                raise AssertionError(f"equation {EQUATIONS[row]} is not linear in {cols}")
            c = {n: monom[idx[n]] for n in consts if monom[idx[n]]}
            pose = tuple(monom[idx[n]] for n in _POSE)
            yield row, part, col_of[key], int(coeff), c, pose


def _link_constants(links: Sequence[StandardLink], exact: bool) -> dict[str, sp.Expr | float]:
    """The link constants ``la_i, mu_i, a_i, d_i`` of links 1–5: exact, or as floats."""
    out: dict[str, sp.Expr | float] = {}
    for i, L in enumerate(links[:5], start=1):
        c, s = cos_sin(L.alpha)
        vals = {"la": c, "mu": s, "a": L.a, "d": L.d}
        for k, v in vals.items():
            out[f"{k}{i}"] = v if exact else to_float(v)
    return out


@dataclass(frozen=True)
class EliminationMatrices:
    """The fourteen equations ``P(θ3) m45 = Q m12`` of one arm, exact.

    ``P`` (14×9) holds ``cos θ3, sin θ3`` linearly and the right sides' constant terms
    (with a minus sign, in its last column); ``Q`` (14×8) the coefficients of
    :data:`M12`. The target enters through ``direction`` (l) and ``point`` (p): the third
    and fourth columns of ``base⁻¹ · T · tool⁻¹ · A6⁻¹`` (with θ6 = 0: they do not depend on
    it). θ_i is the full
    angle of link i of the standard form (:func:`standard_chain`), offset included.
    """

    P: sp.ImmutableMatrix
    Q: sp.ImmutableMatrix
    m45: sp.ImmutableMatrix
    m12: sp.ImmutableMatrix
    direction: sp.ImmutableMatrix
    point: sp.ImmutableMatrix
    equations: tuple[str, ...] = EQUATIONS

    def residual(self) -> sp.ImmutableMatrix:
        """``P m45 − Q m12``: zero at every solution (14×1)."""
        return sp.ImmutableMatrix(self.P * self.m45 - self.Q * self.m12)


def elimination_matrices(table: DHTable) -> EliminationMatrices:
    """The exact Raghavan–Roth matrices of a six-joint revolute table (for printing).

    They come from the split ``A3 A4 A5 = A2⁻¹ A1⁻¹ T A6⁻¹`` and its fourteen equations in
    ``p``, ``l``, ``p·p``, ``p·l``, ``p×l``, ``(p·p) l − 2 (p·l) p`` (see the module text):
    row k of ``P(θ3) m45 = Q m12`` is equation ``EQUATIONS[k]``, left side minus the
    right side's constant term equal to the rest of the right side.

    >>> from dhsym.model.table import DHRow, DHTable
    >>> rows = [DHRow.revolute(f"q{i}", d=i, a=1, alpha="pi/2") for i in range(1, 7)]
    >>> m = elimination_matrices(DHTable.from_rows(rows))
    >>> m.P.shape, m.Q.shape, m.m45[0], m.m12[-1]
    ((14, 9), (14, 8), sin(theta4)*sin(theta5), cos(theta2))
    >>> m.P[0, 8]
    4*sin(theta3) + cos(theta3) + 1
    """
    chain = _standard(table)
    d = _derive()
    values = _link_constants(chain.links, exact=True)
    th = sp.symbols("theta1:7", real=True)
    trig = {f"c{i}": sp.cos(th[i - 1]) for i in range(1, 6)}
    trig |= {f"s{i}": sp.sin(th[i - 1]) for i in range(1, 6)}
    lx, ly, lz, px, py, pz = sp.symbols("l_x l_y l_z p_x p_y p_z", real=True)
    pose_syms = {"px": px, "py": py, "pz": pz, "lx": lx, "ly": ly, "lz": lz}
    P = sp.zeros(14, 9)
    Q = sp.zeros(14, 8)
    for side in ("left", "right"):
        for row, part, col, coeff, consts, pose in _terms(d, side):
            term = sp.Integer(coeff)
            for n, e in consts.items():
                term *= values[n] ** e
            for n, e in zip(_POSE, pose, strict=True):
                term *= pose_syms[n] ** e
            if side == "left":
                P[row, col] += term * (1, trig["c3"], trig["s3"])[part]
            elif col == 8:
                P[row, 8] -= term
            else:
                Q[row, col] += term
    P = P.applyfunc(sp.expand)
    Q = Q.applyfunc(sp.expand)

    def product(word: str) -> sp.Expr:
        return sp.Integer(1) if word == "1" else sp.Mul(*(trig[w] for w in word.split("*")))

    return EliminationMatrices(
        sp.ImmutableMatrix(P),
        sp.ImmutableMatrix(Q),
        sp.ImmutableMatrix([product(w) for w in M45]),
        sp.ImmutableMatrix([product(w) for w in M12]),
        sp.ImmutableMatrix([lx, ly, lz]),
        sp.ImmutableMatrix([px, py, pz]),
    )
