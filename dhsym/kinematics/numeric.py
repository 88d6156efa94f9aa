"""Numbers from the symbolic result: code generated once with CSE, vectorised.

There is no second numeric kinematics path: :func:`compile_pose` lambdifies
the simplified symbolic matrix (with common-subexpression elimination) into a
function that takes one configuration ``(n,)`` or a batch ``(N, n)`` and gives
``(4, 4)`` or ``(N, 4, 4)``.

Examples
--------
>>> import sympy as sp
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

import numpy as np
import sympy as sp

from dhsym.errors import DHError

__all__ = ["compile_matrix", "compile_pose"]

FkFunction = Callable[[object], np.ndarray]
_CHUNK = 4096


def compile_pose(
    matrix: sp.MatrixBase,
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
) -> FkFunction:
    """Generate a vectorised numpy function for a 4×4 homogeneous ``matrix``.

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
    M = _substituted(matrix, variables, values)
    exprs = [M[i, j] for i in range(3) for j in range(4)]
    # numpy's namespace as a module: modules="numpy" would run `from numpy import *`, which
    # imports all of numpy's lazy submodules (as long as importing numpy itself)
    fn = sp.lambdify(list(variables), exprs, modules=[np], cse=True)
    n = len(variables)

    def fk(q: object) -> np.ndarray:
        Q, single = _configurations(q, n)
        N = Q.shape[0]
        out = np.empty((N, 4, 4))
        flat = out.reshape(N, 16)
        flat[:, 12:15] = 0.0
        flat[:, 15] = 1.0
        # cache-sized chunks: the temporaries stay in L2 (about 2x faster for large N)
        for start in range(0, N, _CHUNK):
            block = flat[start : start + _CHUNK]
            for k, v in enumerate(fn(*Q[start : start + _CHUNK].T)):
                block[:, k] = v  # cells are the first 12 entries of the row-major 4x4
            block[:, :12] += 0.0  # -0.0 -> 0.0, so printed poses read cleanly
        return out[0] if single else out

    return fk


def _configurations(q: object, n: int) -> tuple[np.ndarray, bool]:
    """``q`` as a batch ``(N, n)``, and whether it was one configuration."""
    arr = np.asarray(q, dtype=float)
    single = arr.ndim <= 1
    Q = arr.reshape(1, -1) if single else arr
    if Q.shape[-1] != n:
        raise DHError(f"expected {n} joint values per configuration, got {Q.shape[-1]}")
    return Q, single


def _substituted(
    matrix: sp.MatrixBase,
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None,
) -> sp.Matrix:
    """``matrix`` with ``values`` substituted; every other symbol must be a variable."""
    M = sp.Matrix(matrix).subs(dict(values or {}))
    missing = M.free_symbols - set(variables)
    if missing:
        names = ", ".join(sorted(str(s) for s in missing))
        raise DHError(f"no numeric value for {names}: give values for these symbols")
    return M


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
    M = _substituted(matrix, variables, values)
    rows, cols = M.shape
    fn = sp.lambdify(list(variables), list(M), modules="numpy", cse=True)
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
