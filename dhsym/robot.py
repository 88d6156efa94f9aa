"""``Robot``: the facade over a :class:`~dhsym.kinematics.chain.KinematicChain` with the
conveniences of the rooms above the kinematics.

A :class:`Robot` is a :class:`~dhsym.kinematics.chain.KinematicChain` (table, notation, ``^iT_j``,
``fk``, ``jacobian``, ``jacob0``, …) that also derives and solves its inverse kinematics
(:mod:`dhsym.ik`), its dynamics (:mod:`dhsym.dynamics`), draws itself (:mod:`dhsym.plot`),
writes itself in other tools' formats (:mod:`dhsym.formats`) and loads its exported C
(:mod:`dhsym.export`). It is a room of its own, above all of these and below
:mod:`dhsym.explain`; each room it reaches is imported on first use. What it computes is
cached in typed fields, one per kind of result, shared by every robot of an equal table
(the process's memo, :mod:`dhsym.cache.memo`): a second ``load("puma560")`` derives nothing
again.

Examples
--------
>>> r = load("planar2r")
>>> r
Robot('Planar 2R', RR, standard)
>>> [b.role for b in r.inverse().branches]
['elbow']
>>> r.ik(r.fk([0.4, 0.9]), check="position").q.shape
(2, 2)
"""

from __future__ import annotations

import os
import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, overload

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.chain import JacobianKey, KinematicChain
from dhsym.model.kinds import Convention
from dhsym.model.library import load_table
from dhsym.model.table import DHTable
from dhsym.notation.printers import TrigStyle

if TYPE_CHECKING:
    import numpy as np
    from matplotlib.figure import Figure

    from dhsym.dynamics.compiled_dynamics import (
        DynamicsFunctions,
        NativeRowsCompiler,
        Trajectory,
    )
    from dhsym.dynamics.equations import EquationsOfMotion
    from dhsym.dynamics.static_forces import Statics
    from dhsym.export.shared_library import CompiledRobot
    from dhsym.ik.choices import IKCache
    from dhsym.ik.closed_form import ClosedForm
    from dhsym.ik.general6r import Elimination
    from dhsym.ik.protocols import NativeCompiler
    from dhsym.ik.solution import IKSolution
    from dhsym.model.angles import AngleSnap
    from dhsym.screws.product import ProductOfExponentials, ScrewJacobian
    from dhsym.trajectory.paths import CartesianPath, JointPath

__all__ = ["Robot", "RobotState", "from_poe", "from_rtb", "from_urdf", "inverse", "load"]


@dataclass(eq=False)
class RobotState:
    """What a robot derives above its kinematics, shared by every robot of an equal table
    and notation (:mod:`dhsym.cache.memo`): the inverse kinematics and its sub-chains
    (``ik_cache``), the equations of motion (one field per method) and the compiled
    dynamics by the values given (:func:`dhsym.kinematics.numeric.values_key`). ``lock``
    makes threads that ask for the same result derive it once."""

    ik_cache: IKCache | None = None
    lagrange: EquationsOfMotion | None = None
    newton_euler: EquationsOfMotion | None = None
    dynamics_functions: dict[object, DynamicsFunctions] = field(default_factory=dict)
    poe: ProductOfExponentials | None = None
    screw_jacobians: dict[str, ScrewJacobian] = field(default_factory=dict)
    lock: threading.RLock = field(default_factory=threading.RLock, repr=False)

    def memo_size(self) -> int:
        """The estimated size (:class:`dhsym.cache.memo.Sized`, expression nodes): a rough
        figure per derived result."""
        return (
            1
            + 50_000 * (self.ik_cache is not None)
            + 200_000 * ((self.lagrange is not None) + (self.newton_euler is not None))
            + 50_000 * len(self.dynamics_functions)
        )


