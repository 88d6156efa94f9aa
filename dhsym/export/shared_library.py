"""The fast path back into Python: the exported C, built once into a cache, called by ctypes.

:func:`compiled` builds the C of :func:`dhsym.export.export` with ``cc`` in a private
temporary folder, keeps the library in dhsym's disk cache (:mod:`dhsym.cache.store`:
folders ``0700``, files ``0600``, each entry verified against an HMAC under a key only
this user can read) under a name made of the SHA-256 of the source and the compiler
flags, and loads it with :mod:`ctypes`. A library is loaded only after it passed the
store's checks: one planted or changed under the predictable name fails its HMAC, is
deleted and built again, and its code never runs. With the cache turned off
(``DHSYM_NO_CACHE=1``, ``--no-cache``) the library is built and loaded from the
temporary folder. Each call loads the library again (cheap: the OS shares it).
Without a C compiler it returns the same interface on dhsym's NumPy path
(``robot.fk``, ``robot.jacobian``, ``robot.ik``), with ``backend == "numpy"``.

Examples
--------
>>> import dhsym, numpy as np
>>> r = dhsym.load("planar2r")
>>> fast = compiled(r)
>>> fast.backend in ("c", "numpy")
True
>>> q = np.array([0.3, 0.5])
>>> bool(np.abs(fast.fk(q) - r.fk(q)).max() < 1e-12), len(fast.ik(r.fk(q)))
(True, 1)

``rne(q, qd, qdd)`` (robots with numeric inertial parameters) builds its own library on
its first call:

>>> from dhsym.model.tablefile import read_table_text
>>> arm = dhsym.Robot(read_table_text('''
... joints:
...   - {type: R, theta: q1, d: 0, a: 1, alpha: pi/2, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}
...   - {type: R, theta: q2, d: 0, a: 1, alpha: 0, m: 1, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}
... '''))
>>> x = np.array([0.3, -0.7])
>>> bool(np.allclose(compiled(arm).rne(x, x, x), arm.rne(x, x, x), rtol=1e-9, atol=1e-9))
True
"""

from __future__ import annotations

import ctypes
import functools
import os
import shutil
import subprocess
import sys
import tempfile
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from dhsym.errors import DHError

if TYPE_CHECKING:
    from collections.abc import Sequence

    import sympy as sp
    from numpy.typing import ArrayLike

    from dhsym.dynamics.compiled_dynamics import NativeRun
    from dhsym.ik.choices import IKCache
    from dhsym.ik.protocols import NativeProgram, NativeRule
    from dhsym.ik.solution import IKSolution
    from dhsym.kinematics.chain import KinematicChain
    from dhsym.kinematics.numeric import NumericProgram

__all__ = [
    "CompiledRobot",
    "cache_dir",
    "compiled",
    "library_name",
    "native_compiler",
    "native_program",
    "native_rows",
    "native_source",
    "rows_source",
]

_FLAGS = ("-O2", "-shared", "-fPIC", "-std=c99")
_PREFIX = "dhsym_arm"


def cache_dir() -> Path:
    """Where the libraries are kept: the entries of dhsym's disk cache
    (:func:`dhsym.cache.store.cache_root`: ``$DHSYM_CACHE``, else the user cache folder)."""
    from dhsym.cache.store import Store, cache_root

    return Store(cache_root()).entries


@dataclass(frozen=True, eq=False)
class CompiledRobot:
    """``fk(q)`` → (4, 4), ``jacobian(q)`` → (6, n), ``ik(T, tol=None)`` → (k, n) for one
    point each (the exported IK's tolerance: ``tol``, else dhsym's rule for poses as they
    come, :mod:`dhsym.ik.accuracy`);
    ``rne(q, qd, qdd)`` → (n,) (built on its first call; a robot without numeric inertial
    parameters raises then).

    ``backend`` is ``"c"`` (the exported C through ctypes) or ``"numpy"`` (no compiler:
    dhsym's own compiled NumPy functions); ``library`` the shared library's path.
    """

    fk: Callable[[ArrayLike], np.ndarray]
    jacobian: Callable[[ArrayLike], np.ndarray]
    ik: Callable[..., IKSolution]
    backend: str
    library: Path | None
    njoints: int
    rne: Callable[[object, object, object], np.ndarray] | None = None


def _compiler() -> str | None:
    return os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")


