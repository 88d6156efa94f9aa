"""Numbers of the equations of motion, compiled once and batched like ``fk``.

τ is the Newton–Euler recursion evaluated on numbers (:mod:`.numeric_recursion`, the
recursion of :mod:`.recursive_newton_euler` on float arrays: no symbolic derivation
before the first numbers; the tests prove it equal to the exact τ, M and g); with
roboticstoolbox's names:

* ``rne(q, qd, qdd)``: joint torques, with ``Jm G²`` and friction ``B G² q̇ + |G| Tc``;
* ``inertia(q)``: M(q) (with ``Jm G²``), ``M[:, j] = τ(q, 0, e_j)`` without gravity;
* ``coriolis(q, qd)``: C(q, q̇) from the Christoffel symbols
  ``c_jk = ½ ∂²τ(q, q̇, 0)/∂q̇_j∂q̇_k`` (so ``C @ qd`` is the velocity term);
* ``gravload(q)``: g(q); ``accel(q, qd, tau)``: forward dynamics; ``simulate``: RK4.

Every argument is one state ``(n,)`` or a batch ``(..., n)``: the table's joint variables,
their rates and accelerations, whatever the rate of a variable in its cell (the Jaco's
``theta: -theta1``; :mod:`.model`), and τ their generalized forces; motor inertia and
friction are defined on these variables.

A long run of small calls (a simulation, a controller) switches after
:data:`COMPILE_AFTER` of them from the numeric recursion to τ written out once as a
straight-line program (:class:`~dhsym.kinematics.numeric.NumericProgram`, kept in the
disk cache). With a :class:`NativeRowsCompiler` (the facade passes the export room's C
when a compiler is there, :func:`dhsym.export.shared_library.native_rows`) that program
runs as native code, row by row, in buffers made once: one state of ``rne`` is one call
into C; otherwise it is compiled for Python floats. Batches stay on the recursion.

Examples
--------
>>> from dhsym.kinematics.chain import KinematicChain
>>> from dhsym.model.tablefile import read_table_text
>>> pendulum = KinematicChain(read_table_text('''
... gravity: [0, -9.81, 0]
... joints: [{type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}]
... '''))
>>> f = dynamics_functions(pendulum)
>>> f.gravload([0.0]), f.inertia([0.0]), f.rne([[0.0], [0.0]], [[0.0], [1.0]], [[1.0], [0.0]])
(array([9.81]), array([[0.6]]), array([[10.41],
       [ 9.81]]))
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Protocol, TypeGuard

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.numeric import (
    NumericProgram,
    compile_program,
    evaluate_chunked,
    stored_program,
    to_float,
)
from dhsym.model.parsing import REAL

from .lagrange_euler import potential_energies
from .model import DynamicModel, dynamic_model
from .numeric_recursion import NumericRecursion, numeric_recursion
from .recursive_newton_euler import rne_expressions

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

#: a call with at most this many states is "small" (one state, or ``accel``'s n + 1)
SMALL = 64
#: small calls answered by the numeric recursion before τ is compiled for them: a
#: simulation (thousands of small calls) then runs on the compiled program, about ten
#: times faster per state, while a first answer never waits for a derivation
COMPILE_AFTER = 256

__all__ = [
    "DynamicsFunctions",
    "NativeRowsCompiler",
    "NativeRun",
    "Trajectory",
    "dynamics_functions",
    "numeric_model",
]

#: a program in native code bound to its caller's buffers: ``run(m)`` evaluates the
#: first ``m`` rows of the input buffer into the first ``m`` rows of the output buffer
NativeRun = Callable[[int], None]


class NativeRowsCompiler(Protocol):
    """A compiler of a straight-line program of floats into native code evaluated row by
    row: the facade passes the export room's C
    (:func:`dhsym.export.shared_library.native_rows`) when a C compiler is there; the
    dynamics room never imports it.

    Called with the program, its variables (one column of ``inputs`` each, in order) and
    the caller's buffers ``inputs`` ``(R, len(variables))`` and ``outputs``
    ``(R, len(program.outputs))`` (C-contiguous floats); returns a :data:`NativeRun` bound
    to them, or ``None`` when it cannot build one (the program compiled for Python floats
    answers instead, with the same numbers).
    """

    def __call__(
        self,
        program: NumericProgram,
        variables: Sequence[sp.Symbol],
        inputs: np.ndarray,
        outputs: np.ndarray,
    ) -> NativeRun | None: ...


class _Compiled:
    """``f(*arrays)`` of compiled expressions into an array ``(..., *shape)``; the
    expressions (``exprs()``) are written out and code generated on first use (numpy for
    batches, plain floats for one state); their program is kept in the disk cache as
    ``entry`` when given (:func:`~dhsym.kinematics.numeric.stored_program`)."""

    def __init__(
        self,
        exprs: Callable[[], Sequence[sp.Expr]],
        args: Sequence[sp.Symbol],
        shape: tuple[int, ...],
        entry: str | None = None,
    ) -> None:
        self.shape = shape
        self.size = int(np.prod(shape)) if shape else 1
        self._exprs = exprs
        self._args = list(args)
        self._entry = entry
        self._program: NumericProgram | None = None
        self._batch: Callable[..., list[Any]] | None = None
        self._single: Callable[..., list[Any]] | None = None

    def program(self) -> NumericProgram:
        """The program of the expressions (written out, or read from the disk cache, once)."""
        if self._program is None:
            self._program = stored_program(self._entry, self._exprs, self._args)
        return self._program

    def _compile(self, floats: bool) -> Callable[..., list[Any]]:
        return compile_program(self.program(), self._args, floats=floats)

    def __call__(self, *parts: np.ndarray) -> np.ndarray:
        lead = parts[0].shape[:-1]
        if not lead:  # one state: plain Python floats
            if self._single is None:
                self._single = self._compile(floats=True)
            values = self._single(*[x for p in parts for x in p.tolist()])
            return np.array(values, dtype=float).reshape(self.shape)
        if self._batch is None:
            self._batch = self._compile(floats=False)
        flat = [p.reshape(-1, p.shape[-1]) for p in parts]
        out = evaluate_chunked(self._batch, *flat, out=np.empty((flat[0].shape[0], self.size)))
        return out.reshape(*lead, *self.shape)


def _is_state(x: object, n: int) -> TypeGuard[np.ndarray]:
    """``x`` is one state as an array ``(n,)`` (the calls' path without broadcasting)."""
    return type(x) is np.ndarray and x.shape == (n,)


class _NativeRows:
    """τ(q, q̇, q̈, g) and the friction torque in native code for up to ``R`` rows at once:
    the buffers ``inputs`` ``(R, 3n + 3)`` (q, q̇, q̈, g per row) and ``outputs``
    ``(R, 2n)`` (τ, then the friction torque ``B G² q̇ + |G| Tc`` of the row's q̇), made
    once and shared under a lock; ``run`` the program bound to them."""

    def __init__(self, n: int, run: NativeRun, inputs: np.ndarray, outputs: np.ndarray) -> None:
        self.n = n
        self.run = run
        self.inputs = inputs
        self.outputs = outputs
        self.lock = threading.Lock()
        # the gravity (a read-only array) row 0 holds, until other rows are written
        self.gravity: np.ndarray | None = None

    def states(self, Q: np.ndarray, V: np.ndarray, A: np.ndarray, G: object) -> np.ndarray:
        """τ and the friction torque ``(m, 2n)`` at the rows of ``V``, ``A`` ``(m, n)`` with
        ``Q`` ``(m, n)`` or one ``(n,)`` for every row, gravity ``(m, 3)`` or ``(3,)``."""
        n, m = self.n, V.shape[0]
        rows = self.inputs.shape[0]
        if m > rows:  # a batch: block by block through the buffers
            Qs, Gs = np.broadcast_to(Q, (m, n)), np.broadcast_to(np.asarray(G), (m, 3))
            blocks = range(0, m, rows)
            return np.concatenate(
                [self.states(*(x[i : i + rows] for x in (Qs, V, A, Gs))) for i in blocks]
            )
        with self.lock:
            x = self.inputs
            x[:m, :n] = Q
            x[:m, n : 2 * n] = V
            x[:m, 2 * n : 3 * n] = A
            x[:m, 3 * n :] = G
            self.gravity = None
            self.run(m)
            out: np.ndarray = self.outputs[:m].copy()
            return out

    def one(
        self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, g: np.ndarray, friction: bool
    ) -> np.ndarray:
        """τ at one state ``(n,)`` with gravity ``g`` (the robot's), with its friction."""
        n = self.n
        with self.lock:
            x = self.inputs[0]
            x[:n] = q
            x[n : 2 * n] = qd
            x[2 * n : 3 * n] = qdd
            if self.gravity is not g:
                x[3 * n :] = g
                self.gravity = g
            self.run(1)
            y = self.outputs[0]
            tau: np.ndarray = y[:n] + y[n:] if friction else y[:n].copy()
            return tau


@dataclass(frozen=True)
class Trajectory:
    """A simulated motion: times ``t`` ``(T,)``, ``q`` and ``qd`` ``(T, ..., n)``."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray


class DynamicsFunctions:
    """The numeric dynamics of one robot with numeric parameters (see the module docstring).

    One function computes everything, ``τ(q, q̇, q̈, g)`` of the Newton–Euler recursion
    (:class:`~.numeric_recursion.NumericRecursion`, built on the first call; the gravity
    vector an argument); M, C and g are read off it as roboticstoolbox does, each in one
    batch: ``M[:, j] = τ(q, 0, e_j, 0)``, ``g = τ(q, 0, 0, g)``, and the Christoffel
    symbols ``c_jj = τ(q, e_j, 0, 0)``, ``c_jk = (τ(q, e_j + e_k, 0, 0) − c_jj − c_kk) / 2``.
    """

    def __init__(
        self,
        dm: DynamicModel,
        *,
        entry: str | None = None,
        native: NativeRowsCompiler | None = None,
    ) -> None:
        self.model = dm
        n = self.n = dm.n
        # the gravity arguments: names no table can give a symbol (the parser's are words)
        gsym = sp.symbols("gravity·x gravity·y gravity·z", **REAL)

        def tau() -> list[sp.Expr]:
            return list(rne_expressions(dm, gravity=gsym))

        def potential() -> list[sp.Expr]:
            return [sum(potential_energies(dm), sp.Integer(0))]

        self._recursion: NumericRecursion | None = None
        # τ(q, q̇, q̈, g) compiled for small calls after COMPILE_AFTER of them (kept in the
        # disk cache as ``entry``); until then, and for batches, the numeric recursion
        self._args = (*dm.variables, *dm.rates, *dm.accelerations, *gsym)
        self._compiled = _Compiled(tau, self._args, (n,), entry)
        # the same program in native code (built at the switch when ``native`` is given)
        self._native_compiler = native
        self._native: _NativeRows | None = None
        self._small = 0
        self._exact_only = False
        self._potential = _Compiled(potential, dm.variables, (1,))
        self.gravity = np.array([to_float(g) for g in dm.gravity])
        self.gravity.flags.writeable = False  # one state's C input keeps it (_NativeRows.one)
        links = [dm.links[r - 1] for r in dm.joints]
        try:
            self._viscous = np.array([to_float(L.B * L.G**2) for L in links])
            self._coulomb = np.array(
                [[to_float(abs(L.G) * L.Tc[0]), to_float(abs(L.G) * L.Tc[1])] for L in links]
            )
        except DHError as err:
            raise DHError(f"friction: {err.message}") from None
        self.has_friction = bool(np.any(self._viscous) or np.any(self._coulomb))
        # the rates and accelerations M and the Christoffel symbols are read off at
        unit = self._unit = np.eye(n)
        self._pairs = np.array([(j, k) for j in range(n) for k in range(j + 1, n)], dtype=int)
        self._pairs = self._pairs.reshape(-1, 2)
        self._diagonal = np.arange(n) * (n + 1)
        self._pair_rates = np.array([*unit, *(unit[j] + unit[k] for j, k in self._pairs)])
        self._pair_rates = self._pair_rates.reshape(-1, n)
        self._accel_accs = np.vstack([np.zeros((1, n)), unit])  # bias, then M's columns
        self._accel_gravity = np.zeros((n + 1, 3))
        self._accel_gravity[0] = self.gravity

    def _tau(self, Q: np.ndarray, V: np.ndarray, A: np.ndarray, g: np.ndarray) -> np.ndarray:
        """τ at states ``(..., n)`` (broadcast together) with gravity ``g`` ``(3,)``."""
        shape = np.broadcast_shapes(Q.shape, V.shape, A.shape)
        Qf, Vf, Af = (np.broadcast_to(x, shape).reshape(-1, self.n) for x in (Q, V, A))
        return self._rows(Qf, Vf, Af, g).reshape(shape)

    def _rows(self, Q: np.ndarray, V: np.ndarray, A: np.ndarray, g: np.ndarray) -> np.ndarray:
        """τ at the states ``(m, n)`` with gravity ``(3,)`` or ``(m, 3)``: the numeric
        recursion, or for a small call after :data:`COMPILE_AFTER` of them the compiled
        program state by state (native code, or plain floats without a compiler); once the
        native program is built, batches go through it too."""
        m = Q.shape[0]
        G = np.broadcast_to(g, (m, 3))
        if m <= SMALL:
            self._small += 1
            if self._small > COMPILE_AFTER:
                native = self._native if self._native is not None else self._build_native()
                if native is not None:
                    return native.states(Q, V, A, G)[:, : self.n]
                return np.stack([self._compiled(Q[i], V[i], A[i], G[i]) for i in range(m)])
        if self._native is not None:  # past the switch: a batch in native code too
            return self._native.states(Q, V, A, G)[:, : self.n]
        if self._recursion is None and not self._exact_only:
            try:
                self._recursion = numeric_recursion(self.model)
            except DHError:
                # a parameter without a number (``rz1`` of a planar arm) may vanish from
                # the exact τ (its products by exact zeros): the compiled program answers,
                # or names what is missing
                self._exact_only = True
        if self._recursion is None:
            return self._compiled(Q, V, A, G)
        return self._recursion.tau(Q, V, A, g)

    def _build_native(self) -> _NativeRows | None:
        """The compiled program in native code, asked of the compiler once (``None``: the
        program for Python floats answers). Its outputs are τ, then the friction torque
        ``B G² q̇ + |G| Tc`` per joint (as :meth:`friction`)."""
        compiler, self._native_compiler = self._native_compiler, None
        if compiler is None:
            return None
        n = self.n
        rates = self.model.rates
        friction = [
            sp.Float(float(b)) * v
            + sp.Piecewise((float(up), v > 0), (float(down), v < 0), (0.0, True))
            for v, b, (up, down) in zip(rates, self._viscous, self._coulomb)
        ]
        tau = self._compiled.program()
        program = NumericProgram(tau.assignments, (*tau.outputs, *friction))
        rows = max(SMALL, n * (n + 1) // 2, n + 1)  # a small call, or one state's C or M
        inputs = np.zeros((rows, len(self._args)))
        outputs = np.zeros((rows, 2 * n))
        run = compiler(program, self._args, inputs, outputs)
        if run is not None:
            self._native = _NativeRows(n, run, inputs, outputs)
        return self._native

    def _columns(self, Q: np.ndarray, V: np.ndarray, A: np.ndarray, g: np.ndarray) -> np.ndarray:
        """τ at the states ``Q`` ``(..., n)`` for each of the ``K`` rates and accelerations
        ``V``, ``A`` ``(K, n)``, in one batch: ``(K, ..., n)``."""
        K = V.shape[0]
        lead = (1,) * (Q.ndim - 1)
        shape = (K, *Q.shape)
        return self._tau(
            np.broadcast_to(Q, shape),
            np.broadcast_to(V.reshape(K, *lead, self.n), shape),
            np.broadcast_to(A.reshape(K, *lead, self.n), shape),
            g,
        )

    # --- the calls ---------------------------------------------------------------------
    def _states(self, *xs: object) -> list[np.ndarray]:
        arrays = [np.asarray(x, dtype=float) for x in xs]
        for a in arrays:
            if a.ndim == 0 or a.shape[-1] != self.n:
                raise DHError(f"expected {self.n} joint values per state, got shape {a.shape}")
        shape = np.broadcast_shapes(*(a.shape for a in arrays))
        return [np.broadcast_to(a, shape) for a in arrays]

    def friction(self, qd: object) -> np.ndarray:
        """The friction torque ``B G² q̇ + |G| Tc`` (``Tc+`` when ``q̇ > 0``, ``Tc−`` below)."""
        (v,) = self._states(qd)
        coulomb = np.where(v > 0, self._coulomb[:, 0], np.where(v < 0, self._coulomb[:, 1], 0.0))
        torque: np.ndarray = self._viscous * v + coulomb
        return torque

    def rne(self, q: object, qd: object, qdd: object, *, friction: bool = True) -> np.ndarray:
        """Joint torques τ(q, q̇, q̈) (with gravity, motor inertia and friction)."""
        native, n = self._native, self.n
        if (
            native is not None  # one state in native code: no broadcasting, one call
            and type(q) is np.ndarray
            and type(qd) is np.ndarray
            and type(qdd) is np.ndarray
            and q.shape == qd.shape == qdd.shape == (n,)
        ):
            return native.one(q, qd, qdd, self.gravity, friction and self.has_friction)
        Q, V, A = self._states(q, qd, qdd)
        tau = self._tau(Q, V, A, self.gravity)
        return tau + self.friction(V) if friction and self.has_friction else tau

    def inertia(self, q: object) -> np.ndarray:
        """M(q), ``(..., n, n)``: column j is τ(q, 0, e_j) without gravity."""
        native = self._native
        if native is not None and _is_state(q, self.n):
            zeros = np.zeros((self.n, self.n))
            M: np.ndarray = native.states(q, zeros, self._unit, np.zeros(3))[:, : self.n].T
            return M
        (Q,) = self._states(q)
        cols = self._columns(Q, np.zeros((self.n, self.n)), np.eye(self.n), np.zeros(3))
        return np.moveaxis(cols, 0, -1)

    def christoffel(self, q: object) -> np.ndarray:
        """The Christoffel symbols ``c[..., i, j, k]`` = Spong's ``c_ijk`` (0-based), from
        τ(q, q̇, 0) without gravity at ``q̇ = e_j`` and ``e_j + e_k``."""
        n, rates = self.n, self._pair_rates
        native = self._native
        if native is not None and _is_state(q, n):
            h = native.states(q, rates, np.zeros_like(rates), np.zeros(3))[:, :n]
            lead: tuple[int, ...] = ()
        else:
            (Q,) = self._states(q)
            h = np.moveaxis(self._columns(Q, rates, np.zeros_like(rates), np.zeros(3)), 0, -2)
            lead = Q.shape[:-1]
        # h[..., m, :]: τ at the m-th rate, e_j (m < n) or e_j + e_k (the pairs j < k);
        # c[..., j, k, :] is row j n + k of c with its (j, k) axes as one
        j, k = self._pairs.T
        c = np.empty((*lead, n * n, n))
        c[..., self._diagonal, :] = h[..., :n, :]
        c[..., j * n + k, :] = c[..., k * n + j, :] = (
            h[..., n:, :] - h[..., j, :] - h[..., k, :]
        ) / 2
        return c.reshape(*lead, n, n, n)

    def coriolis(self, q: object, qd: object) -> np.ndarray:
        """C(q, q̇) with ``C[k, j] = Σ_i c_ijk q̇_i``, ``(..., n, n)``."""
        if self._native is not None and _is_state(q, self.n) and _is_state(qd, self.n):
            one: np.ndarray = np.einsum("ijk,i->kj", self.christoffel(q), qd)
            return one
        Q, V = self._states(q, qd)
        c = self.christoffel(Q)
        C: np.ndarray = np.einsum("...ijk,...i->...kj", c, V)
        return C

    def gravload(self, q: object) -> np.ndarray:
        """g(q), the torques that hold the arm still against gravity: τ(q, 0, 0)."""
        native = self._native
        if native is not None and _is_state(q, self.n):
            zero = np.zeros(self.n)
            return native.one(q, zero, zero, self.gravity, False)
        (Q,) = self._states(q)
        return self._tau(Q, np.zeros_like(Q), np.zeros_like(Q), self.gravity)

    def accel(self, q: object, qd: object, tau: object) -> np.ndarray:
        """Forward dynamics: q̈ = M(q)⁻¹ (τ − C q̇ − g − friction), the bias
        ``C q̇ + g + friction`` being τ(q, q̇, 0) with its friction, M's columns τ(q, 0, e_j)
        without gravity, one batch; solved by ``numpy.linalg.solve``."""
        n = self.n
        native = self._native
        if native is not None and _is_state(q, n) and _is_state(qd, n) and _is_state(tau, n):
            rates = np.zeros((n + 1, n))
            rates[0] = qd
            out = native.states(q, rates, self._accel_accs, self._accel_gravity)
            bias = out[0, :n] + out[0, n:] if self.has_friction else out[0, :n]
            one: np.ndarray = np.linalg.solve(out[1:, :n].T, tau - bias)
            return one
        Q, V, T = self._states(q, qd, tau)
        # one batch: the bias τ(q, q̇, 0, g) and the columns of M, τ(q, 0, e_j, 0)
        shape = (n + 1, *Q.shape)
        rates = np.broadcast_to(V, shape).copy()
        rates[1:] = 0.0
        accs = np.zeros(shape)
        for j in range(n):
            accs[j + 1, ..., j] = 1.0
        gravity = np.zeros((*shape[:-1], 3))
        gravity[0] = self.gravity
        Qf, Vf, Af = (np.broadcast_to(x, shape).reshape(-1, n) for x in (Q, rates, accs))
        out = self._rows(Qf, Vf, Af, gravity.reshape(-1, 3)).reshape(shape)
        bias = out[0] + self.friction(V) if self.has_friction else out[0]
        M = np.moveaxis(out[1:], 0, -1)
        return np.linalg.solve(M, (T - bias)[..., None])[..., 0]

    def energy(self, q: object, qd: object) -> np.ndarray:
        """Total energy ``½ q̇ᵀ M q̇ + P(q)`` (motor inertia included)."""
        Q, V = self._states(q, qd)
        kinetic = 0.5 * np.einsum("...i,...ij,...j->...", V, self.inertia(Q), V)
        total: np.ndarray = kinetic + self._potential(Q)[..., 0]
        return total

    def simulate(
        self,
        q0: object,
        qd0: object,
        duration: float,
        *,
        dt: float = 1e-3,
        tau: object = None,
    ) -> Trajectory:
        """Integrate the motion with fixed-step RK4 from ``(q0, qd0)`` for ``duration`` s.

        ``tau`` is None (no drive: a free swing), a constant torque ``(n,)`` or a
        function ``tau(t, q, qd)``. States may be batched: ``q0`` ``(..., n)``.
        """
        Q, V = (np.array(a, dtype=float) for a in self._states(q0, qd0))
        steps = max(1, int(round(duration / dt)))
        h = duration / steps

        def drive(t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
            if tau is None:
                return np.zeros_like(q)
            if callable(tau):
                return np.broadcast_to(np.asarray(tau(t, q, v), dtype=float), q.shape)
            return np.broadcast_to(np.asarray(tau, dtype=float), q.shape)

        def f(t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            return v, self.accel(q, v, drive(t, q, v))

        ts = np.linspace(0.0, steps * h, steps + 1)
        qs, vs = [Q], [V]
        for k in range(steps):
            t = ts[k]
            k1q, k1v = f(t, Q, V)
            k2q, k2v = f(t + h / 2, Q + h / 2 * k1q, V + h / 2 * k1v)
            k3q, k3v = f(t + h / 2, Q + h / 2 * k2q, V + h / 2 * k2v)
            k4q, k4v = f(t + h, Q + h * k3q, V + h * k3v)
            Q = Q + h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q)
            V = V + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            qs.append(Q)
            vs.append(V)
        return Trajectory(ts, np.stack(qs), np.stack(vs))


def dynamics_functions(
    robot: KinematicChain,
    values: Mapping[object, object] | None = None,
    *,
    textbook: bool = True,
    native: NativeRowsCompiler | None = None,
) -> DynamicsFunctions:
    """The numeric dynamics of ``robot`` with the table's values and ``values`` (numbers
    for lengths and inertial symbols; the model: :func:`numeric_model`), evaluated by the
    numeric recursion (:mod:`.numeric_recursion`): nothing is derived before the first
    numbers. A long run of small calls (a simulation) compiles τ after
    :data:`COMPILE_AFTER` of them, the program kept in the disk cache (:mod:`dhsym.cache`)
    named by the table, ``values`` and ``textbook``; with ``native`` (a
    :class:`NativeRowsCompiler`: ``Robot.dynamics_functions`` passes the export room's C
    when a compiler is there) that program then runs in native code."""
    from dhsym.cache.keys import entry_name
    from dhsym.model.table import symbol_values

    given = sorted(f"{sp.srepr(k)}={sp.srepr(v)}" for k, v in symbol_values(values).items())
    entry = entry_name(robot.table, "rne", f"textbook={textbook}", *given)
    dm = numeric_model(robot, values, textbook=textbook)
    return DynamicsFunctions(dm, entry=entry, native=native)


def numeric_model(
    robot: KinematicChain, values: Mapping[object, object] | None = None, *, textbook: bool = True
) -> DynamicModel:
    """The dynamic model of ``robot`` with the table's values and ``values`` (numbers for
    lengths and inertial symbols) substituted, as :func:`dynamics_functions` compiles it."""
    from dhsym.kinematics.chain import KinematicChain
    from dhsym.model.table import symbol_values

    table = robot.table
    extra = symbol_values(values)
    known = set(table.constants) | set().union(
        *(r.inertia.free_symbols for r in table.rows if r.inertia),
        *(g.free_symbols for g in table.gravity),
    )
    vals = {**table.value_map, **{k: v for k, v in extra.items() if k in known}}
    numeric = KinematicChain(replace(table, values=tuple(vals.items())).substituted())
    dm = dynamic_model(numeric, textbook=textbook)
    if extra:  # values for the textbook symbols of rows without parameters
        gravity = tuple(g.xreplace(extra) for g in dm.gravity)
        dm = replace(dm, links=tuple(L.subs(extra) for L in dm.links), gravity=gravity)
    return dm
