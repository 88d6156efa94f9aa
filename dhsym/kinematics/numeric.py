"""Compiled numbers of exact expressions: code generated once, evaluated in cache-sized chunks.

Every numeric path of dhsym that evaluates an expression more than once (``fk``, the
Jacobians, the dynamics, :func:`numeric_equal
<dhsym.kinematics.simplification.numeric_equal>`, the checks of frame assignment
and conversion) goes through this module; constants are folded to floats first
(:mod:`dhsym.kinematics.constants`), and one-off expressions are walked instead of
compiled (:mod:`dhsym.kinematics.interpreter`):

* :func:`compile_exprs` generates code once (common-subexpression elimination)
  for numpy arrays or for plain Python floats;
* :func:`evaluate_chunked` runs such code over a batch of points in cache-sized
  chunks (every compiled batch of dhsym: poses, Jacobians, dynamics);
* :func:`compile_pose` builds a :class:`PoseFunction` for a 4×4 homogeneous
  matrix: a pure-float path for one configuration ``(n,)`` → ``(4, 4)`` and a
  numpy path for a batch ``(N, n)`` → ``(N, 4, 4)``; :func:`compile_matrix` any
  ``m × k`` matrix;
* :func:`compile_word` multiplies a word of elementary transforms numerically
  (no symbolic product at all: the check of a 10-joint conversion takes
  milliseconds whatever its twists); :func:`word_product` is the same for a one-off
  word, its values from the tree walker;
* :func:`elementary_stack` is the numeric twin of
  :func:`~dhsym.kinematics.transforms.elementary_matrix` (the word is shared: words
  come from :mod:`dhsym.kinematics.transforms`), and :func:`numeric_rigid_inverse`
  the twin of :func:`~dhsym.kinematics.transforms.rigid_inverse`.

:func:`to_float`, :func:`float_constants`, :func:`as_basic` (from
:mod:`~dhsym.kinematics.constants`) and :func:`evaluate`, :func:`evaluate_many`,
:class:`EvaluationError` (from :mod:`~dhsym.kinematics.interpreter`) are importable
from here too.

Examples
--------
>>> q1, a1 = sp.symbols("q1 a1", real=True)
>>> M = sp.ImmutableMatrix([[sp.cos(q1), -sp.sin(q1), 0, a1 * sp.cos(q1)],
...                         [sp.sin(q1), sp.cos(q1), 0, a1 * sp.sin(q1)],
...                         [0, 0, 1, 0], [0, 0, 0, 1]])
>>> f = compile_pose(M, (q1,), {a1: 2})
>>> f([0.0])[0, 3]
np.float64(2.0)
>>> f(np.zeros((5, 1))).shape
(5, 4, 4)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError

from .constants import as_basic, float_constants, to_float
from .interpreter import EvaluationError, evaluate, evaluate_many

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from dhsym.model.table import Elementary

__all__ = [
    "CHUNK",
    "EvaluationError",
    "as_basic",
    "PoseFunction",
    "NumericProgram",
    "compile_exprs",
    "compile_program",
    "kept_tuples",
    "stored_pose_function",
    "stored_program",
    "compile_matrix",
    "compile_pose",
    "compile_word",
    "elementary_stack",
    "evaluate",
    "evaluate_chunked",
    "evaluate_many",
    "float_constants",
    "numeric_rigid_inverse",
    "to_float",
    "values_key",
    "word_product",
]

#: Points per chunk of a compiled batch (:func:`evaluate_chunked`): the temporaries of one
#: chunk stay in the L2 cache, about twice as fast as one pass over a large batch.
CHUNK = 4096
_FLOAT = np.dtype(float)


class _PlusZero(sp.Function):
    """``x + 0.0`` in the float code: ``-0.0`` becomes ``0.0``, so printed poses read cleanly."""

    def _pythoncode(self, printer: Any) -> str:  # a sympy code printer (untyped)
        return f"({printer._print(self.args[0])} + 0.0)"


@dataclass(frozen=True)
class NumericProgram:
    """What :func:`compile_exprs` turns into code: the expressions with their constants
    folded to floats, their shared subexpressions named (``assignments``, in order) and
    the ``outputs`` written with those names. Plain expressions: the disk cache keeps a
    program (:mod:`dhsym.cache.codec`) and :func:`compile_program` compiles it again.

    >>> x, y = sp.symbols("x y")
    >>> p = NumericProgram.of([sp.sqrt(3) * sp.sin(x + y), sp.cos(x + y) * sp.sin(x + y)], (x, y))
    >>> p.assignments, p.outputs
    (((x0, x + y), (x1, sin(x0))), (1.7320508075688772*x1, x1*cos(x0)))
    """

    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    outputs: tuple[sp.Expr, ...]

    @classmethod
    def of(cls, exprs: Sequence[sp.Basic], variables: Sequence[sp.Symbol]) -> NumericProgram:
        """Fold the constants of ``exprs`` (:func:`float_constants`) and name their shared
        subexpressions (``sympy.cse``); symbols other than ``variables`` raise
        :class:`~dhsym.errors.DHError`."""
        folded = [float_constants(e) for e in exprs]
        missing = set().union(*(e.free_symbols for e in folded)) - set(variables)
        if missing:
            names = ", ".join(sorted(str(s) for s in missing))
            raise DHError(f"no numeric value for {names}: give values for these symbols")
        assignments, outputs = sp.cse(folded, list=False)
        return cls(tuple((s, e) for s, e in assignments), tuple(outputs))


def compile_program(
    program: NumericProgram, variables: Sequence[sp.Symbol], *, floats: bool = False
) -> Callable[..., list[Any]]:
    """Compile a :class:`NumericProgram` into ``f(*variables) -> list`` (numpy arrays, or plain
    floats with ``floats=True``), as :func:`compile_exprs` does."""
    # numpy's namespace as a module: modules="numpy" would run `from numpy import *`, which
    # imports all of numpy's lazy submodules (as long as importing numpy itself)
    module = "math" if floats else [np]
    compiled: Callable[..., list[Any]] = sp.lambdify(
        list(variables),
        list(program.outputs),
        modules=module,
        cse=lambda exprs: (list(program.assignments), exprs),
    )
    return compiled


def stored_program(
    name: str | None,
    exprs: Callable[[], Sequence[sp.Basic]],
    variables: Sequence[sp.Symbol],
    extra: Mapping[str, type] | None = None,
) -> NumericProgram:
    """The :class:`NumericProgram` of ``exprs()`` for ``variables``, kept in the disk cache as entry
    ``name`` (:mod:`dhsym.cache`: verified when read; ``None`` or the cache turned off:
    not kept). ``exprs`` is called only when the entry is absent or refused; ``extra``
    names dhsym's own functions the program may hold (:func:`dhsym.cache.codec.read_exprs`)."""

    def build() -> list[sp.Tuple]:
        program = NumericProgram.of(exprs(), variables)
        lhs = sp.Tuple(*(s for s, _ in program.assignments))
        return [lhs, sp.Tuple(*(e for _, e in program.assignments)), sp.Tuple(*program.outputs)]

    lhs, rhs, outputs = kept_tuples(lambda: name, build, 3, extra)
    return NumericProgram(tuple(zip(lhs.args, rhs.args)), tuple(outputs.args))


