"""The prepared part of a matrix key: ``^iT_j`` (or one entry), ``J``, ``det J``, dynamics.

A matrix key is derived once per worker, before any answer's clock starts
(:func:`prepare_matrix`, :func:`prepare_dynamics`): the expected matrix, the same with
the table's numbers for its lengths, its text and LaTeX, and the two diagnosis samples
(:class:`DiagnosisSample`) at which the mistakes of wrong answers are recomputed, with
the mistakes' variants there.  A
determinant key also keeps its singularities (:class:`DeterminantPart`), a dynamics key
its part under each catalogued mistake (:class:`DynamicsPart`).  Every part is a frozen
value.

Examples
--------
>>> from dhsym.checking.judging.key import Key, prepare
>>> part = prepare(Key.load("planar2r", "T0_2[0,3]")).part
>>> type(part).__name__, part.expected_text[0][0]
('MatrixPart', 'a1*C1 + a2*C12')
>>> type(prepare(Key.load("planar2r", "det J")).part).__name__
'DeterminantPart'
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from types import MappingProxyType
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.model.table import DHTable
from dhsym.notation.mathml import latex_mathml

from ..comparing.dynamics_values import dynamics_key, part_matrix, question_symbols, rate_aliases
from ..comparing.equivalence import Sample, values
from ..mistakes.registry import (
    MatrixCase,
    Mistake,
    Variants,
    mistakes_for,
    prepare_variants,
    variant_matrices,
)
from ..reading.answer_names import NameContext
from ..reading.questions import Question

if TYPE_CHECKING:
    from dhsym.kinematics.singularities import Singularities
    from dhsym.robot import Robot

__all__ = [
    "DeterminantPart",
    "DiagnosisSample",
    "DynamicsPart",
    "KeyMathML",
    "MatrixPart",
    "prepare_dynamics",
    "prepare_matrix",
    "sample_for",
]


@dataclass(frozen=True, eq=False)
class DiagnosisSample:
    """The points the mistakes of wrong answers are recomputed at (fixed per key), the
    key's values there, and each whole-matrix mistake's variants there (``variants``:
    :func:`~dhsym.checking.mistakes.registry.prepare_variants`), all built when the key is
    prepared, before any answer's clock starts.

    Only the diagnosis uses them: every verdict draws its own fresh points.
    """

    sample: Sample
    key_values: np.ndarray
    variants: Mapping[Mistake, Variants]


class KeyMathML:
    """The key's entries as MathML for the feedback pages, each converted once.

    A grading run converts every entry of the keys its students share when it prepares
    them, before its sandbox children fork (:meth:`convert_all`); an entry of a key of one
    student's own (a variant) is converted the first time a page shows it.  Only the
    conversion is kept: the MathML of an entry never changes.

    >>> m = KeyMathML(("a_{1}", "0"))
    >>> m.entry(1).count("<mn>0</mn>"), m.converted
    (1, 1)
    >>> m.convert_all(); m.converted
    2
    """

    def __init__(self, latex: tuple[str, ...]) -> None:
        self._latex = latex
        self._mathml: list[str | None] = [None] * len(latex)

    @property
    def converted(self) -> int:
        """How many entries are converted so far."""
        return sum(m is not None for m in self._mathml)

    def entry(self, k: int) -> str:
        """The MathML of entry ``k`` (row by row), converted the first time."""
        m = self._mathml[k]
        if m is None:
            m = self._mathml[k] = latex_mathml(self._latex[k])
        return m

    def convert_all(self) -> None:
        """Convert every entry now."""
        for k in range(len(self._latex)):
            self.entry(k)


@dataclass(frozen=True, eq=False)
class MatrixPart:
    """What checking answers to a matrix key shares.

    ``expected`` is the key's matrix (1×1 for one entry), ``expected_valued`` the same
    with the table's numbers for its lengths (the exact proofs of answers that use the
    numbers), ``expected_text`` each entry as (text, LaTeX), ``expected_mathml`` each
    entry's LaTeX as MathML (:class:`KeyMathML`), ``symbols`` every symbol
    the key may use.  ``symbolic``/``valued`` serve only the diagnosis of wrong answers
    (:func:`sample_for` tells which one an answer gets).
    """

    expected: sp.ImmutableMatrix
    expected_valued: sp.ImmutableMatrix
    expected_text: tuple[tuple[str, str], ...]
    expected_mathml: KeyMathML
    symbols: frozenset[sp.Symbol]
    symbolic: DiagnosisSample
    valued: DiagnosisSample

    def diagnosis(self, table: DHTable, answer: sp.Basic) -> DiagnosisSample:
        """The diagnosis sample for ``answer`` (:func:`sample_for`)."""
        return self.valued if sample_for(table, answer) == "valued" else self.symbolic


@dataclass(frozen=True, eq=False)
class DeterminantPart(MatrixPart):
    """A ``det J`` key: also the key's singularities (their factors and blocks, which the
    determinant's mistakes leave out)."""

    singularities: Singularities