class Robot(KinematicChain):
    """A :class:`~dhsym.kinematics.chain.KinematicChain` with inverse kinematics, dynamics, plots,
    file formats and compiled code, each reached on first use and cached.

    ``compact`` and ``style`` set how its matrices print (as for ``KinematicChain``).
    """

    def __init__(
        self, table: DHTable, *, compact: bool = True, style: TrigStyle | str = TrigStyle.UPPER
    ) -> None:
        super().__init__(table, compact=compact, style=style)
        from dhsym.cache.memo import MEMO, MemoKey

        # the inverse kinematics, equations of motion and compiled dynamics, shared
        self._shared = MEMO.get(MemoKey(table, RobotState, self.notation), RobotState)

    # -- inverse kinematics (dhsym.ik) -------------------------------------------------
    def ik_cache(self) -> IKCache:
        """The derived inverse kinematics of this robot and of its sub-chains with a joint
        given (:class:`dhsym.ik.choices.IKCache`), made on first use."""
        shared = self._shared
        if shared.ik_cache is None:
            from dhsym.ik.choices import IKCache

            with shared.lock:
                if shared.ik_cache is None:
                    shared.ik_cache = IKCache(self, _native_compiler())
        return shared.ik_cache

    def inverse(self) -> ClosedForm | Elimination:
        """The inverse kinematics derived step by step (:mod:`dhsym.ik`), cached: the closed
        form, or for the general 6R the elimination (threads asking at once derive it once)."""
        with self._shared.lock:
            return self.ik_cache().inverse()

    def ik(
        self,
        T: object,
        *,
        check: str | None = "pose",
        tol: float | None = None,
        singular_tol: float = 1e-6,
        values: Mapping[object, object] | None = None,
        free: Mapping[int, float] | None = None,
        limits: bool = False,
        near: object = None,
    ) -> IKSolution:
        """Every solution of a pose or a batch of poses (see :mod:`dhsym.ik`).

        One pose ``(4, 4)`` gives an ``IKSolution`` with ``.q`` ``(k, n)`` and branch
        names; a batch ``(N, 4, 4)`` the same type over a leading axis (padded
        ``(N, K, n)`` with a validity mask, ``solution(i)`` for pose ``i``).
        ``free={7: 0.3}`` gives joint 7 (1-based) and solves the others; ``limits=True``
        keeps the solutions within the joint limits (angles shifted by 2π into range);
        ``near=q0`` orders them by distance to ``q0`` (:func:`dhsym.ik.choices.solve`).

        Poses as they come (measured, rounded, typed from a teach pendant): a rotation that
        is not exactly a rotation is brought to the nearest one (polar decomposition, the
        position kept) and the branches computed there; each solution's ``residual`` is
        the largest entry error of its ``fk`` against the pose *as given* (position
        entries in length units; rotation entries, which for small errors bound the
        orientation error in radians). A solution is kept when its residual is within
        ``tol``: by default 1e-9 for an exact pose, else ``max(1e-9, 2·max(off,
        min(h, 3·off)))``, ``off`` the rotation's largest entry distance from the nearest
        rotation and ``h`` half a unit of the last decimal the entries were written with
        (:mod:`dhsym.ik.accuracy`); ``tol=`` overrides. ``np.round(T, 6)`` of a UR5 pose
        gives its 8 solutions:

        >>> import dhsym, numpy as np
        >>> r = dhsym.load("ur5")
        >>> T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
        >>> len(r.ik(T)), len(r.ik(np.round(T, 6))), len(r.ik(np.round(T, 3)))
        (8, 8, 8)
        """
        cache = self._shared.ik_cache  # made once (ik_cache); no import on each call
        if cache is None:
            cache = self.ik_cache()
        return cache.solve(
            self,
            T,
            check=check,
            tol=tol,
            singular_tol=singular_tol,
            values=values,
            free=free,
            limits=limits,
            near=near,
        )

    # -- screws and the product of exponentials (dhsym.screws) -------------------------
    def poe(self) -> ProductOfExponentials:
        """This robot as a product of exponentials (:mod:`dhsym.screws.product`): the space
        screw axes and the home configuration ``M`` read off the DH frames at ``q = 0``,
        with the steps; the space frame is the frame of ``fk``, the tool frame its end."""
        from dhsym.screws.product import from_chain

        shared = self._shared
        if shared.poe is None:
            with shared.lock:
                if shared.poe is None:
                    shared.poe = from_chain(self)
        return shared.poe

    def screw_axes(self, frame: str = "space") -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix]:
        """``(S, M)``: the screw axes as the columns of a 6×n matrix (rows ``[ω; v]``, Lynch
        and Park, *Modern Robotics*) in the ``"space"`` frame (``S_i``) or the ``"body"``
        frame (``B_i``), and the home configuration ``M``, exact.

        >>> S, M = load("planar2r").screw_axes("body")
        >>> S.T
        Matrix([
        [0, 0, 1, 0, a1 + a2, 0],
        [0, 0, 1, 0,      a2, 0]])
        """
        poe = self.poe()
        return poe.screw_matrix(frame), poe.home

    def _screw_jacobian(self, frame: str) -> ScrewJacobian:
        shared = self._shared
        with shared.lock:
            found = shared.screw_jacobians.get(frame)
            if found is None:
                poe = self.poe()
                found = poe.jacobian_space() if frame == "space" else poe.jacobian_body()
                shared.screw_jacobians[frame] = found
            return found

    @overload
    def jacobian_space(self, q: None = None) -> ScrewJacobian: ...
    @overload
    def jacobian_space(
        self, q: object, *, values: Mapping[object, object] | None = None
    ) -> np.ndarray: ...
    def jacobian_space(
        self, q: object = None, *, values: Mapping[object, object] | None = None
    ) -> ScrewJacobian | np.ndarray:
        """The space Jacobian ``J_s`` (rows ``[ω; v]``), exact; at ``q`` its numbers (``(n,)``
        → ``(6, n)``, ``(N, n)`` → ``(N, 6, n)``, as :meth:`jacob0`). It relates to the DH
        Jacobian (rows ``[v; ω]``) by ``J_s = [[0, I], [I, [p]]] jacob0``
        (:func:`dhsym.screws.product.space_from_geometric`).

        >>> load("planar2r").jacobian_space([0.0, 0.0])[:, 1]
        array([ 0.,  0.,  1.,  0., -1.,  0.])
        """
        return self._screw_jacobian_at("space", q, values)

    @overload
    def jacobian_body(self, q: None = None) -> ScrewJacobian: ...
    @overload
    def jacobian_body(
        self, q: object, *, values: Mapping[object, object] | None = None
    ) -> np.ndarray: ...
    def jacobian_body(
        self, q: object = None, *, values: Mapping[object, object] | None = None
    ) -> ScrewJacobian | np.ndarray:
        """The body Jacobian ``J_b`` (rows ``[ω; v]``, in the tool frame), exact or at ``q``;
        it is :meth:`jacobe` with its halves swapped
        (:func:`dhsym.screws.product.body_from_geometric`).

        >>> import numpy as np
        >>> r = load("planar2r")
        >>> np.allclose(r.jacobian_body([0.3, 0.5])[3:], r.jacobe([0.3, 0.5])[:3])
        True
        """
        return self._screw_jacobian_at("body", q, values)

    def _screw_jacobian_at(
        self, frame: str, q: object, values: Mapping[object, object] | None
    ) -> ScrewJacobian | np.ndarray:
        from dhsym.kinematics.numeric import values_key
        from dhsym.screws.poe_numbers import screw_jacobian_function

        if q is None:
            if values is not None:
                raise DHError(f"jacobian_{frame}() without q is exact: values need q")
            return self._screw_jacobian(frame)
        vals = self.table.with_values(dict(values or {})).value_map
        key = JacobianKey(f"screw-{frame}", None, values_key(values))
        f = self._jacobian_functions.get(key)
        if f is None:
            f = self._jacobian_functions[key] = screw_jacobian_function(self.poe(), frame, vals)
        return f(q)

    # -- formats and compiled code (dhsym.formats, dhsym.export) -------------------------
    def to_urdf(self, *, name: str | None = None) -> str:
        """A URDF of this robot, one link per DH frame (see :func:`dhsym.formats.urdf.write_urdf`).

        >>> arm = Robot(load("planar2r").table.with_values({"a1": 1, "a2": 0.5}))
        >>> arm.to_urdf().count("<link ")
        6
        """
        from dhsym.formats.urdf import write_urdf

        return write_urdf(self, name=name)

    def to_rtb(self) -> object:
        """A roboticstoolbox ``DHRobot`` of this robot (see :func:`dhsym.formats.rtb.to_rtb`;
        needs ``pip install roboticstoolbox-python``)."""
        from dhsym.formats.rtb import to_rtb

        return to_rtb(self)

    def compiled(self, lang: str = "c") -> CompiledRobot:
        """fk, Jacobian and IK as exported C built once (a file cache) and called by ctypes;
        dhsym's NumPy path without a compiler (see :mod:`dhsym.export.shared_library`)."""
        from dhsym.export.shared_library import compiled

        return compiled(self, lang, cache=self.ik_cache(), rne=self.rne)

    # -- dynamics (dhsym.dynamics) -------------------------------------------------------
    def dynamics(self, method: str = "lagrange") -> EquationsOfMotion:
        r"""The equations of motion :math:`M(q)\,\ddot q + C(q, \dot q)\,\dot q + g(q) = \tau`,
        exact (``"lagrange"`` or ``"newton-euler"``), cached.

        Rows without inertial parameters get the textbook symbols (``m1``, ``rx1``, …).
        See :mod:`dhsym.dynamics`.
        """
        from dhsym.dynamics import lagrange, newton_euler

        key = str(method).strip().lower().replace("_", "-")
        shared = self._shared
        if key == "lagrange":
            with shared.lock:
                if shared.lagrange is None:
                    shared.lagrange = lagrange(self)
                return shared.lagrange
        if key in ("newton-euler", "ne"):
            with shared.lock:
                if shared.newton_euler is None:
                    shared.newton_euler = newton_euler(self)
                return shared.newton_euler
        raise DHError(f"unknown dynamics method {method!r}: expected lagrange or newton-euler")

    def dynamics_functions(self, values: Mapping[Any, object] | None = None) -> DynamicsFunctions:
        """The compiled dynamics, cached by ``values``
        (:class:`dhsym.dynamics.compiled_dynamics.DynamicsFunctions`)."""
        from dhsym.dynamics.compiled_dynamics import dynamics_functions
        from dhsym.kinematics.numeric import values_key

        key = values_key(values)
        found = self._shared.dynamics_functions
        f = found.get(key)
        if f is None:
            with self._shared.lock:
                f = found.get(key)
                if f is None:
                    native = _native_rows_compiler()
                    f = found[key] = dynamics_functions(self, values, native=native)
        return f

    def rne(
        self, q: object, qd: object, qdd: object, *, values: Mapping[object, object] | None = None
    ) -> np.ndarray:
        """Joint torques τ(q, q̇, q̈), with motor inertia ``Jm G²`` and friction when given.

        One state ``(n,)`` → ``(n,)``; a batch ``(..., n)`` → ``(..., n)``.
        """
        return self.dynamics_functions(values).rne(q, qd, qdd)

    def inertia(self, q: object, *, values: Mapping[object, object] | None = None) -> np.ndarray:
        """The inertia matrix M(q): ``(n,)`` → ``(n, n)``, ``(..., n)`` → ``(..., n, n)``."""
        return self.dynamics_functions(values).inertia(q)

    def coriolis(
        self, q: object, qd: object, *, values: Mapping[object, object] | None = None
    ) -> np.ndarray:
        """C(q, q̇) from the Christoffel symbols; ``C @ qd`` is the velocity term."""
        return self.dynamics_functions(values).coriolis(q, qd)

    def gravload(self, q: object, *, values: Mapping[object, object] | None = None) -> np.ndarray:
        """The gravity torques g(q)."""
        return self.dynamics_functions(values).gravload(q)

    def accel(
        self, q: object, qd: object, tau: object, *, values: Mapping[object, object] | None = None
    ) -> np.ndarray:
        """Forward dynamics q̈ = M⁻¹(τ − C q̇ − g − friction)."""
        return self.dynamics_functions(values).accel(q, qd, tau)

    def simulate(
        self,
        q0: object,
        qd0: object,
        duration: float,
        *,
        dt: float = 1e-3,
        tau: object = None,
        values: Mapping[object, object] | None = None,
    ) -> Trajectory:
        """Fixed-step RK4 integration of the motion (a ``Trajectory``: ``t``, ``q``, ``qd``)."""
        return self.dynamics_functions(values).simulate(q0, qd0, duration, dt=dt, tau=tau)

    @overload
    def statics(self) -> Statics: ...
    @overload
    def statics(
        self, q: object, wrench: object, *, values: Mapping[object, object] | None = None
    ) -> np.ndarray: ...
    def statics(
        self,
        q: object = None,
        wrench: object = None,
        *,
        values: Mapping[object, object] | None = None,
    ) -> Statics | np.ndarray:
        """The exact τ = Jᵀ F (:func:`dhsym.dynamics.statics`).

        ``robot.statics(q, wrench)`` is kept as an alias of the numbers,
        :meth:`static_torques`: an array, not a ``Statics``.
        """
        if q is not None:
            return self.static_torques(q, wrench, values=values)
        if wrench is not None or values is not None:
            raise DHError("statics() without q is exact: numbers are static_torques(q, wrench)")
        from dhsym.dynamics.static_forces import statics

        return statics(self)

    def static_torques(
        self, q: object, wrench: object, *, values: Mapping[object, object] | None = None
    ) -> np.ndarray:
        """The joint torques τ = J(q)ᵀ F that balance a tip wrench ``F = [f; n]`` (base frame)
        at ``q``: one state ``(n,)`` → ``(n,)``, a batch ``(..., n)`` with wrenches
        ``(..., 6)`` → ``(..., n)`` (:func:`dhsym.dynamics.static_forces.static_torques`).

        >>> load("planar2r").static_torques([0.0, 0.0], [0, 1, 0, 0, 0, 0])
        array([1.8, 0.8])
        """
        from dhsym.dynamics.static_forces import static_torques

        return static_torques(self, q, wrench, values=values)

    # -- paths (dhsym.trajectory) --------------------------------------------------------
    def jtraj(
        self, q0: object, qf: object, t: object, qd0: object = None, qd1: object = None
    ) -> JointPath:
        """A joint-space motion from ``q0`` to ``qf``: a quintic per joint, all ending at
        ``max(t)`` (see :func:`dhsym.trajectory.jtraj`).

        >>> load("planar2r").jtraj([0, 0], [1, 2], [0.0, 1.0, 2.0]).q[1]
        array([0.5, 1. ])
        """
        from dhsym.trajectory.paths import jtraj

        return jtraj(q0, qf, t, qd0, qd1, joints=len(self.table.joint_rows))

    def ctraj(
        self,
        T0: object,
        T1: object,
        t: object,
        *,
        near: object = None,
        max_step: float = 0.5,
        singular: bool = True,
        check: str = "pose",
    ) -> CartesianPath:
        """The straight line from pose ``T0`` to ``T1`` solved by this robot's inverse
        kinematics per sample, branch by branch (see :func:`dhsym.trajectory.ctraj`).

        >>> r = load("planar2r")
        >>> path = r.ctraj(r.fk([0.3, 1.2]), r.fk([0.6, 0.9]), 5, near=[0.3, 1.2],
        ...                check="position")
        >>> path.complete, path.q.shape
        (True, (5, 2))
        """
        from dhsym.trajectory.paths import ctraj

        return ctraj(
            self,
            T0,
            T1,
            t,
            near=near,
            cache=self.ik_cache(),
            max_step=max_step,
            singular=singular,
            check=check,
        )

    # -- pictures (dhsym.plot) -----------------------------------------------------------
    def plot(self, q: object = None, **kw: Any) -> Figure:
        """A matplotlib Figure of the arm with its DH frames (see :mod:`dhsym.plot.figures`).

        ``kw`` are the options of :func:`dhsym.plot.figures.plot_robot` (``ax``, ``frames``,
        ``labels``, ``deg``, ``view``, ``scale``, ``title``, ``limits``, ``alpha``).
        """
        from dhsym.plot.figures import plot_robot

        return plot_robot(self, q, **kw)

    def view(
        self, q: Sequence[float] | None = None, *, deg: bool = False, workspace: int = 4000
    ) -> Any:
        """A 3D view of the arm in Jupyter: a slider per joint (in the table's units, within its
        limits), its DH frames, the arm matrix read out live (:mod:`dhsym.view`).

        ``view.q`` is shared both ways with the sliders. Needs anywidget (the ``widgets``
        extra); ``dhsym view NAME -o arm.html`` writes the same view as a page that needs
        nothing. Where widgets do not run, it shows a picture of the arm at ``q``.
        """
        from dhsym.plot.figures import joint_values
        from dhsym.view.widget import arm_view

        start = None if q is None else list(joint_values(self, q, deg=deg))
        return arm_view(self, start, workspace=workspace)


