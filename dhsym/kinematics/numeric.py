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

__all__ = ["compile_pose"]

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
    M = sp.Matrix(matrix).subs(dict(values or {}))
    missing = M.free_symbols - set(variables)
    if missing:
        names = ", ".join(sorted(str(s) for s in missing))
        raise DHError(f"no numeric value for {names}: give values for these symbols")
    exprs = [M[i, j] for i in range(3) for j in range(4)]
    # numpy's namespace as a module: modules="numpy" would run `from numpy import *`, which
    # imports all of numpy's lazy submodules (as long as importing numpy itself)
    fn = sp.lambdify(list(variables), exprs, modules=[np], cse=True)
    n = len(variables)

    def fk(q: object) -> np.ndarray:
        arr = np.asarray(q, dtype=float)
        single = arr.ndim <= 1
        Q = arr.reshape(1, -1) if single else arr
        if Q.shape[-1] != n:
            raise DHError(f"expected {n} joint values per configuration, got {Q.shape[-1]}")
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
