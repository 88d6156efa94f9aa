r"""The closed form by kinematic decoupling (spherical wrist, planar arms), as lecture steps.

:func:`derive_decoupled` reads the structure of a DH table (never its name) and derives the
joint values from a pose ``T = [n s a p; 0 0 0 1]`` step by step, the way the
lectures do (Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, §5.3;
Craig, *Introduction to Robotics*, §4.7):

1. **Kinematic decoupling.** When the last three axes meet in one point (a spherical
   wrist), that point, the *wrist centre* ``c``, depends on the first three joints only:
   ``c = p + R ·ⁿc``. With one last revolute joint (planar 3R, SCARA) a point of its
   axis plays the same part; a positioning arm places its tool point ``p`` itself.
2. **Position.** Joint 1 turns the arm about ``z0``. If the wrist centre keeps a
   constant *shoulder offset* ``e`` from the plane of joints 2 and 3, its radial reach is
   ``r = ±√(x_c² + y_c² − e²)`` (left/right arm) and ``θ1 = atan2(y_c, x_c) − atan2(e, r)``.
   The remaining joints come from the equations of the arm's plane: the sum of squares
   (the law of cosines: elbow up/down, or ``±√`` for a prismatic reach) and then the
   two coordinates together, linear in ``C_j, S_j`` (one ``atan2``). A planar arm gets
   its elbow from ``x² + y²`` first and ``θ1`` last.
3. **Orientation.** ``R_w = (ᵃʳᵐR)ᵀ R`` is the wrist's own rotation
   ``Rz(θ4) Rx(α4) Rz(θ5) Rx(α5) Rz(θ6)``: ``θ5`` from one entry (``±√``: the wrist
   flip), ``θ4`` and ``θ6`` from its row and column by ``atan2``.

Every step is a :class:`~dhsym.ik.steps.Step` — a sentence and exact sympy expressions;
``atan2`` and the signs ``σ = ±1`` of each branch are explicit. The solver of
:mod:`dhsym.ik.closed_form_solver` compiles the steps once (``lambdify`` with the steps as
the common subexpressions), with the ``fk`` check, into a numpy function over a batch of
poses and all branches at once and into a function of plain floats for one pose (the
rewriting: :mod:`dhsym.ik.rewriting`).

Results. One pose ``(4, 4)`` gives an :class:`~dhsym.ik.solution.IKSolution`: ``q`` is
``(k, n)`` (k ≤ 8, only real, checked, distinct solutions) with a name per solution and the
singularities each one is near. A batch ``(N, 4, 4)`` gives the same type with a leading
axis: ``q`` is padded to
``(N, K, n)`` with NaN, ``valid`` ``(N, K)`` is the mask, ``K = 2^(number of branches)``.
By default a branch is kept only when its ``fk`` reproduces the whole pose to ``1e-9``
(``check="pose"``). An arm with fewer than six joints cannot reach every pose, so a branch
that only matches the coordinates it solves is dropped: a planar 2R has one solution for
a whole pose and two (elbow up and down) for a position ``(3,)``. Near a singularity a
solution is flagged (``singular``) with the kind of the singular factor (from
:mod:`dhsym.kinematics.singularities`); at ``sin θ5 = 0`` only ``θ4 + θ6`` is defined
and ``θ4 = 0``.

Arms without such structure get a :class:`~dhsym.kinematics.decoupling.StructureError`
naming what is missing; other families live beside this module (:mod:`dhsym.ik.families`
chooses), and :func:`~dhsym.ik.levenberg_marquardt.numeric_ik` is a separate, clearly
numeric solver.

Examples
--------
>>> import dhsym
>>> import numpy as np
>>> ik = derive_decoupled(dhsym.load("planar2r"))
>>> for step in ik.steps:
...     print(ik.text(step))
D_2 = (p_x**2 + p_y**2 - a1**2 - a2**2)/(2*a1*a2)
theta2 = atan2(sigma_2*sqrt(1 - D_2**2), D_2)
theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)
>>> r = dhsym.load("puma560")
>>> q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
>>> sol = r.ik(r.fk(q))
>>> len(sol), bool(np.abs(sol.q - q).max(axis=1).min() < 1e-9)
(8, True)
>>> sol.branches[0]
'right arm, elbow down, wrist not flipped'
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, TypeAlias

import sympy as sp

from dhsym.kinematics.decoupling import (
    ArmGeometry,
    Decoupling,
    StructureError,
    arm_geometry,
    decouple,
)
from dhsym.kinematics.simplification import compose
from dhsym.kinematics.transforms import chain_word, plain_product
from dhsym.model.table import Elementary
from dhsym.notation.layout import sentence, word_expr

from .closed_form import ClosedForm
from .steps import (
    BRANCH_NAMES,
    REAL,
    Builder,
    Equation,
    pose_symbols,
    rot_x,
    rot_z,
    solve_equations,
    solve_joint_from_entry,
    undo_prefix,
)

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["derive_decoupled"]

Matrix: TypeAlias = sp.ImmutableMatrix


def _position(b: Builder, geo: ArmGeometry, target: Matrix) -> None:
    """Steps for the arm joints from the point ``target`` (symbols of c or p)."""
    robot, dec = b.robot, b.dec
    table = robot.table
    arm_vars = [table.rows[r - 1].variable for r in dec.arm]
    u = undo_prefix(
        b,
        "position",
        "The point in the frame before joint 1 (undo the constant transform that precedes it).",
        target,
        geo.prefix_matrix,
    )
    ux, uy, uz = u
    g = geo.point
    q1 = arm_vars[0]
    unknowns = list(arm_vars[1:])
    equations: list[Equation] = []
    final_theta1: tuple[sp.Expr, sp.Expr] | None = None
    if geo.first.kind == "R":
        if geo.offset_axis is not None:
            e = geo.offset
            assert e is not None  # arm_geometry sets the offset with its axis
            radial_axis = 1 - geo.offset_axis
            r = sp.Symbol("r", **REAL)
            arm = b.branch(
                "arm",
                q1,
                f"{{plus}}: {BRANCH_NAMES['arm'][0]} (the point in front of the shoulder, "
                f"{{front}}); {{minus}}: {BRANCH_NAMES['arm'][1]}",
                front=sp.Gt(r, 0),
            )
            sigma = arm.symbol
            reach = sp.sqrt(ux**2 + uy**2 - e**2)
            b.add(
                "position",
                sentence(
                    "Joint 1 turns the arm about {z0}; the point keeps the shoulder offset "
                    "{e} from the plane of the arm, so its reach in that plane is",
                    z0=sp.Symbol("z_0"),
                    e=sp.Eq(sp.Symbol("e"), e),
                ),
                r,
                sigma * reach,
                equation=sp.Eq(ux**2 + uy**2, r**2 + e**2),
                branch=arm,
            )
            if e == 0 and radial_axis == 0:
                x1 = sp.atan2(sigma * uy, sigma * ux)
            elif e == 0:
                x1 = sp.atan2(-sigma * ux, sigma * uy)
            else:
                gx, gy = (r, e) if radial_axis == 0 else (e, r)
                x1 = sp.atan2(uy, ux) - sp.atan2(gy, gx)
            b.add(
                "position",
                sentence(
                    "The angle of the point minus the angle of {re} in the arm's frame:",
                    re=sp.Tuple(r, sp.Symbol("e")),
                ),
                q1,
                solve_joint_from_entry(x1, geo.first.value, q1),
            )
            radial, height = g[radial_axis], g[2]
            kr = sp.Add(
                *[
                    t
                    for t in sp.Add.make_args(sp.expand(radial))
                    if not t.free_symbols & set(unknowns)
                ]
            )
            kz = sp.Add(
                *[
                    t
                    for t in sp.Add.make_args(sp.expand(height))
                    if not t.free_symbols & set(unknowns)
                ]
            )
            r2 = (ux**2 + uy**2 - e**2) if kr == 0 else (r - kr) ** 2
            equations += [
                Equation(
                    (radial - kr) ** 2 + (height - kz) ** 2 - r2 - (uz - kz) ** 2,
                    sp.Eq((radial - kr) ** 2 + (height - kz) ** 2, r2 + (uz - kz) ** 2),
                    "the sum of squares of the two coordinates in the arm's plane",
                ),
                Equation(radial - r, sp.Eq(radial, r), "the reach in the arm's plane"),
                Equation(height - uz, sp.Eq(height, uz), "the height"),
            ]
        else:
            equations += [
                Equation(
                    g[0] ** 2 + g[1] ** 2 - ux**2 - uy**2,
                    sp.Eq(g[0] ** 2 + g[1] ** 2, ux**2 + uy**2),
                    "the squared distance from the axis of joint 1",
                ),
                Equation(g[2] - uz, sp.Eq(g[2], uz), "the height"),
                # Pieper: when the axes of joints 1 and 2 meet at the origin, the distance
                # from it depends on the joints after joint 2 alone
                Equation(
                    g[0] ** 2 + g[1] ** 2 + g[2] ** 2 - ux**2 - uy**2 - uz**2,
                    sp.Eq(g[0] ** 2 + g[1] ** 2 + g[2] ** 2, ux**2 + uy**2 + uz**2),
                    "the squared distance from the origin",
                ),
            ]
            final_theta1 = (g[0], g[1])
    else:
        unknowns = list(arm_vars)
        full = geo.first.value
        point = Matrix([g[0], g[1], g[2] + full])
        for i, c in enumerate("xyz"):
            equations.append(
                Equation(point[i] - u[i], sp.Eq(point[i], u[i]), f"the {c} coordinate")
            )
    solve_equations(b, equations, unknowns)
    if final_theta1 is not None:
        gx, gy = (b.tidy(v) for v in final_theta1)
        x1 = sp.atan2(uy, ux) - sp.atan2(gy, gx)
        b.add(
            "position",
            "Joint 1: the angle of the point minus the angle the other joints "
            "give it in the frame of joint 1:",
            q1,
            solve_joint_from_entry(x1, geo.first.value, q1),
        )


# --- orientation -------------------------------------------------------------------------------


def _rotation_word(word: Sequence[Elementary]) -> list[Elementary]:
    return [e for e in word if e.kind == "R"]


def _x_twist(word: Sequence[Elementary], where: str) -> sp.Expr:
    R = plain_product(word)[:3, :3] if word else sp.eye(3)
    R = sp.Matrix(R).applyfunc(sp.nsimplify)
    if R[0, 0] != 1 or R[0, 1] != 0 or R[0, 2] != 0:
        raise StructureError(f"the wrist's {where} is not a twist about x: not in DH form")
    return sp.atan2(R[2, 1], R[1, 1])


def _orientation(b: Builder, pose: Matrix) -> None:
    robot, dec = b.robot, b.dec
    table = robot.table
    wvars = [table.rows[r - 1].variable for r in dec.wrist]
    word = chain_word(table, 0, robot.n)
    k = next(i for i, e in enumerate(word) if wvars[0] in e.value.free_symbols)
    arm_R = compose(word[:k])[:3, :3]
    rot = _rotation_word(word[k:])
    pos = [next(i for i, e in enumerate(rot) if v in e.value.free_symbols) for v in wvars]
    if any(rot[p].axis != "z" for p in pos):
        raise StructureError("a wrist joint does not turn about its z axis")
    Q = plain_product(rot[pos[-1] + 1 :])[:3, :3] if rot[pos[-1] + 1 :] else sp.eye(3)
    R = pose[:3, :3]
    M = (sp.Matrix(arm_R).T * R * sp.Matrix(Q).T).applyfunc(sp.expand)
    names = {}

    def m(i: int, j: int) -> sp.Symbol:
        if (i, j) not in names:
            sym = sp.Symbol(f"m_{i + 1}{j + 1}", **REAL)
            names[(i, j)] = sym
            b.add(
                "orientation",
                sentence(
                    "An entry of the wrist's rotation {Rw} (the arm's rotation transposed "
                    "times {R}):",
                    Rw=sp.Symbol("R_w"),
                    R=sp.Symbol("R"),
                ),
                sym,
                b.tidy(M[i, j]),
            )
        return names[(i, j)]

    xs = [rot[p].value for p in pos]
    if len(wvars) == 1:
        x = sp.atan2(m(1, 0), m(0, 0))
        b.add(
            "orientation",
            "The wrist's rotation is Rz of the last joint angle:",
            wvars[0],
            solve_joint_from_entry(x, xs[0], wvars[0]),
        )
        return
    a4 = _x_twist(rot[pos[0] + 1 : pos[1]], "twist between its first two axes")
    a5 = _x_twist(rot[pos[1] + 1 : pos[2]], "twist between its last two axes")
    s4, c4, s5, c5 = sp.sin(a4), sp.cos(a4), sp.sin(a5), sp.cos(a5)
    if s4 == 0 or s5 == 0:
        raise StructureError("two neighbouring wrist axes are parallel: not a spherical wrist")
    j5 = b.number[wvars[1]]
    cx5 = sp.Symbol(f"c_{j5}", **REAL)
    wrist_word = [Elementary("R", "z", xs[0]), Elementary("R", "x", a4)]
    wrist_word += [Elementary("R", "z", xs[1]), Elementary("R", "x", a5)]
    wrist_word += [Elementary("R", "z", xs[2])]
    b.add(
        "orientation",
        sentence(
            "Entry (3, 3) of {word} depends on {v} alone:",
            word=word_expr(wrist_word),
            v=wvars[1],
        ),
        cx5,
        b.tidy((c4 * c5 - m(2, 2)) / (s4 * s5)),
    )
    br = b.branch(
        "wrist",
        wvars[1],
        f"{{plus}}: {BRANCH_NAMES['wrist'][0]} ({{up}}); {{minus}}: {BRANCH_NAMES['wrist'][1]}",
        up=sp.Gt(sp.sin(wvars[1]), 0),
    )
    sg = br.symbol
    sx5 = sp.Symbol(f"s_{j5}", **REAL)
    v = sp.expand(-(c4 * s5 * cx5 + s4 * c5))
    qq = sp.expand(s4 * c5 * cx5 + c4 * s5)
    if v == 0:  # twists of ±90°: the third column is (±s cos θ4, ±s sin θ4, c)
        b.add(
            "orientation",
            sentence(
                "The rest of column 3 has length {length}; two signs: the wrist flip.",
                length=sp.Abs(sp.sin(wvars[1])),
            ),
            sx5,
            sg * sp.sqrt(m(0, 2) ** 2 + m(1, 2) ** 2),
            branch=br,
        )
    else:
        b.add(
            "orientation",
            "Two signs of the root: the wrist flip.",
            sx5,
            sg * sp.sqrt(1 - cx5**2),
            branch=br,
        )
    b.add(
        "orientation",
        sentence("{v} from its sine and cosine:", v=wvars[1]),
        wvars[1],
        solve_joint_from_entry(sp.atan2(sx5, cx5), xs[1], wvars[1]),
    )
    if v == 0:
        x4 = sp.atan2(sp.sign(s5) * sg * m(1, 2), sp.sign(s5) * sg * m(0, 2))
    else:
        x4 = sp.atan2(m(1, 2), m(0, 2)) - sp.atan2(v, s5 * sx5)
    if qq == 0:
        x6 = sp.atan2(-sp.sign(s4) * sg * m(2, 1), sp.sign(s4) * sg * m(2, 0))
    else:
        x6 = sp.atan2(qq, s4 * sx5) - sp.atan2(m(2, 1), m(2, 0))
    # near sin θ5 = 0 only θ4 + θ6 is well determined: θ6 then comes from the whole
    # rotation, Rz(θ6) = (Rz(θ4) Rx(α) Rz(θ5) Rx(α'))ᵀ R_w, and at sin θ5 = 0 θ4 is set to 0
    turn4 = rot_z(xs[0])
    turn5 = sp.Matrix([[cx5, -sx5, 0], [sx5, cx5, 0], [0, 0, 1]])
    N = (turn4 * rot_x(a4) * turn5 * rot_x(a5)).T * sp.Matrix(3, 3, lambda i, j: m(i, j))
    x6_singular = sp.atan2(b.tidy(N[1, 0]), b.tidy(N[0, 0]))
    b.add(
        "orientation",
        sentence("Column 3 of the wrist's rotation gives {v}:", v=wvars[0]),
        wvars[0],
        solve_joint_from_entry(x4, xs[0], wvars[0]),
        singular=solve_joint_from_entry(sp.Integer(0), xs[0], wvars[0]),
    )
    b.add(
        "orientation",
        sentence("Row 3 of the wrist's rotation gives {v}:", v=wvars[2]),
        wvars[2],
        solve_joint_from_entry(x6, xs[2], wvars[2]),
        singular=solve_joint_from_entry(x6_singular, xs[2], wvars[2]),
    )


# --- the family ----------------------------------------------------------------------------


def _sizes(joints: int) -> list[int]:
    """Wrist sizes to try, in order, for a chain of ``joints`` joints."""
    if joints == 6:
        return [3]
    if joints in (4, 5):
        return [1]
    if joints == 3:
        return [3, 0, 1]
    return [0] if joints in (1, 2) else []  # more than six joints: redundant, nothing to try


def _structure_text(robot: KinematicChain, dec: Decoupling) -> str:
    number = {r: i for i, r in enumerate(robot.table.joint_rows, start=1)}

    def joints(rows: Sequence[int]) -> str:
        js = [number[r] for r in rows]
        return f"{js[0]}–{js[-1]}" if len(js) > 2 else ", ".join(map(str, js))

    if len(dec.wrist) == 3 and dec.arm:
        return (
            f"spherical wrist: joints {joints(dec.arm)} place the wrist centre (origin of "
            f"frame {dec.centre}), joints {joints(dec.wrist)} turn about it"
        )
    if len(dec.wrist) == 3:
        return f"a spherical wrist alone: joints {joints(dec.wrist)} turn about one point"
    if dec.wrist:
        return (
            f"last joint revolute: joints {joints(dec.arm)} place a point of its axis (origin "
            f"of frame {dec.centre}), joint {joints(dec.wrist)} turns the tool about it"
        )
    return (
        f"positioning arm: joints {joints(dec.arm)} place the tool point "
        f"(origin of frame {dec.centre})"
    )


def _wrist_centre(b: Builder, pose: Matrix) -> Matrix:
    v = b.dec.centre_in_last
    c = pose[:3, 3] + pose[:3, :3] * v
    names = [sp.Symbol(f"c_{k}", **REAL) for k in "xyz"]
    point = "wrist centre" if len(b.dec.wrist) == 3 else "point of the last joint's axis"
    cs, ps, rs = sp.symbols("c p R")
    if v == Matrix.zeros(3, 1):
        text = sentence(
            f"The {point} is the origin of frame {b.robot.n}: {{same}}.", same=sp.Eq(cs, ps)
        )
    else:
        text = sentence(
            f"The {point} sits at {{v}} in frame {b.robot.n}: {{c}} = {{p}} + {{R}} {{v}}, with "
            "{R} the rotation of the pose.",
            v=sp.Tuple(*v),
            c=cs,
            p=ps,
            R=rs,
        )
    for name, value in zip(names, c):
        b.add("wrist centre", text, name, sp.expand(value))
    return Matrix(names)


def derive_decoupled(robot: KinematicChain) -> ClosedForm:
    """The closed form by kinematic decoupling: spherical wrist, last joint revolute, or a
    positioning arm (tried in this order for the number of joints).

    Raises
    ------
    StructureError
        Naming what is missing for each decoupling tried.

    >>> import dhsym
    >>> ik = derive_decoupled(dhsym.load("puma560"))
    >>> print(ik.structure)
    spherical wrist: joints 1–3 place the wrist centre (origin of frame 4), joints 4–6 turn ...
    >>> [b.role for b in ik.branches], ik.count
    (['arm', 'elbow', 'wrist'], 8)
    >>> derive_decoupled(dhsym.load("planar4r"))
    Traceback (most recent call last):
    ...
    dhsym.kinematics.decoupling.StructureError: last joint revolute: the position sub-problem ...
    """
    joints = len(robot.variables)
    reasons = []
    if joints > 6:
        reasons.append(f"{joints} joints: a redundant arm has infinitely many solutions")
    for size in _sizes(joints):
        label = {3: "spherical wrist", 1: "last joint revolute", 0: "positioning arm"}[size]
        try:
            dec = decouple(robot, size)
            b = Builder(robot, dec)
            pose = pose_symbols()
            target = _wrist_centre(b, pose) if dec.wrist and dec.arm else pose[:3, 3]
            if dec.arm:
                _position(b, arm_geometry(robot, dec), target)
            if dec.wrist:
                _orientation(b, pose)
        except StructureError as err:
            reasons.append(f"{label}: {err.message}")
            continue
        family = "spherical wrist" if len(dec.wrist) == 3 else label
        return ClosedForm(
            robot,
            _structure_text(robot, dec),
            dec,
            pose,
            tuple(b.steps),
            tuple(b.branches),
            family=family,
        )
    raise StructureError("; ".join(reasons) or f"{joints} joints: nothing to decouple")
