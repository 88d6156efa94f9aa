"""Judging a DH table: does it describe the same robot as the key?

Two tables describe the same robot when, at every configuration, their joint
axes are the same lines in space (up to where frame 0 is put) and the tool
frames agree.  The DH freedoms are allowed: a z axis reversed (that joint's
variable changes sign), x0 chosen differently or frame 0 moved along z0 (a
constant base transform about/along z0), another common normal between parallel
axes (d values shift), and another tool frame when the question allows it.

Symbols stand for themselves: an answer that writes symbols is judged with one random
value per symbol name (:func:`symbolic_values`), so ``d4`` is never ``a2`` because a key
gives both the same number, and joint variables are matched by position (θ2 in row 1
is never θ1).  The key's numbers judge only an answer written in numbers, and serve
the diagnosis.

The check is numeric (:mod:`dhsym.kinematics.numeric`, the core's link words):
frame 0 of the answer is matched to the key's from the joint axes at the zero
configuration, then joint by joint at random configurations the axes are
compared and each joint's sign found; the first joint whose axis is elsewhere is
where the geometry diverges.

Examples
--------
>>> from dhsym import load_table
>>> from dhsym.model.table import DHRow, DHTable
>>> key = load_table("planar2r")
>>> alt = DHTable.from_rows([DHRow.revolute("theta1 - 90", a="a1"),
...                          DHRow.revolute("theta2", a="a2")], angles="deg")
>>> m = compare_tables(key, alt)
>>> m.same_robot, m.differences
(True, ('x0 rotated by 90° about z0',))
>>> compare_tables(key, DHTable.from_rows([DHRow.revolute("theta1", a="a2"),
...                                        DHRow.revolute("theta2", a="a2")])).diverges_at
2
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import TypeAlias

import numpy as np
import sympy as sp

from dhsym.kinematics.numeric import elementary_stack, numeric_rigid_inverse
from dhsym.model.table import Convention, DHRow, DHTable, JointType

from ..reading.limits import check_time
from .sampled_frames import EvaluationError, chained, evaluate, frames, link_values
from .tolerances import TOLERANCES

__all__ = [
    "Chain",
    "KeyFrames",
    "RowVerdicts",
    "TableMatch",
    "compare_tables",
    "same_cells",
    "symbolic_values",
]

_CONFIGS = 6


@dataclass(frozen=True)
class Chain:
    """Rows and a convention without the checks of :class:`~dhsym.model.table.DHTable`.

    Mistake variants (a table read in the wrong unit, rows shifted) need not be
    valid tables; :func:`compare_tables` takes either.
    """

    rows: tuple[DHRow, ...]
    convention: Convention

    @property
    def n(self) -> int:
        """Number of rows."""
        return len(self.rows)

    @classmethod
    def of(cls, table: DHTable | Chain) -> Chain:
        """The chain of a table."""
        return cls(tuple(table.rows), Convention(table.convention))


@dataclass(frozen=True)
class TableMatch:
    """How an answer table relates to the key.

    ``diverges_at`` is the first joint (1-based) whose axis differs, ``n + 1``
    for the tool frame, 0 when the number or kinds of joints differ.
    """

    same_robot: bool
    same_table: bool = False
    diverges_at: int | None = None
    differences: tuple[str, ...] = ()
    reason: str = ""
    reversed_joints: tuple[int, ...] = ()
    tool_differs: bool = False
    base_on_axis: bool = True
    details: dict[str, object] = field(default_factory=dict, compare=False, repr=False)


#: a joint of a chain: (its row, 1-based; its kind; its variable; the variable's sign)
_Joint: TypeAlias = tuple[int, JointType, sp.Symbol, float]


def _joints(chain: Chain) -> list[_Joint]:
    """(row, kind, variable, sign of the variable in its entry) of every joint."""
    out = []
    for i, r in enumerate(chain.rows, 1):
        if r.variable is None or r.variable_field is None:
            continue
        slope = getattr(r, r.variable_field).as_coefficients_dict().get(r.variable, 1)
        sign = -1.0 if (slope.is_number and slope.is_negative) else 1.0
        out.append((i, r.joint, r.variable, sign))
    return out


def _variable(row: DHRow) -> sp.Symbol | None:
    if row.variable is not None:
        return row.variable
    entry = getattr(row, row.variable_field) if row.variable_field else sp.Integer(0)
    syms = sorted(entry.free_symbols, key=sp.default_sort_key)
    return syms[0] if syms else None


def _with_variables(chain: Chain) -> Chain:
    from dataclasses import replace

    if all(r.variable is not None or r.joint is JointType.FIXED for r in chain.rows):
        return chain
    return Chain(
        tuple(
            r if r.variable is not None else replace(r, variable=_variable(r)) for r in chain.rows
        ),
        chain.convention,
    )


def _constants(chain: Chain) -> set[sp.Symbol]:
    out: set[sp.Symbol] = set()
    for r in chain.rows:
        for e in r.params().values():
            out |= e.free_symbols
    return out - {r.variable for r in chain.rows if r.variable is not None}


def _constant_value(s: sp.Symbol, values: Mapping[sp.Symbol, sp.Expr], seed: int) -> float:
    """The value of the constant ``s``: its number in ``values``, else one drawn for its
    name (the same whatever else is in the tables)."""
    if s in values:
        return float(values[s])
    rng = np.random.default_rng([seed, zlib.crc32(s.name.encode())])
    return float(rng.uniform(*TOLERANCES.length_range))


def _constant_env(
    key: Chain, answer: Chain, values: Mapping[sp.Symbol, sp.Expr], seed: int
) -> dict[sp.Symbol, float]:
    return {s: _constant_value(s, values, seed) for s in _constants(key) | _constants(answer)}


def _axes(F: np.ndarray, chain: Chain, joints: list[_Joint]) -> tuple[np.ndarray, np.ndarray]:
    """Points and directions of the joint axes, shape (K, joints, 3) each."""
    shift = 1 if chain.convention is Convention.STANDARD else 0
    idx = [j[0] - shift for j in joints]
    G = F[:, idx]
    return G[..., :3, 3], G[..., :3, 2]


def _rz_tz(phi: float, t: float, flip: bool) -> np.ndarray:
    """``Rz(phi) Tz(t)``, followed by a half turn about x when ``flip``."""
    word = [("R", "z", phi), ("T", "z", t)] + ([("R", "x", math.pi)] if flip else [])
    out = np.eye(4)
    for kind, axis, value in word:
        out = out @ elementary_stack(kind, axis, [value])[0]
    return out


def _normalizer(p: np.ndarray, u: np.ndarray) -> np.ndarray:
    """A frame with z along the line (p, u), origin at the foot of the base origin."""
    z = u / np.linalg.norm(u)
    o = p - np.dot(p, z) * z
    x = np.array([1.0, 0, 0]) - z[0] * z
    if np.linalg.norm(x) < TOLERANCES.pick_axis_eps:
        x = np.array([0, 1.0, 0]) - z[1] * z
    x /= np.linalg.norm(x)
    N = np.eye(4)
    N[:3, 0], N[:3, 1], N[:3, 2], N[:3, 3] = x, np.cross(z, x), z, o
    return N


def _foot(p: np.ndarray, u: np.ndarray) -> tuple[float, np.ndarray] | None:
    """Height on the z axis and horizontal normal towards a non-vertical line (p, u)."""
    uz = u[2]
    if abs(uz * uz - 1) < TOLERANCES.vertical_eps:
        return None
    s = (np.dot(u, p) - p[2] * uz) / (uz * uz - 1)
    h = p[2] + s * uz
    n = p + s * u - np.array([0, 0, h])
    if np.linalg.norm(n[:2]) < TOLERANCES.short_length:
        n = np.cross([0, 0, 1.0], u)
    return float(h), n


def _candidates(
    Fk: np.ndarray, Fa: np.ndarray, key: Chain, ans: Chain, jk: list[_Joint], ja: list[_Joint]
) -> Iterator[np.ndarray]:
    """Base transforms worth trying: from the tool at zero, then from the axes at zero."""
    yield Fa[0, -1] @ numeric_rigid_inverse(Fk[0, -1])
    Pk, Uk = _axes(Fk[:1], key, jk)
    Pa, Ua = _axes(Fa[:1], ans, ja)
    Nk, Na = _normalizer(Pk[0, 0], Uk[0, 0]), _normalizer(Pa[0, 0], Ua[0, 0])
    iNk, iNa = numeric_rigid_inverse(Nk), numeric_rigid_inverse(Na)
    for flip in (False, True):
        F = _rz_tz(0.0, 0.0, flip)
        phis: list[float] = []
        t = None
        for k in range(1, len(jk)):
            pk = (F @ iNk @ np.append(Pk[0, k], 1))[:3]
            uk = (F @ iNk)[:3, :3] @ Uk[0, k]
            pa = (iNa @ np.append(Pa[0, k], 1))[:3]
            ua = iNa[:3, :3] @ Ua[0, k]
            fk, fa = _foot(pk, uk), _foot(pa, ua)
            if fk is not None and fa is not None:
                base = math.atan2(fa[1][1], fa[1][0]) - math.atan2(fk[1][1], fk[1][0])
                phis = phis or [base, base + math.pi]
                t = fa[0] - fk[0]
                break
            if (
                fk is None
                and fa is None
                and not phis
                and np.linalg.norm(pk[:2]) > TOLERANCES.short_length
            ):
                phis = [math.atan2(pa[1], pa[0]) - math.atan2(pk[1], pk[0])]
        if t is None:
            tk = (F @ iNk @ Fk[0, -1])[2, 3]
            t = (iNa @ Fa[0, -1])[2, 3] - tk
        for phi in phis or [0.0]:  # no informative axis: still try frame 0 on frame 0
            yield Na @ _rz_tz(phi, t, False) @ F @ iNk


def _cross_norms(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``|u × v|`` for each row of two ``(K, 3)`` arrays: ``np.cross``'s products and
    differences, the same numbers, without its set-up (a third of the cost at K = 7).

    >>> u, v = np.array([[1.0, 0, 0], [0, 2, 0]]), np.array([[0, 1.0, 0], [0, 1, 0]])
    >>> _cross_norms(u, v)
    array([1., 0.])
    """
    c = np.empty(np.broadcast_shapes(u.shape, v.shape))
    u0, u1, u2 = u[..., 0], u[..., 1], u[..., 2]
    v0, v1, v2 = v[..., 0], v[..., 1], v[..., 2]
    c[..., 0] = u1 * v2 - u2 * v1
    c[..., 1] = u2 * v0 - u0 * v2
    c[..., 2] = u0 * v1 - u1 * v0
    norms: np.ndarray = np.linalg.norm(c, axis=-1)
    return norms