@dataclass(frozen=True, eq=False)
class DynamicsPart(MatrixPart):
    """A dynamics key: also the key's part under each catalogued mistake,
    ``(kind, matrix, detail)``, derived here, once."""

    variants: tuple[tuple[str, sp.ImmutableMatrix, str], ...]


def sample_for(table: DHTable, answer: sp.Basic) -> str:
    """``valued`` (the table's numbers for its lengths) when the answer uses none of the
    symbols that have numbers, else ``symbolic`` (random values for every symbol).

    >>> from dhsym.model.library import load_table
    >>> t = load_table("planar2r")
    >>> a1 = sp.Symbol("a1", real=True)
    >>> sample_for(t, sp.Integer(1)), sample_for(t.with_values({a1: 1}), a1)
    ('valued', 'symbolic')
    """
    valued = set(table.value_map)
    if valued and not (answer.free_symbols & valued):
        return "valued"
    return "symbolic"


def _texts(
    robot: Robot, expected: sp.ImmutableMatrix
) -> tuple[tuple[tuple[str, str], ...], KeyMathML]:
    """Each entry of the key as (text, LaTeX), and its MathML (converted when first shown)."""
    nota = robot.notation
    texts = tuple((nota.text(e), nota.latex(e)) for e in expected)
    return texts, KeyMathML(tuple(tex for _, tex in texts))


def _samples(
    table: DHTable,
    question: Question,
    robot: Robot,
    expected: sp.ImmutableMatrix,
    syms: set[sp.Symbol],
    singularities: Singularities | None = None,
    dynamics_variants: tuple[tuple[str, sp.ImmutableMatrix, str], ...] = (),
    fixed: Mapping[sp.Symbol, float] | None = None,
) -> tuple[DiagnosisSample, DiagnosisSample, sp.ImmutableMatrix]:
    """The symbolic and valued diagnosis samples with the mistakes' variants there, and
    ``expected`` with the table's numbers.  The valued sample gets variants only when the
    table has numbers (else no answer is diagnosed there: :func:`sample_for`); symbols in
    ``fixed`` (the joints of a transform asked at joint values) keep their value in both."""
    out = []
    mistakes = mistakes_for(question.kind)
    value_map = table.value_map
    scratch: dict[tuple[object, ...], object] = {}  # what both samples' variants derive
    for numbers in (None, value_map):
        sample = Sample.random(syms, fixed={**(numbers or {}), **(fixed or {})} or None)
        kv = values(expected, sample)
        variants: Mapping[Mistake, Variants] = MappingProxyType({})
        if numbers is None or numbers:
            case = MatrixCase(  # the key's own case: the answer is the key
                tuple(table.rows),
                table.convention,
                question.frm,
                question.to,
                question.entry,
                expected,
                expected,
                sample,
                kv,
                kv,
                (),
                robot.notation,
                robot=robot,
                singularities=singularities,
                dynamics_variants=dynamics_variants,
                cache=scratch,
            )
            variants = prepare_variants(case, mistakes)
        out.append(DiagnosisSample(sample, kv, variants))
    valued = expected.subs(value_map) if value_map else expected
    return out[0], out[1], valued


