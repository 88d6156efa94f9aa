r"""Checking one answer against a key: read it, compare it, explain it.

Examples
--------
>>> key = Key.load("planar2r", "T0_2")
>>> r = check_answer(key, r"\begin{bmatrix} C_{12} & -S_{12} & 0 & a_1 C_1 + a_2 C_{12} \\"
...                       r" S_{12} & C_{12} & 0 & a_1 S_1 + a_2 S_{12} \\ 0&0&1&0 \\ 0&0&0&1"
...                       r"\end{bmatrix}")
>>> r.verdict.value, r.entries[3].proof
('correct', 'exact')
>>> r = check_answer(key, "[[C12, -S12, 0, a1*C1 - a2*C12], [S12, C12, 0, a1*S1 + a2*S12],"
...                       " [0, 0, 1, 0]]")
>>> r.verdict.value, r.kinds, r.diagnoses[0].entries
('incorrect', ('wrong_sign',), ((1, 4),))
>>> check_answer(key, "__import__('os').system('ls')").verdict.value
'unreadable'
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.model.library import load_table
from dhsym.model.table import AngleUnit, Convention, DHTable, JointType
from dhsym.notation.printers import format_angle
from dhsym.robot import Robot

from ..mistakes._dynamics_mistakes import dynamics_mistakes
from ..mistakes.registry import (
    DET_MISTAKES,
    JACOBIAN_MISTAKES,
    MATRIX_MISTAKES,
    BlockTransposed,
    MatrixCase,
    TableCase,
    diagnose_matrix,
    diagnose_table,
)
from ..reading.answer_names import NameContext
from ..reading.answer_value import (
    AnswerForm,
    IKAnswer,
    MatrixAnswer,
    ReadCell,
    TableAnswer,
    read_answer_value,
)
from ..reading.limits import (
    DEFAULT_ANSWER_LIMITS,
    AnswerLimits,
    CheckTimeout,
    check_time,
    time_limit,
)
from ..reading.questions import Question
from .equivalence import (
    EXACT_RTOL,
    Sample,
    agree_precisely,
    cancellation,
    close,
    prove_entry,
    values,
)
from .rounding import DEFAULT_ROUNDING, Rounding, rounding_accepts
from .table_match import compare_tables, symbolic_values
from .verdict import CheckResult, Diagnosis, EntryResult, Verdict

__all__ = ["Key", "PreparedKey", "PreparedKeys", "check_answer", "prepare", "table_cells"]


@dataclass(frozen=True)
class Key:
    """The key of one question: a DH table and what is asked about it.

    ``tool_free`` accepts another tool frame (last frame) in a table answer;
    ``rounding`` is how much rounding of decimals is accepted (:class:`Rounding`).
    """

    table: DHTable
    question: Question
    name: str = ""
    tool_free: bool = False
    rounding: Rounding = DEFAULT_ROUNDING

    @classmethod
    def load(
        cls,
        ref: str | Path | DHTable,
        question: str | Question,
        *,
        tool_free: bool = False,
        rounding: object = None,
        keys: PreparedKeys | None = None,
    ) -> Key:
        """A key from a built-in robot name, a table file or a table.

        ``rounding``: anything :meth:`Rounding.parse` reads (``"digits=4"``, ``"abs=1e-3"``,
        ``{"rel": 0.001}``, ``"off"``); None is the default (3 significant digits).
        The key is prepared once to check it (into ``keys`` when given, for later use).
        """
        if not isinstance(ref, (str, Path, DHTable)):
            raise DHError(
                "the key is a built-in robot's name, a table file or a DHTable, "
                f"got {type(ref).__name__}"
            )
        table = ref if isinstance(ref, DHTable) else load_table(ref)
        q = question if isinstance(question, Question) else Question.parse(question, table.n)
        name = table.name or (Path(ref).stem if not isinstance(ref, DHTable) else "")
        key = cls(table, q, name, tool_free, Rounding.parse(rounding))
        # a key that cannot be checked against (too large, wrong values) stops here
        keys.get(key) if keys is not None else prepare(key)
        return key


@dataclass(frozen=True, eq=False)
class DiagnosisSample:
    """The points the mistakes of wrong answers are recomputed at (fixed per key, so the
    mistakes' variants are computed once per worker) and the key's values there.

    Only the diagnosis uses them: every verdict draws its own fresh points.
    """

    sample: Sample
    key_values: np.ndarray


@dataclass(eq=False)
class PreparedKey:
    """What checking many answers to one key shares: the robot, names, derived values.

    Built once per worker (:class:`PreparedKeys`) before any answer's clock starts;
    every field is typed.  ``symbolic``/``valued`` serve only the diagnosis of wrong
    answers (:class:`DiagnosisSample`); every verdict draws its own points.
    ``variant_values`` is the mistake catalogue's memo: a mistake's values at a
    diagnosis sample, by (mistake, sample origin, …), computed on the first wrong answer
    that needs them.
    """

    key: Key
    robot: Robot
    names: NameContext
    expected: sp.ImmutableMatrix | None = None
    #: ``expected`` with the table's numbers for its lengths (the exact proofs of answers
    #: that use the numbers)
    expected_valued: sp.ImmutableMatrix | None = None
    expected_text: tuple[tuple[str, str], ...] = ()
    symbolic: DiagnosisSample | None = None
    valued: DiagnosisSample | None = None
    symbols: frozenset[sp.Symbol] = frozenset()
    #: a determinant key's singularities (a Jacobian key's, once a diagnosis needs them)
    singularities: Any = None
    #: a dynamics key's part under each catalogued mistake: (kind, matrix, detail)
    dynamics_variants: tuple[tuple[str, sp.ImmutableMatrix, str], ...] = ()
    #: an inverse-kinematics key: its solution, the question's pose (``ik@…``), the
    #: branches' names there or in general, and the random poses of the diagnosis
    ik: Any = None
    ik_pose: Any = None
    ik_pose_names: tuple[str, ...] = ()
    ik_names: tuple[str, ...] = ()
    ik_samples: dict[bool, Any] = field(default_factory=dict)
    variant_values: dict[tuple[object, ...], Any] = field(default_factory=dict)

    def sample_for(self, answer: sp.Basic) -> str:
        """``valued`` (the table's numbers for its lengths) when the answer uses none of
        the symbols that have numbers, else ``symbolic`` (random values for every symbol)."""
        valued = set(self.key.table.value_map)
        if valued and not (answer.free_symbols & valued):
            return "valued"
        return "symbolic"

    def form(self) -> AnswerForm:
        """What reading an answer to this key needs: the question, the names, the key's
        shape, the joints whose Jacobian column may be missing, the convention, the joint
        variables and the lengths."""
        table = self.key.table
        joints = [r.joint for r in table.rows if r.variable is not None]
        return AnswerForm(
            self.key.question,
            self.names,
            self.expected.shape if self.expected is not None else (4, 4),
            tuple(k for k, j in enumerate(joints) if j is JointType.PRISMATIC),
            table.convention,
            tuple(self.robot.variables),
            frozenset(table.constants),
        )

    def diagnosis(self, answer: sp.Basic) -> DiagnosisSample:
        """The diagnosis sample for ``answer`` (:meth:`sample_for`)."""
        out = self.valued if self.sample_for(answer) == "valued" else self.symbolic
        assert out is not None, "a matrix key has its diagnosis samples"
        return out

    def singular(self) -> Any:
        """The key's :func:`~dhsym.kinematics.singularities.singularities`, derived once."""
        if self.singularities is None:
            from dhsym.kinematics.singularities import singularities

            self.singularities = singularities(self.robot)
        return self.singularities


class PreparedKeys:
    """A worker's prepared keys: each :class:`Key` (a frozen value) prepared once, on
    first use, and kept as long as this map (a grading worker's life).

    >>> keys = PreparedKeys()
    >>> k = Key.load("planar2r", "T0_2")
    >>> keys.get(k) is keys.get(Key.load("planar2r", "T0_2")), len(keys)
    (True, 1)
    """

    def __init__(self) -> None:
        self._prepared: dict[Key, PreparedKey] = {}

    def __len__(self) -> int:
        return len(self._prepared)

    def get(self, key: Key) -> PreparedKey:
        """``key`` prepared (:func:`prepare`), the first time only."""
        pk = self._prepared.get(key)
        if pk is None:
            pk = self._prepared[key] = prepare(key)
        return pk


def _diagnosis_samples(pk: PreparedKey, syms: set[sp.Symbol]) -> None:
    assert pk.expected is not None
    for name, fixed in (("symbolic", None), ("valued", pk.key.table.value_map)):
        sample = Sample.random(syms, fixed=fixed)
        setattr(pk, name, DiagnosisSample(sample, values(pk.expected, sample)))
    value_map = pk.key.table.value_map
    pk.expected_valued = pk.expected.subs(value_map) if value_map else pk.expected


def prepare(key: Key) -> PreparedKey:
    """Prepare a key: its robot, names, expected answer and what the diagnosis of wrong
    answers shares.  Not memoised: a worker keeps its keys in :class:`PreparedKeys`."""
    table = key.table
    robot = Robot(table)
    names = NameContext.from_table(table)
    pk = PreparedKey(key, robot, names)
    q = key.question
    if q.kind == "table":
        return pk
    if q.kind == "ik":
        from .ik_check import prepare_ik

        return prepare_ik(pk)
    if q.kind == "dynamics":
        return _prepare_dynamics(pk)
    full = _expected(pk)
    pk.expected = sp.ImmutableMatrix([[full[q.entry]]]) if q.entry else full
    nota = robot.notation
    pk.expected_text = tuple((nota.text(e), nota.latex(e)) for e in pk.expected)
    syms = set(table.variables) | set(table.constants)
    pk.symbols = frozenset(syms)
    _diagnosis_samples(pk, syms)
    return pk


def _prepare_dynamics(pk: PreparedKey) -> PreparedKey:
    """A dynamics key: its part of the equations of motion (or ``Jᵀ F``) and, for the
    diagnosis, the same part under each catalogued mistake, all derived here, once."""
    from ..mistakes._dynamics_mistakes import variant_matrices
    from ._dynamics_values import dynamics_key, part_matrix, question_symbols, rate_aliases

    q, robot, table = pk.key.question, pk.robot, pk.key.table
    extra = question_symbols(robot, q)
    pk.names = pk.names.extended([*((s.name, s) for s in extra), *rate_aliases(robot)])
    if q.part == "tau_static":
        pk.expected = dynamics_key(robot, q)
    else:
        eom = robot.dynamics()
        pk.expected = part_matrix(eom, q)
        pk.dynamics_variants = tuple(variant_matrices(robot, eom, q))
    nota = robot.notation
    pk.expected_text = tuple((nota.text(e), nota.latex(e)) for e in pk.expected)
    syms = set(table.variables) | set(table.constants) | set(extra)
    pk.symbols = frozenset(syms)
    _diagnosis_samples(pk, syms)
    return pk


def _expected(pk: PreparedKey) -> sp.ImmutableMatrix:
    """The key's matrix: ``^iT_j``, the geometric Jacobian (base frame, tool point), or
    ``[det J]`` factored (the measure of :func:`~dhsym.kinematics.singularities.singularities`)."""
    q, robot = pk.key.question, pk.robot
    if q.kind == "jacobian":
        J = robot.jacobian().matrix
        if q.entry is not None and not q.entry[1] < J.cols:
            raise DHError(f"question {q.spec!r}: the columns of J are 0 … {J.cols - 1}")
        return sp.ImmutableMatrix(J)
    if q.kind == "det":
        from dhsym.kinematics.singularities import singularities

        s = singularities(robot)
        pk.singularities = s
        return sp.ImmutableMatrix([[s.determinant]])
    return robot.transform(q.frm, q.to).matrix


def table_cells(table: DHTable) -> tuple[tuple[str, ...], ...]:
    """A table as text cells, header first, in its own convention's column order."""
    deg = table.angles is AngleUnit.DEG
    if table.convention is Convention.MODIFIED:
        head, order = (
            ("i", "alpha_{i-1}", "a_{i-1}", "d_i", "theta_i", "joint"),
            ("alpha", "a", "d", "theta"),
        )
    else:
        head, order = (
            ("i", "theta_i", "d_i", "a_i", "alpha_i", "joint"),
            ("theta", "d", "a", "alpha"),
        )
    rows: list[tuple[str, ...]] = [head]
    for i, row in enumerate(table.rows, 1):
        cells = [str(i)]
        for name in order:
            v = getattr(row, name)
            if name in ("theta", "alpha"):
                cells.append(format_angle(v, deg, latex=False))
            else:
                cells.append(
                    f"{float(v):.6g}" if v.is_Rational and not v.is_Integer else sp.sstr(v)
                )
        rows.append((*cells, row.joint.value))
    return tuple(tuple(r) for r in rows)


def _unreadable(key: Key, reason: str) -> CheckResult:
    return CheckResult(
        key.question.spec,
        Verdict.UNREADABLE,
        f"The answer could not be read: {reason}",
        reason=reason,
        key=key.name,
    )


def check_answer(
    key: Key,
    answer: str | bytes,
    *,
    limits: AnswerLimits = DEFAULT_ANSWER_LIMITS,
    keys: PreparedKeys | None = None,
) -> CheckResult:
    """Check one answer (text or bytes, untrusted) against ``key``.

    Never raises on bad answers: they come back ``unreadable`` with the reason (parse
    errors, limits, answers too large to process). A key that cannot be prepared raises
    its :class:`~dhsym.errors.DHError`; an exception of any other kind is a bug of dhsym
    and is raised too, never disguised as an unreadable answer.
    The whole check runs under ``limits.seconds`` (where a time limit is possible).
    ``keys`` is the caller's map of prepared keys (a grading worker's): without it the
    key is prepared for this one check.
    """
    if not isinstance(key, Key):
        raise DHError(
            f"check_answer: expected a Key (Key.load(robot, question)), got {type(key).__name__}"
        )
    # a fault of the key raises here: it is never the answer's
    pk = keys.get(key) if keys is not None else prepare(key)
    try:
        with time_limit(limits.seconds):
            read = read_answer_value(pk.form(), answer, limits)  # the one reading
            if isinstance(read, TableAnswer):
                return _check_table(pk, read)
            if isinstance(read, IKAnswer):
                from .ik_check import check_ik

                return check_ik(pk, read)
            return _check_matrix(pk, read, limits)
    except CheckTimeout as err:
        return _unreadable(key, str(err))
    except DHError as err:
        return _unreadable(key, str(err))
    except (RecursionError, MemoryError, OverflowError) as err:  # an answer too large to handle
        return _unreadable(key, f"it could not be processed ({type(err).__name__})")
    # Anything else is a bug of dhsym, not a fault of the answer: it propagates, and the
    # grading run reports it as that submission's internal error while the batch goes on.


def _shown(cell: str) -> str:
    cell = " ".join(cell.split())
    return cell if len(cell) <= 200 else cell[:199] + "…"


def _compare(
    pk: PreparedKey, ans: sp.ImmutableMatrix, cells: tuple[ReadCell, ...], limits: AnswerLimits
) -> tuple[list[EntryResult], list[tuple[int, int]], list[sp.Basic]]:
    """Entry results, wrong positions and the unknown symbols, at fresh random points.

    Per entry: equal at every point → the exact proof if affordable (``exact``), else the
    numbers stand (``numeric``); a proof that says "not equal" is checked once more with
    60-digit numbers.  Not equal → right up to rounding if the key's :class:`Rounding`
    accepts its decimals (``rounding``).
    """
    q, nota, expected, expected_valued = (
        pk.key.question,
        pk.robot.notation,
        pk.expected,
        pk.expected_valued,
    )
    assert expected is not None and expected_valued is not None
    unknown = sorted(ans.free_symbols - pk.names.symbols, key=sp.default_sort_key)
    valued = pk.sample_for(ans) == "valued"
    value_map = pk.key.table.value_map
    sample = Sample.random(pk.symbols | set(unknown), fixed=value_map if valued else None)
    kv = values(expected, sample)
    av = values(ans, sample)
    near = np.asarray(close(av, kv, EXACT_RTOL, axis=0))
    entries: list[EntryResult] = []
    wrong: list[tuple[int, int]] = []
    for i in range(expected.rows):
        for j in range(expected.cols):
            a, e = ans[i, j], expected[i, j]
            k = i * expected.cols + j
            proof, note = "", ""
            check_time()  # the answer's deadline (see reading.limits.time_limit)
            target = expected_valued[i, j] if valued else e
            if near[i, j]:
                exact = prove_entry(a, target, limits, agreed=True) if not unknown else None
                if exact is None or (exact is False and agree_precisely(a, target)):
                    proof = "numeric"
                elif exact:
                    proof = "exact"
            elif not unknown and cancellation(a, sample, av[:, i, j] - kv[:, i, j]):
                # the doubles cannot tell: their difference is the rounding error of the sums
                # the answer cancels; 60-digit numbers or the exact proof decide
                exact = prove_entry(a, target, limits)
                if exact:
                    proof = "exact"
                elif agree_precisely(a, target):
                    proof = "numeric"
            if not proof and cells[k].template is not None:
                note = _rounded(pk, cells[k], sample, kv[:, i, j])
                proof = "rounding" if note else ""
            if not proof:
                wrong.append((i, j))
            where = (q.entry[0] + 1, q.entry[1] + 1) if q.entry else (i + 1, j + 1)
            e_text, e_latex = pk.expected_text[k]
            raw = cells[k].text
            if proof or len(raw) > 160:  # right, or long: what the student wrote
                a_text, a_latex = _shown(raw), ""
            else:  # wrong: the student's entry in the key's notation
                a_text, a_latex = nota.text(a), nota.latex(a)
            entries.append(
                EntryResult(*where, bool(proof), a_text, e_text, a_latex, e_latex, proof, note)
            )
    return entries, wrong, unknown


def _rounded(pk: PreparedKey, cell: ReadCell, sample: Sample, key: np.ndarray) -> str:
    """How the cell, written with decimals, is right up to rounding under the key's rule,
    or ``""``."""
    assert cell.template is not None
    env = sample.extended(cell.template.free_symbols - set(sample.symbols)).env
    how = rounding_accepts(pk.key.rounding, cell.template, cell.literals, env, sample.size, key)
    return how or ""


def _diagnosis_values(
    pk: PreparedKey, ans: sp.ImmutableMatrix, unknown: list[sp.Basic]
) -> tuple[Sample, np.ndarray, np.ndarray]:
    """The key's diagnosis sample (fixed per key, so the mistakes' variants are cached),
    extended with the unknown symbols, the key's and the answer's values there."""
    d = pk.diagnosis(ans)
    sample = d.sample.extended(unknown)
    return sample, d.key_values, values(ans, sample)


def _index_renames(unknown: list[sp.Symbol], names: NameContext) -> dict[sp.Symbol, sp.Symbol]:
    """``alpha_i`` → ``alpha_im1`` (and back) when only the other index is a key symbol."""
    out = {}
    for s in unknown:
        for a, b in (("_i", "_im1"), ("_im1", "_i"), ("i", "im1")):
            if s.name.endswith(a):
                target = names.symbol(s.name[: -len(a)] + b)
                if target is not None:
                    out[s] = target
                    break
    return out


def _shape_lead(pk: PreparedKey, answer: MatrixAnswer) -> tuple[Diagnosis, ...]:
    """What the answer's shape tells: a Jacobian one column short left out the column of
    a prismatic joint (the reader put zeros there)."""
    k = answer.missing_column
    if k is None:
        return ()
    n = answer.shape[1]
    var = pk.robot.variables[k]
    return (
        Diagnosis(
            "missing_column",
            "column of a prismatic joint missing",
            f"The answer has {n - 1} columns; J has one per joint, {n}: column {k + 1} belongs "
            f"to the prismatic joint {var}, whose column is its axis over zero (no rotation).",
            tuple((i + 1, k + 1) for i in range(6)),
        ),
    )


def _check_matrix(pk: PreparedKey, answer: MatrixAnswer, limits: AnswerLimits) -> CheckResult:
    key, q, nota = pk.key, pk.key.question, pk.robot.notation
    ans, cells, shape_lead = answer.matrix, answer.cells, _shape_lead(pk, answer)
    entries, wrong, unknown = _compare(pk, ans, cells, limits)
    total = len(entries)
    lead: tuple[Diagnosis, ...] = ()
    renames = _index_renames(unknown, pk.names)
    if renames and len(renames) == len(unknown):
        shown = ", ".join(f"{a} for {b}" for a, b in renames.items())
        lead = (
            Diagnosis(
                "index_shift",
                "α/a index shifted by one row",
                (
                    f"The answer uses {shown}: in the {key.table.convention.value} convention "
                    "link i "
                    "has the parameters of this table's row i."
                ),
            ),
        )
        ans = ans.xreplace(renames)
        entries, wrong, unknown = _compare(pk, ans, cells, limits)
        if not wrong:
            return CheckResult(
                q.spec,
                Verdict.INCORRECT,
                f"The answer is right except for the indices. {lead[0].detail}",
                tuple(entries),
                lead,
                key=key.name,
            )
    if wrong and q.kind == "det":
        flipped = _compare(pk, -ans, cells, limits)
        if not flipped[1]:  # -det J: the rows of J in the other order ([ω; v]) or the joints
            return CheckResult(
                q.spec,
                Verdict.CORRECT,
                "The determinant is right up to its sign, which depends on the order of the "
                "rows of J ([v; ω] or [ω; v]) and of its columns; the singular configurations "
                "are the same.",
                tuple(flipped[0]),
                key=key.name,
            )
    if wrong and q.kind == "jacobian" and q.entry is None and ans.rows == 6:
        cols = ans.cols  # [ω; v]: the same Jacobian with the angular rows first
        swapped = sp.ImmutableMatrix.vstack(ans[3:, :], ans[:3, :])
        order = [*range(3 * cols, 6 * cols), *range(3 * cols)]
        other = _compare(pk, swapped, tuple(cells[k] for k in order), limits)
        if not other[1]:
            return CheckResult(
                q.spec,
                Verdict.CORRECT,
                "The Jacobian is right, in the row order [ω; v] (angular velocity first); "
                "the key writes [v; ω]. Both are used: say which one you write.",
                tuple(other[0]),
                alternative="rows [ω; v]",
                key=key.name,
            )
    if not wrong and not shape_lead:
        what = f"{_one(q)} is right" if total == 1 else f"All {total} entries are right"
        rounded = [e for e in entries if e.proof == "rounding"]
        if rounded:
            how = "; ".join(sorted({e.rounding for e in rounded}))
            some = " up to rounding" if total == 1 else f"; {len(rounded)} of them up to rounding"
            what = f"{what}{some} ({how})"
        return CheckResult(q.spec, Verdict.CORRECT, what + ".", tuple(entries), key=key.name)
    sample, kv, av = _diagnosis_values(pk, ans, unknown)
    case = MatrixCase(
        tuple(key.table.rows),
        key.table.convention,
        q.frm,
        q.to,
        q.entry,
        pk.expected,
        ans,
        sample,
        kv,
        av,
        tuple(wrong),
        nota,
        pk.variant_values,
        pk.robot,
        pk,
    )
    kinds = {
        "jacobian": (*JACOBIAN_MISTAKES, BlockTransposed()),
        "det": DET_MISTAKES,
        "dynamics": dynamics_mistakes(),
    }
    diagnoses = shape_lead + lead + diagnose_matrix(case, kinds.get(q.kind, MATRIX_MISTAKES))
    if unknown:
        names = ", ".join(str(s) for s in unknown)
        known = ", ".join(str(s) for s in sorted(pk.names.symbols, key=sp.default_sort_key))
        diagnoses = (
            Diagnosis(
                "unknown_symbol",
                "unknown symbols",
                (
                    f"The answer uses {names}, which this robot does not have "
                    f"(its symbols: {known})."
                ),
            ),
        ) + diagnoses
    what = f"{_one(q)} is wrong" if total == 1 else f"{len(wrong)} of {total} entries are wrong"
    first = next(
        (d for d in diagnoses if d.kind not in ("unexplained", "unknown_symbol")), diagnoses[0]
    )
    message = f"{what}. Most likely: {first.title}. {first.detail}"
    return CheckResult(q.spec, Verdict.INCORRECT, message, tuple(entries), diagnoses, key=key.name)


def _one(q: Question) -> str:
    """How a one-cell answer is called: the determinant is an answer, not an entry."""
    return "Your determinant" if q.kind == "det" else "The entry"


def _check_table(pk: PreparedKey, answer: TableAnswer) -> CheckResult:
    key = pk.key
    table = key.table
    ans = answer.table
    values_ = table.value_map  # for the diagnosis; the verdict is symbolic first
    expected_table, answer_table = table_cells(table), table_cells(ans)
    note = (
        " (Your angles were read as degrees, from a value above 2π, a ° or deg mark"
        " or the file's angles: deg.)"
        if answer.degrees and table.angles is not AngleUnit.DEG
        else ""
    )
    judged = symbolic_values(table, ans)
    match = compare_tables(table, ans, tool_free=key.tool_free, values=judged)
    if match.same_robot and ans.convention is table.convention:
        if match.same_table:
            return CheckResult(
                "table",
                Verdict.CORRECT,
                "Your table is the key's table." + note,
                key=key.name,
                expected_table=expected_table,
                answer_table=answer_table,
            )
        how = "; ".join(match.differences) or "other but equivalent entries"
        return CheckResult(
            "table",
            Verdict.CORRECT,
            f"Your table is a valid alternative: it describes the same robot "
            f"with other frame choices ({how}).{note}",
            alternative=how,
            key=key.name,
            expected_table=expected_table,
            answer_table=answer_table,
        )
    diagnoses = diagnose_table(TableCase(table, ans, key.tool_free, values_))
    if not diagnoses:
        rows = ()
        diagnoses = (
            Diagnosis(
                "geometry",
                "different robot",
                f"The table describes another robot: {match.reason}.",
                rows=rows,
            ),
        )
    where = (
        f" The geometry first differs at joint {match.diverges_at}: {match.reason}."
        if match.diverges_at and not match.same_robot
        else ""
    )
    message = (
        f"The table is wrong. Most likely: {diagnoses[0].title}. {diagnoses[0].detail}{where}{note}"
    )
    return CheckResult(
        "table",
        Verdict.INCORRECT,
        message,
        diagnoses=diagnoses,
        key=key.name,
        expected_table=expected_table,
        answer_table=answer_table,
    )