def _verify(
    B: np.ndarray,
    key: Chain,
    ans: Chain,
    jk: list[_Joint],
    ja: list[_Joint],
    Fk: np.ndarray,
    frames_a: Callable[[list[float]], np.ndarray],
    size: int,
    tol: float,
) -> tuple[int, list[float], list[float], np.ndarray | None]:
    """(joints that matched, variable signs, axis directions, E or None).

    ``frames_a(signs)`` are the answer's frames with its variables' signs."""
    signs = [1.0] * len(ja)
    dirs = [1.0] * len(ja)
    Pk, Uk = _axes(Fk, key, jk)
    Pk = (B[:3, :3] @ Pk[..., None])[..., 0] + B[:3, 3]
    Uk = (B[:3, :3] @ Uk[..., None])[..., 0]
    Fa = frames_a(signs)
    Pa, Ua = _axes(Fa, ans, ja)
    for k, (_, kind, _, _) in enumerate(ja):
        cross = _cross_norms(Ua[:, k], Uk[:, k])
        if (cross > tol).any():
            return k, signs, dirs, None
        if kind is JointType.REVOLUTE:
            off = _cross_norms(Pa[:, k] - Pk[:, k], Ua[:, k])
            if (off > tol).any():
                return k, signs, dirs, None
        along = np.einsum("ij,ij->i", Ua[:, k], Uk[:, k])
        dirs[k] = -1.0 if (along < 0).all() else 1.0
        dots = along * ja[k][3] * jk[k][3]
        if (dots < 0).all():
            signs[k] = -1.0
            Fa = frames_a(signs)
            Pa, Ua = _axes(Fa, ans, ja)  # the axes of the frames with this sign
        elif (dots < 0).any():
            return k, signs, dirs, None
    E = numeric_rigid_inverse(B @ Fk[:, -1]) @ Fa[:, -1]
    if (np.abs(E - E[0]) > tol).any():
        return len(ja), signs, dirs, None
    return len(ja), signs, dirs, E[0]


