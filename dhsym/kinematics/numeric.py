"""The one numeric evaluator of exact expressions: constants folded to floats, code compiled once.

Every numeric path of dhsym (``fk``, compiled poses, :func:`numeric_equal
<dhsym.kinematics.simplification.numeric_equal>`, the checks of frame assignment
and conversion) goes through this module:

* :func:`to_float` evaluates an exact constant (huge integers, nested roots, π)
  with arbitrary precision and returns a float, or raises :class:`~dhsym.errors.DHError`;
* :func:`float_constants` replaces every constant subtree of an expression by its
  float, at compile time, so generated code sees floats only (never a Python
  integer beyond 2⁶³ under ``sqrt``);
* :func:`compile_exprs` generates code once (common-subexpression elimination)
  for numpy arrays or for plain Python floats;
* :func:`compile_pose` builds a :class:`PoseFunction` for a 4×4 homogeneous
  matrix: a pure-float path for one configuration ``(n,)`` → ``(4, 4)`` and a
  numpy path for a batch ``(N, n)`` → ``(N, 4, 4)``;
* :func:`compile_word` multiplies a word of elementary transforms numerically
  (no symbolic product at all: the check of a 10-joint conversion takes
  milliseconds whatever its twists);
* :func:`evaluate` walks one expression at many points at once, without code
  generation (the checker's one-off expressions: a student's answer at 64 random
  points), its constants through :func:`to_float`; :func:`word_product` is the same
  for a word of elementary transforms;
* :func:`elementary_stack` is the numeric twin of
  :func:`~dhsym.kinematics.transforms.elementary_matrix` (the word is shared: words
  come from :mod:`dhsym.kinematics.transforms`), and :func:`numeric_rigid_inverse`
  the twin of :func:`~dhsym.kinematics.transforms.rigid_inverse`.

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
>>> huge = sp.sqrt(sp.Integer(10) ** 40 + 1) / 10**20
>>> to_float(huge), float_constants(huge * q1)
(1.0, 1.0*q1)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np
import sympy as sp

from dhsym.errors import DHError

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from dhsym.model.table import Elementary

__all__ = [
    "EvaluationError",
    "as_basic",
    "PoseFunction",
    "Program",
    "compile_exprs",
    "compile_program",
    "stored_pose_function",
    "stored_program",
    "compile_matrix",
    "compile_pose",
    "compile_word",
    "elementary_stack",
    "evaluate",
    "evaluate_many",
    "float_constants",
    "numeric_rigid_inverse",
    "to_float",
    "values_key",
    "word_product",
]

FkFunction = Callable[[object], np.ndarray]
_CHUNK = 4096
_DIGITS = 30  # working precision of constant evaluation (decimal digits)
_FLOAT = np.dtype(float)
_EXACT_INT = 2**53


class _PlusZero(sp.Function):
    """``x + 0.0`` in the float code: ``-0.0`` becomes ``0.0``, so printed poses read cleanly."""

    def _pythoncode(self, printer: Any) -> str:  # a sympy code printer (untyped)
        return f"({printer._print(self.args[0])} + 0.0)"


def to_float(expr: object) -> float:
    """The value of an exact real constant as a float (evaluated at 30 digits first).

    Safe for integers far beyond 2⁶³, nested roots and π; raises
    :class:`~dhsym.errors.DHError` for symbols, non-real or non-finite values.

    >>> to_float(sp.sqrt(2) / 2), to_float(sp.pi), to_float(sp.Integer(7) ** 400 / 7 ** 399)
    (0.7071067811865476, 3.141592653589793, 7.0)
    >>> to_float(sp.Integer(10) ** 400)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: the number 1000000000000...0000000000000 is too large for a float
    >>> to_float(sp.zoo)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: zoo is not a real number
    """
    if isinstance(expr, float):
        value = expr
    else:
        e = as_basic(expr)
        if e.free_symbols:
            raise DHError(f"no numeric value for {', '.join(sorted(map(str, e.free_symbols)))}")
        if e.is_Rational:
            value = _rational_float(e)
        elif e.is_Float:
            value = float(e)
        elif (turn := _pi_multiple(e)) is not None:  # θ = π/2 in a table: no evalf
            value = float(turn * _PI)
        else:
            v = sp.N(e, _DIGITS)
            re, im = v.as_real_imag()
            real = re.is_Number and im.is_Number and sp.nan not in (re, im)
            if not real or abs(im) > abs(re) * 1e-20 + 1e-40:  # below the 30 digits: round-off
                raise DHError(f"{_short(e)} is not a real number")
            value = float(re) if re.is_finite else math.inf
    if not math.isfinite(value):
        raise DHError(f"the number {_short(expr)} is too large for a float")
    return value


#: π to 60 digits, exact as a fraction: ``float(r * _PI)`` is the rounded value of ``r·π``
_PI = Fraction(314159265358979323846264338327950288419716939937510582097494, 10**59)


def _pi_multiple(e: sp.Basic) -> Fraction | None:
    """``r`` when ``e`` is ``π`` or ``r·π`` with a rational ``r`` (an angle of a table), else None.

    >>> _pi_multiple(-sp.pi / 2), _pi_multiple(sp.pi), _pi_multiple(sp.sqrt(2))
    (Fraction(-1, 2), Fraction(1, 1), None)
    """
    if e is sp.pi:
        return Fraction(1)
    if e.is_Mul and len(e.args) == 2 and e.args[1] is sp.pi and e.args[0].is_Rational:
        r = e.args[0]
        return Fraction(int(r.p), int(r.q))
    return None


def _rational_float(r: sp.Rational) -> float:
    try:
        return int(r.p) / int(r.q)  # exact rounding, even for huge integers
    except OverflowError:
        return math.inf


def _short(expr: object) -> str:
    s = str(expr)
    return s if len(s) <= 60 else f"{s[:30]}...{s[-30:]}"


def float_constants(expr: sp.Basic) -> sp.Basic:
    """``expr`` with every constant subtree replaced by its float (integer exponents kept).

    >>> x = sp.Symbol("x")
    >>> float_constants(sp.sqrt(2) * sp.cos(x + sp.pi / 3) - x**2 / 4)
    -0.25*x**2 + 1.4142135623730951*cos(x + 1.0471975511965979)
    """
    memo: dict[sp.Basic, sp.Basic] = {}

    def walk(e: sp.Basic) -> sp.Basic:
        hit = memo.get(e)
        if hit is not None:
            return hit
        if not e.free_symbols:
            small = e.is_Integer and abs(int(e)) <= _EXACT_INT  # ±1, 2: exact in floats too
            out: sp.Basic = e if small or not isinstance(e, sp.Expr) else sp.Float(to_float(e), 17)
        elif e.is_Atom:
            out = e
        elif e.is_Pow and e.exp.is_Integer:
            out = sp.Pow(walk(e.base), e.exp)
        elif e.is_Add or e.is_Mul:  # fold the constant part as one number
            const, rest = e.as_independent(*e.free_symbols, as_Add=e.is_Add)
            out = e.func(walk(const), *(walk(a) for a in e.func.make_args(rest)))
        else:
            out = e.func(*(walk(a) for a in e.args))
        memo[e] = out
        return out

    return walk(as_basic(expr))


def as_basic(value: object) -> sp.Basic:
    """A sympy object for a sympy object or a Python/numpy number; text is refused.

    Nothing here parses or evaluates a string (``sympy.sympify`` would): text goes
    through :func:`dhsym.model.parsing.parse_expression` first.

    >>> as_basic(3), as_basic(0.5), as_basic(sp.Symbol("t"))
    (3, 0.500000000000000, t)
    >>> as_basic("__import__('os')")
    Traceback (most recent call last):
    ...
    TypeError: expected a sympy expression or a number, got str
    """
    if hasattr(value, "dtype") and hasattr(value, "item"):  # numpy scalar
        value = value.item()
    if isinstance(value, sp.Basic):
        return value
    if isinstance(value, int) and not isinstance(value, bool):
        return sp.Integer(value)
    if isinstance(value, float):
        return sp.Float(value)
    raise TypeError(f"expected a sympy expression or a number, got {type(value).__name__}")


@dataclass(frozen=True)
class Program:
    """What :func:`compile_exprs` turns into code: the expressions with their constants
    folded to floats, their shared subexpressions named (``assignments``, in order) and
    the ``outputs`` written with those names. Plain expressions: the disk cache keeps a
    program (:mod:`dhsym.cache.codec`) and :func:`compile_program` compiles it again.

    >>> x, y = sp.symbols("x y")
    >>> p = Program.of([sp.sqrt(3) * sp.sin(x + y), sp.cos(x + y) * sp.sin(x + y)], (x, y))
    >>> p.assignments, p.outputs
    (((x0, x + y), (x1, sin(x0))), (1.7320508075688772*x1, x1*cos(x0)))
    """

    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    outputs: tuple[sp.Expr, ...]

    @classmethod
    def of(cls, exprs: Sequence[sp.Basic], variables: Sequence[sp.Symbol]) -> Program:
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
    program: Program, variables: Sequence[sp.Symbol], *, floats: bool = False
) -> Callable[..., list[Any]]:
    """Compile a :class:`Program` into ``f(*variables) -> list`` (numpy arrays, or plain
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
) -> Program:
    """The :class:`Program` of ``exprs()`` for ``variables``, kept in the disk cache as entry
    ``name`` (:mod:`dhsym.cache`: verified when read; ``None`` or the cache turned off:
    not kept). ``exprs`` is called only when the entry is absent or refused; ``extra``
    names dhsym's own functions the program may hold (:func:`dhsym.cache.codec.read_exprs`)."""
    from dhsym.cache.codec import CodecError, read_exprs, write_exprs
    from dhsym.cache.store import default_store

    store = default_store() if name is not None else None
    data = store.read(name) if store is not None and name is not None else None
    if data is not None:
        try:
            lhs, rhs, outputs = read_exprs(data, extra)
            return Program(tuple(zip(lhs.args, rhs.args)), tuple(outputs.args))
        except (CodecError, ValueError, AttributeError):
            pass  # not a program this version reads: derive it again
    program = Program.of(exprs(), variables)
    if store is not None and name is not None:
        try:
            lhs_rhs = [sp.Tuple(*(s for s, _ in program.assignments))]
            lhs_rhs.append(sp.Tuple(*(e for _, e in program.assignments)))
            text = write_exprs([*lhs_rhs, sp.Tuple(*program.outputs)], extra)
        except CodecError:
            return program  # a class the codec does not write: kept in this process only
        store.write(name, text.encode())
    return program


