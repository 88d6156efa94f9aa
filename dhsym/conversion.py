"""Standard ↔ modified DH conversion that keeps the tool pose, and rigid transforms as words.

The two link matrices (seed 002) are words of the same four elementaries:

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
When the base ends (or the tool starts) with ``Rx``/``Tx``, they are absorbed
back into the first (last) row, so a round trip gives back the table.

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

import argparse
import sys
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from .errors import DHError, TableError
from .table import Convention, DHRow, DHTable, Elementary

__all__ = [
    "check_conversion",
    "convert",
    "register_cli",
    "rotation_word",
    "to_modified",
    "to_standard",
    "transform_word",
]

_AXES = "xyz"


def _nonzero(e: Elementary) -> bool:
    return sp.simplify(e.value) != 0


def _word(*elems: Elementary) -> tuple[Elementary, ...]:
    return tuple(e for e in elems if _nonzero(e))


def _take(seq: Sequence[Elementary], from_end: bool) -> tuple[list[Elementary], dict[str, sp.Expr]]:
    """Split off at most one ``Rx`` and one ``Tx`` at one end of a word (they commute)."""
    rest = list(seq)
    taken: dict[str, sp.Expr] = {}
    while rest:
        e = rest[-1] if from_end else rest[0]
        key = {("R", "x"): "alpha", ("T", "x"): "a"}.get((e.kind, e.axis))
        if key is None or key in taken:
            break
        taken[key] = e.value
        rest.pop(-1 if from_end else 0)
    return rest, taken


def to_modified(table: DHTable, *, absorb: bool = True) -> DHTable:
    """The same robot in the modified (Craig) convention; the tool pose is unchanged.

    >>> from dhsym import load_table
    >>> m = to_modified(load_table("puma560"))
    >>> [r.alpha for r in m.rows], m.tool
    ([0, pi/2, 0, -pi/2, pi/2, -pi/2], ())
    """
    if table.convention is Convention.MODIFIED:
        return table
    base = list(table.base)
    first: dict[str, sp.Expr] = {}
    if absorb:
        base, first = _take(base, from_end=True)
    rows = []
    prev_a, prev_alpha = first.get("a", sp.Integer(0)), first.get("alpha", sp.Integer(0))
    for row in table.rows:
        rows.append(replace(row, a=prev_a, alpha=prev_alpha))
        prev_a, prev_alpha = row.a, row.alpha
    tool = _word(Elementary("T", "x", prev_a), Elementary("R", "x", prev_alpha)) + table.tool
    return _rebuild(table, rows, Convention.MODIFIED, tuple(base), tool)


def to_standard(table: DHTable, *, absorb: bool = True) -> DHTable:
    """The same robot in the standard convention; the tool pose is unchanged.

    >>> from dhsym import load_table
    >>> s = to_standard(load_table("puma560_modified"))
    >>> [(r.a, r.alpha) for r in s.rows][:3], s.base
    ([(0, -pi/2), (a2, 0), (a3, -pi/2)], ())
    """
    if table.convention is Convention.STANDARD:
        return table
    first = table.rows[0]
    base = table.base + _word(Elementary("R", "x", first.alpha), Elementary("T", "x", first.a))
    tool = list(table.tool)
    last: dict[str, sp.Expr] = {}
    if absorb:
        tool, last = _take(tool, from_end=False)
    rows = []
    for k, row in enumerate(table.rows):
        if k + 1 < table.n:
            nxt = table.rows[k + 1]
            rows.append(replace(row, a=nxt.a, alpha=nxt.alpha))
        else:
            rows.append(
                replace(row, a=last.get("a", sp.Integer(0)), alpha=last.get("alpha", sp.Integer(0)))
            )
    return _rebuild(table, rows, Convention.STANDARD, base, tuple(tool))


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
    from .robot import Robot

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
    A = Robot(before).fk(q, values={**missing, **before.value_map})
    B = Robot(after).fk(q, values={**missing, **after.value_map})
    err = float(np.max(np.abs(A - B))) if samples else 0.0
    if err > tol:
        raise TableError(
            f"the converted table's tool pose differs by {err:.3g} (> {tol:g}) at random q"
        )
    return err


# --- rigid transforms as words of elementaries --------------------------------------------


def _rot(axis: int, angle: object, exact: bool = True) -> object:
    """3×3 rotation about x/y/z: exact (sympy) or numeric (numpy)."""
    cos, sin = (sp.cos, sp.sin) if exact else (np.cos, np.sin)
    c, s = cos(angle), sin(angle)
    j, k = (axis + 1) % 3, (axis + 2) % 3
    M = sp.eye(3) if exact else np.eye(3)
    M[j, j], M[j, k], M[k, j], M[k, k] = c, -s, s, c
    return M


def _same(A: object, B: object, exact: bool) -> bool:
    if exact:
        return all(sp.simplify(x) == 0 for x in sp.Matrix(A) - sp.Matrix(B))
    return bool(np.allclose(A, B, atol=1e-10))


def _euler(R: object, seq: tuple[int, int, int], exact: bool, gimbal: bool | None = None):
    """Angles (a, b, c) with ``R = R_i(a) R_j(b) R_k(c)`` (Tait–Bryan or proper Euler), or None.

    ``gimbal``: when the middle angle locks the outer two, c = 0 and a takes
    the whole turn (decided numerically, then reused for the exact solve).
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


