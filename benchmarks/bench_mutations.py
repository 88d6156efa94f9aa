"""Mistakes students make, mined by mutation: is each single-edit slip named with its kind?

Run ``python benchmarks/bench_mutations.py`` (``--limit N`` for a seeded sample of N
single-edit mutants, ``--doubles N`` of N double-edit mutants, ``--robots NAME …`` for some
built-in robots only, ``--no-singles``, ``--misses`` to list the mutants not diagnosed with
their kind).

Double edits: one entry edited twice, by two of the entry kinds below (a single edit, then
one of another kind on its result; a seeded draw of one per entry). A double mutant equal
to a single-edit one is left out (it is a single slip); one equal to the key must be graded
CORRECT. It counts as diagnosed when *both* its kinds are named (goal ≥ 90 %); the CPU time
per answer is printed (the machine is shared: CPU, not wall time, measures the search).

Two slips in one DH table (``--tables N`` for a seeded sample, ``--no-tables``): the key's
table of every built-in robot, typed as a student types it (Markdown, angles in degrees by
the header), with two slips of the kinds ``wrong_sign`` (a cell negated; a joint's offset),
``degrees_as_radians`` (one row's constant angles typed as their radians), ``offset_missing``
(a joint's offset left out), ``index_shift`` (α, or α and a, taken from the next or the
previous row) and ``single_wrong_row`` (a length typed as 0.37): a seeded draw of two
tables per pair of kinds, two of one kind in two different rows. A table that still gives
the key's tool frame at every configuration up to a base transform (the benchmark's own
check in numbers: two slips may undo each other) must be graded CORRECT, as must the key
typed in degrees, in radians and with its numbers. A two-slip table counts as diagnosed
when both its kinds are named (a kind twice: named twice; goal ≥ 90 %).

Every entry of ``^0T_n`` and of the Jacobian ``J`` of every built-in robot is mutated
by one edit, written out in the lecture notation and graded through
:func:`dhsym.checking.check_answer`, exactly as a student's answer:

- ``wrong_sign``: one term of a sum (at any depth: inside a bracket or a product) negated;
- ``dropped_term``: one term of a sum (at any depth) left out;
- ``sin_cos_swapped``: one sine or cosine factor swapped for the other;
- ``wrong_joint_index``: a sum angle moved by one joint (``C12`` for ``C23``);
- ``missing_length``: one length symbol left out of one product;
- ``transposed``: one 3×3 block transposed (the rotation of ``^0T_n``, the blocks of J);
- ``degrees_as_radians``: ``^0T_n`` with one row's constant angle in degrees taken as
  radians (``cos(90)``): the degrees of one row of the table.

The mutations are generated here, independently of the detectors in
``dhsym/checking/mistakes/_entry_mistakes.py``. A mutant whose value equals the key's (the edit
of a zero term, a sign of a term that cancels) must be graded CORRECT; so must the key
itself and its expanded and re-simplified forms. A mutant counts as *diagnosed with the
right kind* when the first diagnosis names its generating kind, or another kind whose
single edit gives the very same entry (``-S1`` dropped from ``C1 - S1`` is also ``C1``
... the kinds are then ambiguous, and both count); the strict figure is printed too.
"""

from __future__ import annotations

import argparse
import itertools
import random
import sys
import time
from collections import Counter, defaultdict
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import sympy as sp

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from dhsym.checking import Key, check_answer  # noqa: E402
from dhsym.checking.comparing.verdict import Verdict  # noqa: E402
from dhsym.checking.judging.key import PreparedKeys, prepare  # noqa: E402
from dhsym.kinematics.interpreter import evaluate  # noqa: E402
from dhsym.kinematics.numeric import word_product  # noqa: E402
from dhsym.kinematics.transforms import link_matrix, link_word  # noqa: E402
from dhsym.model.library import builtin_names  # noqa: E402
from dhsym.model.table import Convention, DHRow, DHTable  # noqa: E402
from dhsym.notation.printers import Notation  # noqa: E402


@dataclass(frozen=True)
class Mutant:
    """One answer to grade: the robot, the question, the text, its kind (None: correct)."""

    robot: str
    question: str
    text: str
    kind: str | None
    accepted: frozenset[str] = field(default_factory=frozenset)
    where: str = ""