def compile_exprs(
    exprs: Sequence[sp.Basic], variables: Sequence[sp.Symbol], *, floats: bool = False
) -> Callable[..., list[Any]]:
    """Compile ``exprs`` once into ``f(*variables) -> list`` (numpy arrays, or plain floats).

    Constants are folded to floats first (:func:`float_constants`); symbols
    other than ``variables`` raise :class:`~dhsym.errors.DHError`. With
    ``floats=True`` the code uses :mod:`math` and takes Python floats (fast for
    one point); otherwise numpy, elementwise over arrays. The steps are
    :meth:`Program.of` and :func:`compile_program`.

    >>> x, y = sp.symbols("x y")
    >>> compile_exprs([sp.sqrt(3) * x, x + y], (x, y), floats=True)(2.0, 1.0)
    [3.4641016151377544, 3.0]
    >>> compile_exprs([x * y], (x,))
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: no numeric value for y: give values for these symbols
    """
    return compile_program(Program.of(exprs, variables), variables, floats=floats)


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
        # cache-sized chunks: the temporaries stay in L2 (about 2x faster for large N)
        for start in range(0, N, _CHUNK):
            block = flat[start : start + _CHUNK]
            for k, v in enumerate(self._numpy()(*Q[start : start + _CHUNK].T)):
                block[:, k] = v  # cells are the first 12 entries of the row-major 4x4
            block[:, :12] += 0.0  # -0.0 -> 0.0, so printed poses read cleanly
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
        flat = np.empty((N, rows * cols))
        for start in range(0, N, _CHUNK):
            block = flat[start : start + _CHUNK]
            for k, v in enumerate(fn(*Q[start : start + _CHUNK].T)):
                block[:, k] = v
        flat += 0.0  # -0.0 -> 0.0
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
        factor = elementary_stack(e.kind, e.axis, v if v.shape == (size,) else _points(v, size))
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