@functools.cache
def native_compiler() -> str | None:
    """The C compiler ``robot.ik`` and ``robot.fk`` build their native code with, chosen
    once per process: ``None`` (dhsym's NumPy path) when ``DHSYM_NO_COMPILE`` is ``1``,
    ``true`` or ``yes`` or no compiler is found (``$CC``, ``cc``, ``gcc``)."""
    if os.environ.get("DHSYM_NO_COMPILE", "").strip().lower() in ("1", "true", "yes"):
        return None
    return _compiler()


def library_name(source: dict[str, str], cc: str) -> str:
    """The cache entry of the library built from ``source`` by ``cc``: ``lib-<sha256>.so``
    (``.dylib`` on macOS) of the source files, the flags and the compiler."""
    from dhsym.cache.keys import source_name

    text = "\n".join(f"{k}\n{source[k]}" for k in sorted(source))
    suffix = ".dylib" if sys.platform == "darwin" else ".so"
    return source_name("lib", text + " ".join(_FLAGS) + cc) + suffix


def _load(source: dict[str, str], cc: str) -> tuple[ctypes.CDLL, Path | None]:
    """The library of ``source``: from the disk cache when it passes the store's checks,
    else built (and kept when the cache is on); loaded with ctypes, and its path in the
    cache (``None`` when the cache is off)."""
    from dhsym.cache.store import default_store

    name = library_name(source, cc)
    store = default_store()
    found = store.verified_file(name) if store is not None else None
    if found is not None:
        return ctypes.CDLL(str(found)), found
    with tempfile.TemporaryDirectory(prefix="dhsym-build-") as tmp:  # 0700, this user's
        for file, body in source.items():
            (Path(tmp) / file).write_text(body)
        out = Path(tmp) / name
        done = subprocess.run(
            [cc, *_FLAGS, f"{_PREFIX}.c", "-o", str(out), "-lm"],
            cwd=tmp,
            capture_output=True,
            text=True,
            check=False,
        )
        if done.returncode != 0:
            raise DHError(f"building the exported C failed: {done.stderr.strip()[:2000]}")
        kept = store.put_file(name, out) if store is not None else None
        # loaded from the private build folder: what was just built, whatever the cache holds
        return ctypes.CDLL(str(out)), kept


def _vector(q: object, n: int) -> np.ndarray:
    qa = np.ascontiguousarray(q, dtype=float)
    if qa.shape != (n,):
        raise DHError(f"expected {n} joint values, got an array of shape {qa.shape}")
    return qa


def _address(a: np.ndarray) -> int:
    address: int = a.__array_interface__["data"][0]
    return address


