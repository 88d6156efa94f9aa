r"""The prepared part of a product-of-exponentials key: ``S``, ``B``, ``Mhome``, ``Js``, ``Jb``
or ``T(theta)`` (one column ``S3``, or one entry), from the screws room.

The key's matrix is the robot's PoE (Lynch and Park, *Modern Robotics*), read off its DH
frames at home by :func:`dhsym.screws.product.from_chain` (through the facade:
:meth:`~dhsym.robot.Robot.poe`, :meth:`~dhsym.robot.Robot.jacobian_space`,
:meth:`~dhsym.robot.Robot.jacobian_body`); the answer to ``T(theta)`` is judged against the
space form of the fk, which equals the DH fk (proven in the screws room).  The key's part
under each catalogued mistake
(:func:`~dhsym.checking.mistakes._screw_mistakes.screw_variants`) is derived here, once.

Examples
--------
>>> from dhsym.checking.judging.key import Key, prepare
>>> part = prepare(Key.load("planar2r", "S")).part
>>> type(part).__name__, part.expected.T.tolist()
('ScrewPart', [[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -a1, 0]])
>>> prepare(Key.load("planar2r", "S2[4,0]")).part.expected_text
(('-a1', '-a_{1}'),)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from dhsym.model.table import DHTable

from ..comparing.equivalence import close, values
from ..mistakes.registry import screw_variants
from ..reading.answer_names import NameContext
from ..reading.questions import Question
from .matrix_key import MatrixPart, _samples, _texts

if TYPE_CHECKING:
    from dhsym.robot import Robot

__all__ = ["ScrewPart", "axes_listed", "prepare_screw", "screw_key_matrix"]


@dataclass(frozen=True, eq=False)
class ScrewPart(MatrixPart):
    """A PoE key: also the key's part under each catalogued mistake,
    ``(kind, matrix, detail)``, derived here, once."""

    variants: tuple[tuple[str, sp.ImmutableMatrix, str], ...]


def screw_key_matrix(robot: Robot, part: str) -> sp.ImmutableMatrix:
    """The whole matrix a PoE question asks: the space or body axes (6×n, rows ``[ω; v]``),
    the home configuration, ``J_s``, ``J_b`` or the fk in PoE form.

    >>> import dhsym
    >>> screw_key_matrix(dhsym.load("planar2r"), "Mhome")[:, 3].T
    Matrix([[a1 + a2, 0, 0, 1]])
    """
    poe = robot.poe()
    if part in ("S", "B"):
        return poe.screw_matrix("space" if part == "S" else "body")
    if part == "Mhome":
        return poe.home
    if part == "Js":
        return robot.jacobian_space().matrix
    if part == "Jb":
        return robot.jacobian_body().matrix
    return poe.fk_space().matrix


def _cut(X: sp.ImmutableMatrix, q: Question) -> sp.ImmutableMatrix:
    """The asked column (``S3``) and entry of a whole matrix."""
    if q.column is not None:
        X = sp.ImmutableMatrix(X[:, q.column - 1])
    return sp.ImmutableMatrix([[X[q.entry]]]) if q.entry is not None else X


def prepare_screw(
    table: DHTable, question: Question, robot: Robot, names: NameContext
) -> tuple[NameContext, ScrewPart]:
    """A PoE key prepared: its matrix, the diagnosis samples and its mistakes' variants;
    the names are the table's."""
    expected = _cut(screw_key_matrix(robot, question.part), question)
    found = screw_variants(robot, question.part)
    variants = tuple((kind, _cut(m, question), detail) for kind, m, detail in found)
    syms = set(table.variables) | set(table.constants)
    symbolic, valued, expected_valued = _samples(
        table, question, robot, expected, syms, dynamics_variants=variants
    )
    common = (expected, expected_valued, *_texts(robot, expected), frozenset(syms))
    return names, ScrewPart(*common, symbolic, valued, variants)


def axes_listed(part: ScrewPart, table: DHTable, answer: sp.ImmutableMatrix) -> bool:
    """Whether a 6×6 answer of six screw axes reads closer to the key, or to the key under
    one of its mistakes, with its rows as the axes (``S_1 … S_6`` listed one per row, as
    often printed) than with its columns; compared at the key's diagnosis sample.

    >>> from dhsym.checking.judging.key import Key, prepare
    >>> pk = prepare(Key.load("puma560", "S"))
    >>> axes_listed(pk.part, pk.key.table, pk.part.expected.T)
    True
    >>> axes_listed(pk.part, pk.key.table, pk.part.expected)
    False
    """
    d = part.diagnosis(table, answer)
    sample = d.sample.extended(answer.free_symbols - set(d.sample.symbols))
    targets = [d.key_values, *(values(m, d.sample) for _, m, _ in part.variants)]

    def distance(M: sp.ImmutableMatrix) -> int:
        got = values(M, sample)
        return min(int(np.sum(~np.asarray(close(got, t, axis=0)))) for t in targets)

    return distance(sp.ImmutableMatrix(answer.T)) < distance(answer)
