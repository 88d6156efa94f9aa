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
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.decoupling import StructureError
from dhsym.kinematics.jacobian import axis_frame
from dhsym.kinematics.numeric import evaluate_chunked
from dhsym.model.entries import as_expr
from dhsym.model.table import JointType

from .accuracy import REFINE
from .closed_form import ClosedForm
from .kept_programs import derivation_text, kept_program
from .protocols import NativeCompiler, NativeProgram, NativeRule, read_poses
from .rewriting import (
    MATH,
    NUMPY,
    REMAINDER,
    STRETCHED,
    TAU,
    WRIST_NEAR,
    WRIST_ZERO,
    Residual,
    Wrap,
    lift_residuals,
    per_branch,
    pull_signs,
    reuse_names,
    schedule,
    with_safe_sqrt,
    wrap,
)
from .solution import IKSolution
from .steps import REAL, Branch, branch_word

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from dhsym.kinematics.chain import KinematicChain
    from dhsym.kinematics.singularities import Singularities

__all__ = ["ClosedFormSolver", "Layout"]

#: what an :class:`IKSolution` of a closed form says it is
METHOD = "closed form"
#: fraction of a singular factor's largest value below which branches may coincide
_SUSPECT = 1e-4
#: the single poses a solver answers with its program for floats before it builds the
#: native one (a first answer does not wait for a C compiler; a solver in use gets it)
NATIVE_AFTER = 16


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


#: The programs a :class:`ClosedFormSolver` compiles (see :meth:`ClosedFormSolver._program`).
ProgramKind = Literal["raw", "checked", "stretched", "scalar", "singular"]


@dataclass
class Programs:
    """The lambdified programs of one :class:`ClosedFormSolver`, each built on first use:
    ``raw`` and ``checked`` (numpy, all branches by broadcasting), ``scalar`` (floats,
    every branch written out), ``singular`` (numpy: θ4 and θ6 at a singular wrist)."""

    raw: Callable[..., list[Any]] | None = None
    checked: Callable[..., list[Any]] | None = None
    stretched: Callable[..., list[Any]] | None = None
    scalar: Callable[..., list[Any]] | None = None
    singular: Callable[..., list[Any]] | None = None