def _edits(e: sp.Basic, edit: Callable, angles: bool = True) -> Iterator[sp.Basic]:
    """``e`` with one node rewritten by ``edit``, at any depth (inside the angle of a sine
    or cosine only with ``angles``: a term of a sum angle is a joint index, not a term)."""
    yield from edit(e)
    if not angles and isinstance(e, (sp.sin, sp.cos)):
        return
    for i, arg in enumerate(e.args):
        for new in _edits(arg, edit, angles):
            args = list(e.args)
            args[i] = new
            yield e.func(*args)


def _joints(table: object) -> tuple[list[sp.Symbol], Notation]:
    """The revolute joints' angles, and the lecture notation labelling them by row."""
    rows = [(i, r) for i, r in enumerate(table.rows, 1) if r.variable_field == "theta"]
    rows = [(i, r) for i, r in rows if r.variable is not None]
    joints = [r.variable for _, r in rows]
    return joints, Notation.from_variables(joints, [str(i) for i, _ in rows])


def entry_mutations(
    e: sp.Expr, joints: list[sp.Symbol], variables: list[sp.Symbol]
) -> Iterator[tuple[str, sp.Expr]]:
    """(kind, mutant) for one entry; ``joints`` the revolute angles, ``variables`` all."""
    index = {v: k for k, v in enumerate(joints)}

    def sign(n: sp.Basic) -> Iterator[sp.Basic]:
        if isinstance(n, sp.Add):
            for t in n.args:
                yield n - 2 * t

    def drop(n: sp.Basic) -> Iterator[sp.Basic]:
        if isinstance(n, sp.Add):
            for t in n.args:
                yield n - t

    def swap(n: sp.Basic) -> Iterator[sp.Basic]:
        if isinstance(n, sp.sin):
            yield sp.cos(n.args[0])
        elif isinstance(n, sp.cos):
            yield sp.sin(n.args[0])

    def shift(n: sp.Basic) -> Iterator[sp.Basic]:
        if isinstance(n, (sp.sin, sp.cos)):
            terms = sp.Add.make_args(n.args[0])
            used = sorted(index[t] for t in terms if t in index)
            rest = sp.Add(*[t for t in terms if t not in index])
            if len(used) >= 2 and not rest.free_symbols:  # a sum angle
                for step in (-1, 1):
                    moved = [k + step for k in used]
                    if 0 <= moved[0] and moved[-1] < len(joints):
                        yield n.func(sp.Add(*[joints[k] for k in moved]) + rest)

    def length(n: sp.Basic) -> Iterator[sp.Basic]:
        if isinstance(n, sp.Mul):
            for f in n.args:
                if f.is_Symbol and f not in variables:
                    yield n / f

    for kind, edit, angles in (
        ("wrong_sign", sign, False),
        ("dropped_term", drop, False),
        ("sin_cos_swapped", swap, True),
        ("wrong_joint_index", shift, True),
        ("missing_length", length, False),
    ):
        for m in _edits(e, edit, angles):
            yield kind, m


def _matrix_text(m: sp.Matrix, nota: Notation) -> str:
    """The matrix as a student types it (C12 notation; cos/sin in full for an angle the
    short notation writes as ``C[12-4]``, which the answer parser does not read)."""
    full = Notation(nota.labels, compact=False)

    def cell(x: sp.Expr) -> str:
        text = nota.text(x)
        return full.text(x) if "[" in text else text

    return "[" + ", ".join("[" + ", ".join(cell(x) for x in row) + "]" for row in m.tolist()) + "]"


def _fingerprint(e: sp.Expr, symbols: list[sp.Symbol], points: np.ndarray) -> tuple:
    """The values at the points, rounded (the numeric kernel's tree walker: no code
    generation per mutant)."""
    env = {s: points[:, k] for k, s in enumerate(symbols)}
    v = evaluate(e, env, len(points))
    return tuple(np.round(v, 9))