def _native_compiler() -> NativeCompiler | None:
    """What compiles the closed form's program for one pose into C for ``robot.ik``
    (:func:`dhsym.export.shared_library.native_program`), or ``None`` when the process
    has no C compiler or ``DHSYM_NO_COMPILE=1`` (chosen once per process:
    :func:`~dhsym.export.shared_library.native_compiler`): then one pose is solved by the
    NumPy path's program for floats. The results are the same either way."""
    from dhsym.export.shared_library import native_compiler, native_program

    return native_program if native_compiler() is not None else None


def _native_rows_compiler() -> NativeRowsCompiler | None:
    """What compiles the dynamics' program into C for one state of ``robot.rne``,
    ``inertia``, ``gravload``, ``coriolis`` and ``accel`` after the switch of
    :mod:`dhsym.dynamics.compiled_dynamics` (:func:`dhsym.export.shared_library.native_rows`),
    or ``None`` without a C compiler or with ``DHSYM_NO_COMPILE=1`` (as
    :func:`_native_compiler`): then the program is compiled for Python floats. The
    results are the same either way."""
    from dhsym.export.shared_library import native_compiler, native_rows

    return native_rows if native_compiler() is not None else None


def load(name_or_path: str | Path, **kw: Any) -> Robot:
    """A :class:`Robot` from a built-in name or a table file (``compact``, ``style`` as Robot).

    A ``.urdf`` path (or URDF text) is read by :func:`from_urdf`, which also takes ``tip``,
    ``base``, ``convention`` and ``snap_angles``. A ``.poe.yaml`` path (a product of
    exponentials, :mod:`dhsym.screws.poefile`) is read by :func:`from_poe`, which also
    takes ``convention``.

    >>> load("planar2r").name
    'Planar 2R'
    """
    text = str(name_or_path)
    if text.lstrip().startswith("<") or Path(text).suffix.lower() in (".urdf", ".xacro"):
        return from_urdf(name_or_path, **kw)
    from dhsym.screws.poefile import is_poe_path

    if is_poe_path(text):
        return from_poe(name_or_path, **kw)
    return Robot(load_table(name_or_path), **kw)


