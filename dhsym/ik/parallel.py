r"""Three consecutive parallel axes (the arms of Universal Robots), derived as lecture steps.

When the axes of joints 2, 3 and 4 are parallel (direction ``u``) and the axes of joints
5 and 6 meet in a point ``W`` (the *wrist point*), the arm decouples along ``u``
(Hawkins, *Analytic inverse kinematics for the Universal Robots UR-5/UR-10 arms*, 2013):

1. **The wrist point.** ``W`` is fixed in the tool frame: ``W = p + R ·ⁿW``.
2. **The shoulder, θ1.** Joints 2–4 turn about ``u`` and joints 5 and 6 do not move
   ``W``, so the component of ``W`` along ``u``, seen from the frame after joint 1, is a
   constant ``h`` of the table. That is one equation ``A cos θ1 + B sin θ1 = h``: two
   solutions (the shoulder right and left), ``atan2(B, A) ± atan2(√(A² + B² − h²), h)``.
3. **The wrist, θ5 and θ6.** The axis of joint 6 is fixed in the tool frame; its
   component along ``u`` depends on θ5 alone: ``±√`` (the wrist flipped or not). The
   row ``uᵀ R`` of the rotation is linear in ``cos θ6``, ``sin θ6``: one ``atan2``.
4. **The planar arm, θ2, θ3, θ4.** With θ1, θ5 and θ6 known, the frame before joint 4 is
   known: its origin moves in the plane normal to ``u`` as a planar 2R (the law of
   cosines for θ3, elbow up or down; then θ2), and the rotation left is θ4 about ``u``.

Eight solutions in general. Works in either convention: everything is read from the
chain of elementary transforms, never from a robot's name.

Examples
--------
>>> import dhsym
>>> import numpy as np
>>> r = dhsym.load("ur5")
>>> ik = r.inverse()
>>> print(ik.structure)
axes 2, 3, 4 parallel; axes 5, 6 meet in the wrist point (origin of frame 5): joint 1 ...
>>> q = [0.3, -1.1, 1.4, -0.6, 1.2, 0.4]
>>> sol = r.ik(r.fk(q))
>>> len(sol), bool(np.abs(sol.q - q).max(axis=1).min() < 1e-9)
(8, True)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.decoupling import Decoupling, StructureError, decouple
from dhsym.kinematics.jacobian import axis_frame
from dhsym.kinematics.simplification import compose, normalize_word
from dhsym.kinematics.transforms import chain_word
from dhsym.model.table import Elementary
from dhsym.notation.layout import sentence

from .closed_form import ClosedForm
from .steps import (
    REAL,
    Builder,
    Equation,
    pose_symbols,
    rot_z,
    solve_equations,
    solve_joint_from_entry,
    undo_prefix,
)
from .structure import PARALLEL

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["derive_parallel"]

Matrix: TypeAlias = sp.ImmutableMatrix


def _at(word: Sequence[Elementary], var: sp.Symbol) -> int:
    """Index of the elementary transform of ``word`` that holds joint variable ``var``."""
    return next(i for i, e in enumerate(word) if var in e.value.free_symbols)


def _constant(e: sp.Expr, zero: dict[sp.Symbol, int]) -> sp.Expr:
    """``e`` at joint values 0 for the joints it does not depend on (proved invariant)."""
    return sp.nsimplify(sp.simplify(e.xreplace(zero)), rational=False)


def derive_parallel(robot: KinematicChain) -> ClosedForm:
    """The closed form of a 6R arm whose axes 2, 3, 4 are parallel and axes 5, 6 meet.

    Raises
    ------
    StructureError
        When the axes are not so (named in the message).

    >>> import dhsym
    >>> ik = derive_parallel(dhsym.load("ur5"))
    >>> [b.role for b in ik.branches], ik.count
    (['arm', 'wrist', 'elbow'], 8)
    """
    table = robot.table
    rows = table.joint_rows
    q = list(robot.variables)
    if len(q) != 6:
        raise StructureError(f"three parallel axes: this family has 6 joints, not {len(q)}")
    meet = decouple(robot, 2)  # the point where the axes of joints 5 and 6 meet
    dec = Decoupling(rows[:3], rows[3:], axis_frame(robot, rows[3]), meet.centre_in_last)
    b = Builder(robot, dec)
    pose = pose_symbols()
    R, p = pose[:3, :3], pose[:3, 3]
    word = chain_word(table, 0, robot.n)
    k1, k2, k4 = _at(word, q[0]), _at(word, q[1]), _at(word, q[3])
    first = word[k1]
    if first.kind != "R" or first.axis != "z":
        raise StructureError("three parallel axes: joint 1 does not turn about z")
    prefix = compose(normalize_word(word[:k1]))
    zero = {v: 0 for v in q[1:]}
    u = Matrix(compose(word[k1 + 1 : k2])[:3, 2]).applyfunc(sp.nsimplify)  # axis 2 after joint 1

    # 1. the wrist point
    v = meet.centre_in_last
    names = [sp.Symbol(f"w_{k}", **REAL) for k in "xyz"]
    ws, ps, rs = sp.symbols("w p R")
    text = sentence(
        "The axes of joints 5 and 6 meet in the wrist point {w}, at {v} in frame "
        f"{robot.n}: {{eq}}.",
        w=ws,
        v=sp.Tuple(*v),
        eq=sp.Eq(ws, ps + rs * sp.Symbol("v")),
    )
    for name, value in zip(names, p + R * v):
        b.add("wrist centre", text, name, sp.expand(value))
    w = undo_prefix(
        b,
        "wrist centre",
        "The wrist point in the frame before joint 1 (undo the constant transform "
        "that precedes it).",
        Matrix(names),
        prefix,
    )

    # 2. the shoulder: the height of W along u is a constant of the table
    to_centre = chain_word(table, 0, meet.centre)
    h = _constant((u.T * compose(to_centre[k1 + 1 :])[:3, 3])[0], zero)
    turn = rot_z(first.value)
    height = sp.expand((u.T * turn.T * w)[0])
    hs = sp.Symbol("h", **REAL)
    b.add(
        "shoulder",
        sentence(
            "Joints 2, 3, 4 turn about parallel axes (direction {u} after joint 1) and joints "
            "5, 6 do not move the wrist point: its height {h} along them is a constant.",
            u=sp.Tuple(*u),
            h=hs,
        ),
        hs,
        h,
    )
    b.part = "shoulder"
    solve_equations(
        b,
        [
            Equation(
                height - hs,
                sp.Eq(height, hs),
                "the height of the wrist point along the parallel axes",
                role="arm",
            )
        ],
        [q[0]],
    )

    # 3. the wrist: the axis of joint 6 along u gives θ5, the row uᵀR gives θ6
    f6 = axis_frame(robot, rows[5])
    z6 = _constant(robot.transform(f6, robot.n).matrix[:3, :3].T[:, 2], {q[5]: 0})
    known_R = (turn.T * prefix[:3, :3].T * R).applyfunc(sp.expand)
    row = (u.T * known_R).applyfunc(sp.expand)
    ks = sp.Symbol("k_6", **REAL)
    b.add(
        "wrist",
        sentence(
            "The axis of joint 6 is {z} in the tool frame; its component along the parallel axes:",
            z=sp.Tuple(*z6),
        ),
        ks,
        sp.expand((row * z6)[0]),
    )
    to_f6 = chain_word(table, 0, f6)
    b.part = "wrist"
    model5 = _constant((u.T * compose(to_f6[k1 + 1 :])[:3, 2])[0], {v_: 0 for v_ in q[1:4]})
    solve_equations(
        b,
        [
            Equation(
                model5 - ks,
                sp.Eq(model5, ks),
                "the axis of joint 6 along the parallel axes",
                role="wrist",
            )
        ],
        [q[4]],
    )
    rsyms = [sp.Symbol(f"r_{j + 1}", **REAL) for j in range(3)]
    for j, sym in enumerate(rsyms):
        b.add(
            "wrist",
            sentence(
                "Row {u} of the rotation, seen from the frame after joint 1:", u=sp.Symbol("u")
            ),
            sym,
            row[j],
        )
    model_row = (u.T * compose(word[k1 + 1 :])[:3, :3]).applyfunc(
        lambda e: _constant(e, {v_: 0 for v_ in q[1:4]})
    )
    solve_equations(
        b,
        [
            Equation(model_row[j] - rsyms[j], sp.Eq(model_row[j], rsyms[j]), f"entry {j + 1}")
            for j in range(3)
        ],
        [q[5]],
    )

    # 4. the planar arm: the frame before joint 4 is known
    # the inverses as words of inverse elementaries, composed in compact form
    before = [e.inverse() for e in reversed(word[: k1 + 1])]
    after = [e.inverse() for e in reversed(word[k4 + 1 :])]
    Q = compose(before) * pose * compose(after)
    L = compose(word[k1 + 1 : k4])
    e1 = Matrix([1, 0, 0])
    e2 = Matrix(u.cross(e1)).applyfunc(sp.nsimplify)
    X, Y = sp.symbols("x_4 y_4", real=True)
    for sym, axis in ((X, e1), (Y, e2)):
        b.add(
            "planar arm",
            sentence(
                "With joints 1, 5, 6 known, the frame before joint 4 is known: its origin in the "
                "plane of the parallel axes,"
            ),
            sym,
            (axis.T * Q[:3, 3])[0],
        )
    b.part = "planar arm"
    mx, my = sp.expand((e1.T * L[:3, 3])[0]), sp.expand((e2.T * L[:3, 3])[0])
    arm = set(q[1:3])
    kx = sp.Add(*[t for t in sp.Add.make_args(mx) if not t.free_symbols & arm])
    ky = sp.Add(*[t for t in sp.Add.make_args(my) if not t.free_symbols & arm])
    solve_equations(
        b,
        [
            Equation(
                (mx - kx) ** 2 + (my - ky) ** 2 - (X - kx) ** 2 - (Y - ky) ** 2,
                sp.Eq((mx - kx) ** 2 + (my - ky) ** 2, (X - kx) ** 2 + (Y - ky) ** 2),
                "the sum of squares in the plane of the parallel axes",
            ),
            Equation(mx - X, sp.Eq(mx, X), "the first coordinate"),
            Equation(my - Y, sp.Eq(my, Y), "the second coordinate"),
        ],
        [q[1], q[2]],
    )
    col = [sp.Symbol(f"n_{k}4", **REAL) for k in "xyz"]
    for sym, value in zip(col, Q[:3, 0]):
        b.add("planar arm", "The first column of that frame's rotation:", sym, value)
    left = (L[:3, :3].T * Matrix(col)).applyfunc(sp.expand)
    x4 = word[k4].value
    b.add(
        "planar arm",
        sentence(
            "What joints 2 and 3 leave of it is a turn by {v} about the parallel axes:", v=q[3]
        ),
        q[3],
        solve_joint_from_entry(sp.atan2(b.tidy(left[1]), b.tidy(left[0])), x4, q[3]),
    )
    structure = (
        f"axes 2, 3, 4 parallel; axes 5, 6 meet in the wrist point (origin of frame "
        f"{meet.centre}): joint 1 from the wrist point's height along the parallel axes, "
        "joints 5 and 6 from the tool's rotation, joints 2–4 as a planar arm"
    )
    return ClosedForm(
        robot, structure, dec, pose, tuple(b.steps), tuple(b.branches), family=PARALLEL
    )