def matrix_mutants(robot: str, question: str) -> list[Mutant]:
    """Single-edit mutants (and correct rewritings) of every entry of one matrix question."""
    pk = prepare(Key.load(robot, question))
    expected = sp.Matrix(pk.part.expected)
    joints, nota = _joints(pk.key.table)
    variables = [r.variable for r in pk.key.table.rows if r.variable is not None]
    symbols = sorted(expected.free_symbols | set(variables), key=sp.default_sort_key)
    rng = np.random.default_rng(7)
    points = rng.uniform(0.2, 1.3, size=(5, len(symbols)))
    out = [Mutant(robot, question, _matrix_text(expected, nota), None, where="key")]
    for how, rewrite in (("expanded", sp.expand), ("re-simplified", sp.trigsimp)):
        out.append(
            Mutant(
                robot, question, _matrix_text(expected.applyfunc(rewrite), nota), None, where=how
            )
        )
    rows = 3 if expected.shape == (4, 4) else expected.shape[0]
    for i in range(rows):
        for j in range(expected.shape[1]):
            e = expected[i, j]
            if not e.free_symbols:
                continue
            right = _fingerprint(e, symbols, points)
            found = list(dict.fromkeys(entry_mutations(e, joints, variables)))
            kinds_of: dict[tuple, set[str]] = defaultdict(set)
            prints = []
            for kind, m in found:
                fp = _fingerprint(m, symbols, points)
                kinds_of[fp].add(kind)
                prints.append(fp)
            for (kind, m), fp in zip(found, prints):
                wrong = expected.copy()
                wrong[i, j] = m
                same = fp == right
                out.append(
                    Mutant(
                        robot,
                        question,
                        _matrix_text(wrong, nota),
                        None if same else kind,
                        frozenset(kinds_of[fp]),
                        f"({i + 1},{j + 1}) {nota.text(m)}",
                    )
                )
    blocks = (
        [(0, 0)]
        if expected.shape == (4, 4)
        else [(r, c) for r in (0, 3) for c in range(0, expected.shape[1] - 2, 3)]
    )
    for r, c in blocks:
        wrong = expected.copy()
        wrong[r : r + 3, c : c + 3] = expected[r : r + 3, c : c + 3].T
        if wrong != expected:
            out.append(
                Mutant(
                    robot,
                    question,
                    _matrix_text(wrong, nota),
                    "transposed",
                    frozenset({"transposed"}),
                    f"block ({r + 1},{c + 1})",
                )
            )
    return out


#: The kinds of single edits composed in pairs (the entry kinds: each rewrites one entry).
PAIR_KINDS = (
    "wrong_sign",
    "dropped_term",
    "sin_cos_swapped",
    "wrong_joint_index",
    "missing_length",
)


def double_mutants(robot: str, question: str, per_entry: int = 1) -> list[Mutant]:
    """Two-edit mutants of each entry (a seeded draw of ``per_entry`` per entry): a single
    edit of one kind, then one of another kind on its result. A double mutant equal to the
    key is a correct answer; one equal to a single-edit mutant of the entry is left out
    (that is a single slip, counted above); its kind is ``"a+b"``."""
    pk = prepare(Key.load(robot, question))
    expected = sp.Matrix(pk.part.expected)
    joints, nota = _joints(pk.key.table)
    variables = [r.variable for r in pk.key.table.rows if r.variable is not None]
    symbols = sorted(expected.free_symbols | set(variables), key=sp.default_sort_key)
    points = np.random.default_rng(7).uniform(0.2, 1.3, size=(5, len(symbols)))
    rows = 3 if expected.shape == (4, 4) else expected.shape[0]
    out = []
    for i in range(rows):
        for j in range(expected.shape[1]):
            e = expected[i, j]
            if not e.free_symbols:
                continue
            rng = random.Random(f"{robot} {question} {i} {j}")
            singles = list(dict.fromkeys(entry_mutations(e, joints, variables)))
            single_prints = {_fingerprint(m, symbols, points) for _, m in singles}
            right = _fingerprint(e, symbols, points)
            made = 0
            for _ in range(12 * per_entry):
                if made >= per_entry or not singles:
                    break
                k1, m1 = rng.choice(singles)
                seconds = [
                    (k2, m2)
                    for k2, m2 in dict.fromkeys(entry_mutations(m1, joints, variables))
                    if k2 != k1 and k2 in PAIR_KINDS
                ]
                if not seconds:
                    continue
                k2, m2 = rng.choice(seconds)
                fp = _fingerprint(m2, symbols, points)
                if fp in single_prints and fp != right:
                    continue
                wrong = expected.copy()
                wrong[i, j] = m2
                kind = None if fp == right else "+".join(sorted((k1, k2)))
                where = f"({i + 1},{j + 1}) {nota.text(m2)}" if kind else "double edit that cancels"
                out.append(Mutant(robot, question, _matrix_text(wrong, nota), kind, where=where))
                made += 1
    return out


