"""Standard ↔ modified DH conversion that keeps the tool pose, and rigid transforms as words.

The two link matrices (Mohan, Lecture 9) are words of the same four elementaries:

* standard  ``A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)``
* modified  ``^{i-1}T_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)``

so a product of standard links regroups into modified links with the same
numbers, because ``Tx`` and ``Rx`` commute::

    Rz(θ1)Tz(d1) · Tx(a1)Rx(α1) Rz(θ2)Tz(d2) · … · Tx(an)Rx(αn)
    └ row 1 ┘      └───── row 2 (α1, a1, d2, θ2) ─┘      └ tool ┘

Standard → modified: row *i* gets α_{i−1}, a_{i−1} of standard row *i − 1*
(row 1 gets 0, 0) and ``Tx(a_n) Rx(α_n)`` moves into the tool transform.
Modified → standard: the reverse; ``Rx(α_0) Tx(a_0)`` moves into the base.
The joint variables, their offsets and limits do not change, so the tool
pose is the same function of q (``check_conversion`` confirms it at random q).
When the base ends with ``Rx Tx`` (or the tool starts with ``Tx Rx``; either
factor alone, in that order) they are absorbed into the first (last) row. Where
that would take a factor that is not the row's own, the converted table keeps a
zero step as a marker (a standard row with a_n = α_n = 0 and a tool ``Tx(t)``
becomes the modified tool ``Tx(0) Tx(t)``), so a round trip gives back the table
exactly; only explicit zero steps at that end of a base or tool, which do nothing,
are dropped.

Examples
--------
>>> from dhsym import load_table
>>> mod = to_modified(load_table("planar2r"))
>>> [(r.alpha, r.a, r.d, r.theta) for r in mod.rows], mod.tool
([(0, 0, 0, theta1), (0, a1, 0, theta2)], (Tx(a2),))
>>> to_standard(mod) == load_table("planar2r")
True
>>> check_conversion(load_table("puma560"), to_modified(load_table("puma560"))) < 1e-12
True
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError, TableError
from dhsym.kinematics.numeric import compile_word, elementary_stack, to_float
from dhsym.kinematics.transforms import chain_word, elementary_matrix
from dhsym.model.table import Convention, DHRow, DHTable, Elementary

from .axes import exact_matrix

__all__ = [
    "check_conversion",
    "convert",
    "euler_solution",
    "rotation_word",
    "to_modified",
    "to_standard",
    "transform_word",
]

_AXES = "xyz"


def _nonzero(e: Elementary) -> bool:
    return bool(sp.simplify(e.value) != 0)


def _word(*elems: Elementary) -> tuple[Elementary, ...]:
    return tuple(e for e in elems if _nonzero(e))


_KEYS = {("R", "x"): "alpha", ("T", "x"): "a"}


def _take(seq: Sequence[Elementary], at_end: bool) -> tuple[list[Elementary], dict[str, sp.Expr]]:
    """Split off the row's own ``Rx(α) Tx(a)`` from one end of a base or tool word.

    The end of a base may hold ``Rx(α0) Tx(a0)`` (modified row 1), the start of
    a tool ``Tx(an) Rx(αn)`` (standard row n), each factor optional, in that
    order; values may be zero (a zero step marks a factor that is absent).
    """
    rest = list(seq)
    taken: dict[str, sp.Expr] = {}
    for key in ("a", "alpha"):  # the Tx next to the row, then the Rx
        if not rest:
            break
        e = rest[-1] if at_end else rest[0]
        if _KEYS.get((e.kind, e.axis)) != key:
            continue
        taken[key] = e.value
        rest.pop(-1 if at_end else 0)
    return rest, taken


def _emit(
    rest: Sequence[Elementary], taken: dict[str, sp.Expr], at_end: bool
) -> tuple[Elementary, ...]:
    """The shortest ``Rx(α) Tx(a)`` (base end) or ``Tx(a) Rx(α)`` (tool start) that
    :func:`_take` splits back into exactly ``rest`` and ``taken``.

    Zero factors are left out unless the way back would otherwise take a factor
    of ``rest`` for the row's own: then a zero step (``Tx(0)``) marks the place.
    """
    factors = {
        "alpha": Elementary("R", "x", taken.get("alpha", sp.Integer(0))),
        "a": Elementary("T", "x", taken.get("a", sp.Integer(0))),
    }
    order = ("alpha", "a") if at_end else ("a", "alpha")
    options = [[k for k in order if _nonzero(factors[k]) or k in extra] for extra in _EXTRAS]
    for keys in sorted(options, key=len):
        word = tuple(factors[k] for k in keys)
        trial = [*rest, *word] if at_end else [*word, *rest]
        back_rest, back = _take(trial, at_end)
        if back_rest == list(rest) and all(
            sp.simplify(back.get(k, 0) - taken.get(k, 0)) == 0 for k in ("a", "alpha")
        ):
            return word
    return tuple(factors[k] for k in order)  # both factors: always split back exactly


_EXTRAS = ((), ("a",), ("alpha",), ("a", "alpha"))


def to_modified(table: DHTable, *, absorb: bool = True) -> DHTable:
    """The same robot in the modified (Craig) convention; the tool pose is unchanged.

    ``to_standard(to_modified(t)) == t`` for every standard table ``t`` (a base
    that ends with an explicit zero step ``Rx(0)``/``Tx(0)`` comes back without it).

    >>> from dhsym import load_table
    >>> m = to_modified(load_table("puma560"))
    >>> [r.alpha for r in m.rows], m.tool
    ([0, pi/2, 0, -pi/2, pi/2, -pi/2], ())
    """
    if table.convention is Convention.MODIFIED:
        return table
    base: list[Elementary] = list(table.base)
    first: dict[str, sp.Expr] = {}
    if absorb:
        base, first = _take(base, at_end=True)
    rows = []
    prev_a, prev_alpha = first.get("a", sp.Integer(0)), first.get("alpha", sp.Integer(0))
    for row in table.rows:
        rows.append(replace(row, a=prev_a, alpha=prev_alpha))
        prev_a, prev_alpha = row.a, row.alpha
    last = {"a": prev_a, "alpha": prev_alpha}
    own = (
        _emit(table.tool, last, at_end=False)
        if absorb
        else _word(Elementary("T", "x", prev_a), Elementary("R", "x", prev_alpha))
    )
    return _rebuild(table, rows, Convention.MODIFIED, tuple(base), own + table.tool)


def to_standard(table: DHTable, *, absorb: bool = True) -> DHTable:
    """The same robot in the standard convention; the tool pose is unchanged.

    ``to_modified(to_standard(m)) == m`` for every modified table ``m`` (a tool
    that starts with an explicit zero step ``Tx(0)``/``Rx(0)`` comes back without it).

    >>> from dhsym import load_table
    >>> s = to_standard(load_table("puma560_modified"))
    >>> [(r.a, r.alpha) for r in s.rows][:3], s.base
    ([(0, -pi/2), (a2, 0), (a3, -pi/2)], ())
    """
    if table.convention is Convention.STANDARD:
        return table
    first = {"a": table.rows[0].a, "alpha": table.rows[0].alpha}
    own = (
        _emit(table.base, first, at_end=True)
        if absorb
        else _word(Elementary("R", "x", first["alpha"]), Elementary("T", "x", first["a"]))
    )
    tool: list[Elementary] = list(table.tool)
    last: dict[str, sp.Expr] = {}
    if absorb:
        tool, last = _take(tool, at_end=False)
    rows = []
    for k, row in enumerate(table.rows):
        if k + 1 < table.n:
            nxt = table.rows[k + 1]
            rows.append(replace(row, a=nxt.a, alpha=nxt.alpha))
        else:
            rows.append(
                replace(row, a=last.get("a", sp.Integer(0)), alpha=last.get("alpha", sp.Integer(0)))
            )
    return _rebuild(table, rows, Convention.STANDARD, table.base + own, tuple(tool))


def convert(table: DHTable, to: Convention | str) -> DHTable:
    """Convert ``table`` to convention ``to`` (``'standard'`` or ``'modified'``).

    >>> from dhsym import load_table
    >>> convert(load_table("planar4r"), "modified").tool
    (Tx(a4),)
    """
    target = Convention.parse(to)
    return to_modified(table) if target is Convention.MODIFIED else to_standard(table)


def _rebuild(
    table: DHTable,
    rows: list[DHRow],
    convention: Convention,
    base: tuple[Elementary, ...],
    tool: tuple[Elementary, ...],
) -> DHTable:
    note = _note(table.convention)
    back = "; " + _note(convention)  # present when ``table`` came from ``convention``
    if table.source == back[2:]:
        source = ""
    elif table.source.endswith(back):
        source = table.source[: -len(back)]
    else:
        source = f"{table.source}; {note}" if table.source else note
    return replace(
        table, rows=tuple(rows), convention=convention, base=base, tool=tool, source=source
    )


def _note(convention: Convention) -> str:
    return f"converted from {convention.value} DH by dhsym (tool pose unchanged)"


def check_conversion(
    before: DHTable, after: DHTable, *, samples: int = 20, seed: int = 0, tol: float = 1e-12
) -> float:
    """Largest difference of the tool pose (world → tool) of two tables at random q.

    Constant symbols use the tables' ``values`` (random numbers in [0.5, 1.5]
    for symbols without a value, the same for both tables). Raises
    :class:`~dhsym.errors.TableError` when the difference exceeds ``tol``.
    """
    if before.variables != after.variables:
        raise TableError(
            f"the tables have different joint variables: {before.variables} vs {after.variables}"
        )
    rng = np.random.default_rng(seed)
    missing = {
        s: sp.Float(rng.uniform(0.5, 1.5))
        for s in sorted(set(before.constants) | set(after.constants), key=str)
    }
    q = rng.uniform(-np.pi, np.pi, size=(samples, len(before.variables)))
    A, B = (
        compile_word(chain_word(t, -1, t.n + 1), t.variables, {**missing, **t.value_map})(q)
        for t in (before, after)
    )
    err = float(np.max(np.abs(A - B))) if samples else 0.0
    if err > tol:
        raise TableError(
            f"the converted table's tool pose differs by {err:.3g} (> {tol:g}) at random q"
        )
    return err


# --- rigid transforms as words of elementaries --------------------------------------------


def _rot(axis: int, angle: object, exact: bool = True) -> Any:
    """3×3 rotation about x/y/z: exact (sympy) or numeric (numpy), from the one kernel."""
    name = "xyz"[axis]
    if exact:
        return elementary_matrix(Elementary("R", name, angle))[:3, :3]
    return elementary_stack("R", name, [angle])[0, :3, :3]


def _same(A: Any, B: Any, exact: bool) -> bool:
    if exact:
        return all(sp.simplify(x) == 0 for x in sp.Matrix(A) - sp.Matrix(B))
    return bool(np.allclose(A, B, atol=1e-10))


#: Euler angles (a, b, c) and whether the middle one locks the outer two, or None.
_Found = tuple[tuple[Any, Any, Any], bool | None] | None


def euler_solution(
    R: Any, seq: tuple[int, int, int], exact: bool, gimbal: bool | None = None
) -> _Found:
    """Angles (a, b, c) with ``R = R_i(a) R_j(b) R_k(c)`` (Tait–Bryan or proper Euler), or None.

    ``gimbal``: when the middle angle locks the outer two, c = 0 and a takes
    the whole turn (decided numerically, then reused for the exact solve). Returns the
    angles and whether the middle angle locked, or None; the URDF reader uses it for rpy.

    >>> euler_solution(sp.Matrix([[0, -1, 0], [1, 0, 0], [0, 0, 1]]), (2, 1, 0), exact=True)
    ((pi/2, 0, 0), False)
    """
    i, j, k = seq
    atan2, sqrt = (sp.atan2, sp.sqrt) if exact else (np.arctan2, np.sqrt)
    m = 3 - i - j if k == i else k
    eps = 1 if (i, j, m) in ((0, 1, 2), (1, 2, 0), (2, 0, 1)) else -1
    if k == i:  # proper Euler i-j-i
        side = sqrt(R[i, j] ** 2 + R[i, m] ** 2)
        b = atan2(side, R[i, i])
        a, c = atan2(R[j, i], -eps * R[m, i]), atan2(R[i, j], eps * R[i, m])
    else:  # Tait–Bryan i-j-k
        side = sqrt(R[i, i] ** 2 + R[i, j] ** 2)
        b = atan2(eps * R[i, k], side)
        a, c = atan2(-eps * R[j, k], R[k, k]), atan2(-eps * R[i, j], R[i, i])
    if gimbal is None:
        gimbal = bool(abs(float(side)) < 1e-12)
    if gimbal:
        rest = R @ _rot(j, -b, exact)
        a, c = atan2(rest[(i + 2) % 3, (i + 1) % 3], rest[(i + 1) % 3, (i + 1) % 3]), 0
    if exact:
        a, b, c = (sp.simplify(x) for x in (a, b, c))
    return _checked(R, seq, (a, b, c), gimbal, exact)


def _checked(
    R: Any, seq: tuple[int, int, int], angles: tuple[Any, ...], gimbal: bool | None, exact: bool
) -> _Found:
    i, j, k = seq
    a, b, c = angles
    ok = _same(_rot(i, a, exact) @ _rot(j, b, exact) @ _rot(k, c, exact), R, exact)
    return ((a, b, c), gimbal) if ok else None


def _nice(angle: float) -> sp.Expr | None:
    """The exact multiple of a quarter degree that the float ``angle`` is, or None."""
    quarters = float(angle) * 720 / np.pi
    if abs(quarters - round(quarters)) > 1e-7:
        return None
    return sp.pi * sp.Rational(int(round(quarters)), 720)


_SEQUENCES = (
    (2, 1, 0),
    (0, 1, 2),
    (2, 1, 2),
    (2, 0, 2),
    (0, 1, 0),
    (0, 2, 0),
    (1, 0, 2),
    (1, 2, 0),
    (2, 0, 1),
    (0, 2, 1),
    (1, 0, 1),
    (1, 2, 1),
)


def rotation_word(R: sp.MatrixBase) -> tuple[Elementary, ...]:
    """A short exact word of elementary rotations equal to the numeric 3×3 rotation ``R``.

    The Tait–Bryan and Euler sequences are ranked numerically by their number of
    non-zero angles, then of angles that are not multiples of a quarter degree;
    the best one is then solved and checked exactly.

    >>> from dhsym.kinematics.transforms import Rx, Rz
    >>> rotation_word((Rz(sp.pi / 2) * Rx(-sp.pi / 2))[:3, :3])
    (Rz(pi/2), Rx(-pi/2))
    >>> rotation_word(sp.eye(3))
    ()
    """
    R = exact_matrix(R)  # text is read, never sympified
    if R.free_symbols:
        raise DHError(f"rotation_word needs a numeric rotation, got symbols {R.free_symbols}")
    Rn = np.array([[to_float(x) for x in row] for row in R.tolist()])
    if not np.allclose(Rn.T @ Rn, np.eye(3), atol=1e-9) or np.linalg.det(Rn) < 0:
        raise DHError(f"not a rotation matrix: {R.tolist()}")
    ranked = []
    for order, seq in enumerate(_SEQUENCES):
        found = euler_solution(Rn, seq, exact=False)
        if found is not None:
            angles, gimbal = found
            nonzero = sum(abs(x) > 1e-12 for x in angles)
            odd = sum(_nice(x) is None for x in angles)
            ranked.append((nonzero, odd, order, seq, gimbal, angles))
    for _, _, _, seq, gimbal, angles in sorted(ranked):
        nice = [_nice(x) for x in angles]
        found = None
        if all(x is not None for x in nice):  # k·π/720: check the exact angles directly
            found = _checked(R, seq, tuple(nice), gimbal, exact=True)
        found = found or euler_solution(R, seq, exact=True, gimbal=gimbal)
        if found is not None:
            return _word(
                *(Elementary("R", _AXES[ax], v) for ax, v in zip(seq, found[0], strict=True))
            )
    raise DHError(f"could not write {R.tolist()} as elementary rotations")


def transform_word(T: sp.MatrixBase) -> tuple[Elementary, ...]:
    """A 4×4 rigid transform as ``Tx Ty Tz`` (non-zero ones) then a rotation word.

    >>> from dhsym.kinematics.transforms import Rx, Tz
    >>> transform_word(Tz(sp.Symbol("h", real=True)) * Rx(sp.pi))
    (Tz(h), Rx(pi))
    """
    T = exact_matrix(T)
    trans = _word(*(Elementary("T", _AXES[i], sp.simplify(T[i, 3])) for i in range(3)))
    return trans + rotation_word(T[:3, :3])


# --- command line -----------------------------------------------------------------------