def compiled(
    robot: KinematicChain,
    lang: str = "c",
    *,
    cache: IKCache | None = None,
    rne: Callable[[object, object, object], np.ndarray] | None = None,
) -> CompiledRobot:
    """The robot's fk, Jacobian and IK as exported C loaded with ctypes (built once, cached).

    Falls back to dhsym's NumPy path when no C compiler is found. The IK is included
    when the robot has a closed form. ``cache`` is where the closed-form IK is derived
    and kept (a fresh :class:`~dhsym.ik.choices.IKCache` by default); ``rne`` the NumPy
    inverse dynamics of the fallback (by default compiled on its first call).
    ``Robot.compiled`` passes the robot's own.
    """
    if lang != "c":
        raise DHError(f"compiled(): only 'c' is built and loaded; got {lang!r}")
    from dhsym.ik.choices import IKCache, solve

    from . import export
    from .ik_source import derivation

    cache = cache if cache is not None else IKCache(robot)
    n = len(robot.variables)
    try:
        derivation(robot, cache)  # no closed form, or the general 6R: not exported
        what: tuple[str, ...] = ("fk", "jacobian", "ik")
    except DHError:
        what = ("fk", "jacobian")
    cc = _compiler()
    if cc is None:
        return CompiledRobot(
            lambda q: robot.fk(q),
            lambda q: robot.jacob0(q),
            lambda T, tol=None: solve(robot, T, tol=tol, cache=cache),
            "numpy",
            None,
            n,
            rne if rne is not None else _rne_numpy(robot),
        )
    lib, lib_path = _load(export(robot, "c", what=what, prefix=_PREFIX, cache=cache), cc)
    ptr = ctypes.c_void_p
    for name in ("fk", "jacobian") + (("ik",) if "ik" in what else ()):
        fn = getattr(lib, f"{_PREFIX}_{name}")
        fn.argtypes = [ptr, ctypes.c_double, ptr, ptr] if name == "ik" else [ptr, ptr]
        fn.restype = ctypes.c_int if name == "ik" else None
    fk_c, jac_c = lib.dhsym_arm_fk, lib.dhsym_arm_jacobian
    ik_c = lib.dhsym_arm_ik if "ik" in what else None
    K = 2 ** len(cache.inverse().branches) if ik_c is not None else 0

    def fk(q: object) -> np.ndarray:
        qa = _vector(q, n)
        out = np.empty((4, 4))
        fk_c(_address(qa), _address(out))
        return out

    def jacobian(q: object) -> np.ndarray:
        qa = _vector(q, n)
        out = np.empty((6, n))
        jac_c(_address(qa), _address(out))
        return out

    def ik(T: object, tol: float | None = None) -> IKSolution:
        from dhsym.ik.solution import IKSolution

        if ik_c is None:
            raise DHError(f"{robot.name or 'this robot'} has no closed-form IK to compile")
        Ta = np.ascontiguousarray(T, dtype=float)
        if Ta.shape != (4, 4):
            raise DHError(f"ik expects one pose of shape (4, 4), got {Ta.shape}")
        out = np.empty((K, n))
        residual = np.empty(K)
        count = ik_c(_address(Ta), 0.0 if tol is None else tol, _address(out), _address(residual))
        q = out[:count]

        def names(rows: np.ndarray, _signs: np.ndarray) -> tuple[str, ...]:
            # the branch each row is: the nearest solution robot.ik finds (angles modulo 2π)
            ref = solve(robot, Ta, cache=cache)
            if not len(ref):
                return tuple(f"solution {k}" for k in range(1, len(rows) + 1))
            d = rows[:, None, :] - ref.q[None, :, :]
            d = np.abs(np.remainder(d + np.pi, 2 * np.pi) - np.pi).max(axis=-1)
            return tuple(ref.branches[int(j)] for j in d.argmin(axis=1))

        return IKSolution(
            q,
            np.ones(count, dtype=bool),
            residual[:count],
            np.zeros((count, 0), dtype=bool),
            (),
            np.zeros((count, 0), dtype=int),
            "compiled",
            None if count else "no branch of the exported closed form reproduces the pose",
            namer=names,
        )

    return CompiledRobot(fk, jacobian, ik, "c", lib_path, n, _rne_c(robot, cc, n))


def _rne_numpy(robot: KinematicChain) -> Callable[[object, object, object], np.ndarray]:
    """``rne(q, qd, qdd)`` on dhsym's NumPy path, compiled on the first call."""
    from dhsym.dynamics.compiled_dynamics import DynamicsFunctions, dynamics_functions

    built: list[DynamicsFunctions] = []  # the compiled dynamics, once built

    def rne(q: object, qd: object, qdd: object) -> np.ndarray:
        if not built:
            built.append(dynamics_functions(robot))
        return np.asarray(built[0].rne(q, qd, qdd))

    return rne


def _rne_c(
    robot: KinematicChain, cc: str, n: int
) -> Callable[[object, object, object], np.ndarray]:
    """``rne(q, qd, qdd)`` of the exported C, built and loaded on the first call (the
    recursion of a 6R takes seconds to write out: only then)."""
    from . import export

    loaded: list[Callable[..., None]] = []  # the loaded function, once built

    def rne(q: object, qd: object, qdd: object) -> np.ndarray:
        if not loaded:
            source = export(robot, "c", what=("dynamics",), prefix=_PREFIX)
            fn = _load(source, cc)[0].dhsym_arm_rne
            fn.argtypes = [ctypes.c_void_p] * 4
            fn.restype = None
            loaded.append(fn)
        qa, va, aa = _vector(q, n), _vector(qd, n), _vector(qdd, n)
        out = np.empty(n)
        loaded[0](_address(qa), _address(va), _address(aa), _address(out))
        return out

    return rne


# -- the closed-form solver's program for one pose, in C ------------------------------------
_NATIVE = "dhsym_arm_program"