def degree_mutants(robot: str) -> list[Mutant]:
    """``^0T_n`` computed with one row's constant angle in degrees used as radians
    (``cos(90)`` for cos 90°): the degrees of one row of the table."""
    table = Key.load(robot, "table").table
    n = len(table.rows)
    joints, nota = _joints(table)
    out = []
    for k, row in enumerate(table.rows):
        for name in ("alpha", "theta"):
            value = getattr(row, name)
            const = sp.Add(*[t for t in sp.Add.make_args(value) if not t.free_symbols])
            if const == 0:
                continue
            rows = list(table.rows)
            rows[k] = replace(row, **{name: value - const + const * 180 / sp.pi})
            m = sp.eye(4)
            for r in rows:
                m = m * link_matrix(r, table.convention)
            text = _matrix_text(m, nota)
            out.append(
                Mutant(
                    robot,
                    f"T0_{n}",
                    text,
                    "degrees_as_radians",
                    frozenset({"degrees_as_radians"}),
                    f"row {k + 1} {name}",
                )
            )
    return out


def all_mutants(robots: list[str] | None = None) -> list[Mutant]:
    """Every single-edit mutant of every built-in robot (deterministic order)."""
    out: list[Mutant] = []
    for robot in robots or builtin_names():
        n = len(Key.load(robot, "table").table.rows)
        out += matrix_mutants(robot, f"T0_{n}")
        out += matrix_mutants(robot, "J")
        out += degree_mutants(robot)
    return out


def all_double_mutants(robots: list[str] | None = None, per_entry: int = 1) -> list[Mutant]:
    """Two-edit mutants of every entry of ``^0T_n`` and J of every built-in robot."""
    out: list[Mutant] = []
    for robot in robots or builtin_names():
        n = len(Key.load(robot, "table").table.rows)
        out += double_mutants(robot, f"T0_{n}", per_entry)
        out += double_mutants(robot, "J", per_entry)
    return out


# --- DH tables: two slips in one table ---------------------------------------------------

#: The kinds of table slips composed in pairs (each generated here, on the key's rows).
TABLE_KINDS = (
    "wrong_sign",
    "degrees_as_radians",
    "offset_missing",
    "index_shift",
    "single_wrong_row",
)
#: A wrong number typed for a length (no key length is this number).
_WRONG_LENGTH = sp.Rational(37, 100)


@dataclass(frozen=True)
class TableEdit:
    """One slip in a table: its kind, the rows it touches (0-based; every row for a shift),
    and how it rewrites the rows and the rows written in radians."""

    kind: str
    rows: frozenset[int]
    cell: tuple[int, str] | None
    apply: Callable[[list[DHRow], set[int]], None]
    label: str


def _constant(value: sp.Expr) -> sp.Expr:
    return sp.Add(*[t for t in sp.Add.make_args(value) if not t.free_symbols])


