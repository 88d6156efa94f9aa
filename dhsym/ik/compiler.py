"""The closed form in numbers: the steps of a derivation compiled into one solver over all
branches (the derivations are in the family modules of :mod:`dhsym.ik`).

The steps of a derivation, the ``fk`` of their solutions and the singular factors of
:mod:`dhsym.kinematics.singularities` are compiled once into one straight-line program
(the steps are its common subexpressions), in two forms:

* numpy, for a batch: all branches at once by broadcasting the branch signs (branches on
  the leading axes, poses on the last), each ``atan2``, sine and cosine only over the
  branches it depends on; the residual of ``fk`` is reduced inside the program;
* plain floats (``math``), for one pose: the program written out once per branch, a
  few microseconds for the eight branches of a PUMA, checks included.

Both keep a branch only when its ``fk`` reproduces the pose (``check="pose"``, default).
The ``fk`` in the check is the robot's own compact matrix at the computed angles, with
``cos(σx) = cos x``, ``sin(x + π) = −sin x`` and the like used exactly for the signs
σ = ±1 of the branches (so the two wrist flips share one evaluation, as they share the
pose).

Examples
--------
>>> import dhsym
>>> r = dhsym.load("scara")
>>> batch = r.ik(r.fk([[0.3, 0.5, 0.1, 0.2], [1.0, -0.4, 0.2, 0.0]]))
>>> batch.q.shape, batch.count.tolist()
((2, 2, 4), [2, 2])
>>> one = r.ik(r.fk([0.3, 0.5, 0.1, 0.2]))  # one pose: the program for floats
>>> len(one), bool(np.abs(one.q - batch.q[0]).max() < 1e-12)
(2, True)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.decoupling import StructureError
from dhsym.model.table import JointType

from .results import IKBatch, IKSolution

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from dhsym.kinematics.singularities import Singularities

    from .closed_form import InverseKinematics

__all__ = ["Solver"]

_REAL = {"real": True}


# --- numbers --------------------------------------------------------------------------------


class SafeSqrt(sp.Function):
    """``sqrt`` that reads a radicand within rounding of 0 as 0 (compile-time only)."""


class Wrap(sp.Function):
    """An angle wrapped to [−π, π] (compile-time only)."""


class Residual(sp.Function):
    """``max |d|`` over its arguments, NaN when one is NaN (compile-time only).

    For numpy ``maximum(maximum(abs(d1), abs(d2)), …)``, one difference at a time (NaN
    propagates); for floats ``max(0.0 * (d1 + d2 + …), abs(d1), abs(d2), …)``, whose
    first term, NaN or ±0, is kept by ``max`` when it is NaN (also for an infinity).
    """

    def _numpycode(self, printer: Any) -> str:  # a sympy code printer (untyped)
        maximum = printer._module_format("numpy.maximum")
        args = [f"abs({printer._print(a)})" for a in self.args]
        out = args[0]
        for a in args[1:]:
            out = f"{maximum}({out}, {a})"
        return out

    def _pythoncode(self, printer: Any) -> str:  # a sympy code printer (untyped)
        args = [printer._print(a) for a in self.args]
        return f"max(0.0 * ({' + '.join(args)}), {', '.join(f'abs({a})' for a in args)})"


_ROUNDING = 1e-10
_TWO_PI = 2 * np.pi
_INV_TWO_PI = 1 / _TWO_PI


def _safe_sqrt(x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, dtype=float)
    return np.sqrt(np.where(x > -_ROUNDING, np.maximum(x, 0.0), x))  # NaN stays NaN


def _wrap(x: np.ndarray) -> np.ndarray:
    """Angles to [−π, π] (faster than ``np.remainder``)."""
    return x - _TWO_PI * np.rint(x * _INV_TWO_PI)


def _safe_sqrt_float(x: float) -> float:
    """:func:`_safe_sqrt` of one float."""
    if x >= 0.0:
        return math.sqrt(x)
    return 0.0 if x > -_ROUNDING else math.nan


#: the wrap for floats, inline: ``math.remainder(x, 2π)`` is in [−π, π] and keeps NaN; it
#: equals :func:`_wrap` except within rounding of ±π, where either end may come out
_REMAINDER = sp.Function("remainder")
_TAU = sp.Symbol("TWO_PI")
_NUMPY = [{"SafeSqrt": _safe_sqrt, "Wrap": _wrap}, "numpy"]
_MATH = [
    {"SafeSqrt": _safe_sqrt_float, "TWO_PI": _TWO_PI},
    "math",
]


def _with_safe_sqrt(e: sp.Expr) -> sp.Expr:
    return e.replace(lambda t: t.is_Pow and t.exp == sp.S.Half, lambda t: SafeSqrt(t.base)).replace(
        lambda t: t.is_Pow and t.exp == -sp.S.Half, lambda t: 1 / SafeSqrt(t.base)
    )


#: poses per block: large enough that numpy's cost per call is small against its work,
#: small enough that a block's temporaries stay in the cache (measured: 1024-4096 alike)
_CHUNK = 2048

#: |sin θ5| below which θ6 comes from the whole wrist rotation, and below which θ4 = 0
_WRIST_NEAR = 1e-5
_WRIST_ZERO = 1e-12
#: fraction of a singular factor's largest value below which branches may coincide
_SUSPECT = 1e-4


def _schedule(
    steps: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """The steps as one straight-line program for ``outputs``, subexpressions shared.

    Steps no output needs are dropped; ``cse`` runs over all right-hand sides at once and
    each shared subexpression is placed right after the last step it depends on.
    """
    needed = set().union(*(e.free_symbols for e in outputs)) if outputs else set()
    kept = []
    for lhs, rhs in reversed(steps):
        if lhs in needed:
            kept.append((lhs, rhs))
            needed |= rhs.free_symbols
    steps = kept[::-1]
    exprs = [rhs for _, rhs in steps] + list(outputs)
    repl, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_w"), optimizations=None)
    position = {lhs: i for i, (lhs, _) in enumerate(steps)}
    level: dict[sp.Symbol, int] = {}
    for sym, e in repl:
        deps = [position[s] for s in e.free_symbols if s in position]
        deps += [level[s] for s in e.free_symbols if s in level]
        level[sym] = max(deps, default=-1)
    program = [(sym, e) for sym, e in repl if level[sym] == -1]
    for i, (lhs, _) in enumerate(steps):
        program.append((lhs, reduced[i]))
        program += [(sym, e) for sym, e in repl if level[sym] == i]
    return program, list(reduced[len(steps) :])


def _signed(e: sp.Expr, signs: set[sp.Symbol]) -> tuple[sp.Expr, sp.Expr]:
    """``e = σ · rest`` with σ the product of the branch signs that are factors of ``e``."""
    sigma = sp.Mul(*[f for f in sp.Mul.make_args(e) if f in signs])
    return sigma, (e / sigma if sigma != 1 else e)


def _shifted(e: sp.Expr, signs: set[sp.Symbol]) -> tuple[sp.Expr, sp.Expr]:
    """``e = rest + shift`` with ``shift = d (σ − 1)`` for each sign σ that ``e`` depends on
    only through a constant multiple of π/2 (e.g. ``π(1 − σ)/2``: the atan2 of −Y, −X)."""
    shift = sp.S.Zero
    for s in sorted(e.free_symbols & signs, key=str):
        d = sp.diff(e, s)
        if not d.free_symbols and (2 * d / sp.pi).is_Integer:
            shift += d * (s - 1)
            e = e.xreplace({s: 1})
    return shift, e


def _trig_signs(e: sp.Expr, signs: set[sp.Symbol]) -> sp.Expr:
    """``sin`` and ``cos`` with the branch signs σ = ±1 taken out of their arguments.

    An argument odd in σ: ``cos(σx) = cos x``, ``sin(σx) = σ sin x``; an argument that moves
    by kπ between σ = +1 and σ = −1: ``cos(x + kπ(1 − σ)/2) = σᵏ cos x`` (the same for sin).
    Both are identities for σ = ±1, so each sine and cosine is computed only over the
    branches its argument really depends on.
    """

    def rule(t: sp.Expr) -> sp.Expr:
        arg = t.args[0]
        for s in sorted(arg.free_symbols & signs, key=str):
            plus, minus = arg.xreplace({s: 1}), arg.xreplace({s: -1})
            if sp.expand(plus + minus) == 0:
                factor = s if isinstance(t, sp.sin) else sp.S.One
                return factor * _trig_signs(t.func(plus), signs)
            k = sp.expand((minus - plus) / sp.pi)
            if k.is_Integer:
                return s ** (int(k) % 2) * _trig_signs(t.func(plus), signs)
        return t

    return e.replace(
        lambda t: isinstance(t, (sp.sin, sp.cos)) and bool(t.args[0].free_symbols & signs), rule
    )


def _pull_signs(
    steps: Sequence[tuple[sp.Symbol, sp.Expr]],
    outputs: Sequence[sp.Expr],
    signs: Sequence[sp.Symbol],
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """Move branch signs σ = ±1 out of square roots' neighbours, ``atan2``, sin and cos.

    A step ``x = σ·E`` becomes ``x' = E`` with ``x = σ x'`` downstream, a step
    ``x = E + π(1 − σ)/2`` becomes ``x' = E`` with ``x = x' + π(1 − σ)/2`` downstream, and
    ``atan2(σa Y, σb X) ≡ σa σb atan2(Y, X) + π(1 − σb)/2`` (mod 2π), so that each
    ``atan2`` (and each sine and cosine, :func:`_trig_signs`; ``|σx| = |x|``,
    ``wrap(σx) = σ wrap(x)``) runs once for the branches it does not depend on. Only
    used for numbers: the angles it changes are wrapped to [−π, π] afterwards.
    """
    sset = set(signs)

    def square_free(e: sp.Expr) -> sp.Expr:
        return e.replace(
            lambda t: t.is_Pow and t.base in sset and t.exp.is_Integer,
            lambda t: t.base ** (int(t.exp) % 2),
        )

    def pull(e: sp.Expr) -> sp.Expr:
        def rewrite(t: sp.atan2) -> sp.Expr:
            sy, Y = _signed(t.args[0], sset)
            sx, X = _signed(t.args[1], sset)
            if sy == 1 and sx == 1:
                return t
            return sx * sy * sp.atan2(Y, X) + sp.pi * (1 - sx) / 2

        def odd(t: Wrap) -> sp.Expr:  # the wrap is odd (exactly, in floats too)
            sigma, rest = _signed(t.args[0], sset)
            return sigma * Wrap(rest)

        e = e.replace(lambda t: isinstance(t, sp.atan2), rewrite)
        e = square_free(_trig_signs(square_free(e), sset))

        def unsigned(t: sp.Abs) -> sp.Expr:  # |σx| = |x|
            return sp.Abs(_signed(t.args[0], sset)[1])

        e = e.replace(lambda t: isinstance(t, sp.Abs), unsigned)
        return e.replace(lambda t: isinstance(t, Wrap), odd)

    sub: dict[sp.Symbol, sp.Expr] = {}
    out = []
    for lhs, rhs in steps:
        e = pull(square_free(rhs.xreplace(sub)))
        sigma, rest = _signed(e, sset)
        shift = sp.S.Zero
        if sigma == 1:
            shift, rest = _shifted(e, sset)
        if sigma != 1 or shift != 0:
            bare = sp.Symbol(f"{lhs.name}_", **_REAL)
            out.append((bare, rest))
            sub[lhs] = sigma * bare + shift
        else:
            out.append((lhs, e))
    return out, [pull(square_free(o.xreplace(sub))) for o in outputs]


def _per_branch(
    program: Sequence[tuple[sp.Symbol, sp.Expr]],
    outputs: Sequence[sp.Expr],
    signs: Sequence[sp.Symbol],
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[list[sp.Expr]]]:
    """The program written out for every branch, for scalars: the signs become numbers.

    A line that depends on the signs S (directly or through earlier lines) is repeated
    once per combination of S; a line that does not is computed once. The outputs are
    lines too (an angle that depends on one sign is wrapped twice, not once per branch)
    and are returned as one list per branch, in the order of :attr:`Solver.branch_signs`.
    """
    sset = set(signs)
    deps: dict[sp.Symbol, tuple[sp.Symbol, ...]] = {}
    bound: dict[tuple[sp.Symbol, tuple[int, ...]], sp.Expr] = {}

    def bind(e: sp.Expr, choice: Mapping[sp.Symbol, int]) -> sp.Expr:
        rep: dict[sp.Symbol, sp.Expr] = {s: sp.Integer(choice[s]) for s in e.free_symbols & sset}
        for x in e.free_symbols:
            if x in deps:
                rep[x] = bound[(x, tuple(choice[s] for s in deps[x]))]
        return e.xreplace(rep)

    names = [sp.Symbol(f"_out{i}") for i in range(len(outputs))]
    lines = []
    for sym, e in [*program, *zip(names, outputs)]:
        used = set(e.free_symbols & sset).union(*(deps[x] for x in e.free_symbols if x in deps))
        d = deps[sym] = tuple(s for s in signs if s in used)
        for combo in itertools.product((1, -1), repeat=len(d)):
            value = bind(e, dict(zip(d, combo)))
            if value.is_Number or value.is_Symbol:
                bound[(sym, combo)] = value
                continue
            name = sym
            if d:
                tag = "".join("p" if c > 0 else "m" for c in combo)
                name = sp.Symbol(f"{sym.name}__{tag}", **sym.assumptions0)
            lines.append((name, value))
            bound[(sym, combo)] = name
    outs = []
    for combo in itertools.product((1, -1), repeat=len(signs)):
        choice = dict(zip(signs, combo))
        outs.append([bound[(o, tuple(choice[s] for s in deps[o]))] for o in names])
    return lines, outs


def _reuse_names(
    program: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """The program with a line's name bound again once its value is no longer needed.

    For numpy: rebinding a name frees the array it held, so a block's temporaries are
    few at any time and reused (fewer cache misses and page faults than when every
    intermediate array lives until the function returns).
    """
    alias: dict[sp.Symbol, sp.Expr] = {}  # lines x = y: y itself (lambdify reads a line
    lines = []  # x = argument as "x is that argument" everywhere, so x must not be reused)
    for sym, e in program:
        e = e.xreplace(alias)
        if e.is_Symbol:
            alias[sym] = e
        else:
            lines.append((sym, e))
    program, outputs = lines, [o.xreplace(alias) for o in outputs]
    last: dict[sp.Symbol, int] = {}
    for i, (_, e) in enumerate(program):
        for x in e.free_symbols:
            last[x] = i
    for o in outputs:
        for x in o.free_symbols:
            last[x] = len(program)
    defined = {sym for sym, _ in program}
    rename: dict[sp.Symbol, sp.Symbol] = {}
    free: list[sp.Symbol] = []
    out = []
    for i, (sym, e) in enumerate(program):
        free += [rename[x] for x in e.free_symbols if x in defined and last[x] == i]
        name = free.pop() if free else sym
        out.append((name, e.xreplace(rename)))
        rename[sym] = name
        if sym not in last:  # never used: its name is free again at once
            free.append(name)
    return out, [o.xreplace(rename) for o in outputs]


def _lift_residuals(
    program: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """Each argument of a :class:`Residual` (a line or an output) becomes a line of the
    program of its own (for floats it is printed twice: in the sum that catches NaN and
    in its ``abs``)."""
    names = sp.numbered_symbols("_d")
    lines: list[tuple[sp.Symbol, sp.Expr]] = []

    def lift(e: sp.Expr) -> sp.Expr:
        if not isinstance(e, Residual):
            return e
        args = []
        for a in e.args:
            if not a.is_Symbol:
                sym = next(names)
                lines.append((sym, a))
                a = sym
            args.append(a)
        return Residual(*args)

    for sym, e in program:
        e = lift(e)
        lines.append((sym, e))
    return lines, [lift(o) for o in outputs]


@dataclass(frozen=True)
class Layout:
    """Where each output of a compiled program sits, by name.

    A numpy program (``"raw"``, ``"checked"``) returns one array per output: the joint
    values, the wrist sines, the residual over the whole pose and over its position, the
    singular factors. The program for floats returns one float per branch and output,
    grouped: the residuals of every branch (whole pose, then position), the wrist sines,
    then the joint values and the factors branch by branch.

    >>> Layout.numpy(n=6, w=1, factors=2).whole, Layout.scalar(n=6, w=1, factors=2, K=8).joints
    (slice(7, 8, None), slice(24, 72, None))
    """

    joints: slice
    wrist: slice
    whole: slice
    position: slice
    factors: slice

    @classmethod
    def numpy(cls, n: int, w: int, factors: int) -> Layout:
        """The layout of a numpy program (one array per output)."""
        return cls(
            slice(0, n),
            slice(n, n + w),
            slice(n + w, n + w + 1),
            slice(n + w + 1, n + w + 2),
            slice(n + w + 2, n + w + 2 + factors),
        )

    @classmethod
    def scalar(cls, n: int, w: int, factors: int, K: int) -> Layout:
        """The layout of the program for floats (``K`` branches written out)."""
        wrist = slice(2 * K, 2 * K + K * w)
        joints = slice(wrist.stop, wrist.stop + K * n)
        return cls(
            joints,
            wrist,
            slice(0, K),
            slice(K, 2 * K),
            slice(joints.stop, joints.stop + K * factors),
        )


#: The programs a :class:`Solver` compiles (see :meth:`Solver._program`).
ProgramKind = Literal["raw", "checked", "scalar", "singular"]


@dataclass
class Programs:
    """The lambdified programs of one :class:`Solver`, each built on first use: ``raw`` and
    ``checked`` (numpy, all branches by broadcasting), ``scalar`` (floats, every branch
    written out), ``singular`` (numpy: θ4 and θ6 at a singular wrist)."""

    raw: Callable[..., list[Any]] | None = None
    checked: Callable[..., list[Any]] | None = None
    scalar: Callable[..., list[Any]] | None = None
    singular: Callable[..., list[Any]] | None = None


class Solver:
    """The steps of an :class:`InverseKinematics`, compiled for numbers.

    :meth:`solve` takes one pose ``(4, 4)`` (an :class:`IKSolution`) or a batch
    ``(N, 4, 4)`` (an :class:`IKBatch`: padded arrays with a validity mask). Poses are
    world-to-tool, as ``fk`` gives them; base and tool transforms are undone first.

    The steps, the ``fk`` of the solutions and the singular factors at them are compiled
    into one straight-line program (``lambdify`` with the steps as the common
    subexpressions), twice: for numpy, where every branch of a block of poses is
    computed at once by broadcasting the signs (branches on the leading axes, poses on
    the last, contiguous one), and for plain floats (``math``), where the program is
    written out once per branch and one pose costs a few microseconds.
    """

    def __init__(self, ik: InverseKinematics, values: Mapping[sp.Symbol, sp.Expr]) -> None:
        robot = ik.robot
        self.ik = ik
        self.robot = robot
        self.values = dict(values)
        self.n = len(robot.variables)
        self.revolute = np.array(
            [r.joint is JointType.REVOLUTE for r in robot.table.rows if r.variable is not None]
        )
        self.pose_args = [ik.pose[i, j] for j in range(4) for i in range(3)]
        self.targets = [sp.Dummy(f"T{i + 1}{j + 1}", **_REAL) for j in range(4) for i in range(3)]
        self.signs = [b.symbol for b in ik.branches]
        self._steps = [(st.lhs, _with_safe_sqrt(st.rhs.xreplace(self.values))) for st in ik.steps]
        self._singular = {st.lhs: st.singular for st in ik.steps if st.singular is not None}
        # the wrist sines watched for sin θ5 = 0: only a derivation that says what to do
        # there (the singular values of θ4 and θ6) has them
        self._wrist_s = [
            s.lhs
            for s in ik.steps
            if self._singular and s.branch is not None and s.branch.role == "wrist"
        ]
        self.singular_vars = [robot.variables.index(v) for v in self._singular]
        free = set().union(*(e.free_symbols for _, e in self._steps)) if self._steps else set()
        defined = {lhs for lhs, _ in self._steps}
        missing = free - defined - set(self.pose_args) - set(self.signs)
        if missing:
            names = ", ".join(sorted(str(s) for s in missing))
            raise DHError(f"no numeric value for {names}: give values for these symbols")
        B = len(self.signs)
        self.shape = (2,) * B
        self.K = 2**B
        self._sign_arrays = []
        for k in range(B):
            shape = [1] * (B + 1)
            shape[k] = 2
            self._sign_arrays.append(np.array([1.0, -1.0]).reshape(shape))
        self.branch_signs = np.array(list(itertools.product([1, -1], repeat=B)), dtype=int).reshape(
            self.K, B
        )
        self.branch_signs.flags.writeable = False  # shared by the solutions that keep all
        self._base = self._constant(-1, 0) if robot.table.base else None
        self._tool = self._constant(robot.n, robot.n + 1) if robot.table.tool else None
        self._base_inv = None if self._base is None else np.linalg.inv(self._base)
        self._tool_inv = None if self._tool is None else np.linalg.inv(self._tool)
        self._factors: tuple[tuple[str, Callable[[object], np.ndarray], float], ...] | None = None
        self._factor_exprs: tuple[sp.Expr, ...] = ()
        self._frames: dict[int | None, Callable[[ArrayLike], np.ndarray]] = {}
        # lambdified programs: lists of floats (scalar) or of arrays (numpy)
        self._programs = Programs()

    def frame(self, k: int | None = None) -> Callable[[ArrayLike], np.ndarray]:
        """The compiled ``^0T_k`` (``None``: the whole ``fk``, world to tool), cached."""
        if k not in self._frames:
            fk = self.robot.fk_function
            self._frames[k] = fk(values=self.values) if k is None else fk(0, k, self.values)
        return self._frames[k]

    def _constant(self, i: int, j: int) -> np.ndarray:
        M = self.robot.transform(i, j).matrix.xreplace(self.values)
        return np.array(M.evalf(), dtype=float)

    # -- the compiled programs ----------------------------------------------------------------
    def _outputs(self, kind: ProgramKind) -> list[sp.Expr]:
        """What a program computes for each branch (``kind`` as in :meth:`_program`).

        ``"raw"``: the joint values (angles wrapped) and ``|sin θ5|``. ``"checked"`` and
        ``"scalar"``: also the residual of ``fk`` against the target pose over its 12
        entries and over its position, and the singular factors as fractions of their
        largest values.
        """
        joints = [Wrap(v) if r else v for v, r in zip(self.robot.variables, self.revolute)]
        joints += [sp.Abs(s) for s in self._wrist_s]
        if kind == "raw":
            return joints
        factors = self._singular_factors()
        M = self.robot.tool_pose().matrix.xreplace(self.values)
        diffs = [M[i, j] - t for (i, j), t in zip(_CELLS, self.targets)]
        closeness = [
            sp.Float(1 / s, 17) * sp.Abs(e) for e, (_, _, s) in zip(self._factor_exprs, factors)
        ]
        position = Residual(*[diffs[c] for c in _POSITION])  # one line, shared (cse)
        whole = Residual(*[diffs[c] for c in _ALL if c not in _POSITION], position)
        return joints + [whole, position] + closeness

    def _program(self, kind: ProgramKind) -> Callable[..., list[Any]]:
        """The compiled program of one ``kind``, built on first use.

        ``"raw"`` and ``"checked"`` (numpy, all branches by broadcasting), ``"scalar"``
        (floats, every branch written out), ``"singular"`` (numpy: θ4 and θ6 at a
        singular wrist).
        """
        built: Callable[..., list[Any]] | None = getattr(self._programs, kind)
        if built is None:
            if kind == "singular":
                # θ4 as this program computes it, θ4 at sin θ5 = 0, θ6 from the whole rotation
                # with that θ4 (the pair stays consistent: near sin θ5 = 0 each alone is
                # ill-conditioned, their sum is not), and θ6 with θ4 = 0
                (t4, zero4), (_, whole6) = list(self._singular.items())
                alts = [t4, zero4, whole6, whole6.xreplace({t4: zero4})]
                outputs = [_with_safe_sqrt(e.xreplace(self.values)) for e in alts]
            else:
                outputs = self._outputs(kind)
            program, reduced = _schedule(*_pull_signs(self._steps, outputs, self.signs))
            if kind == "scalar":
                # the wrap inline: one C call, no Python function
                program, reduced = _lift_residuals(program, reduced)
                reduced = [
                    e.replace(lambda t: isinstance(t, Wrap), lambda t: _REMAINDER(t.args[0], _TAU))
                    for e in reduced
                ]
                program, per_branch = _per_branch(program, reduced, self.signs)
                # grouped for _solve_one: residuals and wrist sines of all branches first,
                # then the joint values branch by branch, then the factors branch by branch
                n, w = self.n, len(self._wrist_s)
                groups = [range(n + w, len(reduced) - len(self._factor_exprs))]
                groups += [
                    range(n, n + w),
                    range(n),
                    range(len(reduced) - len(self._factor_exprs), len(reduced)),
                ]
                reduced = [o[i] for i in groups[0] for o in per_branch]
                reduced += [o[i] for i in groups[1] for o in per_branch]
                reduced += [o[i] for o in per_branch for i in groups[2]]
                reduced += [o[i] for o in per_branch for i in groups[3]]
                args, modules = self.pose_args + self.targets, _MATH
            elif kind == "checked":
                program, reduced = _reuse_names(program, reduced)
                args, modules = self.pose_args + self.signs + self.targets, _NUMPY
            else:
                program, reduced = _reuse_names(program, reduced)
                args, modules = self.pose_args + self.signs, _NUMPY
            built = sp.lambdify(args, reduced, modules=modules, cse=lambda exprs: (program, exprs))
            setattr(self._programs, kind, built)
        return built

    # -- raw closed form ----------------------------------------------------------------------
    def raw(self, T: np.ndarray) -> np.ndarray:
        """All branches for poses ``(N, 4, 4)`` (frame 0 to frame n): ``(N, K, n)``, unchecked.

        The result is a view of an array laid out joint by joint (branches, then poses).
        A single pose ``(4, 4)`` is a batch of one: ``(1, K, n)``.

        >>> import dhsym
        >>> solver = dhsym.load("planar2r").inverse().solver()
        >>> solver.raw(np.eye(4)).shape
        (1, 2, 2)
        >>> solver.raw(np.eye(3))
        Traceback (most recent call last):
        ...
        dhsym.errors.DHError: raw() takes poses of shape (N, 4, 4) or one pose (4, 4), not (3, 3)
        """
        poses = np.asarray(T, dtype=float)
        if poses.shape == (4, 4):
            poses = poses[None]
        if poses.ndim != 3 or poses.shape[1:] != (4, 4):
            raise DHError(
                f"raw() takes poses of shape (N, 4, 4) or one pose (4, 4), not {tuple(poses.shape)}"
            )
        q, _, _ = self._evaluate(poses, None, None)
        angles: np.ndarray = q.transpose(2, 1, 0)
        return angles

    def _evaluate(
        self, inner: np.ndarray, target: np.ndarray | None, cells: Sequence[int] | None
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        """Every branch of every pose: ``q`` ``(n, K, N)``; with a ``target`` (the poses
        before base and tool were undone) also the residual ``(K, N)`` over ``cells`` (of
        the 12, column by column) and each singular factor's closeness ``(F, K, N)``."""
        N, K, n = inner.shape[0], self.K, self.n
        checked = target is not None
        fn = self._program("checked" if checked else "raw")
        full = (*self.shape, N)
        q = np.empty((n, K, N))
        qv = q.reshape(n, *full)
        if checked:
            assert target is not None and cells is not None
            residual = np.empty((K, N))
            rv = residual.reshape(full)
            F = len(self._factor_exprs)
            closeness = np.empty((F, K, N))
            cv = closeness.reshape(F, *full)
        w = len(self._wrist_s)
        at = Layout.numpy(n, w, len(self._factor_exprs) if checked else 0)
        rows, wrists = [], []
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            for start in range(0, N, _CHUNK):
                sl = slice(start, min(start + _CHUNK, N))
                # the 12 entries column by column, each contiguous over the poses
                args = [*_entries(inner[sl]), *self._sign_arrays]
                if target is not None:  # checked
                    args += args[:12] if target is inner else _entries(target[sl])
                res = fn(*args)
                joints, sines = res[at.joints], res[at.wrist]
                for k in range(n):
                    qv[k, ..., sl] = joints[k]
                if w:  # |sin θ5| near 0: θ4 and θ6 from the whole rotation, below
                    small = np.asarray(sines[0] < _WRIST_NEAR)
                    hit = np.nonzero(small.reshape(-1, small.shape[-1]).any(axis=0))[0]
                    if hit.size:
                        s = np.broadcast_to(sines[0], (*self.shape, sl.stop - start))
                        rows.append(hit + start)
                        wrists.append(s.reshape(K, -1)[:, hit])
                if target is not None and cells is not None:  # checked
                    (rv[..., sl],) = res[at.position if tuple(cells) == _POSITION else at.whole]
                    for f, value in enumerate(res[at.factors]):
                        cv[f, ..., sl] = value
        if rows:
            hits = np.concatenate(rows)
            self._singular_wrist(inner[hits], q, hits, np.concatenate(wrists, axis=1))
            if checked:
                assert target is not None and cells is not None
                qs = q[:, :, hits].transpose(2, 1, 0)
                residual[:, hits], closeness[:, :, hits] = self._check(qs, target[hits], cells)
        if not checked:
            return q, None, None
        return q, residual, closeness

    def _singular_wrist(
        self, inner: np.ndarray, q: np.ndarray, rows: np.ndarray, wrist: np.ndarray
    ) -> None:
        """Near ``sin θ5 = 0``: θ6 from the whole wrist rotation; at 0 also θ4 = 0.

        ``inner`` are the poses of ``rows``, ``wrist`` ``(K, rows)`` their ``|sin θ5|``.
        """
        m = len(rows)
        with np.errstate(invalid="ignore", divide="ignore"):
            own4, zero4, whole6, whole6_zero4 = (
                np.broadcast_to(np.asarray(v, dtype=float), (*self.shape, m)).reshape(self.K, m)
                for v in self._program("singular")(*_entries(inner), *self._sign_arrays)
            )
        i4, i6 = self.singular_vars
        near, zero = wrist < _WRIST_NEAR, wrist < _WRIST_ZERO
        q6, q4 = q[i6], q[i4]
        q6[:, rows] = np.where(
            zero, _wrap(whole6_zero4), np.where(near, _wrap(whole6), q6[:, rows])
        )
        q4[:, rows] = np.where(zero, _wrap(zero4), np.where(near, _wrap(own4), q4[:, rows]))

    def _check(
        self, q: np.ndarray, target: np.ndarray, cells: Sequence[int]
    ) -> tuple[np.ndarray, np.ndarray]:
        """Residual ``(K, m)`` and closeness ``(F, K, m)`` of solutions ``q`` ``(m, K, n)``
        by the compiled ``fk`` and singular factors (for the few poses a program could not
        finish: a singular wrist)."""
        m, K, n = q.shape
        flat = q.reshape(-1, n)
        factors = self._singular_factors()
        closeness = np.empty((len(factors), K, m))
        with np.errstate(invalid="ignore"):
            got = self.frame()(flat).reshape(m, K, 4, 4)
            want = target.reshape(m, 1, 4, 4)
            diff = np.stack([got[..., i, j] - want[..., i, j] for i, j in _CELLS], axis=-1)
            residual = np.abs(diff[..., list(cells)]).max(axis=-1)
            for f, (_, fn, s) in enumerate(factors):
                closeness[f] = (np.abs(fn(flat)) / s).reshape(m, K).T
        return residual.T, closeness

    # -- checked solutions --------------------------------------------------------------------
    def solve(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float = 1e-9,
        singular_tol: float = 1e-6,
    ) -> IKSolution | IKBatch:
        """Every solution of one pose or a batch of poses.

        Parameters
        ----------
        T
            ``(4, 4)`` or ``(N, 4, 4)`` world-to-tool poses; or positions ``(3,)`` /
            ``(N, 3)`` for an arm without a wrist (then ``check="position"``).
        check
            ``"pose"`` keeps a branch only when its ``fk`` reproduces the whole pose within
            ``tol`` (max abs over the 12 entries); ``"position"`` compares positions only;
            ``None`` returns every finite branch unchecked.
        singular_tol
            A solution is flagged near a singularity when a factor of the Jacobian
            determinant is below this fraction of its largest value.

        One pose is solved by the program for floats; the few it cannot finish (a
        singular wrist, a division by zero) and batches by the program for numpy.
        """
        arr = np.asarray(T, dtype=float)
        if arr.shape[-1] == 3 and arr.ndim in (1, 2):
            if self.ik.decoupling.wrist:
                raise DHError("this arm has a wrist: give a full 4×4 pose, not a position")
            pose = np.zeros(arr.shape[:-1] + (4, 4))
            pose[..., :3, :3] = np.eye(3)
            pose[..., :3, 3] = arr
            pose[..., 3, 3] = 1.0
            arr, check = pose, ("position" if check is not None else None)
        single = arr.ndim == 2
        if arr.shape[-2:] != (4, 4) or arr.ndim not in (2, 3):
            raise DHError(f"expected poses of shape (4, 4) or (N, 4, 4), got {arr.shape}")
        cells = _POSITION if check == "position" else _ALL
        if single:
            one = self._solve_one(arr, check, cells, tol, singular_tol)
            if one is not None:
                return one
        batch = self._solve_batch(arr.reshape(-1, 4, 4), check, cells, tol, singular_tol)
        return batch.solution(0) if single else batch

    def _inner(self, poses: np.ndarray) -> np.ndarray:
        """Poses from frame 0 to frame n: base and tool undone."""
        if self._base_inv is not None:
            poses = self._base_inv @ poses
        if self._tool_inv is not None:
            poses = poses @ self._tool_inv
        return poses

    def _solve_batch(
        self,
        poses: np.ndarray,
        check: str | None,
        cells: Sequence[int],
        tol: float,
        singular_tol: float,
    ) -> IKBatch:
        inner = self._inner(poses)
        q, residual, closeness = self._evaluate(inner, poses, cells)
        assert residual is not None and closeness is not None
        valid = np.isfinite(residual) if check is None else residual <= tol
        # two branches coincide only where a radicand vanishes, i.e. at a singularity: look
        # for repeats (angles compared by cos and sin) only among poses near one
        suspects = np.nonzero((closeness < _SUSPECT).any(axis=(0, 1)) & valid.any(axis=0))[0]
        if suspects.size:
            qs, vs = q[:, :, suspects].transpose(2, 1, 0), valid[:, suspects].T
            rev = qs[..., self.revolute]
            key = np.concatenate([np.cos(rev), np.sin(rev), qs[..., ~self.revolute]], axis=-1)
            for k in range(1, self.K):
                close = np.abs(key[:, k : k + 1] - key[:, :k]).max(axis=-1) < 1e-9
                vs[:, k] &= ~(vs[:, :k] & close).any(axis=1)
            valid[:, suspects] = vs.T
        np.copyto(q, np.nan, where=~valid)
        near = (closeness < singular_tol) & valid
        names = tuple(f[0] for f in self._singular_factors())
        return IKBatch(
            q.transpose(2, 1, 0),
            valid.T,
            residual.T,
            near.transpose(2, 1, 0),
            names,
            self.branch_signs,
            self,
        )

    def _solve_one(
        self,
        pose: np.ndarray,
        check: str | None,
        cells: Sequence[int],
        tol: float,
        singular_tol: float,
    ) -> IKSolution | None:
        """One pose with the program for floats; ``None`` when it cannot finish it."""
        inner = self._inner(pose)
        args = inner[:3].T.ravel().tolist()
        args += args if inner is pose else pose[:3].T.ravel().tolist()
        try:
            out = self._program("scalar")(*args)
        except (ArithmeticError, ValueError):  # a division by zero, sin(inf): numpy decides
            return None
        n, w, K = self.n, len(self._wrist_s), self.K
        factors = self._singular_factors()
        F = len(factors)
        at = Layout.scalar(n, w, F, K)
        residual = out[at.position if check == "position" else at.whole]
        if w and _smallest(out[at.wrist]) < _WRIST_NEAR:
            return None  # a singular wrist: θ4 and θ6 from the whole rotation (numpy)
        if check is None:
            kept = [k for k, r in enumerate(residual) if r - r == 0]
        else:
            kept = [k for k, r in enumerate(residual) if r <= tol]
        values = out[at.joints]
        close = out[at.factors]
        low = _smallest(close)
        if len(kept) > 1 and low < _SUSPECT:  # two branches coincide only at a singularity
            kept = self._distinct(kept, values)
        if len(kept) == K:
            signs = self.branch_signs
        else:
            values = [v for k in kept for v in values[k * n : k * n + n]]
            residual = [residual[k] for k in kept]
            signs = self.branch_signs[kept]
        singular: tuple[tuple[str, ...], ...] = ((),) * len(kept)
        if low < singular_tol:
            kinds = [kind for kind, _, _ in factors]
            singular = tuple(
                tuple(kind for kind, c in zip(kinds, close[k * F : k * F + F]) if c < singular_tol)
                for k in kept
            )
        return IKSolution(
            np.array(values).reshape(len(kept), n), np.array(residual), singular, signs, self
        )

    def _distinct(self, kept: list[int], values: Sequence[float]) -> list[int]:
        """The branches of ``kept`` whose joint values (angles by cos and sin) differ from
        every earlier one's by more than 1e-9 (one pose; ``values`` branch by branch)."""
        n = self.n
        chosen: list[int] = []
        keys: list[list[float]] = []
        for k in kept:
            key = [
                v
                for x, rev in zip(values[k * n : k * n + n], self.revolute)
                for v in ((math.cos(x), math.sin(x)) if rev else (x,))
            ]
            if not any(max(abs(a - b) for a, b in zip(key, other)) < 1e-9 for other in keys):
                chosen.append(k)
                keys.append(key)
        return chosen

    def _singular_factors(self) -> tuple[tuple[str, Callable[[object], np.ndarray], float], ...]:
        """The non-constant factors of the Jacobian determinant: kind, compiled function and
        largest value over a sample (the scale of closeness); their exprs for the programs."""
        if self._factors is None:
            from dhsym.kinematics.singularities import singularities

            try:
                sing: Singularities = singularities(self.robot)
            except StructureError:
                self._factors = ()
                return self._factors
            rng = np.random.default_rng(0)
            sample = rng.uniform(-np.pi, np.pi, (256, self.n))
            sample[:, ~self.revolute] = rng.uniform(0.0, 1.0, (256, int((~self.revolute).sum())))
            found = []
            named = [f for f in sing.factors if f.kind != "constant"]
            for f, fn in zip(named, sing.factor_functions(self.values)):
                scale = float(np.nanmax(np.abs(fn(sample)))) or 1.0
                found.append((f.kind, fn, scale))
            self._factor_exprs = tuple(f.expr.xreplace(self.values) for f in named)
            self._factors = tuple(found)
        return self._factors


def _entries(poses: np.ndarray) -> list[np.ndarray]:
    """The 12 entries of poses ``(m, 4, 4)`` column by column, each a contiguous ``(m,)``."""
    block = np.ascontiguousarray(poses[:, :3].transpose(2, 1, 0))
    return list(block.reshape(12, -1))


def _smallest(values: Sequence[float]) -> float:
    """The smallest of ``values`` that is not NaN (``inf`` when none is)."""
    low = min(values, default=math.inf)
    if low != low:  # min keeps a NaN that comes first
        low = min((v for v in values if v == v), default=math.inf)
    return low


#: the 12 entries of a pose's top three rows, column by column (the order of the pose args)
_CELLS = [(i, j) for j in range(4) for i in range(3)]
_ALL = tuple(range(12))
_POSITION = (9, 10, 11)