def kept_tuples(
    name: Callable[[], str | None],
    build: Callable[[], Sequence[sp.Tuple]],
    size: int,
    extra: Mapping[str, type] | None = None,
) -> tuple[sp.Tuple, ...]:
    """The tuples of expressions ``build()`` makes (a ready program: its steps, outputs,
    arguments), kept in the disk cache as entry ``name()`` (:mod:`dhsym.cache`: verified
    when read, read by :func:`dhsym.cache.codec.read_exprs` without running code;
    ``name()`` is asked only when the cache is on, and ``None`` keeps nothing). An entry
    that is not ``size`` tuples is built again and rewritten; ``extra``
    names dhsym's own functions they may hold. The one reader and writer of programs:
    :func:`stored_program` and :func:`dhsym.ik.kept_programs.kept_program` take it.

    >>> x = sp.Symbol("x")
    >>> kept_tuples(lambda: None, lambda: [sp.Tuple(x, 2 * x)], 1)
    ((x, 2*x),)
    """
    from dhsym.cache.codec import CodecError, read_exprs, write_exprs
    from dhsym.cache.store import default_store

    store = default_store()
    entry = name() if store is not None else None
    data = store.read(entry) if store is not None and entry is not None else None
    if data is not None:
        try:
            found = tuple(read_exprs(data, extra))
        except (CodecError, ValueError, AttributeError, TypeError):
            found = ()  # not a program this version reads: built again
        if len(found) == size and all(isinstance(t, sp.Tuple) for t in found):
            return found
    made = build()
    if store is not None and entry is not None:
        try:
            text = write_exprs(list(made), extra)
        except CodecError:
            return tuple(made)  # a class the codec does not write: kept in this process only
        store.write(entry, text.encode())
    return tuple(made)


