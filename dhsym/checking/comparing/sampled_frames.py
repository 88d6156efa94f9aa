"""The DH frames of a table at many sample points at once.

The numbers come from the one numeric kernel (:mod:`dhsym.kinematics.numeric`:
:func:`~dhsym.kinematics.numeric.evaluate`, :func:`~dhsym.kinematics.numeric.word_product`),
the words from :mod:`dhsym.kinematics.transforms`; this module only strings the
links of a (possibly wrong, student-written) table together.

Examples
--------
>>> import numpy as np
>>> from dhsym.model.table import DHRow, DHTable
>>> table = DHTable.from_rows([DHRow.revolute("q1", a=1), DHRow.revolute("q2", a=1)])
>>> q1, q2 = table.variables
>>> F = frames(table, {q1: np.zeros(2), q2: np.array([0, np.pi / 2])}, 2)
>>> F[:, -1, :2, 3].round(12) + 0.0
array([[2., 0.],
       [1., 1.]])
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

import numpy as np
import sympy as sp

from dhsym.kinematics.numeric import EvaluationError, evaluate, evaluate_many, word_product
from dhsym.kinematics.transforms import link_word
from dhsym.model.table import Convention, DHRow

__all__ = [
    "EvaluationError",
    "evaluate",
    "evaluate_many",
    "evaluate_or_nan",
    "frames",
    "word_product",
]


class Rows(Protocol):
    """What :func:`frames` reads of a table: a :class:`~dhsym.model.table.DHTable`, or a
    :class:`~dhsym.checking.comparing.table_match.Chain` (rows that need not make a valid table)."""

    @property
    def rows(self) -> tuple[DHRow, ...]: ...

    @property
    def convention(self) -> Convention: ...

    @property
    def n(self) -> int: ...


def evaluate_or_nan(
    expr: sp.Basic,
    env: Mapping[sp.Basic, np.ndarray | float],
    size: int,
    memo: dict[object, np.ndarray] | None = None,
) -> np.ndarray:
    """Values of ``expr`` at ``size`` points, NaN at every point when it has none (a name
    without a value, a node the walker does not know, an overflow): the one evaluation of
    the checker's samples, for answers and keys alike (``memo`` as in :func:`evaluate`).

    >>> x = sp.Symbol("x")
    >>> evaluate_or_nan(sp.sqrt(x), {x: np.array([4.0])}, 1), evaluate_or_nan(x, {}, 2)
    (array([2.]), array([nan, nan]))
    """
    try:
        return evaluate(expr, env, size, memo)
    except (EvaluationError, OverflowError, TypeError, ValueError):
        return np.full(size, np.nan)


def frames(table: Rows, env: Mapping[sp.Basic, np.ndarray | float], size: int) -> np.ndarray:
    """The DH frames ``^0T_k`` for k = 0 … n at every point: shape (size, n + 1, 4, 4)."""
    out = np.empty((size, table.n + 1, 4, 4))
    current = np.broadcast_to(np.eye(4), (size, 4, 4)).copy()
    out[:, 0] = current
    memo: dict[object, np.ndarray] = {}
    for k, row in enumerate(table.rows, start=1):
        current = current @ word_product(link_word(row, table.convention), env, size, memo=memo)
        out[:, k] = current
    return out
