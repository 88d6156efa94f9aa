"""Numbers from the symbolic result: code generated once with CSE, vectorised.

There is no second numeric kinematics path: :func:`compile_pose` lambdifies
the simplified symbolic matrix (with common-subexpression elimination) into a
function that takes one configuration ``(n,)`` or a batch ``(N, n)`` and gives
``(4, 4)`` or ``(N, 4, 4)``.  A chain too long for one closed form is compiled
in parts and :func:`compose_numeric` multiplies them.

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

from .errors import DHError

__all__ = ["compile_chain", "compile_pose", "compose_numeric"]

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
    fn = _lambdify([matrix], variables, values)
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
    """``q`` as an ``(N, n)`` batch, and whether it was one configuration."""
    arr = np.asarray(q, dtype=float)
    single = arr.ndim <= 1
    Q = arr.reshape(1, -1) if single else arr
    if Q.shape[-1] != n:
        raise DHError(f"expected {n} joint values per configuration, got {Q.shape[-1]}")
    return Q, single


def _lambdify(
    matrices: Sequence[sp.MatrixBase],
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None,
) -> Callable:
    """One generated function for the top 3×4 entries of every matrix, in order."""
    exprs = []
    for matrix in matrices:
        M = sp.Matrix(matrix).subs(dict(values or {}))
        missing = M.free_symbols - set(variables)
        if missing:
            names = ", ".join(sorted(str(s) for s in missing))
            raise DHError(f"no numeric value for {names}: give values for these symbols")
        exprs += [M[i, j] for i in range(3) for j in range(4)]
    return sp.lambdify(list(variables), exprs, modules="numpy", cse=True)


def compile_chain(
    matrices: Sequence[sp.MatrixBase],
    variables: Sequence[sp.Symbol],
    values: Mapping[sp.Symbol, sp.Expr] | None = None,
    *,
    cumulative: bool = False,
) -> FkFunction:
    """Like :func:`compile_pose` for the product of ``matrices``, multiplied numerically.

    For a chain whose closed form is too large to write out: the parts are small,
    generated as one function, and their product is taken per configuration.  With
    ``cumulative`` the function returns every partial product ``M1, M1 M2, …``
    (shape ``(k, 4, 4)``, or ``(k, N, 4, 4)`` for a batch).

    >>> import sympy as sp
    >>> q1 = sp.Symbol("q1", real=True)
    >>> Rz = sp.ImmutableMatrix([[sp.cos(q1), -sp.sin(q1), 0, 1], [sp.sin(q1), sp.cos(q1), 0, 0],
    ...                          [0, 0, 1, 0], [0, 0, 0, 1]])
    >>> np.round(compile_chain([Rz, Rz], (q1,))([np.pi / 2])[:2, 3], 12).tolist()
    [1.0, 1.0]
    """
    fn = _lambdify(matrices, variables, values)
    n, k = len(variables), len(matrices)

    def fk(q: object) -> np.ndarray:
        Q, single = _configurations(q, n)
        cells = fn(*Q.T)
        parts = np.zeros((k, Q.shape[0], 4, 4))
        parts[:, :, 3, 3] = 1.0
        for m, v in enumerate(cells):
            parts[m // 12, :, (m % 12) // 4, m % 4] = v
        products = [parts[0]]
        for part in parts[1:]:
            products.append(products[-1] @ part)
        if cumulative:
            stack = np.stack(products) + 0.0
            return stack[:, 0] if single else stack
        out = products[-1] + 0.0
        return out[0] if single else out

    return fk


def compose_numeric(parts: Sequence[FkFunction], *, invert: bool = False) -> FkFunction:
    """``q -> parts[0](q) @ parts[1](q) @ …`` (the rigid inverse of that with ``invert``).

    >>> import sympy as sp
    >>> q1 = sp.Symbol("q1", real=True)
    >>> Rz = sp.ImmutableMatrix([[sp.cos(q1), -sp.sin(q1), 0, 1], [sp.sin(q1), sp.cos(q1), 0, 0],
    ...                          [0, 0, 1, 0], [0, 0, 0, 1]])
    >>> f = compose_numeric([compile_pose(Rz, (q1,))] * 2)
    >>> np.round(f([np.pi / 2])[:2, 3], 12).tolist()
    [1.0, 1.0]
    >>> np.round(compose_numeric([f], invert=True)([np.pi / 2]) @ f([np.pi / 2]), 12)[0].tolist()
    [1.0, 0.0, 0.0, 0.0]
    """

    def fk(q: object) -> np.ndarray:
        out = parts[0](q)
        for part in parts[1:]:
            out = out @ part(q)
        if invert:
            R = np.swapaxes(out[..., :3, :3], -1, -2)
            inv = np.zeros_like(out)
            inv[..., :3, :3] = R
            inv[..., :3, 3] = -(R @ out[..., :3, 3:4])[..., 0]
            inv[..., 3, 3] = 1.0
            out = inv
        return out + 0.0

    return fk