def compile_exprs(
    exprs: Sequence[sp.Basic], variables: Sequence[sp.Symbol], *, floats: bool = False
) -> Callable[..., list[Any]]:
    """Compile ``exprs`` once into ``f(*variables) -> list`` (numpy arrays, or plain floats).

    Constants are folded to floats first (:func:`float_constants`); symbols
    other than ``variables`` raise :class:`~dhsym.errors.DHError`. With
    ``floats=True`` the code uses :mod:`math` and takes Python floats (fast for
    one point); otherwise numpy, elementwise over arrays. The steps are
    :meth:`NumericProgram.of` and :func:`compile_program`.

    >>> x, y = sp.symbols("x y")
    >>> compile_exprs([sp.sqrt(3) * x, x + y], (x, y), floats=True)(2.0, 1.0)
    [3.4641016151377544, 3.0]
    >>> compile_exprs([x * y], (x,))
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: no numeric value for y: give values for these symbols
    """
    return compile_program(NumericProgram.of(exprs, variables), variables, floats=floats)


def evaluate_chunked(
    function: Callable[..., Sequence[object]],
    *arrays: np.ndarray,
    out: np.ndarray,
    chunk: int = CHUNK,
    plus_zero: bool = False,
) -> np.ndarray:
    """Fill ``out`` ``(N, m)`` with the ``m`` values of a compiled ``function`` at ``N`` points,
    in chunks of ``chunk`` points; returns ``out``.

    ``arrays`` are ``(N, k_i)``; ``function`` (from :func:`compile_exprs`) takes their
    columns, in order, and returns its ``m`` values, each an array over the chunk's points
    or a constant (broadcast to them). The temporaries of one chunk stay in the cache
    (:data:`CHUNK`). ``out`` may be a view (the first 12 entries of ``(N, 16)`` poses).
    With ``plus_zero`` every chunk gets ``+ 0.0``: ``-0.0`` becomes ``0.0``, so printed
    results read cleanly.

    >>> x, y = sp.symbols("x y")
    >>> f = compile_exprs([x + y, -x * y, sp.Integer(2)], (x, y))
    >>> evaluate_chunked(f, np.array([[1.0], [2.0], [3.0]]), np.array([[0.0], [1.0], [2.0]]),
    ...                  out=np.empty((3, 3)), chunk=2, plus_zero=True)
    array([[ 1.,  0.,  2.],
           [ 3., -2.,  2.],
           [ 5., -6.,  2.]])
    """
    N = out.shape[0]
    for a in arrays:
        if a.shape[0] != N:
            raise ValueError(f"{N} points expected, got an array of shape {a.shape}")
    for start in range(0, N, chunk):
        block = out[start : start + chunk]
        columns = [c for a in arrays for c in a[start : start + chunk].T]
        for k, v in enumerate(function(*columns)):
            block[:, k] = v
        if plus_zero:
            block += 0.0
    return out