def _deg(x: float) -> str:
    return f"{math.degrees(x):.4g}°"


def _describe(
    B: np.ndarray,
    E: np.ndarray | None,
    signs: list[float],
    dirs: list[float],
    joints: list[_Joint],
    Fk0: np.ndarray,
    Fa0: np.ndarray,
    key: Chain,
    tol: float,
) -> tuple[list[str], bool]:
    out: list[str] = []
    on_axis = bool(abs(abs(B[2, 2]) - 1) < tol and np.linalg.norm(B[:2, 3]) < tol)
    flip = B[2, 2] < 0
    if on_axis:
        if flip and dirs[0] > 0:
            out.append("z0 reversed (frame 0 turned over)")
        phi = math.atan2(B[1, 0], B[0, 0]) * (-1 if flip else 1)
        if abs(math.remainder(phi, 2 * math.pi)) > tol:
            out.append(f"x0 rotated by {_deg(math.remainder(-phi, 2 * math.pi))} about z0")
        if abs(B[2, 3]) > tol:
            out.append(f"frame 0 moved by {-B[2, 3]:.4g} along z0")
    else:
        out.append("frame 0 is not on the axis of joint 1")
    shift = 1 if key.convention is Convention.STANDARD else 0
    for k, (s, d, j) in enumerate(zip(signs, dirs, joints), 1):
        if d < 0:
            sign = "; its variable changes sign" if s < 0 else ""
            out.append(
                f"z{j[0] - shift} reversed (the axis of joint {k} points the other way{sign})"
            )
        elif s < 0:
            out.append(f"the variable of joint {k} changes sign")
    for f in range(1, key.n):
        ok, oa = (B @ Fk0[f])[:3, 3], Fa0[f][:3, 3]
        za = Fa0[f][:3, 2]
        moved = float(np.dot(oa - ok, za))
        if abs(moved) > tol and np.linalg.norm(np.cross(oa - ok, za)) < tol:
            out.append(
                f"origin of frame {f} moved by {moved:.4g} along z{f} (another common normal)"
            )
    if E is not None and (np.abs(E - np.eye(4)) > tol).any():
        out.append(f"another tool frame (offset {np.round(E[:3, 3], 4).tolist()})")
    return out, on_axis