# --- one-off expressions at many points ----------------------------------------------------


class EvaluationError(DHError, ValueError):
    """An expression that has no numeric value: an unknown function, a symbol without
    values, a constant that is not a real float (``zoo``, ``10**400``)."""


_UNARY = {sp.sin: np.sin, sp.cos: np.cos, sp.tan: np.tan}
_UNARY |= {sp.atan: np.arctan, sp.asin: np.arcsin, sp.acos: np.arccos}
_CONSTANT = object()  # the walker's mark of a subtree without symbols


def evaluate(
    expr: sp.Basic,
    env: Mapping[sp.Basic, np.ndarray | float],
    size: int,
    memo: dict[object, np.ndarray] | None = None,
) -> np.ndarray:
    """Values of ``expr`` at ``size`` points (``(size,)``); ``env`` maps each symbol to its values.

    A tree walker (no code generation, no ``lambdify``): each node is one numpy
    operation over all points, shared subtrees are computed once, and every subtree
    without symbols is one constant evaluated exactly by :func:`to_float` (huge
    integers, nested roots). Non-finite results (division by zero, overflow at a
    point) come out as ``nan``/``inf``; an expression without a value raises
    :class:`EvaluationError`. ``memo`` (subtree → values) may be shared by calls with
    the same ``env`` (the entries of one matrix).

    >>> x = sp.Symbol("x")
    >>> evaluate(sp.cos(x) ** 2 + sp.sin(x) ** 2, {x: np.array([0.3, 1.2])}, 2)
    array([1., 1.])
    >>> evaluate(x * sp.sqrt(sp.Integer(10) ** 40 + 1) / 10**20, {x: np.array([2.0])}, 1)
    array([2.])
    """
    memo = {} if memo is None else memo
    try:
        with np.errstate(all="ignore"):
            out = _walk(expr, env, memo)
            if out is _CONSTANT:
                out = _constant(expr, memo)
    except (OverflowError, ZeroDivisionError) as err:  # e.g. x**(10**400)
        raise EvaluationError(f"cannot evaluate numerically ({type(err).__name__})") from None
    return _points(out, size)


