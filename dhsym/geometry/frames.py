"""From geometry to DH: assign frames to joint axes, read off the table, explain each step.

The algorithm follows the lectures step by step:

* **standard** (Asokan, Lecture 2.6; Schilling/Spong): ``z_k`` along the axis of joint
  *k + 1*; ``O_k`` at the intersection of ``z_{k−1}`` and ``z_k`` or at the foot
  of their common normal on ``z_k``; ``x_k`` along the common normal, away from
  ``z_{k−1}`` (``x_k = ±z_{k−1} × z_k / ‖…‖`` when they intersect); the last
  frame at the tool point with ``z_n`` along the approach vector and ``y_n``
  along the sliding vector; points ``b_k`` where ``x_k`` meets ``z_{k−1}``.
* **modified** (Ghosal, Lecture 5; Craig): ``z_i`` along the axis of joint *i*, ``x_i``
  along the common normal from axis *i* to axis *i + 1*, with the first-link
  rule (frame 0 coincident with frame 1 at home) and the last-link rule
  (``d_n = 0``, ``θ_n = 0`` at home); the tool is a constant tool transform.

Special cases (Ghosal, Lecture 5): parallel axes (the common normal through the previous
origin, so the offset d is zero), intersecting axes (a = 0, the sign of x chosen
to keep the joint angle small), a revolute and a prismatic joint on one line (a
cylindrical pair: a = 0, x kept). Coincident revolute axes and parallel
consecutive prismatic joints are errors. Angles come out in (−π, π] and a ≥ 0.

The joint variables are zero at the given (home) pose and turn right-handed
about the given directions (sign +1); the home angles and offsets sit in the
table as constants (``theta3 - pi/2``). With ``offsets=False`` the table has no
constant offsets and :attr:`FrameAssignment.variable_map` says how q shifts.

Examples
--------
>>> import textwrap
>>> axes = [JointAxis((0, 0, 0), (0, 0, 1)), JointAxis((1, 0, 0), (0, 0, 1))]
>>> fa = assign_frames(axes, tool=((2, 0, 0), (0, 0, 1), (0, 1, 0)))
>>> [(r.theta, r.d, r.a, r.alpha) for r in fa.table.rows]
[(theta1, 0, 1, 0), (theta2, 0, 1, 0)]
>>> print(textwrap.fill(fa.steps[2].text, 90))
z0 and z1 are parallel: the common normal is not unique; we choose the one
through O0 = (0, 0, 0), so that d1 = 0; it meets z1 at O1 = (1, 0, 0), x1 = (1, 0, 0) points
away from z0, and a1 = 1.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
import sympy as sp
from sympy.polys.matrices import DomainMatrix

from dhsym.errors import GeometryError
from dhsym.kinematics.numeric import compile_word, to_float
from dhsym.kinematics.transforms import (
    chain_word,
    elementary_matrix,
    plain_product,
    rigid_inverse,
)
from dhsym.model.parsing import symbol
from dhsym.model.table import AngleUnit, Convention, DHRow, DHTable, Elementary
from dhsym.notation.tables import table_markdown

from .axes import (
    CommonNormal,
    Frame,
    JointAxis,
    Relation,
    Tool,
    common_normal,
    cross,
    dot,
    entries,
    exact_number,
    is_zero_vector,
    sign_of,
    simplify_vector,
    unit,
)
from .chains import Step, angle, name, word
from .conversion import transform_word
from .sentences import say

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["FrameAssignment", "VariableMap", "assign_frames"]

Vector: TypeAlias = sp.ImmutableMatrix
_DIGITS, _AGREE = 50, 30  # numeric home check: 50 significant digits must agree to 1e-30


@dataclass(frozen=True)
class VariableMap:
    """``variable = sign · q + offset``, q the motion from the home pose about/along the axis."""

    joint: int
    variable: sp.Symbol
    sign: int
    offset: sp.Expr


@dataclass(frozen=True)
class FrameAssignment:
    """The result: frames 0 … n at home, the points b_k (standard), the DH table, the steps."""

    axes: tuple[JointAxis, ...]
    convention: Convention
    frames: tuple[Frame, ...]
    points_b: tuple[Vector, ...]
    tool: Tool | None
    table: DHTable
    steps: tuple[Step, ...]
    variable_map: tuple[VariableMap, ...]
    values: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()

    @property
    def step_texts(self) -> list[str]:
        """The steps as plain sentences."""
        return [s.text for s in self.steps]

    def chain(self) -> KinematicChain:
        """A :class:`~dhsym.kinematics.chain.KinematicChain` for the table."""
        from dhsym.kinematics.chain import KinematicChain

        return KinematicChain(self.table)

    def verify(self, samples: int = 5, *, seed: int = 0, tol: float = 1e-9) -> float:
        """Largest error of the table against the input geometry at home and random q.

        Frame k of the table at q must equal its home frame moved by the screw
        motions of joints 1 … k about (along) the input axes, so every origin
        stays on its axis and every z along it; the tool pose likewise with all
        joints. Raises :class:`~dhsym.errors.GeometryError` above ``tol``.
        """
        return _verify(self, samples, seed, tol)

    def _repr_markdown_(self) -> str:
        lines = [f"**DH frames from joint axes** ({self.convention.value} convention)", ""]
        lines += [f"{k}. {s.markdown}" for k, s in enumerate(self.steps, start=1)]
        return "\n".join([*lines, "", table_markdown(self.table)])


def assign_frames(
    axes: Sequence[JointAxis | Sequence[object]],
    *,
    convention: Convention | str = Convention.STANDARD,
    base: Frame | object | None = None,
    tool: Tool | Sequence[object] | None = None,
    values: Mapping[Any, object] | None = None,
    offsets: bool = True,
    name: str = "",
    verify: bool = True,
) -> FrameAssignment:
    """Assign DH frames to the joint axes at the home pose and read off the DH table.

    Parameters
    ----------
    axes
        The joint axes, joint 1 first: :class:`~dhsym.geometry.axes.JointAxis` or
        ``(point, direction, 'R'|'P')`` tuples, in world coordinates.
    convention
        ``'standard'`` (Asokan, Lecture 2.6) or ``'modified'`` (Ghosal, Lecture 5).
    base
        Frame 0 (a :class:`~dhsym.geometry.axes.Frame` or 4×4 matrix) with z along axis 1
        (same sense), origin on it. Default: standard, the point of axis 1
        nearest the world origin, x the world x made perpendicular; modified,
        frame 1 at home (Ghosal, Lecture 5). World → frame 0 becomes ``table.base``.
    tool
        A :class:`~dhsym.geometry.axes.Tool` or ``(point, approach, sliding)``; what the
        last DH frame cannot hold becomes ``table.tool``.
    values
        Numbers for symbols in the points (to decide signs, and to verify).
    offsets
        True: variables are zero at home (constant offsets in the table).
    name
        The table's name.
    verify
        Check the result against the geometry at home and 5 random q.

    Examples
    --------
    A revolute joint about z, then a prismatic joint along x at height 1:

    >>> fa = assign_frames([((0, 0, 0), (0, 0, 1), "R"), ((0, 0, 1), (1, 0, 0), "P")],
    ...                    convention="modified")
    >>> [(r.alpha, r.a, r.d, r.theta) for r in fa.table.rows], fa.table.base
    ([(0, 0, 0, theta1), (pi/2, 0, d2, 0)], (Tz(1), Rz(pi/2)))
    >>> [s.rule for s in fa.steps][:4]
    ['numbering', 'first link', 'intersecting', 'last link']
    """
    conv = Convention.parse(convention)
    vals = {
        (symbol(k) if isinstance(k, str) else k): exact_number(v) for k, v in (values or {}).items()
    }
    axs = _axes(axes)
    _check_pairs(axs, vals)
    tool_v = tool if isinstance(tool, Tool) or tool is None else Tool(*tool)
    base_f = None if base is None else _base(base, axs[0], vals)
    build = place_standard if conv is Convention.STANDARD else place_modified
    frames, points_b, log = build(axs, base_f, tool_v, vals)
    rows, vmap, row_steps = _rows(axs, frames, points_b, conv, offsets)
    base_word = transform_word(frames[0].matrix)
    tool_word = (
        transform_word(rigid_inverse(frames[-1].matrix) * tool_v.frame.matrix) if tool_v else ()
    )
    consts = set().union(
        *(e.free_symbols for r in rows for e in r.params().values()),
        *(e.value.free_symbols for e in base_word + tool_word),
    )
    nice = all(_is_nice(e) for r in rows for e in (r.theta, r.alpha))
    table = DHTable(
        tuple(rows),
        conv,
        name=name,
        source="dhsym.geometry.frames.assign_frames",
        values=tuple((k, v) for k, v in vals.items() if k in consts),
        base=base_word,
        tool=tool_word,
        angles=AngleUnit.DEG if nice else AngleUnit.RAD,
    )
    n = len(axs)
    log += row_steps
    log.append(
        say(
            "base transform",
            "base transform" if base_word else "no base transform",
            w=word(base_word),
        )
    )
    log.append(
        say(
            "tool transform",
            "tool transform" if tool_word else "no tool transform",
            n,
            w=word(tool_word),
        )
    )
    result = FrameAssignment(
        axs,
        conv,
        tuple(frames),
        tuple(points_b),
        tool_v,
        table,
        tuple(log),
        tuple(vmap),
        tuple(vals.items()),
    )
    _check_home_exact(result)
    if verify:
        err = result.verify()
        check = say("verified", "verified", e=f"{err:.1e}")
        result = replace(result, steps=result.steps + (check,))
    return result


def _axes(axes: Sequence[JointAxis | Sequence[object]]) -> tuple[JointAxis, ...]:
    out = []
    for k, ax in enumerate(axes, start=1):
        if isinstance(ax, JointAxis):
            out.append(ax if ax.name else replace(ax, name=str(k)))
        else:
            parts: list[Any] = list(ax)  # as given: JointAxis converts and checks each
            if len(parts) < 2:
                raise GeometryError(f"joint {k}: expected (point, direction, type)", row=k)
            joint = parts[2] if len(parts) > 2 else "R"
            out.append(JointAxis(parts[0], parts[1], joint, name=str(k)))
    if not out:
        raise GeometryError("no joint axes: give at least one")
    return tuple(out)


def _check_pairs(axes: tuple[JointAxis, ...], vals: dict[Any, Any]) -> None:
    # only the directions (and for two revolute joints one point) are needed: no common
    # normal with its feet is computed here
    for k in range(1, len(axes)):
        L1, L2 = axes[k - 1], axes[k]
        if L1.joint != L2.joint or not is_zero_vector(cross(L1.direction, L2.direction)):
            continue
        if L1.joint == "P":
            raise GeometryError(
                f"joints {L1.name} and {L2.name} are both prismatic with parallel axes: their "
                "displacements are not independent (two consecutive parallel P joints "
                "act as one); merge them into one prismatic joint",
                row=k + 1,
            )
        if L1.contains(L2.point, vals):
            raise GeometryError(
                f"the axes of joints {L1.name} and {L2.name} coincide: two revolute joints about "
                "one line are not independent (their angles add); merge them",
                row=k + 1,
            )


def _base(base: object, axis: JointAxis, vals: dict[Any, Any]) -> Frame:
    f = base if isinstance(base, Frame) else Frame.from_matrix(base, 0)
    if not is_zero_vector(simplify_vector(f.z - axis.direction)):
        raise GeometryError(
            f"base frame: z0 = {tuple(f.z)} must point along the axis of joint 1, "
            f"{tuple(axis.direction)}",
            row=1,
        )
    if not axis.contains(f.origin, vals):
        raise GeometryError(
            f"base frame: the origin {tuple(f.origin)} is not on the axis of joint 1", row=1
        )
    return Frame(0, f.origin, f.x, f.z)


def _simplify(value: sp.Expr) -> sp.Expr:
    """``simplify``, skipped where it has nothing to do (a rational, a rational times π)."""
    return value if value.is_Rational or (value / sp.pi).is_Rational else sp.simplify(value)


def _atan2(y: sp.Expr, x: sp.Expr) -> sp.Expr:
    y, x = (v if v.is_Rational else sp.radsimp(sp.simplify(v)) for v in (y, x))
    return _simplify(sp.atan2(y, x))


def _rows(
    axes: tuple[JointAxis, ...],
    frames: list[Frame],
    points_b: list[Vector],
    conv: Convention,
    offsets: bool,
) -> tuple[list[DHRow], list[VariableMap], list[Step]]:
    consts = set().union(*(a.point.free_symbols for a in axes))
    rows, vmap, log = [], [], []
    for k, ax in enumerate(axes, start=1):
        F, G = frames[k - 1], frames[k]
        dp = simplify_vector(G.origin - F.origin)
        if conv is Convention.STANDARD:  # about z_{k-1}, then along x_k
            theta, d = _atan2(dot(cross(F.x, G.x), F.z), dot(F.x, G.x)), _simplify(dot(dp, F.z))
            a, alpha = _simplify(dot(dp, G.x)), _atan2(dot(cross(F.z, G.z), G.x), dot(F.z, G.z))
        else:  # along x_{i-1}, then about z_i
            alpha, a = _atan2(dot(cross(F.z, G.z), F.x), dot(F.z, G.z)), _simplify(dot(dp, F.x))
            d, theta = _simplify(dot(dp, G.z)), _atan2(dot(cross(F.x, G.x), G.z), dot(F.x, G.x))
        var = symbol(f"{'theta' if ax.joint == 'R' else 'd'}{k}")
        var = symbol(f"q{k}") if var in consts else var
        home = theta if ax.joint == "R" else d
        entry = var + home if offsets else var
        vmap.append(VariableMap(k, var, 1, sp.Integer(0) if offsets else home))
        if ax.joint == "R":
            rows.append(DHRow.revolute(entry, d=d, a=a, alpha=alpha, variable=var, label=ax.name))
        else:
            rows.append(
                DHRow.prismatic(entry, theta=theta, a=a, alpha=alpha, variable=var, label=ax.name)
            )
        zero = "zero" if offsets else "not zero (no constant offsets)"
        log.append(
            say(
                "parameters",
                f"{conv.value} row",
                k,
                th=angle(theta),
                d=d,
                a=a,
                al=angle(alpha),
                v=name("theta" if ax.joint == "R" else "d", k),
                zero=zero,
                b=points_b[k - 1] if points_b else None,
            )
        )
    return rows, vmap, log


def _is_nice(value: sp.Expr) -> bool:
    const = value.subs({s: 0 for s in value.free_symbols})
    return const == 0 or (const / sp.pi).is_rational is True


# --- verification ---------------------------------------------------------------------------


def _check_home_exact(fa: FrameAssignment) -> None:
    """Frame k of the table at home equals the assigned frame: exactly, or to 50 digits.

    With numbers only (measured axes: nested roots of huge integers) the products
    are compared at 50 significant digits, which is as strict as an exact check
    in practice and takes milliseconds instead of minutes of ``simplify``.
    """
    zero = {m.variable: m.offset for m in fa.variable_map}  # the home pose
    frames = [*fa.frames, fa.tool.frame if fa.tool else fa.frames[-1]]
    table, n = fa.table, fa.table.n
    # world -> frame k is a prefix of world -> tool: one pass, each factor multiplied once
    full = [
        Elementary(e.kind, e.axis, e.value.xreplace(zero)) for e in chain_word(table, -1, n + 1)
    ]
    cut = _prefix_lengths(table)
    if _home_is_rational(full, cut, frames):
        return
    numeric = not any(f.matrix.free_symbols for f in frames) and not any(
        e.value.free_symbols for e in full
    )
    if numeric:
        full = [Elementary(e.kind, e.axis, sp.N(e.value, _DIGITS)) for e in full]
    product, done = sp.eye(4), 0
    for k, f in enumerate(frames):
        product = product * plain_product(full[done : cut[k]])
        done = cut[k]
        if numeric:
            diff = product - f.matrix.evalf(_DIGITS)
            ok = all(abs(x) < sp.Float(10.0**-_AGREE, _DIGITS) for x in diff)
        else:
            ok = is_zero_vector(simplify_vector(product - f.matrix))
        if not ok:
            raise GeometryError(
                f"internal check failed: frame {k} of the table differs from the "
                "assigned frame at home (please report this)"
            )


def _home_is_rational(full: list[Elementary], cut: list[int], frames: list[Frame]) -> bool:
    """The home check exactly over the rationals, when every factor and frame is rational
    (turns by multiples of π/2 and rational lengths: most robot files); False when one
    is not (the caller checks then). The products run in sympy's dense matrices over
    ``QQ`` (a 100-joint chain in milliseconds, not the seconds of generic sympy matrices).
    Raises :class:`~dhsym.errors.GeometryError` when a frame differs.
    """
    wants = [list(entries(f.matrix)) for f in frames]
    if any(not x.is_Rational for w in wants for x in w):
        return False
    # a chain repeats few distinct factors (Rz(0), Tz(1/10), Rx(pi/2), …): each is built
    # and converted once
    distinct: dict[Elementary, DomainMatrix] = {}
    for e in full:
        if e not in distinct:
            m = elementary_matrix(e)
            if any(not x.is_Rational for x in m):
                return False
            distinct[e] = DomainMatrix.from_Matrix(m).convert_to(sp.QQ)
    product, done = DomainMatrix.eye(4, sp.QQ), 0
    for k, want in enumerate(wants):
        for e in full[done : cut[k]]:
            product = product * distinct[e]
        done = cut[k]
        if [sp.QQ.to_sympy(x) for x in product.to_list_flat()] != want:
            raise GeometryError(
                f"internal check failed: frame {k} of the table differs from the "
                "assigned frame at home (please report this)"
            )
    return True


def _prefix_lengths(table: DHTable) -> list[int]:
    """The length of the word world -> frame k, k = 0 … n + 1 (base, four factors a row, tool)."""
    return [len(table.base) + 4 * k for k in range(table.n + 1)] + [
        len(table.base) + 4 * table.n + len(table.tool)
    ]


def _verify(fa: FrameAssignment, samples: int, seed: int, tol: float) -> float:
    rng = np.random.default_rng(seed)
    table, n = fa.table, fa.table.n
    vals = dict(fa.values)
    for s in sorted(table.constants, key=str):
        vals.setdefault(s, sp.Float(rng.uniform(0.5, 1.5)))

    full = chain_word(table, -1, n + 1)  # world -> frame k is a prefix of world -> tool
    prefixes = compile_word(full, table.variables, vals, prefixes=True)
    cut = _prefix_lengths(table)
    homes = [
        np.array([[to_float(x.xreplace(vals)) for x in row] for row in f.matrix.tolist()])
        for f in [*fa.frames, fa.tool.frame if fa.tool else fa.frames[-1]]
    ]
    offsets = [to_float(vm.offset.subs(vals)) for vm in fa.variable_map]
    Q = np.zeros((samples + 1, n))
    for m in range(1, samples + 1):
        Q[m] = rng.uniform(-np.pi, np.pi, n)
    signs = np.array([vm.sign for vm in fa.variable_map], dtype=float)
    every = prefixes(Q * signs + np.array(offsets))  # (samples + 1, len(full) + 1, 4, 4)
    moves = [axis.motions(Q[:, k], vals) for k, axis in enumerate(fa.axes)]
    worst = 0.0
    for m in range(samples + 1):
        now = every[m]
        motion = np.eye(4)
        for k in range(n + 2):
            if 1 <= k <= n:
                motion = motion @ moves[k - 1][m]
            worst = max(worst, float(np.max(np.abs(now[cut[k]] - motion @ homes[k]))))
    if worst > tol:
        raise GeometryError(f"the table does not reproduce the joint axes (error {worst:.3g})")
    return worst


_EX, _EY = Vector([1, 0, 0]), Vector([0, 1, 0])


def _reference(axis: JointAxis) -> tuple[Vector, Vector]:
    """The point of the axis nearest the world origin, and world x (or y) made perpendicular."""
    u = axis.direction
    v = simplify_vector(_EX - dot(_EX, u) * u)
    if is_zero_vector(v):
        v = simplify_vector(_EY - dot(_EY, u) * u)
    return axis.foot((0, 0, 0)), unit(v)


def _closest(candidate: Vector, ref: Vector, vals: dict[Any, Any]) -> tuple[Vector, str]:
    s = sign_of(dot(candidate, ref), vals, what="a direction")
    return (Vector(-candidate), "−") if s < 0 else (candidate, "+")


def _at_home(axis: JointAxis) -> str:
    return " at home (its joint variable)" if axis.joint == "P" else ""


_Link = tuple[CommonNormal, Vector, str, Vector, Vector]
Built = tuple[list[Frame], list[Vector], list[Step]]


def _link(
    L1: JointAxis, L2: JointAxis, start: Vector, prev_x: Vector, vals: dict[Any, Any]
) -> _Link:
    """x along the common normal of L1 and L2; returns (normal, x, sign, foot on L1, on L2).

    Parallel lines: the normal through ``start``; intersecting: the sign of
    ``±L1 × L2`` closest to ``prev_x``; coincident: ``prev_x`` at ``start``.
    """
    cn = common_normal(L1, L2, through=start, values=vals)
    if cn.relation is Relation.INTERSECTING:
        x, sgn = _closest(unit(cross(L1.direction, L2.direction)), prev_x, vals)
        return cn, x, sgn, cn.foot1, cn.foot1
    if cn.relation is Relation.COINCIDENT:
        return cn, prev_x, "", start, start
    return cn, cn.direction, "", cn.foot1, cn.foot2


def place_standard(
    axes: tuple[JointAxis, ...], base: Frame | None, tool: Tool | None, vals: dict[Any, Any]
) -> Built:
    n = len(axes)
    log = [say("numbering", "standard numbering", n=str(n))]
    if base is None:
        origin, x = _reference(axes[0])
        base = Frame(0, origin, x, axes[0].direction)
        log.append(say("base", "standard base", 0, z=base.z, o=base.origin, x=x))
    else:
        log.append(say("base", "given base", 0, z=base.z, o=base.origin, x=base.x))
    frames, bs = [base], []
    for k in range(1, n):
        prev = frames[-1]
        cn, x, sgn, b, origin = _link(axes[k - 1], axes[k], prev.origin, prev.x, vals)
        frames.append(Frame(k, origin, x, axes[k].direction))
        bs.append(b)
        log.append(
            say(
                cn.relation.value,
                f"standard {cn.relation.value}",
                k,
                foot=b,
                o=origin,
                x=x,
                len=cn.length,
                sgn=sgn,
                start=prev.origin,
                home=_at_home(axes[k - 1]),
            )
        )
    last, b, text = _standard_last(axes[-1], frames[-1], tool, vals, n)
    return [*frames, last], [*bs, b], [*log, text]


def _standard_last(
    Ln: JointAxis, prev: Frame, tool: Tool | None, vals: dict[Any, Any], n: int
) -> tuple[Frame, Vector, Step]:
    if tool is None:
        return Frame(n, prev.origin, prev.x, prev.z), prev.origin, say("last link", "no tool", n)
    p, t = tool.point, tool.frame
    foot = Ln.foot(p)
    gap = simplify_vector(p - foot)
    if is_zero_vector(gap, vals):  # the tool point is on the last axis: x_n only ⊥ z_{n−1}
        x = simplify_vector(t.x - dot(t.x, prev.z) * prev.z)
        x = prev.x if is_zero_vector(x) else unit(x)
    else:
        x = unit(gap, vals)
    z = simplify_vector(t.z - dot(t.z, x) * x)
    frame = Frame(n, p, x, prev.z if is_zero_vector(z) else unit(z))
    dh = is_zero_vector(simplify_vector(frame.matrix - t.matrix))
    args = dict(p=p, a=tool.approach, s=tool.sliding, nv=t.x, b=foot, x=frame.x, z=frame.z)
    keys = ("tool", "tool is DH" if dh else "tool is not DH")
    return frame, foot, say("tool", keys, n, **args)


def place_modified(
    axes: tuple[JointAxis, ...], base: Frame | None, tool: Tool | None, vals: dict[Any, Any]
) -> Built:
    n = len(axes)
    log = [say("numbering", "modified numbering", n=str(n))]
    start, prev_x = (base.origin, base.x) if base is not None else _reference(axes[0])
    frames: list[Frame] = []
    for i in range(1, n):
        cn, x, sgn, origin, start = _link(axes[i - 1], axes[i], start, prev_x, vals)
        frames.append(Frame(i, origin, x, axes[i - 1].direction))
        log.append(
            say(
                cn.relation.value,
                f"modified {cn.relation.value}",
                i,
                o=origin,
                x=x,
                len=cn.length,
                sgn=sgn,
                home=_at_home(axes[i - 1]),
            )
        )
        prev_x = x
    frames.append(Frame(n, start, prev_x, axes[-1].direction))
    kind = "revolute" if axes[-1].joint == "R" else "prismatic"
    log.append(say("last link", "last link", n, o=start, kind=kind))
    if base is None:
        base = Frame(0, frames[0].origin, frames[0].x, frames[0].z)
        log.insert(1, say("first link", f"first link {axes[0].joint}", 0))
    else:
        log.insert(1, say("base", "given base", 0, z=base.z, o=base.origin, x=base.x))
    return [base, *frames], [], log