def _swapped_variable(jk: list[_Joint], ja: list[_Joint]) -> tuple[int, str] | None:
    """The first joint whose variable is another joint's variable of the key (joint
    variables are matched by position: θ2 in row 1 is never the key's θ1)."""
    names = [j[2] for j in jk]
    for k, (a, b) in enumerate(zip(jk, ja), 1):
        if b[2] != a[2] and b[2] in names:
            other = names.index(b[2]) + 1
            return k, f"joint {k} moves with {b[2]}, the variable of joint {other}"
    return None


def symbolic_values(key: DHTable, answer: DHTable | Chain) -> Mapping[sp.Symbol, sp.Expr]:
    """The numbers a table answer is judged with: none when the answer writes symbols
    (each symbol then stands for itself, with a random value per name, so ``d4`` is never
    ``a2`` because the key gives both 0.4318), the key's values for an all-number answer.

    >>> from dhsym import load_table
    >>> key = load_table("puma560")
    >>> symbolic_values(key, key)
    {}
    """
    return {} if _constants(Chain.of(answer)) else key.value_map


#: the largest number, and the most nodes, a plainly finite cell may hold
#: (:func:`_plainly_finite`): with values of at most this size, nothing overflows
_PLAIN_NUMBER, _PLAIN_NODES = 1000.0, 32


def _plainly_finite(e: sp.Basic, budget: int = _PLAIN_NODES) -> bool:
    """True when ``e`` has a finite value wherever its symbols have values of at most
    ``_PLAIN_NUMBER``: at most ``_PLAIN_NODES`` nodes of symbols, such numbers, ``pi``,
    sums, products, powers 0 to 4, sines and cosines (what a table's cells are made of);
    anything else is evaluated.

    >>> x = sp.Symbol("x")
    >>> _plainly_finite(sp.cos(x + sp.pi / 2) * x**2), _plainly_finite(1 / x)
    (True, False)
    """
    return _plain_nodes(e, budget) >= 0


