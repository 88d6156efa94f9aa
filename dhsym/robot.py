"""``Robot``: a thin class around a :class:`~dhsym.table.DHTable` and the pure functions.

Examples
--------
>>> from dhsym.table import DHTable, DHRow
>>> r = Robot(DHTable.from_rows([DHRow.revolute("theta1", a="a1"),
...                              DHRow.revolute("theta2", a="a2")], name="2R"))
>>> print(r.arm_matrix().text())
Matrix([
[C12, -S12, 0, a1*C1 + a2*C12],
[S12,  C12, 0, a1*S1 + a2*S12],
[  0,    0, 1,              0],
[  0,    0, 0,              1]])
>>> r.transform(2, 0)[0, 3]
-a1*cos(theta2) - a2
>>> r.fk([0, 0], values={"a1": 1, "a2": 0.5})[0, 3]
np.float64(1.5)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from functools import cache
from typing import TYPE_CHECKING

import sympy as sp

from .errors import DHError
from .notation import Notation
from .parsing import symbol
from .pose import Pose
from .simplification import closed_form_size, compose, numeric_equal, prove_equal
from .table import Convention, DHTable, Elementary, JointType, as_expr
from .transforms import chain_word, link_word, plain_product

if TYPE_CHECKING:  # numpy is imported lazily: `import dhsym` stays close to `import sympy`
    import numpy as np

__all__ = ["MAX_CLOSED_FORM", "Robot"]

FkFunction = Callable[[object], "np.ndarray"]

#: Largest estimated size (expression nodes, :func:`~dhsym.simplification.closed_form_size`)
#: of a ``^iT_j`` written out in closed form.  Every lecture robot is below 1,500, a
#: 10-joint chain of twisted joints about 27,000; above, a derivation would run for
#: minutes and print pages per entry, so it is refused (numbers, ``fk``, still work).
MAX_CLOSED_FORM = 30_000
_NUMERIC_PART = 400  # size of the parts of a chain compiled piecewise for numbers


class Robot:
    """Kinematics of one DH table: link matrices, ``^iT_j``, the arm matrix, ``fk``.

    Frames are numbered 0 … n (DH frames); ``-1`` is the world frame before the
    base transform and ``n + 1`` the tool frame after the tool transform.
    """

    def __init__(self, table: DHTable, *, compact: bool = True, upper: bool = True) -> None:
        self.table = table
        self.notation = Notation.from_variables(
            [r.variable for r in table.rows if r.joint is JointType.REVOLUTE],
            [str(i) for i, r in enumerate(table.rows, 1) if r.joint is JointType.REVOLUTE],
            compact=compact,
            upper=upper,
        )
        self._transform = cache(self._compute_transform)
        self._fk_cache: dict[tuple[int, int, tuple], FkFunction] = {}

    # -- description -----------------------------------------------------------------
    @property
    def name(self) -> str:
        """The table's name."""
        return self.table.name

    @property
    def n(self) -> int:
        """Number of rows (DH frames 1 … n)."""
        return self.table.n

    @property
    def convention(self) -> Convention:
        """The table's convention."""
        return self.table.convention

    @property
    def variables(self) -> tuple[sp.Symbol, ...]:
        """Joint variables in order (the configuration vector of :meth:`fk`)."""
        return self.table.variables

    def __repr__(self) -> str:
        kinds = "".join(r.joint.value for r in self.table.rows)
        return f"Robot({self.name!r}, {kinds}, {self.convention.value})"

    def _repr_markdown_(self) -> str:
        return f"**{self.name}** ({self.convention.value} DH)\n\n" + self.table._repr_markdown_()

    # -- symbolic --------------------------------------------------------------------
    def link_factors(self, i: int) -> tuple[Pose, ...]:
        """The four elementary factors of link matrix ``i`` (1-based), each a 4×4 Pose."""
        self._check_row(i)
        word = link_word(self.table.rows[i - 1], self.convention)
        return tuple(
            Pose(plain_product([e]), "", "", self.notation, symbol=f"{e.kind}_{e.axis}")
            for e in word
        )

    def link_word(self, i: int) -> tuple[Elementary, ...]:
        """The elementary transforms of link ``i`` in multiplication order."""
        self._check_row(i)
        return link_word(self.table.rows[i - 1], self.convention)

    def link_matrix(self, i: int) -> Pose:
        """``^{i-1}T_i`` in compact form."""
        self._check_row(i)
        return self.transform(i - 1, i)

    def transform(self, i: int, j: int) -> Pose:
        """``^iT_j`` in compact form, for any frames ``i``, ``j`` (inverse when ``j < i``).

        Raises :class:`~dhsym.errors.DHError` when its closed form would be too large
        (see :meth:`check_transform_size`).
        """
        return self._transform(i, j)

    def transform_size(self, i: int, j: int) -> int:
        """Estimated size of ``^iT_j`` in closed form (expression nodes), found in microseconds."""
        return closed_form_size(chain_word(self.table, i, j))

    def check_transform_size(self, i: int, j: int) -> None:
        """Refuse a ``^iT_j`` whose closed form would explode, naming the parts that fit.

        >>> from dhsym.table import DHRow, DHTable
        >>> rows = [DHRow.revolute(f"q{k}", d=f"d{k}", a=f"a{k}", alpha=(-1) ** k * sp.pi / 2)
        ...         for k in range(1, 17)]
        >>> Robot(DHTable.from_rows(rows, name="snake")).transform(0, 16)
        Traceback (most recent call last):
        ...
        dhsym.errors.DHError: ^0T_16 of snake is too large to write out in closed form ...
        """
        size = self.transform_size(i, j)
        if size <= MAX_CLOSED_FORM:
            return
        step = 1 if j > i else -1
        k = i + step
        while k != j and self.transform_size(i, k + step) <= MAX_CLOSED_FORM:
            k += step
        raise DHError(
            f"^{i}T_{j} of {self.name or 'this robot'} is too large to write out in closed form "
            f"(an estimated {size:.3g} expression nodes; at most {MAX_CLOSED_FORM}): derive a "
            f"shorter part of the chain with --from/--to (frm=/to= in Python), e.g. "
            f"^{i}T_{k}, and name the parts: ^{i}T_{j} = ^{i}T_{k} ^{k}T_{j}"
        )

    def _compute_transform(self, i: int, j: int) -> Pose:
        self.check_transform_size(i, j)
        matrix = compose(chain_word(self.table, i, j))
        return Pose(matrix, _frame_name(i, self.n), _frame_name(j, self.n), self.notation)

    def plain_transform(self, i: int, j: int) -> sp.ImmutableMatrix:
        """``^iT_j`` as the plain product of the elementary matrices (the reference)."""
        return plain_product(chain_word(self.table, i, j))

    def arm_matrix(self) -> Pose:
        """``^0T_n``, the arm matrix (without base and tool transforms)."""
        return self.transform(0, self.n)

    def tool_pose(self) -> Pose:
        """World to tool: base · ``^0T_n`` · tool (equals the arm matrix without them)."""
        return self.transform(
            -1 if self.table.base else 0, self.n + 1 if self.table.tool else self.n
        )

    def verify(self, i: int = 0, j: int | None = None, *, exact: bool = True) -> bool:
        """Check the compact ``^iT_j`` against the plain product (exactly, or at 20 points)."""
        j = self.n if j is None else j
        compact = self.transform(i, j).matrix
        plain = self.plain_transform(i, j)
        return prove_equal(compact, plain) if exact else numeric_equal(compact, plain)

    # -- numbers ---------------------------------------------------------------------
    def fk_function(
        self,
        i: int | None = None,
        j: int | None = None,
        values: Mapping[object, object] | None = None,
    ) -> FkFunction:
        """A compiled numeric function ``q -> ^iT_j`` (defaults: world to tool).

        A chain too large for one closed form (:data:`MAX_CLOSED_FORM`) is compiled in
        small parts that are multiplied numerically.
        """
        if i is None and j is None:
            i = -1 if self.table.base else 0
            j = self.n + 1 if self.table.tool else self.n
        i, j = (i or 0), (self.n if j is None else j)
        vals = dict(self.table.value_map)
        for k, v in (values or {}).items():
            vals[symbol(k) if isinstance(k, str) else k] = as_expr(v, field="values")  # type: ignore[index]
        return self._compiled(i, j, vals, tuple(sorted((str(k), str(v)) for k, v in vals.items())))

    def _compiled(self, i: int, j: int, vals: dict, tag: tuple) -> FkFunction:
        key = (i, j, tag)
        if key not in self._fk_cache:
            from .numeric import compile_chain, compile_pose, compose_numeric

            if self.transform_size(i, j) <= MAX_CLOSED_FORM:
                fn = compile_pose(self.transform(i, j).matrix, self.variables, vals)
            elif j < i:
                fn = compose_numeric([self._compiled(j, i, vals, tag)], invert=True)
            else:  # small parts, quick to derive, compiled at once and multiplied numerically
                parts, a = [], i
                while a < j:
                    b = a + 1
                    while b < j and self.transform_size(a, b + 1) <= _NUMERIC_PART:
                        b += 1
                    parts.append(self.transform(a, b).matrix)
                    a = b
                fn = compile_chain(parts, self.variables, vals)
            self._fk_cache[key] = fn  # type: ignore[index]
        return self._fk_cache[key]  # type: ignore[index]

    def fk(
        self, q: object, *, deg: bool = False, values: Mapping[object, object] | None = None
    ) -> np.ndarray:
        """Tool pose: one configuration ``(n,)`` → ``(4, 4)``; a batch ``(N, n)`` → ``(N, 4, 4)``.

        With ``deg=True`` revolute joint values are in degrees.
        """
        import numpy as np

        arr = np.asarray(q, dtype=float)
        if deg:
            arr = arr.copy()
            mask = [
                r.joint is JointType.REVOLUTE for r in self.table.rows if r.variable is not None
            ]
            arr[..., np.asarray(mask, dtype=bool)] *= math.pi / 180.0
        return self.fk_function(values=values)(arr)

    def plot(self, q: object = None, **kw: object) -> object:
        """A matplotlib Figure of the arm with its DH frames (see :mod:`dhsym.plotting`)."""
        from .plotting import plot_robot

        return plot_robot(self, q, **kw)

    # -- helpers ---------------------------------------------------------------------
    def _check_row(self, i: int) -> None:
        if not 1 <= i <= self.n:
            raise IndexError(f"{self.name or 'robot'} has links 1 … {self.n}; got {i}")


def _frame_name(i: int, n: int) -> int | str:
    if i == -1:
        return "W"
    if i == n + 1:
        return "tool"
    return i
