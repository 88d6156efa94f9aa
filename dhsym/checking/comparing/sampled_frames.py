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

from collections.abc import Mapping, Sequence
from typing import Protocol

import numpy as np
import sympy as sp

from dhsym.kinematics.numeric import EvaluationError, evaluate, evaluate_many, word_product
from dhsym.kinematics.transforms import link_word
from dhsym.model.table import Convention, DHRow

__all__ = [
    "EvaluationError",
    "chained",
    "evaluate",
    "evaluate_many",
    "evaluate_or_nan",
    "frames",
    "link_values",
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
    memo: dict[object, np.ndarray] = {}
    return chained(
        [link_values(row, table.convention, env, size, memo) for row in table.rows], size
    )


def link_values(
    row: DHRow,
    convention: Convention,
    env: Mapping[sp.Basic, np.ndarray | float],
    size: int,
    memo: dict[object, np.ndarray] | None = None,
) -> np.ndarray:
    """One row's link transform ``^{i-1}T_i`` at every point: shape (size, 4, 4) (``memo``
    as in :func:`~dhsym.kinematics.numeric.word_product`, for the same ``env``)."""
    return word_product(link_word(row, convention), env, size, memo=memo)


def chained(links: Sequence[np.ndarray], size: int) -> np.ndarray:
    """The frames ``^0T_k`` (k = 0 … n) of the link transforms ``links`` (each of shape
    (size, 4, 4)), multiplied in order: shape (size, n + 1, 4, 4).

    >>> turn = np.array([[0.0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    >>> F = chained([turn[None], turn[None]], 1)
    >>> F.shape, F[0, 2, :2, :2].round(12) + 0.0
    ((1, 3, 4, 4), array([[-1.,  0.],
           [ 0., -1.]]))
    """
    out = np.empty((size, len(links) + 1, 4, 4))
    current = np.broadcast_to(np.eye(4), (size, 4, 4)).copy()
    out[:, 0] = current
    for k, link in enumerate(links, start=1):
        current = current @ link
        out[:, k] = current
    return out