class PoseFunction:
    """A compiled 4×4 homogeneous transform of the joint variables.

    ``f(q)`` takes one configuration ``(n,)`` (pure Python floats: a few µs)
    or a batch ``(N, n)`` (numpy, in cache-sized chunks) and returns ``(4, 4)``
    or ``(N, 4, 4)``; ``-0.0`` entries come out as ``0.0``. ``batch`` may be a function
    that compiles the numpy code on the first batch (:func:`stored_pose_function`).
    """

    __slots__ = ("_batch", "_make_batch", "_single", "n")

    def __init__(
        self,
        single: Callable[..., list[Any]],
        batch: Callable[..., list[Any]] | None,
        n: int,
        *,
        make_batch: Callable[[], Callable[..., list[Any]]] | None = None,
    ) -> None:
        self._single = single
        self._batch = batch
        self._make_batch = make_batch
        self.n = n

    def __call__(self, q: ArrayLike) -> np.ndarray:
        if isinstance(q, (list, tuple)):
            if len(q) == self.n:
                return self.single(q)
        elif isinstance(q, np.ndarray) and q.ndim == 1 and q.shape[0] == self.n:
            return self.single(q.tolist())
        return self.batch(q)

    def single(self, q: Sequence[float]) -> np.ndarray:
        """One configuration (a sequence of n numbers) → ``(4, 4)``, in pure Python floats.

        Anything else (nested lists, text, complex numbers, ±inf) goes the numpy way
        of :meth:`batch`, with numpy's rules and errors.
        """
        try:
            out = np.array(self._single(*q))
        except (TypeError, ValueError, OverflowError, ZeroDivisionError):
            return self.batch(q)
        if out.dtype != _FLOAT or out.shape != (16,):  # e.g. a list was added to a list
            return self.batch(q)
        out.shape = (4, 4)
        return out

    def _numpy(self) -> Callable[..., list[Any]]:
        if self._batch is None:
            assert self._make_batch is not None, "a PoseFunction has a batch program or a maker"
            self._batch = self._make_batch()
        return self._batch

    def batch(self, q: ArrayLike) -> np.ndarray:
        """A batch ``(N, n)`` → ``(N, 4, 4)`` (one configuration ``(n,)`` → ``(4, 4)``)."""
        Q, single = _configurations(q, self.n)
        N = Q.shape[0]
        out = np.empty((N, 4, 4))
        flat = out.reshape(N, 16)
        flat[:, 12:15] = 0.0
        flat[:, 15] = 1.0
        # cells are the first 12 entries of the row-major 4x4
        evaluate_chunked(self._numpy(), Q, out=flat[:, :12], plus_zero=True)
        return out[0] if single else out


def compile_pose(
    matrix: sp.MatrixBase,
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
) -> PoseFunction:
    """Compile a 4×4 homogeneous ``matrix`` into a :class:`PoseFunction` of ``variables``.

    Parameters
    ----------
    matrix
        Exact symbolic transform whose free symbols are ``variables`` and the
        keys of ``values``.
    variables
        Joint variables, in the order of the configuration vector.
    values
        Numbers for the constant symbols (lengths, offsets).

    Raises
    ------
    DHError
        When a constant symbol has no value.
    """
    single, batch = _pose_cells(matrix, values)
    variables = tuple(variables)
    return PoseFunction(
        compile_exprs(single, variables, floats=True),
        compile_exprs(batch, variables),
        len(variables),
    )


def stored_pose_function(
    names: tuple[str, str] | None,
    matrix: Callable[[], sp.MatrixBase],
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
) -> PoseFunction:
    """:func:`compile_pose` of ``matrix()``, its two programs (floats, numpy) kept in the disk
    cache as entries ``names`` (:func:`stored_program`; ``None``: not kept); ``matrix`` is
    called only when they are absent or refused, the numpy code compiled on the first batch."""
    variables = tuple(variables)
    cells: list[tuple[list[sp.Basic], list[sp.Basic]]] = []

    def part(k: int) -> Callable[[], list[sp.Basic]]:
        def exprs() -> list[sp.Basic]:
            if not cells:
                cells.append(_pose_cells(matrix(), values))
            return cells[0][k]

        return exprs

    extra = {"_PlusZero": _PlusZero}
    single = stored_program(names and names[0], part(0), variables, extra)

    def make_batch() -> Callable[..., list[Any]]:  # on the first batch only
        batch = stored_program(names and names[1], part(1), variables, extra)
        return compile_program(batch, variables)

    return PoseFunction(
        compile_program(single, variables, floats=True), None, len(variables), make_batch=make_batch
    )


def _pose_cells(
    matrix: sp.MatrixBase, values: Mapping[sp.Symbol, sp.Expr] | None
) -> tuple[list[sp.Basic], list[sp.Basic]]:
    """What :func:`compile_pose` compiles: the 16 cells for floats (``-0.0`` read as
    ``0.0``) and the 12 of the top rows for numpy, constants folded."""
    M = sp.Matrix(matrix).subs(dict(values or {}))
    folded = [float_constants(M[i, j]) for i in range(3) for j in range(4)]
    cells = [_PlusZero(c) if c.free_symbols else c for c in folded]
    last_row = [sp.Float(0.0), sp.Float(0.0), sp.Float(0.0), sp.Float(1.0)]
    return [*cells, *last_row], folded


