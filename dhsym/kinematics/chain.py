"""``KinematicChain``: the typed core around a :class:`~dhsym.model.table.DHTable` and the
pure functions.

A ``KinematicChain`` holds the table, its notation, the cached ``^iT_j`` and the compiled fk and
Jacobian functions: everything the kinematics room provides. The algorithms of the rooms
above (:mod:`dhsym.ik`, :mod:`dhsym.dynamics`, :mod:`dhsym.geometry`, :mod:`dhsym.plot`,
:mod:`dhsym.formats`, :mod:`dhsym.export`) take a ``KinematicChain``; :class:`dhsym.robot.Robot`
is the facade that adds their conveniences (``ik``, ``dynamics``, ``plot``, …).

Examples
--------
>>> from dhsym.model.table import DHTable, DHRow
>>> r = KinematicChain(DHTable.from_rows([DHRow.revolute("theta1", a="a1"),
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
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, overload

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.entries import as_expr
from dhsym.model.table import Convention, DHTable, Elementary, JointType
from dhsym.notation.printers import Notation, TrigStyle, decimal_lengths

from .pose import Pose
from .simplification import closed_form_size, compose, numeric_equal, prove_equal
from .transforms import chain_word, link_word, plain_product

if TYPE_CHECKING:  # numpy is imported lazily: `import dhsym` stays close to `import sympy`
    import numpy as np
    from numpy.typing import ArrayLike

    from .jacobian import AnalyticJacobian, Jacobian

__all__ = [
    "MAX_CLOSED_FORM",
    "ChainState",
    "KinematicChain",
    "JacobianKey",
    "PoseKey",
    "frame_name",
]


#: Largest estimated size (expression nodes, :func:`.simplification.closed_form_size`) of
#: a ``^iT_j`` written out in closed form. Every lecture robot is below 1,500, a 10-joint
#: chain of twisted joints about 27,000; above, a derivation would run for minutes and
#: print pages per entry, so it is refused (numbers, ``fk``, still work: they multiply the
#: chain's elementary transforms numerically, :func:`.numeric.compile_word`).
MAX_CLOSED_FORM = 30_000


@dataclass(frozen=True)
class PoseKey:
    """What a compiled ``q -> ^iT_j`` is cached by: the frames (``None``: world, tool) and
    the ``values`` given (:func:`.numeric.values_key`)."""

    i: int | None
    j: int | None
    values: object


@dataclass(frozen=True)
class JacobianKey:
    """What a compiled numeric Jacobian is cached by: its frame, Euler angles (``None``: the
    geometric Jacobian) and the ``values`` given (:func:`.numeric.values_key`)."""

    frame: int | str
    euler: str | None
    values: object


@dataclass(eq=False)
class ChainState:
    """What a chain derives, shared by every chain of an equal table and notation (the
    process's memo, :mod:`dhsym.cache.memo`): ``^iT_j`` in closed form by frames, the
    compiled fk functions (by :class:`PoseKey`; ``fk_default``: world to tool with the
    table's values) and the numeric Jacobians (by :class:`JacobianKey`)."""

    transforms: dict[tuple[int, int], Pose] = field(default_factory=dict)
    fk_functions: dict[PoseKey, Callable[[ArrayLike], np.ndarray]] = field(default_factory=dict)
    fk_default: Callable[[ArrayLike], np.ndarray] | None = None
    jacobian_functions: dict[JacobianKey, Callable[[object], np.ndarray]] = field(
        default_factory=dict
    )
    #: estimated expression nodes of the closed forms kept (the memo's bound)
    nodes: int = 0

    def memo_size(self) -> int:
        """The estimated size (:class:`dhsym.cache.memo.Sized`): the closed forms' nodes and
        a hundred per compiled function."""
        return 1 + self.nodes + 100 * (len(self.fk_functions) + len(self.jacobian_functions))


class KinematicChain:
    """Kinematics of one DH table: link matrices, ``^iT_j``, the arm matrix, ``fk``.

    Frames are numbered 0 … n (DH frames); ``-1`` is the world frame before the
    base transform and ``n + 1`` the tool frame after the tool transform. The arm
    matrix is the product of the link matrices, :math:`{}^0T_n = {}^0T_1 {}^1T_2 ... {}^{n-1}T_n`,
    and :math:`{}^jT_i = ({}^iT_j)^{-1}` is taken as the exact rigid inverse.
    ``compact`` (C12 or cos/sin) and ``style`` (``C1``, ``c1`` or ``c_theta``, see
    :class:`~dhsym.notation.printers.TrigStyle`) set how its matrices print.
    """

    def __init__(
        self, table: DHTable, *, compact: bool = True, style: TrigStyle | str = TrigStyle.UPPER
    ) -> None:
        self.table = table
        self.notation = Notation.from_variables(
            [r.variable for r in table.rows if r.joint is JointType.REVOLUTE],
            [str(i) for i, r in enumerate(table.rows, 1) if r.joint is JointType.REVOLUTE],
            compact=compact,
            style=style,
            decimals=decimal_lengths([v for r in table.rows for v in (r.d, r.a)]),
        )
        from dhsym.cache.memo import MEMO, MemoKey

        # what is derived, shared by every chain of an equal table and notation: ^iT_j in
        # closed form, compiled fk (a PoseFunction, or a compile_word product for a chain
        # too long to write out) and numeric Jacobians
        self._state = MEMO.get(MemoKey(table, ChainState, self.notation), ChainState)
        self._transforms = self._state.transforms
        self._fk_functions = self._state.fk_functions
        self._jacobian_functions = self._state.jacobian_functions

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
        return f"{type(self).__name__}({self.name!r}, {kinds}, {self.convention.value})"

    def _repr_markdown_(self) -> str:
        return f"**{self.name}** ({self.convention.value} DH)\n\n" + self.table._repr_markdown_()

    def _latex(self, printer: object) -> str:
        """``sympy.latex(robot)``: the robot's DH table as a LaTeX ``array``."""
        return self.table._latex(printer)

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
        pose = self._transforms.get((i, j))
        if pose is None:
            pose = self._transforms[(i, j)] = self._compute_transform(i, j)
            self._state.nodes += self.transform_size(i, j)
        return pose

    def transform_size(self, i: int, j: int) -> int:
        """Estimated size of ``^iT_j`` in closed form (expression nodes), found in microseconds."""
        return closed_form_size(chain_word(self.table, i, j))

    def check_transform_size(self, i: int, j: int) -> None:
        """Refuse a ``^iT_j`` whose closed form would explode, naming the parts that fit.

        >>> from dhsym.model.table import DHRow, DHTable
        >>> rows = [DHRow.revolute(f"q{k}", d=f"d{k}", a=f"a{k}", alpha=(-1) ** k * sp.pi / 2)
        ...         for k in range(1, 17)]
        >>> KinematicChain(DHTable.from_rows(rows, name="snake")).transform(0, 16)
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
        word = chain_word(self.table, i, j)
        whole = i in (-1, 0) and j in (self.n, self.n + 1) and i < j
        matrix = self._stored_transform(i, j, lambda: compose(word)) if whole else compose(word)
        return Pose(matrix, frame_name(i, self.n), frame_name(j, self.n), self.notation, word=word)

    def _stored_transform(
        self, i: int, j: int, derive: Callable[[], sp.ImmutableMatrix]
    ) -> sp.ImmutableMatrix:
        """The closed form of the arm matrix or the tool pose ``^iT_j``, kept in the disk cache
        (:mod:`dhsym.cache`: verified when read); ``derive()`` when absent or refused."""
        from dhsym.cache.codec import CodecError, read_exprs, write_exprs
        from dhsym.cache.keys import entry_name
        from dhsym.cache.store import default_store

        store = default_store()
        if store is None:
            return derive()
        name = entry_name(self.table, "transform", f"{i}-{j}")
        data = store.read(name)
        if data is not None:
            try:
                (found,) = read_exprs(data)
                if isinstance(found, sp.ImmutableMatrix) and found.shape == (4, 4):
                    return found
            except (CodecError, ValueError):
                pass  # not what this version writes: derive it again
        matrix = derive()
        try:
            store.write(name, write_exprs([matrix]).encode())
        except CodecError:
            pass  # an expression the codec does not write: kept in this process only
        return matrix

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
        values: Mapping[Any, object] | None = None,
    ) -> Callable[[ArrayLike], np.ndarray]:
        """A compiled numeric function ``q -> ^iT_j`` (defaults: world to tool), cached.

        The cache key is what changes between calls: the frames and the
        ``values`` given (the table's own values are fixed for this robot).

        >>> from dhsym.model.library import load_table
        >>> r = KinematicChain(load_table("planar2r"))
        >>> r.fk_function() is r.fk_function(), r.fk_function(0, 1)([0.5, 0.0])[0, 3]
        (True, np.float64(0.8775825618903728))
        """
        from .constants import measured
        from .numeric import compile_word, stored_pose_function, values_key

        key = PoseKey(i, j, values_key(values))
        f = self._fk_functions.get(key)
        if f is None:
            if i is None and j is None:
                i = -1 if self.table.base else 0
                j = self.n + 1 if self.table.tool else self.n
            i, j = (i or 0), (self.n if j is None else j)
            vals = self.table.with_values(values or {}).value_map
            word = chain_word(self.table, i, j)
            # measured constants (a skewed URDF axis read as huge exact rationals) would
            # make the closed form's radicals huge: their numbers start from floats
            heavy = any(measured(as_expr(e.value).xreplace(vals)) for e in word)
            if not heavy and self.transform_size(i, j) <= MAX_CLOSED_FORM:
                # its programs are kept in the disk cache (dhsym.cache) by table, frames, values
                f = stored_pose_function(
                    self._fk_entries(i, j, vals),
                    lambda: self.transform(i, j).matrix,
                    self.variables,
                    vals,
                )
            else:  # too long or too heavy for a closed form: the elementary transforms,
                # multiplied as numbers (each constant a float, kinematics.constants.to_float)
                f = compile_word(word, self.variables, vals)
            self._fk_functions[key] = f
        return f

    def _fk_entries(self, i: int, j: int, values: Mapping[sp.Symbol, object]) -> tuple[str, str]:
        """The disk-cache entries of the compiled ``^iT_j`` with ``values`` (floats, numpy)."""
        from dhsym.cache.keys import entry_name

        given = sorted(f"{sp.srepr(k)}={sp.srepr(v)}" for k, v in values.items())
        parts = (f"{i}-{j}", *given)
        return entry_name(self.table, "fk_single", *parts), entry_name(
            self.table, "fk_batch", *parts
        )

    def fk(
        self, q: ArrayLike, *, deg: bool = False, values: Mapping[Any, object] | None = None
    ) -> np.ndarray:
        """Tool pose: one configuration ``(n,)`` → ``(4, 4)``; a batch ``(N, n)`` → ``(N, 4, 4)``.

        With ``deg=True`` revolute joint values are in degrees. One configuration
        runs in pure Python floats (a few µs), a batch in numpy.
        """
        f = self._state.fk_default if values is None else None
        if f is None:
            f = self.fk_function(values=values)
            if values is None:
                self._state.fk_default = f
        if deg:
            import numpy as np

            arr = np.array(q, dtype=float)
            mask = [
                r.joint is JointType.REVOLUTE for r in self.table.rows if r.variable is not None
            ]
            arr[..., np.asarray(mask, dtype=bool)] *= math.pi / 180.0
            q = arr
        return f(q)

    def analytic_jacobian(
        self, euler: str = "zyz", *, frame: int | str = "base"
    ) -> AnalyticJacobian:
        """The exact analytic Jacobian ``J_A = diag(I, B⁻¹) J`` for the Euler set ``euler``
        (``"zyz"`` or ``"rpy"``; :func:`~dhsym.kinematics.jacobian.analytic_jacobian`).

        >>> from dhsym.model.library import load_table
        >>> KinematicChain(load_table("planar2r")).analytic_jacobian("rpy").euler
        'rpy'
        """
        from .jacobian import analytic_jacobian

        return analytic_jacobian(self, euler, frame)

    @overload
    def jacobian(self, q: None = None, *, frame: int | str = "base") -> Jacobian: ...
    @overload
    def jacobian(
        self,
        q: ArrayLike,
        *,
        frame: int | str = "base",
        euler: str | None = None,
        values: Mapping[Any, object] | None = None,
    ) -> np.ndarray: ...
    def jacobian(
        self,
        q: ArrayLike | None = None,
        *,
        frame: int | str = "base",
        euler: str | None = None,
        values: Mapping[Any, object] | None = None,
    ) -> Jacobian | np.ndarray:
        """The exact 6×n geometric Jacobian (:func:`~dhsym.kinematics.jacobian.geometric_jacobian`).

        ``frame`` is where its columns are written: ``"base"`` (the frame of ``fk``),
        ``"tool"`` (the end-effector frame) or a frame number. The exact analytic Jacobian
        is :meth:`analytic_jacobian`.

        ``robot.jacobian(q)`` (with ``frame``, ``euler``, ``values``) is kept as an alias of
        the numbers, :meth:`jacob0` (``frame="base"``) and :meth:`jacobe` (``frame="tool"``):
        an array, not a :class:`~dhsym.kinematics.jacobian.Jacobian`.

        >>> from dhsym.model.library import load_table
        >>> r = KinematicChain(load_table("planar2r"))
        >>> type(r.jacobian()).__name__, r.jacobian([0.0, 0.0]).shape
        ('Jacobian', (6, 2))
        """
        if q is not None:
            return self._jacobian_numbers(q, frame, euler, values)
        if euler is not None or values is not None:
            raise DHError(
                "jacobian() without q is the exact geometric Jacobian: the exact analytic "
                "Jacobian is analytic_jacobian(euler), numbers are jacob0(q, euler=..., "
                "values=...)"
            )
        from .jacobian import geometric_jacobian

        return geometric_jacobian(self, frame)

    def jacob0(
        self,
        q: ArrayLike,
        *,
        euler: str | None = None,
        values: Mapping[Any, object] | None = None,
    ) -> np.ndarray:
        """The Jacobian at ``q`` in the base frame of ``fk`` (roboticstoolbox's ``jacob0``):
        ``(n,)`` → ``(6, n)``, ``(N, n)`` → ``(N, 6, n)``, compiled once and cached.

        The geometric Jacobian, or with ``euler="zyz"`` or ``"rpy"`` the analytic one
        (angles read from ``fk``); ``values`` are numbers for the table's symbols.

        >>> from dhsym.model.library import load_table
        >>> KinematicChain(load_table("planar2r")).jacob0([0.0, 0.0])[:2]
        array([[0. , 0. ],
               [1.8, 0.8]])
        """
        return self._jacobian_numbers(q, "base", euler, values)

    def jacobe(self, q: ArrayLike, *, values: Mapping[Any, object] | None = None) -> np.ndarray:
        """The geometric Jacobian at ``q`` in the end-effector frame (roboticstoolbox's
        ``jacobe``; the tool frame when the table has a tool transform), batched like
        :meth:`jacob0`.

        >>> import math
        >>> from dhsym.model.library import load_table
        >>> r = KinematicChain(load_table("planar2r"))
        >>> r.jacobe([math.pi / 2, 0.0])[:2]  # the tip moves along the tool's y axis
        array([[0. , 0. ],
               [1.8, 0.8]])
        """
        return self._jacobian_numbers(q, "tool", None, values)

    def _jacobian_numbers(
        self,
        q: ArrayLike,
        frame: int | str,
        euler: str | None,
        values: Mapping[Any, object] | None,
    ) -> np.ndarray:
        """The compiled Jacobian of ``frame`` (analytic with ``euler``) at ``q``, cached."""
        from . import jacobian as jac
        from .numeric import values_key

        key = JacobianKey(frame, euler, values_key(values))
        f = self._jacobian_functions.get(key)
        if f is None:
            if euler is not None:
                if frame != "base":
                    raise DHError("the numeric analytic Jacobian is in the base frame")
                f = jac.analytic_jacobian_function(self, euler, values)
            elif frame == "tool":
                f = self._carried_to_tool(values)
            else:
                f = jac.jacobian_function(self, frame, values=values)
            self._jacobian_functions[key] = f
        return f(q)

    def _carried_to_tool(
        self, values: Mapping[Any, object] | None
    ) -> Callable[[object], np.ndarray]:
        """``jacobe`` as ``diag(Rᵀ, Rᵀ) jacob0`` in numbers, ``R`` the tool's rotation: the
        exact Jacobian in the tool frame of a long chain (a Panda's) takes minutes to write
        out, the rotation of the base frame's one is a product of numbers."""

        import numpy as np

        def evaluate(q: object) -> np.ndarray:
            Q = np.asarray(q, dtype=float)
            J0 = self._jacobian_numbers(Q, "base", None, values)
            Rt = np.swapaxes(self.fk(Q, values=values)[..., :3, :3], -1, -2)
            return np.concatenate([Rt @ J0[..., :3, :], Rt @ J0[..., 3:, :]], axis=-2)

        return evaluate

    # -- helpers ---------------------------------------------------------------------
    def _check_row(self, i: int) -> None:
        if not 1 <= i <= self.n:
            raise IndexError(f"{self.name or 'robot'} has links 1 … {self.n}; got {i}")


def frame_name(i: int, n: int) -> int | str:
    """Frame ``i`` of a chain of ``n`` links as printed: ``W`` (world, -1), ``tool`` (n + 1)
    or the number.

    >>> frame_name(-1, 6), frame_name(3, 6), frame_name(7, 6)
    ('W', 3, 'tool')
    """
    if i == -1:
        return "W"
    if i == n + 1:
        return "tool"
    return i