def native_source(
    args: Sequence[sp.Symbol],
    program: Sequence[tuple[sp.Symbol, sp.Expr]],
    outputs: Sequence[sp.Expr],
    rule: NativeRule | None = None,
) -> str:
    """The C of a closed-form solver's program for one pose
    (:class:`dhsym.ik.protocols.NativeCompiler`): the function
    ``void dhsym_arm_program(const double A[16], const double B[16], int stretch,
    double out[])``, and around it, with a ``rule``, robot.ik's rule for a pose as it
    comes (:func:`_given_source`). The program reads its 24 arguments from the two
    row-major poses (12 each, column by column), has one ``const double`` per line of
    the program and one entry of ``out`` per output, as the solver's program for floats
    computes them (``remainder`` of C99 as ``math.remainder``, ``safe_sqrt`` as
    :func:`dhsym.ik.rewriting.safe_sqrt_float`, every negative radicand read as 0 with
    ``stretch``, a residual ``NaN`` when any of its differences is).

    >>> import sympy as sp
    >>> a = sp.symbols("a:24", real=True)
    >>> src = native_source(a, [(sp.Symbol("t"), sp.atan2(a[1], a[0]))], [sp.Symbol("t")])
    >>> [line.strip() for line in src.splitlines() if "t0" in line]
    ['const double t0 = atan2(a1, a0);', 'out[0] = t0;']
    """
    import sympy as sp

    from dhsym.ik.rewriting import ROUNDING, TAU
    from dhsym.model.entries import as_expr

    from .c import NativePrinter

    names: dict[sp.Symbol, sp.Symbol] = {s: sp.Symbol(f"a{k}") for k, s in enumerate(args)}
    names[TAU] = sp.Float(2 * np.pi, 17)
    # math.h of strict C99 has no M_PI: the constants as doubles (as math.pi, math.e)
    names[sp.pi] = sp.Float(np.pi, 17)
    names[sp.E] = sp.Float(np.e, 17)
    lines = []
    for k, (sym, e) in enumerate(program):
        value = e.xreplace(names)
        names[sym] = sp.Symbol(f"t{k}")
        lines.append((names[sym], value))
    printer = NativePrinter()
    body = [
        f"    const double a{k} = {'AB'[k // 12]}[{4 * (k % 3) + (k % 12) // 3}];"
        for k in range(len(args))
    ]
    body += [f"    const double {lhs} = {printer.doprint(rhs)};" for lhs, rhs in lines]
    body += [
        f"    out[{k}] = {printer.doprint(as_expr(o).xreplace(names))};"
        for k, o in enumerate(outputs)
    ]
    return "\n".join(
        [
            "/* dhsym: the closed-form solver's program for one pose (every branch, its fk",
            " * residuals, wrist sines and singular factors), built by robot.ik. */",
            "#include <math.h>",
            "",
            "/* sqrt reading a radicand within rounding of 0 (with stretch: any) as 0 */",
            "static double safe_sqrt(double x, int stretch)",
            "{",
            "    if (x >= 0.0) {",
            "        return sqrt(x);",
            "    }",
            "    if (x != x) {",
            "        return x;",
            "    }",
            f"    return (stretch || x > -{ROUNDING!r}) ? 0.0 : NAN;",
            "}",
            "",
            "/* the larger of two magnitudes, NaN when either is */",
            "static double nan_max(double x, double y)",
            "{",
            "    return (x != x || x > y) ? x : y;",
            "}",
            "",
            f"void {_NATIVE}(const double A[16], const double B[16], int stretch, double out[])",
            "{",
            "    (void)stretch;",
            *body,
            "}",
            "",
            *([] if rule is None else [_given_source(len(outputs), rule)]),
        ]
    )