def _plain_nodes(e: sp.Basic, budget: int) -> int:
    """What is left of ``budget`` after the nodes of a plainly finite ``e``, or -1."""
    budget -= 1
    if budget < 0:
        return -1
    if e.is_Symbol or e is sp.pi:
        return budget
    if e.is_Number:
        return budget if e.is_finite and abs(float(e)) <= _PLAIN_NUMBER else -1
    if e.is_Pow:
        k = e.exp
        return _plain_nodes(e.base, budget) if k.is_Integer and 0 <= k <= 4 else -1
    if e.is_Add or e.is_Mul or isinstance(e, (sp.sin, sp.cos)):
        for arg in e.args:
            budget = _plain_nodes(arg, budget)
            if budget < 0:
                return -1
        return budget
    return -1


class RowVerdicts:
    """The rows of candidate tables already compared with one answer (:func:`same_cells`
    with ``verdicts=``), for one diagnosis: a wrong table's diagnosis compares the answer
    with a hundred and more variants of the key, and a variant changes a row or two, so
    each other row is compared once, not once per variant.

    A row's verdict is kept by what it depends on: its place, its joint, cells and
    variable, and the variables of the candidate table (the answer, its numbers ``values``
    and the seed are this object's); a row whose verdict depended on the other rows' cells
    (a variable of one row written in another row's cell) is not kept.  Nothing is kept
    beyond the object, which a diagnosis makes for its one answer.

    >>> from dhsym.model.library import load_table
    >>> t = load_table("planar2r")
    >>> values = t.value_map
    >>> seen = RowVerdicts(t, values)
    >>> same_cells(t, t, values, verdicts=seen), len(seen)
    (True, 2)
    >>> same_cells(t, t, t.value_map, verdicts=seen), len(seen)  # another map: not kept
    (True, 2)
    """

    def __init__(
        self, answer: DHTable | Chain, values: Mapping[sp.Symbol, sp.Expr], seed: int = 3
    ) -> None:
        self.answer, self.values, self.seed = answer, values, seed
        self._seen: dict[tuple[object, ...], bool] = {}

    def __len__(self) -> int:
        return len(self._seen)

    def serves(self, answer: DHTable | Chain, values: object, seed: int) -> bool:
        """True when this memo is for this answer, values map and seed (the same objects)."""
        return answer is self.answer and values is self.values and seed == self.seed

    def get(self, where: tuple[object, ...]) -> bool | None:
        """The verdict of the row ``where`` describes, if it was judged."""
        return self._seen.get(where)

    def put(self, where: tuple[object, ...], verdict: bool) -> None:
        """Keep the verdict of the row ``where`` describes."""
        self._seen[where] = verdict