def from_poe(
    source: str | os.PathLike[str] | ProductOfExponentials,
    convention: Convention | str = "standard",
    **kw: Any,
) -> Robot:
    """A :class:`Robot` from a PoE file or description: its screw axes as lines, given DH
    frames by :func:`dhsym.geometry.frames.assign_frames` (:func:`dhsym.screws.poe_to_dh.to_dh`;
    variables zero at home, in the order of the axes); ``kw`` are Robot's keywords.

    >>> from dhsym.screws.poefile import read_poe_text
    >>> poe = read_poe_text('''
    ... M: [[1, 0, 0, 2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    ... joints: [{w: [0, 0, 1], point: [0, 0, 0]}, {w: [0, 0, 1], point: [1, 0, 0]}]''')
    >>> r = from_poe(poe)
    >>> r.screw_axes()[0] == poe.screw_matrix(), r.fk([0.5, 0.0])[0, 3]
    (True, np.float64(1.7551651237807455))
    """
    from dhsym.screws.poe_to_dh import to_dh
    from dhsym.screws.poefile import read_poe
    from dhsym.screws.product import ProductOfExponentials

    poe = source if isinstance(source, ProductOfExponentials) else read_poe(source)
    return Robot(to_dh(poe, convention).table, **kw)


def from_urdf(
    source: str | os.PathLike[str],
    tip: str | None = None,
    base: str | None = None,
    convention: Convention | str = "standard",
    *,
    snap_angles: AngleSnap | bool | float | None = True,
    **kw: Any,
) -> Robot:
    """A :class:`Robot` from a URDF file or text (see :func:`dhsym.formats.urdf.import_urdf`);
    ``kw`` are Robot's keywords (``compact``, ``style``).

    >>> r = from_urdf('''<robot name="slide"><link name="a"/><link name="b"/>
    ...   <joint name="s" type="prismatic"><parent link="a"/><child link="b"/>
    ...     <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
    ... </robot>''', convention="modified")
    >>> r, r.fk([0.2])[0, 3]
    (Robot('slide', P, modified), np.float64(0.2))
    """
    from dhsym.formats.urdf import import_urdf

    imp = import_urdf(source, tip, base, convention, snap_angles=snap_angles)
    return Robot(imp.table, **kw)


def from_rtb(robot: object, *, name: str | None = None) -> Robot:
    """A :class:`Robot` from a roboticstoolbox ``DHRobot`` (see
    :func:`dhsym.formats.rtb.table_from_rtb`)."""
    from dhsym.formats.rtb import table_from_rtb

    return Robot(table_from_rtb(robot, name=name))


def inverse(robot: Robot | str | Path) -> ClosedForm | Elimination:
    """The inverse kinematics of a robot or built-in name, derived step by step.

    >>> ik = inverse("planar2r")
    >>> [b.role for b in ik.branches], ik.count
    (['elbow'], 2)
    """
    return (robot if isinstance(robot, Robot) else load(robot)).inverse()