def _given_source(m: int, rule: NativeRule) -> str:
    """The C of robot.ik's rule for one pose as it comes around the program
    (:data:`dhsym.ik.protocols.NativeGiven`): ``void dhsym_arm_given(const double T[16],
    double tol, const double base_inv[16], const double tool_inv[16], double out[])``,
    the pose's accuracy and nearest rigid pose as the exported IK finds them (the one
    ``pose_accuracy`` of ``templates/export/c_math.j2``), then the program (``m``
    outputs) at the pose as given (exact) or stretched at its nearest rigid pose, with
    the residuals against it and against the pose as given, and the ``rule``'s verdict
    (:class:`dhsym.ik.protocols.NativeRule`)."""
    from dhsym.ik.accuracy import EXACT, FLOOR, MOST_DECIMALS
    from dhsym.notation.templates import CODE, environment

    macro = environment("text", CODE).from_string(
        '{% import "c_math.j2" as own %}{{ own.pose_accuracy(floor, exact, most)|trim("\\n") }}'
    )
    accuracy = macro.render(floor=FLOOR, exact=EXACT, most=MOST_DECIMALS)
    return "\n".join(
        [
            accuracy,
            "",
            "/* Z = X Y of row-major 4 x 4 matrices */",
            "static void product(const double X[16], const double Y[16], double Z[16])",
            "{",
            "    int i, j;",
            "    for (i = 0; i < 4; ++i) {",
            "        for (j = 0; j < 4; ++j) {",
            "            Z[4 * i + j] = X[4 * i] * Y[j] + X[4 * i + 1] * Y[4 + j]"
            " + X[4 * i + 2] * Y[8 + j] + X[4 * i + 3] * Y[12 + j];",
            "        }",
            "    }",
            "}",
            "",
            "/* robot.ik's rule for one pose as it comes (dhsym.ik.accuracy): out[0] its tolerance",
            " * (tol when tol > 0; not above 0: no rotation near, nothing else written), out[1]",
            " * whether it is not exact, out[2] the verdict (0: the kept branches are the answer;",
            " * 1: robot.ik's own path answers; 2: read the outputs one by one), out[3] the kept",
            " * branches (bit k: branch k), out[4] the smallest closeness to a singularity; from",
            f" * out[5] the program's {m} outputs at the pose (base and tool undone when given):",
            " * an exact pose as it is, else its nearest rigid pose R stretched, and then the",
            " * outputs again against T (the residuals against the pose as given). */",
            "void dhsym_arm_given(const double T[16], double tol, const double base_inv[16],",
            "                     const double tool_inv[16], double out[])",
            "{",
            "    double R[16], with_base[16], inner[16];",
            f"    const double *A = R, *o = out + 5, *g = out + {5 + m};",
            "    double candidate, low = INFINITY, wrist = INFINITY;",
            "    int stretch = 0, k, kept = 0, count = 0, refine = 0;",
            "    out[0] = pose_accuracy(T, tol, R, &stretch);",
            "    out[1] = stretch;",
            "    if (!(out[0] > 0.0)) {",
            "        return;",
            "    }",
            "    if (base_inv) {",
            "        product(base_inv, A, with_base);",
            "        A = with_base;",
            "    }",
            "    if (tool_inv) {",
            "        product(A, tool_inv, inner);",
            "        A = inner;",
            "    }",
            f"    {_NATIVE}(A, R, stretch, out + 5);",
            "    if (stretch) {",
            f"        {_NATIVE}(A, T, 1, out + {5 + m});",
            "    }",
            "    /* a branch within the tolerance of the pose solved (within"
            f" {rule.within!r} of them: a pose",
            "     * that is not exact) is kept when it is within it of the pose as given; one",
            "     * above it but within the candidates' tolerance is to be refined */",
            f"    candidate = stretch ? out[0] * {rule.within!r} : out[0];",
            f"    for (k = 0; k < {rule.branches}; ++k) {{",
            f"        if (!(o[{rule.whole} + k] <= candidate)) {{",
            "            continue;",
            "        }",
            f"        if (stretch && !(g[{rule.whole} + k] <= out[0])) {{",
            f"            refine |= g[{rule.whole} + k] <= candidate;",
            "            continue;",
            "        }",
            "        kept |= 1 << k;",
            "        ++count;",
            "    }",
            "    /* the smallest wrist sine and closeness to a singularity (NaN passed over) */",
            f"    for (k = 0; k < {rule.wrist_count}; ++k) {{",
            f"        wrist = o[{rule.wrist} + k] < wrist ? o[{rule.wrist} + k] : wrist;",
            "    }",
            f"    for (k = 0; k < {rule.factor_count}; ++k) {{",
            f"        low = o[{rule.factors} + k] < low ? o[{rule.factors} + k] : low;",
            "    }",
            f"    if (wrist < {rule.wrist_near!r} || (stretch && (refine || !count))) {{",
            "        out[2] = 1.0;",
            f"    }} else if (low < {rule.suspect!r} || !count) {{",
            "        out[2] = 2.0;",
            "    } else {",
            "        out[2] = 0.0;",
            "    }",
            "    out[3] = kept;",
            "    out[4] = low;",
            "}",
            "",
        ]
    )