def same_cells(
    key: DHTable | Chain,
    answer: DHTable | Chain,
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
    seed: int = 3,
    verdicts: RowVerdicts | None = None,
) -> bool:
    """True when both tables have the same rows, cell by cell (joint variables paired).

    Each pair of cells is compared at one point: a random value per constant
    (:func:`_constant_value`: drawn from a range of lengths, or the number ``values``
    gives) and per row's joint variable.  A cell that is the same expression in both rows,
    with the same variable, has the same value there; one that is plainly finite
    (:func:`_plainly_finite`) and has a moderate value for each of its symbols agrees with
    itself without being evaluated (a mistake's variant changes a cell or two), and
    only the values the other cells need are drawn: the same values, the same answer.
    Each row's verdict depends on that row, its place and the tables' variables only
    (the values are drawn per name and per place), so the rows may be judged in any order
    and a row judged before for the same answer is taken from ``verdicts``
    (:class:`RowVerdicts`), when given for this ``answer``, ``values`` and ``seed``.

    >>> from dhsym.model.library import load_table
    >>> t = load_table("planar2r")
    >>> same_cells(t, t), same_cells(t, t.with_values({}))
    (True, True)
    """
    k, a = _with_variables(Chain.of(key)), _with_variables(Chain.of(answer))
    if k.n != a.n or k.convention is not a.convention:
        return False
    given = dict(values or {})
    variables_k = {r.variable for r in k.rows if r.variable is not None}
    variables_a = {r.variable for r in a.rows if r.variable is not None}
    constants: set[sp.Symbol] | None = None  # both chains', computed only when asked
    consulted = False  # whether a row's verdict asked for the constants of both chains

    def is_constant(s: sp.Symbol) -> bool:
        """Whether ``s`` (a symbol of a cell) gets a constant's value (:func:`_constants`)."""
        nonlocal constants, consulted
        if s not in variables_k and s not in variables_a:
            return True  # a symbol of a cell that is neither chain's variable
        consulted = True
        if constants is None:
            constants = _constants(k) | _constants(a)
        return s in constants

    env: dict[sp.Symbol, np.ndarray] = {}  # the constants' values, drawn when first needed
    drawn: list[np.ndarray] = []  # the joint values of the rows, one draw per row in turn
    rng: np.random.Generator | None = None

    def same_row(row: int, rk: DHRow, ra: DHRow) -> bool:
        nonlocal rng
        if rk.joint is not ra.joint:
            return False
        if ra.variable != rk.variable and ra.variable in variables_k:
            return False  # variables are matched by position, never relabelled
        for name in ("theta", "d", "a", "alpha"):
            ck, ca = getattr(rk, name), getattr(ra, name)
            same_variable = ra.variable == rk.variable
            # the same expression (tested first: a variant changes a cell or two) has the
            # same symbols as the key's cell
            same = same_variable and (ca is ck or ca == ck)
            needed = set(ck.free_symbols) if same else ck.free_symbols | ca.free_symbols
            if same_variable:  # the row's variable has its value in both
                needed.discard(rk.variable)
            known = {s for s in needed if is_constant(s)}
            if (
                same
                and needed == known
                and all(abs(float(given.get(s, 0))) <= _PLAIN_NUMBER for s in known)
                and _plainly_finite(ck)
            ):
                continue
            for s in known - env.keys():
                env[s] = np.array([_constant_value(s, given, seed)])
            rng = rng if rng is not None else np.random.default_rng(seed)
            while len(drawn) <= row:
                drawn.append(np.array([rng.uniform(*TOLERANCES.symbol_range)]))
            q = drawn[row]
            shared = {s: env[s] for s in known}
            env_k = {**shared, rk.variable: q} if rk.variable is not None else shared
            env_a = {**shared, ra.variable: q} if ra.variable is not None else shared
            try:
                vk = float(evaluate(ck, env_k, 1)[0])
                va = float(evaluate(ca, env_a, 1)[0])
            except EvaluationError:
                return False
            if name in ("theta", "alpha"):
                if not abs(math.remainder(vk - va, 2 * math.pi)) <= TOLERANCES.cell_atol:
                    return False
            elif not abs(vk - va) <= TOLERANCES.cell_atol * (1 + abs(vk)):
                return False
        return True

    memo = verdicts if verdicts is not None and verdicts.serves(answer, values, seed) else None
    table_variables = frozenset(variables_k)
    for row, (rk, ra) in enumerate(zip(k.rows, a.rows)):
        if memo is None:
            if not same_row(row, rk, ra):
                return False
            continue
        where = (row, rk.joint, rk.theta, rk.d, rk.a, rk.alpha, rk.variable, table_variables)
        verdict = memo.get(where)
        if verdict is None:
            consulted = False
            verdict = same_row(row, rk, ra)
            if not consulted:
                memo.put(where, verdict)
        if not verdict:
            return False
    return True


def _configurations(joints: list[_Joint], seed: int) -> np.ndarray:
    """The joint values the tables are compared at: the zero configuration, then
    ``_CONFIGS`` drawn from ``seed`` (shape ``(_CONFIGS + 1, joints)``)."""
    rng = np.random.default_rng(seed)
    Q = np.zeros((_CONFIGS + 1, len(joints)))
    for j, (_, kind, _, _) in enumerate(joints):
        Q[1:, j] = (
            rng.uniform(*TOLERANCES.revolute_range, _CONFIGS)
            if kind is JointType.REVOLUTE
            else rng.uniform(*TOLERANCES.prismatic_range, _CONFIGS)
        )
    return Q