def evaluate_many(
    exprs: Sequence[sp.Basic],
    env: Mapping[sp.Basic, np.ndarray | float],
    size: int,
    memo: dict[object, np.ndarray] | None = None,
) -> np.ndarray:
    """Values of several expressions at ``size`` points: shape ``(len(exprs), size)``.

    One walk over all of them (:func:`evaluate`'s rules), their shared subtrees computed
    once: the entries of a matrix, the factors of a word.  The first expression without
    a value raises :class:`EvaluationError`.

    >>> x = sp.Symbol("x")
    >>> evaluate_many([sp.cos(x), 2 * sp.cos(x), sp.pi / 2], {x: np.array([0.0, np.pi])}, 2)
    array([[ 1.        , -1.        ],
           [ 2.        , -2.        ],
           [ 1.57079633,  1.57079633]])
    """
    memo = {} if memo is None else memo
    out = np.empty((len(exprs), size))
    try:
        with np.errstate(all="ignore"):
            for k, expr in enumerate(exprs):
                val = _walk(expr, env, memo)
                out[k] = _points(_constant(expr, memo) if val is _CONSTANT else val, size)
    except (OverflowError, ZeroDivisionError) as err:  # e.g. x**(10**400)
        raise EvaluationError(f"cannot evaluate numerically ({type(err).__name__})") from None
    return out


def _points(value: object, size: int) -> np.ndarray:
    """A walker's result as a fresh float array of ``size`` points (a constant repeated)."""
    points: np.ndarray = np.broadcast_to(np.asarray(value, dtype=float), (size,)).copy()
    return points


def _constant(e: sp.Basic, memo: dict[object, np.ndarray]) -> np.ndarray:
    key = ("constant", e)
    hit = memo.get(key)
    if hit is None:
        try:
            hit = memo[key] = np.asarray(to_float(e))
        except DHError as err:
            raise EvaluationError(err.message) from None
    return hit


def _walk(
    e: sp.Basic, env: Mapping[sp.Basic, np.ndarray | float], memo: dict[object, np.ndarray]
) -> Any:
    """Values of ``e`` at every point, or :data:`_CONSTANT` for a subtree without symbols.

    (``Any``: an ``np.ndarray`` or the ``_CONSTANT`` mark, told apart by ``is``.)
    """
    hit = memo.get(e)
    if hit is not None:
        return hit
    if e.is_Symbol:
        if e not in env:
            raise EvaluationError(f"no value for symbol {e}")
        memo[e] = val = np.asarray(env[e], dtype=float)
        return val
    if not e.args:  # a number, pi, I, zoo, ...
        return _CONSTANT
    parts = [_walk(a, env, memo) for a in e.args]
    if all(p is _CONSTANT for p in parts):
        return _CONSTANT
    if e.is_Pow and parts[1] is _CONSTANT and e.exp.is_Integer:
        base, k = parts[0], int(e.exp)
        val = base**k if k >= 0 else 1.0 / base ** (-k)
    elif e.is_Pow and parts[1] is _CONSTANT and e.exp == sp.S.Half:
        val = np.sqrt(parts[0])
    else:
        args = [_constant(a, memo) if p is _CONSTANT else p for a, p in zip(e.args, parts)]
        val = _apply(e, args)
    memo[e] = val
    return val


def _apply(e: sp.Basic, args: list[np.ndarray]) -> np.ndarray:
    val: np.ndarray
    if e.is_Add:
        val = args[0]
        for a in args[1:]:
            val = val + a
        return val
    if e.is_Mul:
        val = args[0]
        for a in args[1:]:
            val = val * a
        return val
    if e.is_Pow:
        val = np.power(args[0], args[1])
        return val
    if type(e) in _UNARY:
        val = _UNARY[type(e)](args[0])
        return val
    if isinstance(e, sp.atan2):
        val = np.arctan2(args[0], args[1])
        return val
    raise EvaluationError(f"cannot evaluate {type(e).__name__} numerically")