def native_program(
    args: Sequence[sp.Symbol],
    program: Sequence[tuple[sp.Symbol, sp.Expr]],
    outputs: Sequence[sp.Expr],
    rule: NativeRule,
) -> NativeProgram | None:
    """The :class:`dhsym.ik.protocols.NativeCompiler` of the facade: the program's C
    (:func:`native_source`) built by :func:`native_compiler` into the disk cache (as
    :func:`compiled`: verified before it is loaded), its two functions called by ctypes
    (a :class:`~dhsym.ik.protocols.NativeProgram`: ``run``, and ``given`` with the rule
    for a pose as it comes); ``None`` without a compiler, or when the build fails."""
    from dhsym.ik.protocols import NativeProgram

    cc = native_compiler()
    if cc is None:
        return None
    try:
        lib = _load({f"{_PREFIX}.c": native_source(args, program, outputs, rule)}, cc)[0]
    except (DHError, OSError):
        return None
    fn = getattr(lib, _NATIVE)
    fn.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p]
    fn.restype = None
    around = lib.dhsym_arm_given
    ptr = ctypes.c_void_p
    around.argtypes = [ptr, ctypes.c_double, ptr, ptr, ptr]
    around.restype = None
    m = len(outputs)
    # each thread its own buffers, made on its first call (no lock, nothing shared): the
    # poses are copied in, the C writes the outputs into a numpy array, and the call
    # returns a copy of it (an array the caller owns; no list, no address looked up per call)
    local = threading.local()

    def buffers() -> _Buffers:
        poses = np.empty((4, 4, 4))  # the pose from frame 0 to n, as given, base⁻¹, tool⁻¹
        values, around_values = np.empty(m), np.empty(5 + 2 * m)
        at = _address(poses)
        inner, pose, base_inv, tool_inv = poses
        values_at, around_at = _address(values), _address(around_values)
        made = _Buffers(
            inner, pose, base_inv, tool_inv, at, at + 128, at + 256, at + 384,
            values, values_at, around_values, around_at,
        )  # fmt: skip
        local.buffers = made
        return made

    def run(inner: np.ndarray, pose: np.ndarray, stretch: bool) -> np.ndarray:
        try:
            b = local.buffers
        except AttributeError:
            b = buffers()
        b.inner[...] = inner
        if pose is inner:
            fn(b.inner_at, b.inner_at, stretch, b.values_at)
        else:
            b.pose[...] = pose
            fn(b.inner_at, b.pose_at, stretch, b.values_at)
        got: np.ndarray = b.values.copy()
        return got

    def given(
        pose: np.ndarray, tol: float, base_inv: np.ndarray | None, tool_inv: np.ndarray | None
    ) -> np.ndarray:
        try:
            b = local.buffers
        except AttributeError:
            b = buffers()
        b.pose[...] = pose
        base_at = tool_at = None
        if base_inv is not None:
            b.base_inv[...] = base_inv
            base_at = b.base_at
        if tool_inv is not None:
            b.tool_inv[...] = tool_inv
            tool_at = b.tool_at
        around(b.pose_at, tol, base_at, tool_at, b.around_at)
        got: np.ndarray = b.around.copy()
        return got

    return NativeProgram(run, given, lib)


@dataclass(frozen=True, eq=False)
class _Buffers:
    """One thread's buffers of :func:`native_program` and their addresses: the four poses
    (the pose from frame 0 to n, the pose as given, the inverses of base and tool), the
    outputs of ``run`` and those of ``given``."""

    inner: np.ndarray
    pose: np.ndarray
    base_inv: np.ndarray
    tool_inv: np.ndarray
    inner_at: int
    pose_at: int
    base_at: int
    tool_at: int
    values: np.ndarray
    values_at: int
    around: np.ndarray
    around_at: int


# -- a straight-line program of floats, row by row, in C --------------------------------------
_ROWS = "dhsym_rows"