@dataclass(frozen=True, eq=False)
class KeyFrames:
    """A key table's frames at :func:`compare_tables`'s configurations, computed once per
    key (they depend on the key only): with the key's numbers for its constants, and with
    one value per symbol name (the two ways :func:`symbolic_values` judges an answer).

    >>> from dhsym import load_table
    >>> key = load_table("planar2r")
    >>> kf = KeyFrames.of(key)
    >>> kf.get(key.value_map, 11) is not None, kf.get({}, 11) is not None, kf.get({}, 5)
    (True, True, None)
    """

    seed: int
    valued: Mapping[sp.Symbol, sp.Expr]
    #: the frames, shape ``(_CONFIGS + 1, n + 1, 4, 4)``: with ``valued``, with no values
    with_values: np.ndarray | None = field(repr=False)
    without_values: np.ndarray | None = field(repr=False)

    @classmethod
    def of(cls, key: DHTable, seed: int = 11) -> KeyFrames:
        """The frames of ``key`` (None where they cannot be evaluated: computed per answer
        then, which reports why)."""
        kc = _with_variables(Chain.of(key))
        jk = _joints(kc)
        Q = _configurations(jk, seed)
        valued = dict(key.value_map)

        def at(values: Mapping[sp.Symbol, sp.Expr]) -> np.ndarray | None:
            env: dict[sp.Basic, np.ndarray | float] = {
                **{s: _constant_value(s, values, seed) for s in _constants(kc)},
                **{jt[2]: Q[:, j] for j, jt in enumerate(jk)},
            }
            try:
                out = frames(kc, env, _CONFIGS + 1)
            except EvaluationError:
                return None
            out.flags.writeable = False  # shared by every answer to the key
            return out

        return cls(seed, valued, at(valued), at({}))

    def get(self, values: Mapping[sp.Symbol, sp.Expr], seed: int) -> np.ndarray | None:
        """The frames for ``values`` and ``seed``, or None when not computed for them."""
        if seed != self.seed:
            return None
        if not values:
            return self.without_values
        return self.with_values if dict(values) == self.valued else None


def _signed_frames(
    chain: Chain,
    joints: list[_Joint],
    consts: Mapping[sp.Basic, float],
    Q: np.ndarray,
    size: int,
) -> Callable[[list[float]], np.ndarray]:
    """The frames of ``chain`` at the configurations ``Q`` with each joint variable's
    values times its sign: ``frames(signs)``, as :func:`frames` computes them, for the one
    comparison that asks for them (nothing is kept after it).

    Each sign pattern's frames are computed once, and each row's link transforms once per
    signs of the joint variables in its cells: a pattern that flips one joint computes
    that joint's row again (and any row that names its variable), not every row.
    """
    seen: dict[tuple[float, ...], np.ndarray] = {}
    links: dict[tuple[int, tuple[float, ...]], np.ndarray] = {}
    cells = [set().union(*(e.free_symbols for e in r.params().values())) for r in chain.rows]
    uses = [[j for j, jt in enumerate(joints) if jt[2] in names] for names in cells]

    def signed(signs: list[float]) -> np.ndarray:
        key = tuple(signs)
        if key not in seen:
            env: dict[sp.Basic, np.ndarray | float] = {
                **consts,
                **{jt[2]: s * Q[:, j] for j, (jt, s) in enumerate(zip(joints, signs))},
            }
            rows = []
            for k, row in enumerate(chain.rows):
                at = (k, tuple(signs[j] for j in uses[k]))
                if at not in links:
                    links[at] = link_values(row, chain.convention, env, size)
                rows.append(links[at])
            seen[key] = chained(rows, size)
        return seen[key]

    return signed