def table_edits(table: DHTable) -> list[TableEdit]:
    """Every single slip of the kinds in :data:`TABLE_KINDS` on ``table``'s rows."""
    rows = list(table.rows)
    out: list[TableEdit] = []

    def setter(k: int, name: str, value: sp.Expr) -> Callable[[list[DHRow], set[int]], None]:
        def apply(rs: list[DHRow], radians: set[int]) -> None:
            rs[k] = replace(rs[k], **{name: value(rs[k]) if callable(value) else value})

        return apply

    for k, row in enumerate(rows):
        for name in ("theta", "d", "a", "alpha"):
            value = getattr(row, name)
            own = name == row.variable_field
            if name in ("theta", "alpha") and (2 * _constant(value) / (2 * sp.pi)).is_integer:
                flips = False  # -pi is pi: the sign of a half turn is no slip
            else:
                flips = True
            if own and _constant(value) != 0 and row.variable is not None:
                v = row.variable
                if flips:
                    out.append(
                        TableEdit(
                            "wrong_sign",
                            frozenset({k}),
                            (k, name),
                            setter(k, name, lambda r, n=name, v=v: 2 * v - getattr(r, n)),
                            f"row {k + 1} {name} sign",
                        )
                    )
                out.append(
                    TableEdit(
                        "offset_missing",
                        frozenset({k}),
                        (k, name),
                        setter(k, name, v),
                        f"row {k + 1} offset",
                    )
                )
            elif not own and value != 0 and flips:
                out.append(
                    TableEdit(
                        "wrong_sign",
                        frozenset({k}),
                        (k, name),
                        setter(k, name, lambda r, n=name: -getattr(r, n)),
                        f"row {k + 1} {name} sign",
                    )
                )
            if name in ("d", "a") and not own and value != _WRONG_LENGTH:
                out.append(
                    TableEdit(
                        "single_wrong_row",
                        frozenset({k}),
                        (k, name),
                        setter(k, name, _WRONG_LENGTH),
                        f"row {k + 1} {name} = {_WRONG_LENGTH}",
                    )
                )
        if _constant(row.alpha) != 0 or _constant(row.theta) != 0:

            def radians(rs: list[DHRow], flags: set[int], k: int = k) -> None:
                flags.add(k)

            out.append(
                TableEdit(
                    "degrees_as_radians", frozenset({k}), None, radians, f"row {k + 1} radians"
                )
            )
    for step in (1, -1):
        for names in (("alpha", "a"), ("alpha",)):

            def shift(rs: list[DHRow], flags: set[int], step=step, names=names) -> None:
                before = list(rs)
                for k, r in enumerate(before):
                    src = k + step
                    new = {
                        n: getattr(before[src], n) if 0 <= src < len(before) else sp.Integer(0)
                        for n in names
                    }
                    rs[k] = replace(r, **new)

            out.append(
                TableEdit(
                    "index_shift",
                    frozenset(range(len(rows))),
                    None,
                    shift,
                    f"{'+'.join(names)} from the {'next' if step == 1 else 'previous'} row",
                )
            )
    return out


def _angle_text(value: sp.Expr, radians: bool) -> str:
    """An angle cell of a table in degrees: ``theta3 + 90``; a row written in radians by
    mistake gives its constant as the radians' number (``1.5708``)."""
    const = _constant(value)
    rest = sp.expand(value - const)
    if const == 0:
        return sp.sstr(rest) if rest != 0 else "0"
    if radians:
        number = f"{abs(float(const)):.4f}"
    else:
        degrees = sp.nsimplify(abs(const) * 180 / sp.pi)
        number = sp.sstr(degrees) if degrees.is_Integer else f"{float(degrees):.6g}"
    if rest == 0:
        return number if const > 0 else f"-{number}"
    return f"{sp.sstr(rest)} {'+' if const > 0 else '-'} {number}"