def _checked(R: object, seq: tuple[int, int, int], angles: tuple, gimbal: bool, exact: bool):
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

    >>> from dhsym.transforms import Rx, Rz
    >>> rotation_word((Rz(sp.pi / 2) * Rx(-sp.pi / 2))[:3, :3])
    (Rz(pi/2), Rx(-pi/2))
    >>> rotation_word(sp.eye(3))
    ()
    """
    R = sp.Matrix(R)
    if R.free_symbols:
        raise DHError(f"rotation_word needs a numeric rotation, got symbols {R.free_symbols}")
    Rn = np.array(R.evalf(), dtype=float)
    if not np.allclose(Rn.T @ Rn, np.eye(3), atol=1e-9) or np.linalg.det(Rn) < 0:
        raise DHError(f"not a rotation matrix: {R.tolist()}")
    ranked = []
    for order, seq in enumerate(_SEQUENCES):
        found = _euler(Rn, seq, exact=False)
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
        found = found or _euler(R, seq, exact=True, gimbal=gimbal)
        if found is not None:
            return _word(
                *(Elementary("R", _AXES[ax], v) for ax, v in zip(seq, found[0], strict=True))
            )
    raise DHError(f"could not write {R.tolist()} as elementary rotations")


def transform_word(T: sp.MatrixBase) -> tuple[Elementary, ...]:
    """A 4×4 rigid transform as ``Tx Ty Tz`` (non-zero ones) then a rotation word.

    >>> from dhsym.transforms import Rx, Tz
    >>> transform_word(Tz(sp.Symbol("h", real=True)) * Rx(sp.pi))
    (Tz(h), Rx(pi))
    """
    T = sp.Matrix(T)
    trans = _word(*(Elementary("T", _AXES[i], sp.simplify(T[i, 3])) for i in range(3)))
    return trans + rotation_word(T[:3, :3])


# --- command line -----------------------------------------------------------------------


def _cmd_convert(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ._number_list import check_count
    from .library import load_table
    from .tablefile import dump_table

    check_count(args.samples, "--samples", 0, 100_000)
    table = load_table(args.robot)
    target = Convention.parse(args.to)
    if table.convention is target:
        print(
            f"{table.name or args.robot} is already in the {target.value} convention",
            file=sys.stderr,
        )
    new = convert(table, target)
    err = check_conversion(table, new, samples=args.samples)
    text = dump_table(new)
    if args.output:
        Path(args.output).parent.mkdir(parents=True, exist_ok=True)
        Path(args.output).write_text(text, encoding="utf-8")
        print(f"wrote {args.output}", file=sys.stderr)
    else:
        print(text, end="")
    print(
        f"tool pose agrees at {args.samples} random configurations (max difference {err:.2g})",
        file=sys.stderr,
    )
    return 0


def register_cli(subparsers: argparse._SubParsersAction) -> None:
    """Add ``dhsym convert NAME|FILE --to modified|standard [-o FILE]``.

    >>> sub = argparse.ArgumentParser().add_subparsers()
    >>> register_cli(sub)
    >>> sorted(sub.choices)
    ['convert']
    """
    c = subparsers.add_parser(
        "convert",
        help="standard <-> modified DH, with base/tool transforms that keep the tool pose",
    )
    c.add_argument("robot", help="built-in name or table file")
    c.add_argument(
        "--to", required=True, choices=["standard", "modified"], help="target convention"
    )
    c.add_argument("-o", "--output", help="write the YAML table here instead of standard output")
    c.add_argument(
        "--samples",
        type=int,
        default=20,
        help="random configurations for the fk check (default 20)",
    )
    c.set_defaults(func=_cmd_convert)