def compare_tables(
    key: DHTable | Chain,
    answer: DHTable | Chain,
    *,
    tool_free: bool = False,
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
    seed: int = 11,
    key_frames: KeyFrames | None = None,
) -> TableMatch:
    """Compare an answer table with the key (see the module docstring).

    ``values`` are numbers for the key's constant symbols (default: the key's own
    ``values``); symbols without a number get one random value shared by both tables.
    ``key_frames``: the key's frames computed once (:class:`KeyFrames`, from ``key``);
    where they were computed for these ``values`` and ``seed`` they are used, the same
    numbers as computing them here.
    """
    if values is None:
        values = key.value_map if isinstance(key, DHTable) else {}
    kc, ac = _with_variables(Chain.of(key)), _with_variables(Chain.of(answer))
    jk, ja = _joints(kc), _joints(ac)
    if len(jk) != len(ja):
        return TableMatch(
            False, diverges_at=0, reason=f"the table has {len(ja)} joints; the robot has {len(jk)}"
        )
    for k, ((_, tk, _, _), (_, ta, _, _)) in enumerate(zip(jk, ja), 1):
        if tk is not ta:
            kinds = {JointType.REVOLUTE: "revolute", JointType.PRISMATIC: "prismatic"}
            return TableMatch(
                False, diverges_at=k, reason=f"joint {k} is {kinds[tk]}, not {kinds[ta]}"
            )
    swapped = _swapped_variable(jk, ja)
    if swapped:
        return TableMatch(False, diverges_at=swapped[0], reason=swapped[1])
    if same_cells(kc, ac, values):
        return TableMatch(True, same_table=True)
    consts = _constant_env(kc, ac, dict(values), seed)
    size = _CONFIGS + 1
    Q = _configurations(jk, seed)
    env_k: dict[sp.Basic, np.ndarray | float] = {
        **consts,
        **{jt[2]: Q[:, j] for j, jt in enumerate(jk)},
    }

    frames_a = _signed_frames(ac, ja, consts, Q, size)

    try:
        known = key_frames.get(values, seed) if key_frames is not None else None
        Fk = known if known is not None else frames(kc, env_k, size)
        Fa0 = frames_a([1.0] * len(ja))
    except EvaluationError as err:
        return TableMatch(False, diverges_at=0, reason=f"cannot evaluate the table: {err}")
    if not (np.isfinite(Fk).all() and np.isfinite(Fa0).all()):
        return TableMatch(False, diverges_at=0, reason="the table has undefined values")
    scale = 1.0 + float(np.abs(Fk[0, :, :3, 3]).max())
    tol = TOLERANCES.frame_rtol * scale
    best, found = -1, []
    for B in _candidates(Fk, Fa0, kc, ac, jk, ja):
        check_time()  # the answer's deadline (see reading.limits.time_limit)
        got, signs, dirs, E = _verify(B, kc, ac, jk, ja, Fk, frames_a, size, tol)
        best = max(best, got)
        if E is None:
            continue
        Fa = frames_a(signs)
        diffs, on_axis = _describe(B, E, signs, dirs, ja, Fk[0], Fa[0], kc, tol)
        tool = bool((np.abs(E - np.eye(4)) > tol).any())
        flip_only = (
            kc.convention is Convention.MODIFIED and np.abs(E[:3, 3]).max() < tol and E[2, 2] < 0
        )
        ok = on_axis and (not tool or tool_free or flip_only)
        reversed_ = tuple(k for k, d in enumerate(dirs, 1) if d < 0)
        reason = (
            ""
            if ok
            else (
                "frame 0 must lie on the axis of joint 1"
                if not on_axis
                else "the arm is right, but the tool frame (last frame) differs from the key's"
            )
        )
        found.append(
            TableMatch(
                ok,
                False,
                None if ok else len(jk) + 1,
                tuple(diffs),
                reason,
                reversed_,
                tool,
                on_axis,
                {"B": B, "E": E, "signs": signs},
            )
        )
        if ok and len(diffs) <= 1:
            break
    if found:
        return min(found, key=lambda m: (not m.same_robot, len(m.differences)))
    got = best
    where = got + 1
    if where > len(jk):
        reason = "the joint axes agree, but the last frame moves differently"
    else:
        row = jk[got][0]
        culprit = row - 1 if kc.convention is Convention.STANDARD else row
        check = f" (check row {culprit})" if culprit >= 1 else " (check frame 0 and row 1)"
        reason = f"the axis of joint {where} is not where it should be{check}"
    return TableMatch(False, diverges_at=where, reason=reason)