def table_text(
    rows: list[DHRow], convention: Convention, radians: set[int], unit: str = "deg"
) -> str:
    """The table as a student types it (Markdown, angles in degrees by the header, or in
    radians as sympy writes them with ``unit="rad"``)."""
    mark = " (deg)" if unit == "deg" else ""
    if convention is Convention.MODIFIED:
        head = [f"alpha_{{i-1}}{mark}", "a_{i-1}", "d_i", f"theta_i{mark}"]
        order = ("alpha", "a", "d", "theta")
    else:
        head = [f"theta_i{mark}", "d_i", "a_i", f"alpha_i{mark}"]
        order = ("theta", "d", "a", "alpha")
    lines = ["| i | " + " | ".join(head) + " |", "|---" * (len(head) + 1) + "|"]
    for k, row in enumerate(rows, 1):
        cells = []
        for name in order:
            value = getattr(row, name)
            if name in ("theta", "alpha") and unit == "deg":
                cells.append(_angle_text(value, k - 1 in radians))
            else:
                cells.append(sp.sstr(value))
        lines.append(f"| {k} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _as_read(rows: list[DHRow], radians: set[int]) -> list[DHRow]:
    """The rows as the reader takes the typed table: a row written in radians in a table in
    degrees has its constant angles read as that many degrees."""
    out = []
    for k, row in enumerate(rows):
        if k in radians:
            row = replace(
                row,
                **{
                    n: getattr(row, n)
                    - _constant(getattr(row, n))
                    + sp.Float(f"{float(_constant(getattr(row, n))):.4f}") * sp.pi / 180
                    for n in ("theta", "alpha")
                },
            )
        out.append(row)
    return out


def same_robot(
    table: DHTable, rows: list[DHRow], radians: set[int], convention: Convention | None = None
) -> bool:
    """True when ``rows`` (read in ``convention``, the key's by default) give the key's tool
    frame at every configuration up to one constant base transform about and along ``z0``
    and the senses of the joint variables (a z axis reversed): the benchmark's own check,
    in numbers, of whether a two-slip table is still right (two slips may undo each other:
    ``d1`` and ``d2`` of a planar arm both changed only move frame 0 along ``z0``)."""
    rng = np.random.default_rng(11)
    size = 8
    variables = [r.variable for r in table.rows if r.variable is not None]
    q = {v: rng.uniform(-2.5, 2.5, size) for v in variables}
    constants: dict = {}
    symbols = set().union(*(e.free_symbols for r in table.rows for e in r.params().values()))
    for s_ in sorted(symbols - set(variables), key=sp.default_sort_key):
        constants[s_] = float(table.value_map.get(s_, rng.uniform(0.2, 1.3)))

    def frames(rs: list[DHRow], conv: Convention, signs: tuple[int, ...]) -> np.ndarray:
        word = [e for r in rs for e in link_word(r, conv)]
        env = {**constants, **{v: sign * q[v] for v, sign in zip(variables, signs)}}
        return word_product(word, env, size)

    ones = (1,) * len(variables)
    key = frames(list(table.rows), table.convention, ones)
    read = _as_read(rows, radians)
    for signs in itertools.product((1, -1), repeat=len(variables)):
        mutant = frames(read, convention or table.convention, signs)
        base = mutant[0] @ np.linalg.inv(key[0])
        on_axis = abs(abs(base[2, 2]) - 1) < 1e-9 and np.allclose(base[:2, 3], 0, atol=1e-9)
        if on_axis and np.allclose(mutant, base @ key, atol=1e-7):
            return True
    return False


def table_mutants(robot: str, per_pair: int = 2) -> list[Mutant]:
    """Two-slip tables of one robot (a seeded draw of ``per_pair`` for each pair of kinds,
    two of one kind only in two rows, two of different kinds anywhere) and its correct
    writings (in degrees, in radians, with the key's numbers)."""
    table = Key.load(robot, "table").table
    conv = table.convention
    rows = list(table.rows)
    right = table_text(rows, conv, set())
    out = [
        Mutant(robot, "table", right, None, where="key in degrees"),
        Mutant(robot, "table", table_text(rows, conv, set(), "rad"), None, where="key in radians"),
    ]
    if table.value_map:
        numbers = [
            replace(r, **{n: v.xreplace(table.value_map) for n, v in r.params().items()})
            for r in rows
        ]
        out.append(Mutant(robot, "table", table_text(numbers, conv, set()), None, where="numbers"))
    edits = table_edits(table)
    # every row with a constant angle in radians is one slip (the whole table), not two
    angled = {k for k, r in enumerate(rows) if _constant(r.alpha) != 0 or _constant(r.theta) != 0}
    singles = {table_text(rows, conv, angled)}
    for e in edits:
        rs, flags = list(rows), set()
        e.apply(rs, flags)
        singles.add(table_text(rs, conv, flags))
    rng = random.Random(f"{robot} table")
    for i, ka in enumerate(TABLE_KINDS):
        for kb in TABLE_KINDS[i:]:
            if ka == kb == "index_shift":
                continue
            pairs = [
                (a, b)
                for a in edits
                if a.kind == ka
                for b in edits
                if b.kind == kb
                and a is not b
                and (ka != kb or not a.rows & b.rows)  # one kind: in two rows
                and (a.cell is None or a.cell != b.cell or ka != kb)
            ]
            rng.shuffle(pairs)
            made = 0
            for a, b in pairs:
                if made >= per_pair:
                    break
                rs, flags = list(rows), set()
                a.apply(rs, flags)
                b.apply(rs, flags)
                text = table_text(rs, conv, flags)
                if text in singles or text == right:
                    continue  # one slip undoes or repeats the other
                # two slips that give the same robot make a right answer; a table of this
                # robot in the other convention is that mistake too
                kind = None if same_robot(table, rs, flags) else "+".join(sorted((ka, kb)))
                other = Convention.MODIFIED if conv is Convention.STANDARD else Convention.STANDARD
                accepted = (
                    frozenset({"other_convention"})
                    if kind is not None and same_robot(table, rs, flags, other)
                    else frozenset()
                )
                where = f"{a.label}; {b.label}"
                out.append(Mutant(robot, "table", text, kind, accepted, where))
                made += 1
    return out


def all_table_mutants(robots: list[str] | None = None, per_pair: int = 2) -> list[Mutant]:
    """Two-slip tables of every built-in robot."""
    return [m for robot in robots or builtin_names() for m in table_mutants(robot, per_pair)]


@dataclass(frozen=True)
class Outcome:
    mutant: Mutant
    verdict: Verdict
    kind: str | None

    @property
    def false_wrong(self) -> bool:
        """A correct answer (no mutation, or one that cancels) not graded CORRECT."""
        return self.mutant.kind is None and self.verdict is not Verdict.CORRECT

    kinds: tuple[str, ...] = ()
    seconds: float = 0.0

    @property
    def strict(self) -> bool:
        if self.double:  # both generating kinds named (a kind twice: named twice)
            made = Counter(self.mutant.kind.split("+"))  # type: ignore[union-attr]
            return made <= Counter(self.kinds)
        return self.kind == self.mutant.kind

    @property
    def right(self) -> bool:
        return self.kind in self.mutant.accepted or self.strict

    @property
    def double(self) -> bool:
        return self.mutant.kind is not None and "+" in self.mutant.kind


def grade(m: Mutant, keys: PreparedKeys) -> Outcome:
    key = Key.load(m.robot, m.question)
    keys.get(key)  # prepared once, outside the answer's time (as a grading worker does)
    t = time.process_time()
    r = check_answer(key, m.text, keys=keys)
    seconds = time.process_time() - t  # CPU: the machine is shared
    kinds = [k for k in r.kinds if k not in ("unexplained", "unknown_symbol")]
    return Outcome(m, r.verdict, kinds[0] if kinds else None, tuple(kinds), seconds)


def run(mutants: list[Mutant]) -> list[Outcome]:
    keys = PreparedKeys()
    return [grade(m, keys) for m in mutants]


def sample(mutants: list[Mutant], limit: int | None, seed: int = 24) -> list[Mutant]:
    """All mutants, or a seeded sample of ``limit`` that keeps every correct rewriting."""
    if limit is None or limit >= len(mutants):
        return mutants
    keep = [m for m in mutants if m.kind is None and m.where != ""]
    rest = [m for m in mutants if m not in keep]
    return keep + random.Random(seed).sample(rest, max(0, limit - len(keep)))


def _report(title: str, outcomes: list[Outcome], goal: float) -> tuple[float, int, int]:
    """Print the figures of one set of mutants; (right kind, correct graded wrong, wrong
    graded CORRECT)."""
    wrong = [o for o in outcomes if o.mutant.kind is not None]
    correct = [o for o in outcomes if o.mutant.kind is None]
    by_kind: dict[str, Counter] = defaultdict(Counter)
    for o in wrong:
        by_kind[o.mutant.kind]["n"] += 1
        by_kind[o.mutant.kind]["right"] += o.right
        by_kind[o.mutant.kind]["strict"] += o.strict
    print(f"{title}: {len(wrong)} wrong, {len(correct)} correct (rewritings or cancelling edits)")
    print(f"{'kind':<36}{'n':>6}{'right kind':>12}{'strict':>9}")
    for kind, c in sorted(by_kind.items()):
        print(f"{kind:<36}{c['n']:>6}{c['right'] / c['n']:>12.1%}{c['strict'] / c['n']:>9.1%}")
    right = sum(o.right for o in wrong) / max(len(wrong), 1)
    strict = sum(o.strict for o in wrong) / max(len(wrong), 1)
    false_wrong = sum(o.false_wrong for o in correct)
    passed = sum(o.verdict is Verdict.CORRECT for o in wrong)
    what = (
        "diagnosed with both kinds"
        if title.startswith("double")
        else "diagnosed with the right kind"
    )
    print(f"{what}: {right:.1%} (strict: {strict:.1%}); goal >= {goal:.0%}")
    print(f"correct answers graded wrong: {false_wrong} of {len(correct)}; goal 0")
    print(f"wrong answers graded CORRECT: {passed} of {len(wrong)}; goal 0")
    return right, false_wrong, passed


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--limit", type=int, help="grade a seeded sample of this many mutants")
    p.add_argument(
        "--doubles",
        type=int,
        default=None,
        help="grade a seeded sample of this many double mutants",
    )
    p.add_argument("--no-singles", action="store_true", help="grade the double mutants only")
    p.add_argument(
        "--tables",
        type=int,
        default=None,
        help="grade a seeded sample of this many two-slip tables (default: all)",
    )
    p.add_argument("--no-tables", action="store_true", help="leave out the two-slip tables")
    p.add_argument("--robots", nargs="*", help="these built-in robots only (default: all)")
    p.add_argument("--misses", action="store_true", help="list the mutants not diagnosed")
    args = p.parse_args()
    t0 = time.perf_counter()
    singles = [] if args.no_singles else sample(all_mutants(args.robots), args.limit)
    doubles = sample(all_double_mutants(args.robots), args.doubles)
    tables = [] if args.no_tables else sample(all_table_mutants(args.robots), args.tables)
    t1 = time.perf_counter()
    outcomes = run(singles)
    t2 = time.perf_counter()
    double_outcomes = run(doubles)
    t3 = time.perf_counter()
    table_outcomes = run(tables)
    t4 = time.perf_counter()
    ok = True
    if singles:
        right, false_wrong, passed = _report("single-edit mutants", outcomes, 0.95)
        ok &= right >= 0.95 and false_wrong == 0 and passed == 0
    right2, false_wrong2, passed2 = _report("double-edit mutants", double_outcomes, 0.90)
    ok &= right2 >= 0.90 and false_wrong2 == 0 and passed2 == 0
    if tables:
        right3, false_wrong3, passed3 = _report("double-edit tables", table_outcomes, 0.90)
        ok &= right3 >= 0.90 and false_wrong3 == 0 and passed3 == 0
    n1, n2 = max(len(outcomes), 1), max(len(double_outcomes), 1)
    print(
        f"time: generating {t1 - t0:.1f} s, grading {t2 - t1:.1f} s single "
        f"({(t2 - t1) / n1 * 1000:.0f} ms per answer), {t3 - t2:.1f} s double "
        f"({(t3 - t2) / n2 * 1000:.0f} ms per answer); CPU per double answer: mean "
        f"{sum(o.seconds for o in double_outcomes) / n2 * 1000:.0f} ms, the slowest "
        f"{max((o.seconds for o in double_outcomes), default=0.0) * 1000:.0f} ms"
    )
    if tables:
        n3 = len(table_outcomes)
        print(
            f"tables: grading {t4 - t3:.1f} s ({(t4 - t3) / n3 * 1000:.0f} ms per table); CPU "
            f"per table: mean {sum(o.seconds for o in table_outcomes) / n3 * 1000:.0f} ms, "
            f"the slowest {max(o.seconds for o in table_outcomes) * 1000:.0f} ms"
        )
    if args.misses:
        for o in outcomes + double_outcomes + table_outcomes:
            if (o.mutant.kind is not None and not o.right) or o.false_wrong:
                print(
                    f"MISS {o.mutant.robot} {o.mutant.question} {o.mutant.where}: "
                    f"{o.mutant.kind} -> {'+'.join(o.kinds) or None} ({o.verdict.value})"
                )
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