def compile_word(
    word: Sequence[Elementary],
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
    *,
    prefixes: bool = False,
) -> Callable[[object], np.ndarray]:
    """The product of a word of elementary transforms as numbers: ``Q (N, n) -> (N, 4, 4)``.

    ``word`` holds :class:`~dhsym.model.table.Elementary` transforms (kind, axis,
    value); their values are compiled once (:func:`compile_exprs`) and the
    4×4 factors multiplied numerically, so the cost grows linearly with the
    length of the word. One configuration ``(n,)`` gives ``(4, 4)``. With
    ``prefixes=True`` every partial product is returned: ``(N, len(word) + 1, 4, 4)``,
    the identity first.

    >>> from dhsym.model.table import Elementary as E
    >>> q1, a = sp.symbols("q1 a", real=True)
    >>> f = compile_word([E("R", "z", q1), E("T", "x", a)], (q1,), {a: 2})
    >>> f([np.pi / 2]).round(12)[:2, 3] + 0.0
    array([0., 2.])
    >>> f(np.zeros((3, 1))).shape
    (3, 4, 4)
    """
    vals = dict(values or {})
    variables = tuple(variables)
    word = tuple(word)
    exprs = [e.value.subs(vals) for e in word]
    fn = compile_exprs(exprs, variables)
    n = len(variables)

    def product(q: object) -> np.ndarray:
        Q, single = _configurations(q, n)
        result = _multiply(word, fn(*Q.T), Q.shape[0], prefixes)
        return result[0] if single else result

    return product


def compile_matrix(
    matrix: sp.MatrixBase,
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
) -> Callable[[object], np.ndarray]:
    """A vectorised numpy function for any ``m × k`` matrix (a Jacobian, say).

    One configuration ``(n,)`` gives ``(m, k)``; a batch ``(N, n)`` gives ``(N, m, k)``.

    >>> q1 = sp.Symbol("q1", real=True)
    >>> f = compile_matrix(sp.Matrix([[sp.cos(q1), 0], [sp.sin(q1), 1]]), (q1,))
    >>> f([0.0])
    array([[1., 0.],
           [0., 1.]])
    >>> f(np.zeros((3, 1))).shape
    (3, 2, 2)
    """
    M = sp.Matrix(matrix).subs(dict(values or {}))
    rows, cols = M.shape
    variables = tuple(variables)
    fn = compile_exprs(list(M), variables)
    n = len(variables)

    def evaluate(q: object) -> np.ndarray:
        Q, single = _configurations(q, n)
        N = Q.shape[0]
        flat = evaluate_chunked(fn, Q, out=np.empty((N, rows * cols)), plus_zero=True)
        out = flat.reshape(N, rows, cols)
        return out[0] if single else out

    return evaluate


def values_key(values: Mapping[Any, object] | None) -> object:
    """A hashable cache key for ``values`` as given (None when none): what compiled
    functions of a robot (fk, Jacobian, IK solver) are cached by.

    >>> values_key(None), values_key({"a2": 0.43}) == values_key({"a2": 0.43})
    (None, True)
    """
    if not values:
        return None
    try:
        return frozenset(values.items())
    except TypeError:  # an unhashable value: fall back to its text
        return frozenset((str(k), str(v)) for k, v in values.items())


def _configurations(q: object, n: int) -> tuple[np.ndarray, bool]:
    """Joint values as a batch ``(N, n)``, and whether one configuration ``(n,)`` was given."""
    arr = np.asarray(q, dtype=float)
    single = arr.ndim <= 1
    Q = arr.reshape(1, -1) if single else arr
    if Q.shape[-1] != n:
        raise DHError(f"expected {n} joint values per configuration, got {Q.shape[-1]}")
    return Q, single


# --- the numeric twin of the transform kernel ---------------------------------------------