def _expected(question: Question, robot: Robot) -> tuple[sp.ImmutableMatrix, Singularities | None]:
    """The key's matrix: ``^iT_j``, the geometric Jacobian (base frame, tool point), or
    ``[det J]`` factored (the measure of :func:`~dhsym.kinematics.singularities.singularities`),
    with the singularities of a determinant."""
    q = question
    if q.kind == "jacobian":
        J = robot.jacobian().matrix
        if q.entry is not None and not q.entry[1] < J.cols:
            raise DHError(f"question {q.spec!r}: the columns of J are 0 … {J.cols - 1}")
        return sp.ImmutableMatrix(J), None
    if q.kind == "det":
        from dhsym.kinematics.singularities import singularities

        s = singularities(robot)
        return sp.ImmutableMatrix([[s.determinant]]), s
    return robot.transform(q.frm, q.to).matrix, None


def _exact(x: float) -> sp.Expr:
    """A joint value as written: a rational multiple of π (``pi/6``, drawn in degrees) or the
    decimal of its shortest repr (``0.45`` is 9/20).

    >>> _exact(0.5235987755982988), _exact(0.45), _exact(1.2345678)
    (pi/6, 9/20, 6172839/5000000)
    """
    turns = Fraction(x / math.pi).limit_denominator(720)
    if turns and abs(float(turns) * math.pi - x) <= 1e-12 * max(1.0, abs(x)):
        return sp.Rational(turns.numerator, turns.denominator) * sp.pi
    return sp.Rational(repr(x))


def _at_pose(question: Question, table: DHTable) -> dict[sp.Symbol, float]:
    """The joint values of a transform asked at them (``T0_6@q1,…,qn``), by variable."""
    if question.pose is None:
        return {}
    variables = table.variables
    if len(question.pose) != len(variables):
        raise DHError(
            f"question {question.spec!r}: {table.name or 'the robot'} has "
            f"{len(variables)} joint values ({', '.join(map(str, variables))}), "
            f"got {len(question.pose)}"
        )
    return dict(zip(variables, question.pose, strict=True))


def prepare_matrix(
    table: DHTable, question: Question, robot: Robot, names: NameContext
) -> tuple[NameContext, MatrixPart]:
    """A matrix key (``T``, ``J``, ``det J``, one entry of them) prepared: its expected
    matrix and the diagnosis samples; the names are the table's.  A transform asked at
    joint values (``T0_6@q1,…,qn``) is the matrix there (its lengths as symbols, or with
    the table's numbers), and its diagnosis samples keep the joints at those values.

    >>> from dhsym.checking.judging.key import Key, prepare
    >>> part = prepare(Key.load("planar2r", "T0_2[1,3]@pi/2,0")).part
    >>> part.expected, part.expected_valued
    (Matrix([[a1 + a2]]), Matrix([[9/5]]))
    """
    full, sing = _expected(question, robot)
    pose = _at_pose(question, table)
    if pose:
        full = sp.ImmutableMatrix(full.xreplace({v: _exact(x) for v, x in pose.items()}))
    expected = sp.ImmutableMatrix([[full[question.entry]]]) if question.entry else full
    syms = set(table.variables) | set(table.constants)
    symbolic, valued, expected_valued = _samples(
        table, question, robot, expected, syms, sing, fixed=pose
    )
    common = (expected, expected_valued, *_texts(robot, expected), frozenset(syms))
    if sing is not None:
        return names, DeterminantPart(*common, symbolic, valued, sing)
    return names, MatrixPart(*common, symbolic, valued)


def prepare_dynamics(
    table: DHTable, question: Question, robot: Robot, names: NameContext
) -> tuple[NameContext, MatrixPart]:
    """A dynamics key: its part of the equations of motion (or ``Jᵀ F``) and, for the
    diagnosis, the same part under each catalogued mistake, all derived here, once; the
    names gain the inertial symbols, rates and accelerations."""
    q = question
    extra = question_symbols(robot, q)
    names = names.extended([*((s.name, s) for s in extra), *rate_aliases(robot)])
    variants: tuple[tuple[str, sp.ImmutableMatrix, str], ...] = ()
    if q.part == "tau_static":
        expected = dynamics_key(robot, q)
    else:
        eom = robot.dynamics()
        expected = part_matrix(eom, q)
        variants = tuple(variant_matrices(robot, eom, q))
    syms = set(table.variables) | set(table.constants) | set(extra)
    symbolic, valued, expected_valued = _samples(
        table, question, robot, expected, syms, dynamics_variants=variants
    )
    part = DynamicsPart(
        expected,
        expected_valued,
        *_texts(robot, expected),
        frozenset(syms),
        symbolic,
        valued,
        variants,
    )
    return names, part