class ClosedFormSolver:
    """The steps of a :class:`~dhsym.ik.closed_form.ClosedForm`, compiled for numbers (an
    :class:`~dhsym.ik.protocols.IKSolver`).

    :meth:`solve` takes one pose ``(4, 4)`` or a batch ``(N, 4, 4)`` and returns an
    :class:`~dhsym.ik.solution.IKSolution` (for a batch: padded arrays with a validity
    mask). Poses are
    world-to-tool, as ``fk`` gives them; base and tool transforms are undone first.

    The steps, the ``fk`` of the solutions and the singular factors at them are compiled
    into one straight-line program (``lambdify`` with the steps as the common
    subexpressions), twice: for numpy, where every branch of a block of poses is
    computed at once by broadcasting the signs (branches on the leading axes, poses on
    the last, contiguous one), and for plain floats (``math``), where the program is
    written out once per branch and one pose costs a few microseconds.
    """

    def __init__(
        self,
        ik: ClosedForm,
        values: Mapping[sp.Symbol, sp.Expr],
        native: NativeCompiler | None = None,
    ) -> None:
        robot = ik.robot
        self.ik = ik
        self.robot: KinematicChain = robot
        self.values = dict(values)
        self.n = len(robot.variables)
        self.revolute = np.array(
            [r.joint is JointType.REVOLUTE for r in robot.table.rows if r.variable is not None]
        )
        self.pose_args = [ik.pose[i, j] for j in range(4) for i in range(3)]
        self.targets = [sp.Dummy(f"T{i + 1}{j + 1}", **REAL) for j in range(4) for i in range(3)]
        self.signs = [b.symbol for b in ik.branches]
        self._steps = [(st.lhs, with_safe_sqrt(st.rhs.xreplace(self.values))) for st in ik.steps]
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
        # ``valid`` of one pose's solutions (all valid: the program for floats keeps only
        # the valid rows), a read-only view of this, shared as the signs are
        self._all_valid = np.ones(self.K, dtype=bool)
        self._all_valid.flags.writeable = False
        #: the native rule's mask of every branch kept, and ``near`` of branches far from
        #: every singularity (read-only, shared as ``valid``; its factors once known)
        self._every = float(2**self.K - 1)
        self._far_rows: np.ndarray | None = None
        self._base = self._constant(-1, 0) if robot.table.base else None
        self._tool = self._constant(robot.n, robot.n + 1) if robot.table.tool else None
        self._base_inv = None if self._base is None else np.linalg.inv(self._base)
        self._tool_inv = None if self._tool is None else np.linalg.inv(self._tool)
        self._factors: tuple[tuple[str, Callable[[object], np.ndarray], float], ...] | None = None
        self._factor_exprs: tuple[sp.Expr, ...] = ()
        self._frames: dict[int | None, Callable[[ArrayLike], np.ndarray]] = {}
        # lambdified programs: lists of floats (scalar) or of arrays (numpy)
        self._programs = Programs()
        # the program for one pose in native code (:meth:`native`): its compiler, the
        # single poses answered so far without it, and the program once built
        self._native = native
        self._singles = 0
        self._native_program: NativeProgram | None = None
        self._layout: tuple[Layout, tuple[str, ...]] | None = None

    def frame(self, k: int | None = None) -> Callable[[ArrayLike], np.ndarray]:
        """The compiled ``^0T_k`` (``None``: the whole ``fk``, world to tool), cached."""
        if k not in self._frames:
            fk = self.robot.fk_function
            self._frames[k] = fk(values=self.values) if k is None else fk(0, k, self.values)
        return self._frames[k]

    def branch_names(self, q: np.ndarray, signs: np.ndarray) -> tuple[str, ...]:
        """Each solution's branch in words (``"left arm, elbow up, wrist flipped"``), from its
        joint values ``q`` ``(k, n)`` and branch signs ``(k, B)``. The export room names its
        generated branches with the same words.

        >>> import dhsym
        >>> r = dhsym.load("planar2r")
        >>> solver = r.ik_cache().solver()
        >>> solver.branch_names(np.array([[0.4, 0.9]]), np.array([[-1]]))
        ('elbow down',)
        """
        parts: list[list[str]] = [[] for _ in range(len(q))]
        # one elbow: the last joint a law of cosines decides; another such branch (an arm
        # with one joint given may have two) is named by its root
        elbows = [b.joint for b in self.ik.branches if b.role == "elbow"]
        for b, col in zip(self.ik.branches, signs.T):
            var = self.robot.variables[b.joint - 1]
            if b.role == "elbow" and b.joint != max(elbows):
                words = [branch_word("sign", bool(sgn > 0), var) for sgn in col]
            elif b.role == "elbow":
                up = self._elbow_up(q, b) if len(q) else np.zeros(0, dtype=bool)
                words = [branch_word("elbow", bool(u)) for u in up]
            else:
                words = [branch_word(b.role, bool(sgn > 0), var) for sgn in col]
            for k, w in enumerate(words):
                parts[k].append(w)
        return tuple(", ".join(p) for p in parts)

    def _elbow_up(self, q: np.ndarray, branch: Branch) -> np.ndarray:
        """True where the elbow lies above the line from the shoulder to the wrist centre.

        "Above" is the side of +z0 for an arm that moves in a vertical plane, and the left
        of the shoulder-to-wrist line seen from above (+z0) for a planar arm. ``q`` is
        ``(k, n)``.
        """
        robot = self.robot
        rows = robot.table.joint_rows
        elbow_row = rows[branch.joint - 1]
        shoulder_row = rows[branch.joint - 2]
        s = self.frame(axis_frame(robot, shoulder_row))(q)[:, :3, 3]
        E = self.frame(axis_frame(robot, elbow_row))(q)
        e, h = E[:, :3, 3] - s, E[:, :3, 2]
        w = self.frame(self.ik.decoupling.centre)(q)[:, :3, 3] - s
        up = h[:, 2]
        planar = np.abs(up) > 0.5
        h_up = h * np.where(up < 0, -1.0, 1.0)[:, None]
        left = np.einsum("ij,ij->i", e, np.cross(h_up, w)) > 0
        w_perp = w - np.einsum("ij,ij->i", w, h)[:, None] * h
        e_perp = e - np.einsum("ij,ij->i", e, h)[:, None] * h
        n = np.cross(h, w_perp)
        n = n * np.where(n[:, 2] < 0, -1.0, 1.0)[:, None]
        above = np.einsum("ij,ij->i", e_perp, n) > 0
        elbow_up: np.ndarray = np.where(planar, left, above)
        return elbow_up

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

    def native(self, *, now: bool = False) -> NativeProgram | None:
        """The program for one pose in native code (the ``"scalar"`` program compiled by the
        :class:`~dhsym.ik.protocols.NativeCompiler` this solver was given), or ``None``
        (no compiler given, or it could not build it). It is built on the
        :data:`NATIVE_AFTER`-th call (``now=True``: on this one), so a first answer never
        waits for it; until then one pose is solved by the program for floats.

        >>> import dhsym
        >>> r = dhsym.load("planar2r")
        >>> ClosedFormSolver(r.inverse(), r.table.value_map).native(now=True) is None  # none given
        True
        """
        if self._native_program is not None or self._native is None:
            return self._native_program
        self._singles += 1
        if not now and self._singles < NATIVE_AFTER:
            return None
        args, program, reduced = kept_program(
            lambda: self._entry("scalar"), lambda: self._rewritten("scalar")
        )
        at, kinds = self._scalar_layout()
        rule = NativeRule(
            self.K,
            at.whole.start,
            at.wrist.start,
            at.wrist.stop - at.wrist.start,
            at.factors.start,
            at.factors.stop - at.factors.start,
            WRIST_NEAR,
            _SUSPECT,
            float(REFINE),  # the native rule's tolerances for a branch to refine
        )
        built = self._native(list(args), list(program), list(reduced), rule)
        if built is None:
            self._native = None  # not again
        self._native_program = built
        return built

    def _program(self, kind: ProgramKind) -> Callable[..., list[Any]]:
        """The compiled program of one ``kind``, built on first use.

        ``"raw"`` and ``"checked"`` (numpy, all branches by broadcasting), ``"scalar"``
        (floats, every branch written out), ``"singular"`` (numpy: θ4 and θ6 at a
        singular wrist).
        """
        built: Callable[..., list[Any]] | None = getattr(self._programs, kind)
        if built is None:
            # kept on disk: a warm process reads the rewritten program and only compiles it
            args, program, reduced = kept_program(
                lambda: self._entry(kind), lambda: self._rewritten(kind)
            )
            modules = {"scalar": MATH, "stretched": STRETCHED}.get(kind, NUMPY)
            built = sp.lambdify(
                list(args), list(reduced), modules=modules, cse=lambda exprs: (list(program), exprs)
            )
            setattr(self._programs, kind, built)
        return built

    def _entry(self, kind: ProgramKind) -> str:
        """The disk-cache entry of a program: the table, the versions, ``kind`` and the text
        of the steps with their values (:mod:`dhsym.ik.kept_programs`)."""
        from dhsym.cache.keys import entry_name

        values = sorted((sp.srepr(k), sp.srepr(v)) for k, v in self.values.items())
        parts = (self._steps, values, self.signs, self.pose_args, self._wrist_s, self._singular)
        return entry_name(self.robot.table, "ik_program", kind, derivation_text(*parts))

    def _rewritten(self, kind: ProgramKind) -> tuple[list[sp.Symbol], list[Any], list[Any]]:
        """The arguments, steps and outputs of the program of one ``kind`` (as
        :meth:`_program` compiles them)."""
        if kind == "singular":
            # θ4 as this program computes it, θ4 at sin θ5 = 0, θ6 from the whole rotation
            # with that θ4 (the pair stays consistent: near sin θ5 = 0 each alone is
            # ill-conditioned, their sum is not), and θ6 with θ4 = 0
            (t4, zero4), (_, whole6) = list(self._singular.items())
            alts = [t4, zero4, whole6, whole6.xreplace({t4: zero4})]
            outputs = [with_safe_sqrt(e.xreplace(self.values)) for e in alts]
        else:
            outputs = self._outputs(kind)
        program, reduced = schedule(*pull_signs(self._steps, outputs, self.signs))
        if kind == "scalar":
            # the wrap inline: one C call, no Python function
            program, reduced = lift_residuals(program, reduced)
            reduced = [
                e.replace(lambda t: isinstance(t, Wrap), lambda t: REMAINDER(t.args[0], TAU))
                for e in reduced
            ]
            program, written = per_branch(program, reduced, self.signs)
            # grouped for _solve_one: residuals and wrist sines of all branches first,
            # then the joint values branch by branch, then the factors branch by branch
            n, w = self.n, len(self._wrist_s)
            groups = [range(n + w, len(reduced) - len(self._factor_exprs))]
            groups += [
                range(n, n + w),
                range(n),
                range(len(reduced) - len(self._factor_exprs), len(reduced)),
            ]
            reduced = [o[i] for i in groups[0] for o in written]
            reduced += [o[i] for i in groups[1] for o in written]
            reduced += [o[i] for o in written for i in groups[2]]
            reduced += [o[i] for o in written for i in groups[3]]
            args = self.pose_args + self.targets
        elif kind in ("checked", "stretched"):
            program, reduced = reuse_names(program, reduced)
            args = self.pose_args + self.signs + self.targets
        else:
            program, reduced = reuse_names(program, reduced)
            args = self.pose_args + self.signs
        return args, program, reduced

    # -- raw closed form ----------------------------------------------------------------------
    def raw(self, T: np.ndarray) -> np.ndarray:
        """All branches for poses ``(N, 4, 4)`` (frame 0 to frame n): ``(N, K, n)``, unchecked.

        The result is a view of an array laid out joint by joint (branches, then poses).
        A single pose ``(4, 4)`` is a batch of one: ``(1, K, n)``.

        >>> import dhsym
        >>> solver = dhsym.load("planar2r").ik_cache().solver()
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
        self,
        inner: np.ndarray,
        target: np.ndarray | None,
        cells: Sequence[int] | None,
        stretch: bool = False,
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        """Every branch of every pose: ``q`` ``(n, K, N)``; with a ``target`` (the poses
        before base and tool were undone) also the residual ``(K, N)`` over ``cells`` (of
        the 12, column by column) and each singular factor's closeness ``(F, K, N)``.

        The program's values (each ``(*branches, chunk)``) are kept branch by branch, so
        :func:`~dhsym.kinematics.numeric.evaluate_chunked` fills ``(N, outputs × K)`` (a
        view of ``(outputs, K, N)``). ``stretch``: every negative radicand read as 0 (the
        program ``"stretched"``)."""
        N, K, n = inner.shape[0], self.K, self.n
        checked = target is not None
        fn = self._program(("stretched" if stretch else "checked") if checked else "raw")
        w = len(self._wrist_s)
        # the factors, not the program, say how many closeness rows it has: a program read
        # from the disk cache was never rewritten in this process
        F = len(self._singular_factors()) if checked else 0
        at = Layout.numpy(n, w, F)
        keep = list(range(n + w))  # the joint values and the wrist sines
        if checked:
            assert cells is not None
            keep.append((at.position if tuple(cells) == _POSITION else at.whole).start)
            keep += range(at.factors.start, at.factors.stop)
        signs, full = self._sign_arrays, self.shape
        # inputs and outputs laid out column by column (each column contiguous over the
        # poses, as numpy's loops like best), passed to evaluate_chunked as (N, k) views
        arrays = [_entries(inner).T]
        if target is not None and target is not inner:
            arrays.append(_entries(target).T)
        both = len(arrays) == 2

        def program(*columns: np.ndarray) -> list[np.ndarray]:
            pose = list(columns[:12])
            target_args = (list(columns[12:]) if both else pose) if checked else []
            res = fn(*pose, *signs, *target_args)
            size = len(columns[0])
            values = (np.broadcast_to(np.asarray(res[i], dtype=float), (*full, size)) for i in keep)
            return [row for v in values for row in v.reshape(K, size)]

        table = np.empty((len(keep), K, N))
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            evaluate_chunked(program, *arrays, out=table.reshape(len(keep) * K, N).T)
        q, residual, closeness = table[:n], None, None
        if checked:
            residual, closeness = table[n + w], table[n + w + 1 :]
        if w:  # |sin θ5| near 0: θ4 and θ6 from the whole rotation, below
            sines = table[n]
            hits = np.nonzero((sines < WRIST_NEAR).any(axis=0))[0]
            if hits.size:
                self._singular_wrist(inner[hits], q, hits, sines[:, hits])
                if checked:
                    assert target is not None and cells is not None
                    assert residual is not None and closeness is not None
                    qs = q[:, :, hits].transpose(2, 1, 0)
                    residual[:, hits], closeness[:, :, hits] = self._check(qs, target[hits], cells)
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
        near, zero = wrist < WRIST_NEAR, wrist < WRIST_ZERO
        q6, q4 = q[i6], q[i4]
        q6[:, rows] = np.where(zero, wrap(whole6_zero4), np.where(near, wrap(whole6), q6[:, rows]))
        q4[:, rows] = np.where(zero, wrap(zero4), np.where(near, wrap(own4), q4[:, rows]))

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
        stretch: bool = False,
    ) -> IKSolution:
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
        stretch
            Read every negative radicand as 0 (not only those within rounding of 0): a
            pose a little outside the workspace, rounded or measured, gives the arm
            stretched towards it, kept when it reproduces the pose within ``tol``
            (``Robot.ik`` asks for it for poses that are not exact).

        One pose is solved by the program for floats; the few it cannot finish (a
        singular wrist, a division by zero) and batches by the program for numpy.
        """
        arr, check = read_poses(T, check, wrist=bool(self.ik.decoupling.wrist))
        if arr.ndim == 2:
            return self._one(arr, check, tol, singular_tol, stretch)
        cells = _POSITION if check == "position" else _ALL
        return self._solve_batch(arr, check, cells, tol, singular_tol, stretch)

    def solve_pose(
        self, pose: np.ndarray, *, tol: float = 1e-9, singular_tol: float = 1e-6
    ) -> IKSolution:
        """Every solution of one pose ``(4, 4)`` of floats, read already (as
        :func:`~dhsym.ik.protocols.read_poses` gives it), each checked by the whole pose:
        what :meth:`solve` gives for it, without reading it again (``Robot.ik``'s path for
        one exact pose).

        >>> import dhsym
        >>> r = dhsym.load("puma560")
        >>> solver = r.ik_cache().solver()
        >>> T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
        >>> bool((solver.solve_pose(T).q == solver.solve(T).q).all())
        True
        """
        return self._one(pose, "pose", tol, singular_tol, False)

    def _one(
        self, pose: np.ndarray, check: str | None, tol: float, singular_tol: float, stretch: bool
    ) -> IKSolution:
        """One pose read already: the program for floats, else (a singular wrist, a
        division by zero, a stretched pose without native code) the program for numpy."""
        cells = _POSITION if check == "position" else _ALL
        one = self._solve_one(pose, check, cells, tol, singular_tol, stretch)
        if one is None:
            one = self._solve_batch(
                pose.reshape(1, 4, 4), check, cells, tol, singular_tol, stretch
            ).solution(0)
        return one if len(one) else replace(one, reason=self._why(pose, check, tol))

    def _why(self, pose: np.ndarray, check: str | None, tol: float) -> str:
        """Why one pose has no solution: the first step (in the order of the derivation)
        with no real value on any branch, when there is one; else that none reproduces
        the pose.

        >>> import dhsym
        >>> r = dhsym.load("puma560")
        >>> T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
        >>> T[:3, 3] *= 10
        >>> r.ik(T).reason.split(": ")[1].split(" (")[0]
        'no real value of theta3 on any branch'
        """
        said = _empty(check, tol)
        q = self.raw(self._inner(pose))[0]  # (K, n)
        if q.size == 0 or np.isfinite(q).any(axis=0).all():
            return said
        for lhs, _ in self._steps:
            if lhs in self.robot.variables:
                j = self.robot.variables.index(lhs)
                if not np.isfinite(q[:, j]).any():
                    reach = self._reach(pose)
                    return (
                        f"{said}: no real value of {lhs} on any branch (a cosine beyond ±1 "
                        "or a negative radicand, the pose is out of reach)"
                        + (f"; {reach}" if reach else "")
                    )
        return said

    def _reach(self, pose: np.ndarray) -> str | None:
        """How far the pose puts the wrist centre (the tool point of an arm without a
        wrist) from frame 0's origin, and how far the arm reaches it: the farthest of
        20,000 configurations drawn over the joints that place it (seed 0), in the table's
        length unit; None when the centre is within that reach (another step fails)."""
        if not np.isfinite(pose).all():
            return None  # a pose that is not numbers is at no distance
        dec = self.ik.decoupling
        inner = self._inner(pose[None])[0]
        c = np.array([float(v) for v in dec.centre_in_last.xreplace(self.values)] + [1.0])
        away = float(np.linalg.norm((inner @ c)[:3]))
        rng = np.random.default_rng(0)
        q = rng.uniform(-np.pi, np.pi, (20_000, self.n))
        for k, rev in enumerate(self.revolute):
            if not rev:
                lo, hi = self._prismatic_range(k)
                q[:, k] = rng.uniform(lo, hi, len(q))
        with np.errstate(invalid="ignore"):
            far = float(np.nanmax(np.linalg.norm(self.frame(dec.centre)(q)[:, :3, 3], axis=1)))
        if away <= far:
            return None
        point = "wrist centre" if dec.wrist else "tool point"
        return (
            f"the {point} is {away:.3g} from the origin of frame 0; this arm reaches at most "
            f"about {far:.3g} (lengths in the table's unit)"
        )

    def _prismatic_range(self, k: int) -> tuple[float, float]:
        """The range of prismatic joint ``k`` (0-based among the joints): its limits, else
        0 … 1."""
        rows = [r for r in self.robot.table.rows if r.variable is not None]
        limits = rows[k].limits
        if limits is None:
            return 0.0, 1.0
        lo, hi = (float(as_expr(v).xreplace(self.values)) for v in limits)
        return lo, hi

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
        stretch: bool = False,
    ) -> IKSolution:
        inner = self._inner(poses)
        q, residual, closeness = self._evaluate(inner, poses, cells, stretch)
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
        return IKSolution(
            q.transpose(2, 1, 0),
            valid.T,
            residual.T,
            near.transpose(2, 1, 0),
            names,
            self.branch_signs,
            METHOD,
            namer=self.branch_names,
        )

    def _solve_one(
        self,
        pose: np.ndarray,
        check: str | None,
        cells: Sequence[int],
        tol: float,
        singular_tol: float,
        stretch: bool = False,
    ) -> IKSolution | None:
        """One pose with the program for floats (native when built, :meth:`native`);
        ``None`` when it cannot finish it (the program for floats does not stretch; a
        singular wrist: :meth:`_read`)."""
        if not pose.flags.c_contiguous:
            pose = np.ascontiguousarray(pose, dtype=float)
        inner = self._inner(pose)
        fast = self._native_program
        if fast is None:
            fast = self.native()
        if fast is not None:
            out = fast.run(inner, pose, stretch)
        elif stretch:
            return None
        else:
            args = inner[:3].T.ravel().tolist()
            args += args if inner is pose else pose[:3].T.ravel().tolist()
            try:
                out = np.array(self._program("scalar")(*args), dtype=float)
            except (ArithmeticError, ValueError):  # a division by zero, sin(inf): numpy decides
                return None
        return self._read(out, check, tol, singular_tol)

    def solve_given(
        self, pose: np.ndarray, *, tol: float | None, singular_tol: float, within: float
    ) -> IKSolution | None:
        """Every solution of one pose as it comes ``(4, 4)`` (contiguous floats, read
        already) in one call of the native program
        (:data:`~dhsym.ik.protocols.NativeGiven`): the pose's tolerance and nearest rigid
        pose (:mod:`dhsym.ik.accuracy`, ``tol`` when given); an exact pose solved as
        given (as :meth:`solve_pose`), one that is not at its nearest rigid pose,
        stretched, its branches kept within ``within`` tolerances of it and then when
        their residual against the pose as given is within the tolerance.

        ``None`` where the caller's own path (:func:`dhsym.ik.choices.solve`) must answer:
        no native program (yet), no rotation near, a singular wrist, or for a pose that
        is not exact no solution (the reason needs it) or a branch to refine (within
        ``within`` tolerances of the pose as given but not within one).

        >>> import dhsym
        >>> r = dhsym.load("ur5")
        >>> solver = r.ik_cache().solver()
        >>> T = np.round(r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1]), 6)
        >>> _ = solver.native(now=True)  # built now, not on the 16th pose (None: no compiler)
        >>> got = solver.solve_given(T, tol=None, singular_tol=1e-6, within=30.0)
        >>> got is None or (len(got) == 8 and bool(got.residual.max() <= 1e-6))
        True
        """
        fast = self._native_program  # built by the program for floats' calls (native())
        if fast is None or fast.given is None:
            return None
        out = fast.given(pose, 0.0 if tol is None else tol, self._base_inv, self._tool_inv)
        given_tol, stretched, verdict, kept, low = out[:5].tolist()
        if not given_tol > 0.0 or verdict == 1.0:
            return None  # no rotation near (NaN, a reflection), or the caller's path decides
        m = (len(out) - 5) // 2
        if verdict == 2.0 or low < singular_tol or within != REFINE:
            if not stretched:  # exact: solved as given, as solve_pose
                one = self._read(out[5 : 5 + m], "pose", given_tol, singular_tol)
                if one is None or len(one):
                    return one
                return replace(one, reason=self._why(pose, "pose", given_tol))
            return self._read(
                out[5 : 5 + m], "pose", given_tol * within, singular_tol, out[5 + m :], given_tol
            )
        # the verdict: the kept branches are the answer, none near a singularity
        at, kinds = self._layout if self._layout is not None else self._scalar_layout()
        K, n, far = self.K, self.n, self._far_rows
        assert far is not None  # made with the layout
        values = out[5 + at.joints.start : 5 + at.joints.stop].reshape(K, n)
        start = 5 + m if stretched else 5  # the residuals against the pose as given
        residual = out[start + at.whole.start : start + at.whole.stop]
        if kept == self._every:
            k, signs = K, self.branch_signs
        else:
            rows = np.array([j for j in range(K) if int(kept) >> j & 1], dtype=np.intp)
            values, residual = values.take(rows, 0), residual.take(rows)
            k, signs = len(rows), self.branch_signs.take(rows, 0)
        return IKSolution(
            values,
            self._all_valid[:k],
            residual,
            far[:k],
            kinds,
            signs,
            METHOD,
            namer=self.branch_names,
        )

    def _read(
        self,
        out: np.ndarray,
        check: str | None,
        tol: float,
        singular_tol: float,
        given: np.ndarray | None = None,
        given_tol: float = 0.0,
    ) -> IKSolution | None:
        """The solutions in the outputs ``out`` of the program for floats (native or not)
        for one pose; ``None`` at a singular wrist (θ4 and θ6 from the whole rotation:
        numpy). With ``given`` (the outputs again, their residuals against the pose as
        given): the branches kept by ``tol`` are kept when that residual is within
        ``given_tol``; ``None`` when one of them is above it but within ``tol`` (to be
        refined: the caller's path) or none is left.

        The program's outputs are one array: the solutions' joint values and residuals
        are views of it when every branch is kept, rows taken from it otherwise; the few
        floats the decisions need (residuals, wrist sines, factors) are read as lists."""
        layout = self._layout
        at, kinds = layout if layout is not None else self._scalar_layout()
        head = out[: at.joints.start].tolist()  # the residuals and the wrist sines
        if self._wrist_s and _smallest(head[at.wrist]) < WRIST_NEAR:
            return None  # a singular wrist: θ4 and θ6 from the whole rotation (numpy)
        span = at.position if check == "position" else at.whole
        if check is None:
            kept = [k for k, r in enumerate(head[span]) if r - r == 0]
        else:
            kept = [k for k, r in enumerate(head[span]) if r <= tol]
        residual = out[span]
        n, K, F = self.n, self.K, len(kinds)
        values = out[at.joints].reshape(K, n)
        close = out[at.factors].tolist()
        low = _smallest(close)
        if len(kept) > 1 and low < _SUSPECT:  # two branches coincide only at a singularity
            kept = self._distinct(kept, values.ravel().tolist())
        if given is not None:
            residual = given[at.whole]
            against = residual.tolist()
            if any(given_tol < against[j] <= tol for j in kept):
                return None  # near the pose as given, not on it: refined by the caller
            kept = [j for j in kept if against[j] <= given_tol]
            if not kept:
                return None  # no solution: the caller says why
        k = len(kept)
        if k == K:
            signs = self.branch_signs
        else:
            rows = np.array(kept, dtype=np.intp)  # take: cheaper than indexing by a list
            values, residual = values.take(rows, 0), residual.take(rows)
            signs = self.branch_signs.take(rows, 0)
        near = np.zeros((k, F), dtype=bool)
        if low < singular_tol:
            for i, j in enumerate(kept):
                near[i] = [c < singular_tol for c in close[j * F : j * F + F]]
        return IKSolution(
            values,
            self._all_valid[:k],
            residual,
            near,
            kinds,
            signs,
            METHOD,
            _empty(check, tol) if not kept else None,
            namer=self.branch_names,
        )

    def _scalar_layout(self) -> tuple[Layout, tuple[str, ...]]:
        """The layout of the program for floats and the kinds of the singular factors."""
        if self._layout is None:
            kinds = tuple(kind for kind, _, _ in self._singular_factors())
            at = Layout.scalar(self.n, len(self._wrist_s), len(kinds), self.K)
            far = np.zeros((self.K, len(kinds)), dtype=bool)
            far.flags.writeable = False
            self._far_rows = far
            self._layout = (at, kinds)
        return self._layout

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


def _empty(check: str | None, tol: float) -> str:
    """Why one pose has no closed-form solution, as far as the solver knows."""
    if check is None:
        return "no branch of the closed form is finite at this pose"
    return f"no branch of the closed form reproduces the {check} within {tol:g}"


def _entries(poses: np.ndarray) -> np.ndarray:
    """The 12 entries of poses ``(m, 4, 4)`` column by column, each a contiguous ``(m,)``:
    ``(12, m)``."""
    return np.ascontiguousarray(poses[:, :3].transpose(2, 1, 0)).reshape(12, len(poses))


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