def rows_source(program: NumericProgram, variables: Sequence[sp.Symbol]) -> str:
    """The C of a :class:`~dhsym.kinematics.numeric.NumericProgram` evaluated row by row
    (:class:`dhsym.dynamics.compiled_dynamics.NativeRowsCompiler`): one function
    ``void dhsym_rows(const double *in, double *out, int m)`` reading each of the ``m``
    rows of ``in`` (one value per variable, in order) into ``const double a<k>``, one
    ``const double`` per assignment of the program, and writing one entry of the row of
    ``out`` per output: the same operations, in the same order, as
    :func:`~dhsym.kinematics.numeric.compile_program` evaluates for floats.

    >>> import sympy as sp
    >>> from dhsym.kinematics.numeric import NumericProgram
    >>> x, y = sp.symbols("x y", real=True)
    >>> prog = NumericProgram.of([sp.sin(x + y), 2 * sp.cos(x + y)], (x, y))
    >>> for line in rows_source(prog, (x, y)).splitlines()[5:]:
    ...     print(line)
    {
        for (int i = 0; i < m; ++i, in += 2, out += 2) {
            const double a0 = in[0];
            const double a1 = in[1];
            const double t0 = a0 + a1;
            out[0] = sin(t0);
            out[1] = 2*cos(t0);
        }
    }
    """
    import sympy as sp

    from dhsym.model.entries import as_expr

    from .c import NativePrinter

    names: dict[sp.Basic, sp.Basic] = {s: sp.Symbol(f"a{k}") for k, s in enumerate(variables)}
    # math.h of strict C99 has no M_PI: the constants as doubles (as math.pi, math.e)
    names[sp.pi] = sp.Float(np.pi, 17)
    names[sp.E] = sp.Float(np.e, 17)
    printer = NativePrinter()  # libm's sin and cos, as NumPy's evaluation of the program
    body = [f"        const double a{k} = in[{k}];" for k in range(len(variables))]
    for k, (sym, e) in enumerate(program.assignments):
        value = printer.doprint(e.xreplace(names))
        names[sym] = sp.Symbol(f"t{k}")
        body.append(f"        const double t{k} = {value};")
    body += [
        f"        out[{k}] = {printer.doprint(as_expr(o).xreplace(names))};"
        for k, o in enumerate(program.outputs)
    ]
    k, p = len(variables), len(program.outputs)
    return "\n".join(
        [
            "/* dhsym: a straight-line program of floats evaluated row by row (each row of",
            f" * in: {k} values, each row of out: {p}), built by dhsym's numeric dynamics. */",
            "#include <math.h>",
            "",
            f"void {_ROWS}(const double *in, double *out, int m)",
            "{",
            f"    for (int i = 0; i < m; ++i, in += {k}, out += {p}) {{",
            *body,
            "    }",
            "}",
            "",
        ]
    )


def native_rows(
    program: NumericProgram,
    variables: Sequence[sp.Symbol],
    inputs: np.ndarray,
    outputs: np.ndarray,
) -> NativeRun | None:
    """The :class:`dhsym.dynamics.compiled_dynamics.NativeRowsCompiler` of the facade: the
    program's C (:func:`rows_source`) built by :func:`native_compiler` into the disk cache
    (as :func:`compiled`: verified before it is loaded) and bound to the caller's buffers
    ``inputs`` ``(R, len(variables))`` and ``outputs`` ``(R, len(program.outputs))``
    (C-contiguous floats, kept alive by the function): ``run(m)`` evaluates the first
    ``m <= R`` rows of ``inputs`` into those of ``outputs``. ``None`` without a
    compiler, when a buffer does not fit, or when the build fails (a function C does not
    have: the caller keeps its own program for floats)."""
    cc = native_compiler()
    k, p = len(variables), len(program.outputs)
    fits = all(
        a.dtype == np.float64 and a.ndim == 2 and a.flags.c_contiguous and a.shape[1] == w
        for a, w in ((inputs, k), (outputs, p))
    )
    if cc is None or not fits or inputs.shape[0] != outputs.shape[0]:
        return None
    try:
        lib = _load({f"{_PREFIX}.c": rows_source(program, variables)}, cc)[0]
    except (DHError, OSError, NotImplementedError):  # NotImplementedError: C has no such function
        return None
    fn = getattr(lib, _ROWS)
    fn.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int]
    fn.restype = None
    rows = inputs.shape[0]
    at_in, at_out = _address(inputs), _address(outputs)

    def run(m: int) -> None:
        if not 0 <= m <= rows:
            raise DHError(f"{m} rows do not fit the native program's buffers of {rows}")
        fn(at_in, at_out, m)

    # the library and the buffers live as long as the function
    run.keep = (lib, inputs, outputs)  # type: ignore[attr-defined]
    return run