def elementary_stack(kind: str, axis: str, value: object) -> np.ndarray:
    """The ``(N, 4, 4)`` matrices of one elementary transform at ``N`` values.

    The numeric twin of :func:`~dhsym.kinematics.transforms.elementary_matrix`
    (``kind`` ``"R"`` or ``"T"``, ``axis`` ``"x"``, ``"y"`` or ``"z"``).

    >>> elementary_stack("R", "z", [np.pi / 2])[0].round(12) + 0.0
    array([[ 0., -1.,  0.,  0.],
           [ 1.,  0.,  0.,  0.],
           [ 0.,  0.,  1.,  0.],
           [ 0.,  0.,  0.,  1.]])
    >>> elementary_stack("T", "x", np.array([2.0, 3.0]))[:, 0, 3]
    array([2., 3.])
    """
    value = np.asarray(value, dtype=float)
    out = np.zeros((value.shape[0], 4, 4))
    out[:, 0, 0] = out[:, 1, 1] = out[:, 2, 2] = out[:, 3, 3] = 1.0
    i = "xyz".index(axis)
    if kind == "T":
        out[:, i, 3] = value
        return out
    j, k = (i + 1) % 3, (i + 2) % 3
    c, s = np.cos(value), np.sin(value)
    out[:, j, j] = out[:, k, k] = c
    out[:, j, k], out[:, k, j] = -s, s
    return out


def _multiply(
    word: Sequence[Elementary], values: Sequence[object], size: int, prefixes: bool
) -> np.ndarray:
    """The product of ``word`` (``(size, 4, 4)``; with ``prefixes`` every partial product,
    ``(size, len(word) + 1, 4, 4)``, the identity first) given each factor's values.

    A factor whose exact value is zero is the identity and is not multiplied.
    """
    out = [np.broadcast_to(np.eye(4), (size, 4, 4))]
    for e, v in zip(word, values, strict=True):
        if e.value.is_zero:  # an exact zero; no sympify per call
            out.append(out[-1])
            continue
        v = np.asarray(v, dtype=float)
        if v.shape != (size,):  # a constant repeated (np.broadcast_to costs more)
            v = np.full(size, v)
        factor = elementary_stack(e.kind, e.axis, v)
        out.append(out[-1] @ factor)
    return np.stack(out, axis=1) if prefixes else np.array(out[-1])


def word_product(
    word: Sequence[Elementary],
    env: Mapping[sp.Basic, np.ndarray | float],
    size: int,
    *,
    prefixes: bool = False,
    memo: dict[object, np.ndarray] | None = None,
) -> np.ndarray:
    """The product of a word of elementary transforms at ``size`` points: ``(size, 4, 4)``.

    ``env`` maps each symbol to its values (:func:`evaluate`); with ``prefixes`` every
    partial product is returned, ``(size, len(word) + 1, 4, 4)``, the identity first;
    ``memo`` is :func:`evaluate`'s, shared by words with the same ``env``. For one-off
    words (no code generation); :func:`compile_word` compiles a word used often.

    >>> from dhsym.model.table import Elementary as E
    >>> t = sp.Symbol("t")
    >>> M = word_product([E("R", "z", t), E("T", "x", 2)], {t: np.array([0.0, np.pi / 2])}, 2)
    >>> np.round(M[:, :2, 3], 12) + 0.0
    array([[2., 0.],
           [0., 2.]])
    """
    memo = {} if memo is None else memo
    values = evaluate_many([e.value for e in word], env, size, memo)
    return _multiply(word, list(values), size, prefixes)


def numeric_rigid_inverse(T: np.ndarray) -> np.ndarray:
    """Inverse of homogeneous transforms ``(..., 4, 4)`` as ``[Rᵀ, −Rᵀp; 0 0 0 1]``.

    The numeric twin of :func:`~dhsym.kinematics.transforms.rigid_inverse`.

    >>> T = elementary_stack("R", "z", [0.3]) @ elementary_stack("T", "x", [2.0])
    >>> np.allclose(numeric_rigid_inverse(T) @ T, np.eye(4))
    True
    """
    T = np.asarray(T, dtype=float)
    out = np.zeros_like(T)
    R = np.swapaxes(T[..., :3, :3], -1, -2)
    out[..., :3, :3] = R
    out[..., :3, 3] = -(R @ T[..., :3, 3, None])[..., 0]
    out[..., 3, 3] = 1.0
    return out
