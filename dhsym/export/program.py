"""The front end of the exporters: a robot's closed forms as named, straight-line programs.

Every language printer reads the same :class:`Program`: named assignments of exact
expressions (then numbers to 17 digits), each at the *level* of the branch signs it
depends on, and the entries of the result. Joint values are ``q1 … qn``; the sine
and cosine of each joint angle and each sum of joint angles that occurs is computed
once (``s1``, ``c1``, ``s23``, ``c23``) before anything else, and the remaining common
subexpressions are shared through :func:`sympy.cse` (``w0``, ``w1`` …).

* :func:`fk_program`: world to tool, ``base · ^0T_n · tool`` (the pose of ``robot.fk``);
* :func:`jacobian_program`: the geometric Jacobian in that base frame, of the tool point
  (``robot.jacobian(q)``);
* :func:`ik_program`: the closed-form IK steps as the derivation gives them
  (:mod:`dhsym.export.ik_source`), one assignment per step with its sentence.

Examples
--------
>>> import dhsym
>>> prog = fk_program(dhsym.load("planar2r"))
>>> [(a.name, str(a.expr)) for a in prog.body]
[('c1', 'cos(q1)'), ('c12', 'cos(q1 + q2)'), ('s1', 'sin(q1)'), ('s12', 'sin(q1 + q2)')]
>>> [(o.row, o.col, str(o.expr)) for o in prog.outputs][3]
(0, 3, 'c1 + 0.8*c12')
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.transforms import plain_product
from dhsym.model.entries import check_real
from dhsym.model.parsing import REAL as _REAL
from dhsym.model.table import Convention, JointType

from .identifiers import identifier
from .ik_source import IKSource, Refinement, ik_source

if TYPE_CHECKING:
    from dhsym.dynamics.model import DynamicModel
    from dhsym.ik.choices import IKCache
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "Assign",
    "IKProgram",
    "Output",
    "Parameter",
    "Program",
    "RNEProgram",
    "Coulomb",
    "fk_program",
    "ik_program",
    "jacobian_program",
    "links_program",
    "rne_program",
]


@dataclass(frozen=True)
class Assign:
    """``name = expr`` in a generated function.

    ``level`` is the number of branch signs the value depends on (0: before any branch
    loop); ``comment`` the lines said before it (a step's sentence); with ``alt``, a
    triple ``(guard, threshold, expr)``, the value is ``expr`` of ``alt`` when
    ``|guard| < threshold`` (a singular wrist).
    """

    name: str
    expr: sp.Expr
    level: int = 0
    comment: tuple[str, ...] = ()
    alt: tuple[str, float, sp.Expr] | None = None

    def expressions(self) -> tuple[sp.Expr, ...]:
        """What the generated code evaluates for it: ``expr``, and with ``alt`` its guard
        and its singular value."""
        if self.alt is None:
            return (self.expr,)
        return (self.expr, sp.Symbol(self.alt[0]), self.alt[2])


@dataclass(frozen=True)
class Output:
    """Entry ``(row, col)`` of the result."""

    row: int
    col: int
    expr: sp.Expr


@dataclass(frozen=True)
class Parameter:
    """A length or offset passed in at run time (``--symbolic-lengths``): its name in the
    table, its identifier in the code, the table's value (``None``: none given) and its
    place in the parameter array ``p`` (0-based)."""

    table_name: str
    name: str
    value: float | None
    index: int = 0


@dataclass(frozen=True)
class Program:
    """A straight-line function of ``q`` (and parameters): assignments, then outputs."""

    joints: tuple[str, ...]
    parameters: tuple[Parameter, ...]
    body: tuple[Assign, ...]
    outputs: tuple[Output, ...]
    rows: int
    cols: int

    def expressions(self) -> tuple[sp.Expr, ...]:
        """Every expression the function evaluates (its locals and parameters are the
        names these use)."""
        return (*(e for a in self.body for e in a.expressions()), *(o.expr for o in self.outputs))


@dataclass(frozen=True)
class IKProgram:
    """The IK steps as assignments (``body``, levels by branch sign) for a pose ``T``.

    ``pose`` assigns the pose symbols (``n_x`` … ``p_z``) from the input with base and
    tool undone; ``signs`` names the branch signs in loop order; ``branch_names`` gives
    the name of each of the ``2 ** len(signs)`` branches (as ``robot.ik`` names them);
    ``joints`` are the joint values with ``revolute`` telling which to wrap to [−π, π];
    ``check`` the top three rows of the branch's world-to-tool fk (row by row), on the
    values of ``body``, to compare with the pose within ``tolerance``.
    """

    source: IKSource
    parameters: tuple[Parameter, ...]
    pose: tuple[Assign, ...]
    signs: tuple[str, ...]
    body: tuple[Assign, ...]
    joints: tuple[str, ...]
    revolute: tuple[bool, ...]
    branch_names: tuple[str, ...]
    sqrt_rounding: float
    tolerance: float
    check: tuple[sp.Expr, ...] = ()

    def expressions(self) -> tuple[sp.Expr, ...]:
        """Every expression the function evaluates: the pose, the steps and the fk check
        (a parameter the check alone reads is a parameter of the function too)."""
        return (
            *(e for a in (*self.pose, *self.body) for e in a.expressions()),
            *self.check,
        )

    @property
    def floor(self) -> float:
        """The tolerance of an exact pose, the least of any (:mod:`dhsym.ik.accuracy`)."""
        return self.tolerance

    @property
    def exact(self) -> float:
        """A rotation off the rotations by at most this is exact (solved as given)."""
        return self.source.exact

    @property
    def most_decimals(self) -> int:
        """The most decimals looked for in a pose's entries (its half unit)."""
        return self.source.most_decimals

    @property
    def refinement(self) -> Refinement:
        """How a branch near a pose that is not exact is refined (Levenberg–Marquardt on
        the exported fk and Jacobian, as ``robot.ik``)."""
        return self.source.refinement

    @property
    def safe_sqrt(self) -> bool:
        """Whether a step takes a square root (the helper is written only then)."""
        exprs = [a.expr for a in self.body] + [a.alt[2] for a in self.body if a.alt]
        return any(self.source.has_sqrt(e) for e in exprs)


# --- shared pieces ------------------------------------------------------------------------


def _joint_symbols(robot: KinematicChain) -> dict[sp.Symbol, sp.Symbol]:
    return {v: sp.Symbol(f"q{k}", **_REAL) for k, v in enumerate(robot.variables, start=1)}


def _constants(
    robot: KinematicChain, symbolic_lengths: bool, taken: set[str]
) -> tuple[dict[sp.Symbol, sp.Expr], tuple[Parameter, ...]]:
    """What the table's constant symbols become: numbers, or parameters ``p_<name>``."""
    values = robot.table.value_map
    consts = robot.table.constants
    if not symbolic_lengths:
        missing = [c.name for c in consts if c not in values]
        if missing:
            raise DHError(
                f"{robot.name or 'this table'} has no value for {', '.join(missing)}: give "
                "values in the table file, or export with --symbolic-lengths"
            )
        return {c: values[c] for c in consts}, ()
    mapping: dict[sp.Symbol, sp.Expr] = {}
    params = []
    for k, c in enumerate(consts):
        name = identifier(f"p_{c.name}", taken=taken)
        taken.add(name)
        mapping[c] = sp.Symbol(name, **_REAL)
        v = values.get(c)
        params.append(Parameter(c.name, name, None if v is None else float(sp.N(v, 17)), k))
    return mapping, tuple(params)


def _is_joint_sum(arg: sp.Expr, index: Mapping[sp.Symbol, int]) -> list[int] | None:
    terms = sp.Add.make_args(arg)
    if all(t in index for t in terms):
        return sorted(index[t] for t in terms)
    return None


def _trig_name(fn: str, arg: sp.Expr, index: Mapping[sp.Symbol, int]) -> str | None:
    joints = _is_joint_sum(arg, index)
    if joints is None:
        return None
    if all(k < 10 for k in joints):
        return fn + "".join(str(k) for k in joints)
    return fn + "_" + "_".join(str(k) for k in joints)


def _name_trig(
    exprs: Sequence[sp.Expr], index: Mapping[sp.Symbol, int], taken: set[str]
) -> tuple[list[sp.Expr], list[tuple[sp.Symbol, sp.Expr]]]:
    """Replace ``sin``/``cos`` of joint angles and their sums by named symbols.

    Returns the expressions and the definitions (sorted by name, deterministic).
    """
    atoms: set[sp.Expr] = set()
    for e in exprs:
        atoms |= {t for t in sp.preorder_traversal(e) if isinstance(t, (sp.sin, sp.cos))}
    defs: list[tuple[sp.Symbol, sp.Expr]] = []
    mapping: dict[sp.Expr, sp.Symbol] = {}
    for t in sorted(atoms, key=sp.default_sort_key):
        name = _trig_name("s" if isinstance(t, sp.sin) else "c", t.args[0], index)
        if name is None or name in taken:
            continue
        taken.add(name)
        sym = sp.Symbol(name, **_REAL)
        mapping[t] = sym
        defs.append((sym, t))
    defs.sort(key=lambda d: d[0].name)
    return [e.xreplace(mapping) for e in exprs], defs


def _numbers(e: sp.Expr, exponent: bool = False) -> sp.Expr:
    """Exact constants as 17-digit floats; integer exponents and ``±1`` stay integers.

    >>> x = sp.Symbol("x", real=True)
    >>> _numbers(sp.atan2(sp.Rational(1, 4), x) + 2 * x**2 - sp.sqrt(2) * sp.pi)
    2.0*x**2 + atan2(0.25, x) - 4.4428829381583662
    """
    if e.is_Integer:
        return e if exponent or abs(e) == 1 else sp.Float(e, 17)
    if e.is_number and not e.has(sp.I):
        return sp.Float(sp.N(e, 17), 17)
    if not e.args or isinstance(e, sp.Symbol | sp.Indexed):
        return e
    if e.is_Pow:
        return sp.Pow(_numbers(e.base), _numbers(e.exp, exponent=True))
    return e.func(*(_numbers(a) for a in e.args))


def _straight_line(
    exprs: Sequence[sp.Expr], joints: Mapping[sp.Symbol, int], taken: set[str]
) -> tuple[list[Assign], list[sp.Expr]]:
    for e in exprs:  # a value can make an entry complex: exported code computes reals
        for part in (e, *(a for a in e.atoms(sp.Function, sp.Pow) if a.is_number)):
            check_real(part, field="values", text=False)
    named, trig = _name_trig(exprs, joints, taken)
    names = (f"w{k}" for k in range(10**6))
    fresh = (sp.Symbol(n, **_REAL) for n in names if n not in taken)
    common, reduced = sp.cse([_numbers(e) for e in named], symbols=fresh, order="canonical")
    body = [Assign(s.name, t) for s, t in trig]
    body += [Assign(s.name, _numbers(e)) for s, e in common]
    return body, [_numbers(e) for e in reduced]


def _prepared(
    robot: KinematicChain, matrix: sp.Matrix, symbolic_lengths: bool
) -> tuple[list[sp.Expr], tuple[Parameter, ...], dict[sp.Symbol, int], set[str]]:
    qs = _joint_symbols(robot)
    taken = {s.name for s in qs.values()}
    consts, params = _constants(robot, symbolic_lengths, taken)
    exprs = [sp.Integer(e) if isinstance(e, int) else e.xreplace({**qs, **consts}) for e in matrix]
    index = {s: k for k, s in enumerate(qs.values(), start=1)}
    return exprs, params, index, taken


def _program(robot: KinematicChain, matrix: sp.Matrix, symbolic_lengths: bool) -> Program:
    exprs, params, index, taken = _prepared(robot, matrix, symbolic_lengths)
    body, reduced = _straight_line(exprs, index, taken)
    rows, cols = matrix.shape
    outputs = tuple(Output(k // cols, k % cols, e) for k, e in enumerate(reduced))
    return Program(tuple(s.name for s in index), params, tuple(body), outputs, rows, cols)


def fk_program(robot: KinematicChain, *, symbolic_lengths: bool = False) -> Program:
    """World to tool (``robot.fk``) as a :class:`Program` with a 4×4 result."""
    return _program(robot, robot.tool_pose().matrix, symbolic_lengths)


def links_program(robot: KinematicChain) -> Program:
    """Each link matrix ``^{i-1}T_i`` and the point between its row's two halves, for
    drawing the arm: ``4n × 4``, link ``i`` in rows ``4(i-1) … 4i-1`` (its top three rows,
    then the translation of its first two elementary transforms and a 0).

    The point is where a lecture's picture bends: along ``z_{i-1}`` by ``d_i`` (standard),
    or along ``x_{i-1}`` by ``a_{i-1}`` (modified).

    >>> import dhsym
    >>> prog = links_program(dhsym.load("planar2r"))
    >>> (prog.rows, prog.cols), [str(o.expr) for o in prog.outputs[:4]]
    ((8, 4), ['c1', '-s1', '0.0', 'c1'])
    """
    rows: list[list[sp.Expr]] = []
    for i in range(1, robot.n + 1):
        A = robot.link_matrix(i).matrix
        half = plain_product(robot.link_word(i)[:2])
        rows += [list(A.row(r)) for r in range(3)]
        rows.append([half[0, 3], half[1, 3], half[2, 3], sp.Integer(0)])
    return _program(robot, sp.Matrix(rows), False)


def jacobian_program(robot: KinematicChain, *, symbolic_lengths: bool = False) -> Program:
    """The geometric Jacobian of ``robot.jacobian(q)`` (base frame of ``fk``, tool point),
    6 × n.

    >>> import dhsym
    >>> prog = jacobian_program(dhsym.load("planar2r"))
    >>> (prog.rows, prog.cols), str(prog.outputs[0].expr)
    ((6, 2), '-s1 - w0')
    """
    J = robot.jacobian()
    return _program(robot, J.matrix, symbolic_lengths)


# --- inverse kinematics ---------------------------------------------------------------------


def _dependencies(e: sp.Expr) -> set[sp.Symbol]:
    symbols: set[sp.Symbol] = e.free_symbols
    return symbols


def ik_program(
    robot: KinematicChain, *, symbolic_lengths: bool = False, cache: IKCache | None = None
) -> IKProgram:
    """The closed-form IK of ``robot`` as assignments, each step with its sentence.

    >>> import dhsym
    >>> prog = ik_program(dhsym.load("planar2r"))
    >>> prog.signs, prog.branch_names
    (('sigma_2',), ('elbow sigma_2 = +1', 'elbow sigma_2 = -1'))
    >>> [a.name for a in prog.body]
    ['d_2', 'q2', 'c2', 's2', 'q1', 'c12', 's12', 'c1', 's1']
    """
    src = ik_source(robot, cache=cache)
    qs = _joint_symbols(robot)
    taken = {s.name for s in qs.values()} | {f"i{k}" for k in range(1, len(src.signs) + 1)}
    # the parameters first, named as fk_program names them (the functions share p); a pose
    # symbol that meets one (a length called x: p_x) gives way
    consts, params = _constants(robot, symbolic_lengths, taken)
    pose_names: dict[sp.Symbol, sp.Symbol] = {}
    for s in src.pose_symbols:
        pose_names[s] = sp.Symbol(identifier(s.name, taken=taken), **_REAL)
        taken.add(pose_names[s].name)
    rename: dict[sp.Symbol, sp.Symbol] = {**qs, **pose_names}
    level: dict[sp.Symbol, int] = {s: 0 for s in pose_names.values()}
    signs = []
    for k, sym in enumerate(src.signs, start=1):
        new = sp.Symbol(identifier(sym.name, taken=taken), **_REAL)
        taken.add(new.name)
        rename[sym] = new
        level[new] = k
        signs.append(new.name)
    for step in src.steps:
        if step.lhs not in rename:
            new = sp.Symbol(identifier(step.lhs.name, taken=taken), **_REAL)
            taken.add(new.name)
            rename[step.lhs] = new
    index = {s: k for k, s in enumerate(qs.values(), start=1)}

    # one simultaneous replacement: a parameter never meets a pose symbol of its name
    # (a length x is p_x, the derivation's pose symbol p_x becomes p_x_2)
    substitution = {**rename, **consts}

    def convert(e: sp.Expr) -> sp.Expr:
        return src.prepare(e.xreplace(substitution))

    body: list[Assign] = []
    defined_trig: set[sp.Symbol] = set()

    def level_of(e: sp.Expr) -> int:
        return max((level.get(s, 0) for s in _dependencies(e)), default=0)

    def with_trig(e: sp.Expr) -> sp.Expr:
        (named,), defs = _name_trig([e], index, set(taken))
        for sym, t in defs:
            if sym not in defined_trig:
                defined_trig.add(sym)
                level[sym] = level_of(t)
                body.append(Assign(sym.name, _numbers(t), level[sym]))
        return named

    for step in src.steps:
        lhs = rename[step.lhs]
        rhs = with_trig(convert(step.rhs))
        alt = None
        lv = level_of(rhs)
        if step.singular is not None:
            guard, threshold = src.singular_guard(step)
            alt_expr = with_trig(convert(step.singular))
            alt = (rename[guard].name, threshold, _numbers(alt_expr))
            lv = max(lv, level_of(alt_expr), level[rename[guard]])
        level[lhs] = lv
        body.append(Assign(lhs.name, _numbers(rhs), lv, step.comment, alt))
        # a joint value's sine and cosine may be needed again after a singular fix:
        # they are defined after it (with_trig runs on later steps only)
    # the check: the fk (world to tool) of the branch's joint values, its top three rows,
    # on the sines and cosines the steps computed; its common parts at their levels
    tool = robot.tool_pose().matrix
    named = [with_trig(convert(tool[i, j])) for i in range(3) for j in range(4)]
    names = (f"f{k}" for k in range(10**6))
    fresh = (sp.Symbol(n, **_REAL) for n in names if n not in taken)
    common, check = sp.cse([_numbers(e) for e in named], symbols=fresh, order="canonical")
    for sym, e in common:
        level[sym] = level_of(e)
        body.append(Assign(sym.name, _numbers(e), level[sym]))
    check = [_numbers(e) for e in check]
    keep = [s.name for s in qs.values()]
    keep += [s.name for e in check for s in e.free_symbols]
    pose = tuple(Assign(pose_names[s].name, _numbers(convert(e))) for s, e in src.pose_inputs)
    return IKProgram(
        src,
        params,
        pose,
        tuple(signs),
        _ordered(body, keep),
        tuple(s.name for s in qs.values()),
        tuple(r.joint is JointType.REVOLUTE for r in robot.table.rows if r.variable is not None),
        src.branch_names,
        src.sqrt_rounding,
        src.tolerance,
        tuple(check),
    )


def _ordered(body: Sequence[Assign], keep: Iterable[str]) -> tuple[Assign, ...]:
    """The assignments that ``keep`` needs, grouped by level (stable): each lower level's
    values come first (a value never depends on a higher level's)."""
    live = set(keep)
    needed = []
    for a in reversed(body):
        if a.name in live:
            needed.append(a)
            exprs = [a.expr] + ([a.alt[2], sp.Symbol(a.alt[0])] if a.alt else [])
            live |= {s.name for e in exprs for s in e.free_symbols}
    return tuple(sorted(reversed(needed), key=lambda a: a.level))


# --- inverse dynamics -----------------------------------------------------------------------


class Coulomb(sp.Function):
    """``Coulomb(v, up, down)``: ``up`` when ``v > 0``, ``down`` when ``v < 0``, 0 at rest
    (``robot.rne``'s Coulomb friction; each printer writes it with comparisons)."""

    nargs = 3


@dataclass(frozen=True)
class RNEProgram:
    """τ(q, q̇, q̈) as a straight-line program: inputs ``q1 …``, ``qd1 …``, ``qdd1 …``.

    ``inputs`` gives each input's name, its array (``q``, ``qd``, ``qdd``) and 0-based
    index; ``outputs`` are ``τ_k`` (row ``k``, column 0); ``passes`` says what the body
    computes (the recursion's passes, motor inertia and friction).
    """

    joints: tuple[str, ...]
    inputs: tuple[tuple[str, str, int], ...]
    body: tuple[Assign, ...]
    outputs: tuple[Output, ...]
    passes: tuple[str, ...]
    friction: bool
    rows: int
    cols: int = 1

    def expressions(self) -> tuple[sp.Expr, ...]:
        """Every expression the function evaluates."""
        return (*(e for a in self.body for e in a.expressions()), *(o.expr for o in self.outputs))


_PASSES = (
    "Recursive Newton-Euler (Luh, Walker and Paul; Craig, Introduction to Robotics, 6.5),",
    "each link in its own frame, arranged for few operations as Khalil and Dombre do",
    "(Modeling, Identification and Control of Robots, the Newton-Euler algorithm).",
    "Outward pass, link 1 to n: angular velocity and acceleration, then",
    "U_i = [wdot_i] + [w_i][w_i] (the acceleration of a point r of the link is a_i + U_i r),",
    "the acceleration a_i of the frame (gravity enters as an acceleration of the base),",
    "F_i = m_i (a_i + U_i r_ci) and N_i = I_i wdot_i + w_i x I_i w_i.",
    "Inward pass, link n to 1: force f_i, and moment m_i about the joint axis's point, whose",
    "component along the axis is the joint torque.",
)


def _rne_recursion(dm: DynamicModel, clean: Callable[[sp.Expr], sp.Expr]) -> list[sp.Expr]:
    r"""τ of the Newton–Euler recursion arranged for few operations, each entry of each
    step through ``clean`` (which names it).

    The geometry is :func:`~dhsym.dynamics.recursive_newton_euler.rne_expressions`' (a link
    matrix is ``Pre · Rz(θ) Tz(d) · Post``; ``u`` the joint axis times the rate of the
    joint's variable in its cell, ``r_1`` from ``o_{i-1}`` to the joint's point ``A``,
    ``r_2`` from ``A`` to ``o_i``, all in frame *i*), and so is every value; three things
    are arranged differently (Khalil and Dombre, *Modeling, Identification and Control of
    Robots*, §9.5):

    * ``U_i = [ω̇_i]_× + [ω_i]_×[ω_i]_×`` once per link: the acceleration of any point
      ``r`` of the link is ``a_i + U_i r`` (for the next origin and the centre of mass);
    * the force on the link is ``F_i = m_i (a_i + U_i r_c)``, its moment about ``o_i``
      ``n_i = N_i + r_c × F_i + R_{i+1} m_{i+1} + r_{1,i+1} × R_{i+1} f_{i+1}``;
    * ``m_i = n_i + r_2 × f_i``, the moment about ``A``, gives the torque ``u · m_i`` and is
      what the link before receives (rotated once), so no ``p × R f`` is formed.

    >>> import dhsym
    >>> from dhsym.dynamics.compiled_dynamics import numeric_model
    >>> from dhsym.dynamics.recursive_newton_euler import rne_expressions
    >>> dm = numeric_model(dhsym.load("puma560"))
    >>> tau = _rne_recursion(dm, lambda e: e)
    >>> inputs = (*dm.variables, *dm.rates, *dm.accelerations)
    >>> point = {x: 0.1 * k for k, x in enumerate(inputs)}
    >>> diff = [(a - b).xreplace(point) for a, b in zip(tau, rne_expressions(dm))]
    >>> max(abs(d) for d in diff) < 1e-12
    True
    """
    robot = dm.robot
    table = robot.table
    M = sp.ImmutableMatrix
    ez, zero = M([0, 0, 1]), M.zeros(3, 1)

    def keep(v: sp.MatrixBase) -> sp.ImmutableMatrix:
        return M(v).applyfunc(clean)

    def u_matrix(w: sp.MatrixBase, wd: sp.MatrixBase) -> sp.ImmutableMatrix:
        """``[ω̇]_× + ω ωᵀ − |ω|² E``, i.e. ``U r = ω̇ × r + ω × (ω × r)``."""
        x, y, z = wd
        return keep(M([[0, -z, y], [z, 0, -x], [-y, x, 0]]) + w * w.T - (w.T * w)[0, 0] * sp.eye(3))

    index = {row: k for k, row in enumerate(dm.joints)}
    w, wd, a = zero, zero, M([-g for g in dm.gravity])
    U = M.zeros(3, 3)
    links = []
    for i, (row, L) in enumerate(zip(table.rows, dm.links), start=1):
        T = robot.transform(i - 1, i).matrix
        R, p = M(T[:3, :3]), M(T[:3, 3])
        pre = plain_product(
            robot.link_word(i)[:2] if table.convention is Convention.MODIFIED else ()
        )
        R_pre, r1 = M(pre[:3, :3]), M(pre[:3, 3])
        k = index.get(i)
        axis = (R.T * R_pre * ez).applyfunc(sp.expand)
        u = axis if k is None or dm.cell_rates[k] == 1 else axis * dm.cell_rates[k]
        r2 = (R.T * (p - r1)).applyfunc(sp.expand)
        a_before = a
        wp, wdp = keep(R.T * w), keep(R.T * wd)
        a_A = keep(R.T * (a + U * r1))
        if row.joint is JointType.REVOLUTE and k is not None:
            w = keep(wp + u * dm.rates[k])
            wd = keep(wdp + wp.cross(u) * dm.rates[k] + u * dm.accelerations[k])
        else:
            w, wd = wp, wdp
        U = u_matrix(w, wd)
        acc = a_A + U * r2
        turns = True  # the frame only turns about the joint (no sliding)
        if row.joint is JointType.PRISMATIC and k is not None:
            acc += 2 * w.cross(u) * dm.rates[k] + u * dm.accelerations[k]
            turns = False
        a = keep(acc)
        rc = M(L.r)
        F = keep(L.m * (a + U * rc))
        N = L.I * wd + w.cross(L.I * w)
        # the last link needs no acceleration of its own when its frame only turns about an
        # axis through its origin and its centre of mass (a wrist's flange): R a_n = a_{n-1}
        # and R r_c is constant (r_c along u)
        carried = (
            i == table.n > 1
            and turns
            and r1 == zero
            and r2 == zero
            and rc.cross(axis).applyfunc(sp.expand) == zero
        )
        along = (axis.T * rc)[0, 0] * R_pre * ez
        links.append((R, u, r1, r2, rc, k, row.joint, F, N, L.m, U, a_before, along, carried))
    tau: list[sp.Expr] = [sp.Integer(0)] * dm.n
    Rf, Rm = zero, zero  # force and moment about o_i of the link after, in frame i
    for R, u, r1, r2, rc, k, joint, F, N, mass, U, a_before, along, carried in reversed(links):
        if carried:  # F = m a_n + h: m a_n = m R^T a_{n-1} crosses the joint unturned
            h = keep(mass * U * rc)
            m = keep(N + rc.cross(h))  # less r_c × m a_n, which is normal to u
            f = zero
            Rf = mass * a_before + keep(R * h)
            Rm = keep(R * m) + along.cross(mass * a_before)
        else:
            f = keep(F + Rf)
            m = keep(N + rc.cross(F) + Rm + r2.cross(f))
        if k is not None:
            L = dm.links[dm.joints[k] - 1]
            t = (u.T * (m if joint is JointType.REVOLUTE else f))[0, 0]
            tau[k] = clean(t + L.Jm * L.G**2 * dm.accelerations[k])
        if not carried:
            Rf = keep(R * f)
            Rm = R * m + r1.cross(Rf)
    return tau


def _pythagoras(e: sp.Expr) -> sp.Expr:
    """``k sin²x + k cos²x`` → ``k`` in every sum (the recursion's ``Rᵀ R`` products leave
    them; exact, so the torques are the same expressions, shorter).

    >>> x, k = sp.symbols("x k", real=True)
    >>> _pythagoras(k * sp.sin(x) ** 2 + k * sp.cos(x) ** 2 + x)
    k + x
    """

    def fold(add: sp.Expr) -> sp.Expr:
        found: dict[tuple[type, sp.Expr, sp.Expr], sp.Expr] = {}
        for t in add.args:
            for f in sp.Mul.make_args(t):
                if f.is_Pow and f.exp == 2 and isinstance(f.base, (sp.sin, sp.cos)):
                    rest = sp.Mul(*[g for g in sp.Mul.make_args(t) if g is not f])
                    found.setdefault((type(f.base), f.base.args[0], rest), t)
                    break
        terms = list(add.args)
        for (fn, x, rest), t in found.items():
            other = found.get((sp.cos, x, rest)) if fn is sp.sin else None
            if other is not None and t in terms and other in terms:
                terms.remove(t)
                terms.remove(other)
                terms.append(rest)
        return sp.Add(*terms) if len(terms) != len(add.args) else add

    return e.replace(lambda a: a.is_Add, fold)


class _ValueNumbering:
    """Names every compound subexpression once (value numbering): ``numbering(e)`` is
    ``e`` with each sum, product and power, innermost first, replaced by a temporary
    ``_v<k>``, the same one wherever the same value recurs; ``lines`` holds the
    definitions in order. Numbers, symbols, ``-x``, ``k·x`` and the sine and cosine of a
    joint variable stay as they are.

    >>> x, y = sp.symbols("x y", real=True)
    >>> numbering = _ValueNumbering()
    >>> numbering(2 * x * y + sp.sin(x)), numbering(-x * y)
    (_v1, -_v0)
    >>> numbering.lines
    [(_v0, x*y), (_v1, 2*_v0 + sin(x))]
    """

    def __init__(self) -> None:
        self.lines: list[tuple[sp.Symbol, sp.Expr]] = []
        self._names: dict[sp.Expr, sp.Symbol] = {}

    def __call__(self, e: sp.Expr) -> sp.Expr:
        if e.is_Atom or (isinstance(e, (sp.sin, sp.cos)) and e.args[0].is_Atom):
            return e
        coeff, rest = e.as_coeff_Mul()
        if coeff is not sp.S.One:  # -x, k·x: the factor stays outside the name
            return coeff * self(rest)
        value = e.func(*(self(a) for a in e.args))
        if value.is_Atom:
            return value
        name = self._names.get(value)
        if name is None:
            name = self._names[value] = sp.Symbol(f"_v{len(self.lines)}", **_REAL)
            self.lines.append((name, value))
        return name


def _inline_once(
    lines: Sequence[tuple[sp.Symbol, sp.Expr]], exprs: Sequence[sp.Expr]
) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr]]:
    """Each line used once written into its user, where sums meet sums and like terms
    cancel (the lines of one step meet those of the next: ``x + y`` then ``2(x + y) − x``
    is ``x + y``), unless that costs operations; unused lines dropped.

    >>> x, y, z, u, v = sp.symbols("x y z u v", real=True)
    >>> _inline_once([(u, x + y), (v, 2 * u - x)], [v])  # like terms cancel
    ([], [x + 2*y])
    >>> _inline_once([(u, x + y + z)], [3 * u])  # 3x + 3y + 3z would cost two more
    ([(u, x + y + z)], [3*u])
    """
    defs = dict(lines)
    order = [s for s, _ in lines]
    exprs = list(exprs)
    kept: set[sp.Symbol] = set()
    while True:
        uses: dict[sp.Symbol, int] = {}
        for e in [*defs.values(), *exprs]:
            for t in e.free_symbols:
                if t in defs:
                    uses[t] = uses.get(t, 0) + 1
        once = [t for t in order if t in defs and t not in kept and uses.get(t, 0) == 1]
        dead = [t for t in order if t in defs and t not in uses]
        if not once and not dead:
            break
        for t in dead:
            del defs[t]
        # a line used once is written into its user unless that costs operations (a sum
        # times a number is multiplied out); its own uses are counted again next round
        # (one round writes a chain of single uses one link at a time)
        for t in once:
            value = {t: defs[t]}  # as written so far (earlier lines written into it)
            users = [s for s in defs if t in defs[s].free_symbols]
            places = [j for j, e in enumerate(exprs) if t in e.free_symbols]
            before = [defs[s] for s in users] + [exprs[j] for j in places]
            after = [e.xreplace(value) for e in before]
            if sp.count_ops(after) > sp.count_ops(before) + sp.count_ops(value[t]):
                kept.add(t)
                continue
            del defs[t]
            for s, e in zip(users, after):
                defs[s] = e
            for j, e in zip(places, after[len(users) :]):
                exprs[j] = e
    return [(s, defs[s]) for s in order if s in defs], exprs


def _shared_lines(
    lines: Sequence[tuple[sp.Symbol, sp.Expr]],
    exprs: Sequence[sp.Expr],
    joints: Mapping[sp.Symbol, int],
    taken: set[str],
) -> tuple[list[Assign], list[sp.Expr]]:
    """Straight-line code of ``exprs`` on the named ``lines``: the trig of the joints named
    (``s1``, ``c23``), numbers as floats, products common to several lines shared
    (:func:`sympy.cse`), the lines each value needs in dependency order, renamed
    ``w0``, ``w1`` … in that order; unused lines dropped."""
    lines, exprs = _inline_once(lines, exprs)
    every = [e for _, e in lines] + list(exprs)
    for e in every:  # a value can make an entry complex: exported code computes reals
        for part in (e, *(a for a in e.atoms(sp.Function, sp.Pow) if a.is_number)):
            check_real(part, field="values", text=False)
    named, trig = _name_trig(every, joints, taken)
    fresh = (sp.Symbol(f"_x{k}", **_REAL) for k in range(10**6))
    common, reduced = sp.cse([_numbers(e) for e in named], symbols=fresh, order="canonical")
    k = len(lines)
    items = [*common, *((s, e) for (s, _), e in zip(lines, reduced[:k]))]
    outputs = reduced[k:]
    # the lines the outputs need, each after what it uses (stable)
    definition = dict(items)
    live: set[sp.Symbol] = set()
    stack = [s for e in outputs for s in e.free_symbols if s in definition]
    while stack:
        s = stack.pop()
        if s not in live:
            live.add(s)
            stack += [t for t in definition[s].free_symbols if t in definition]
    pending = [(s, e) for s, e in items if s in live]
    ordered: list[tuple[sp.Symbol, sp.Expr]] = []
    done: set[sp.Symbol] = set()
    while pending:
        rest = []
        for s, e in pending:
            if all(t in done or t not in definition for t in e.free_symbols):
                ordered.append((s, e))
                done.add(s)
            else:
                rest.append((s, e))
        pending = rest
    alias: dict[sp.Basic, sp.Basic] = {}  # a line that only renames another is no line
    for s, e in ordered:
        if e.is_Symbol:
            alias[s] = alias.get(e, e)
    ordered = [(s, e.xreplace(alias)) for s, e in ordered if s not in alias]
    outputs = [e.xreplace(alias) for e in outputs]
    names = (f"w{j}" for j in range(10**6))
    final = {
        s: sp.Symbol(name, **_REAL)
        for (s, _), name in zip(ordered, (n for n in names if n not in taken))
    }
    body = [Assign(s.name, t) for s, t in trig]
    body += [Assign(final[s].name, _common_factor(_numbers(e.xreplace(final)))) for s, e in ordered]
    return body, [_common_factor(_numbers(e.xreplace(final))) for e in outputs]


def _common_factor(e: sp.Expr) -> sp.Expr:
    """Terms of a sum with the same number (up to sign) as one product: ``k·x − k·y`` is
    ``k·(x − y)``, one multiplication instead of two (left unevaluated, as printed).

    >>> x, y, z = sp.symbols("x y z", real=True)
    >>> _common_factor(0.4318 * x - 0.4318 * y + 2.0 * z + x * y)
    x*y + 2.0*z + 0.4318*(x - y)
    """
    if not e.is_Add:
        return e
    groups: dict[sp.Expr, list[sp.Expr]] = {}
    for t in e.args:
        k, rest = t.as_coeff_Mul()
        groups.setdefault(abs(k), []).append(sp.sign(k) * rest)
    terms = []
    for k, parts in groups.items():
        if len(parts) < 2 or k == 1:
            terms += [k * p for p in parts]
        else:
            terms.append(sp.Mul(k, sp.Add(*parts), evaluate=False))
    return sp.Add(*terms, evaluate=False) if len(terms) > 1 else terms[0]


def rne_program(
    robot: KinematicChain,
    *,
    symbolic_lengths: bool = False,
    values: Mapping[object, object] | None = None,
) -> RNEProgram:
    """Inverse dynamics τ = rne(q, q̇, q̈) as ``robot.rne`` computes it: the exact
    recursive Newton–Euler recursion of :mod:`dhsym.dynamics.recursive_newton_euler`,
    arranged for few operations (:func:`_rne_recursion`), on the table's numbers (and
    ``values``), plus motor inertia ``Jm G² q̈`` and friction ``B G² q̇ + |G| Tc`` when
    given. Every inertial parameter must be a number. The PUMA 560's comes to 210
    multiplications and 188 additions (``sympy.count_ops``; and 10 squares).

    >>> import dhsym
    >>> from dhsym.model.tablefile import read_table_text
    >>> arm = dhsym.Robot(read_table_text('''
    ... gravity: [0, -9.81, 0]
    ... joints:
    ...   - {type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}
    ... '''))
    >>> prog = rne_program(arm)
    >>> [(a.name, str(a.expr)) for a in prog.body]
    [('c1', 'cos(q1)')]
    >>> [str(o.expr) for o in prog.outputs]  # m g lc cos q1 + (Izz + m lc²) q̈1
    ['9.81*c1 + 0.6*qdd1']
    >>> rne_program(dhsym.load("planar2r"))
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: Planar 2R: the dynamics export needs numeric inertial parameters; ...
    """
    from dhsym.dynamics.compiled_dynamics import numeric_model
    from dhsym.kinematics.numeric import to_float

    name = robot.name or "this robot"
    if symbolic_lengths:
        raise DHError(
            f"{name}: the dynamics export bakes in the numbers; export it without "
            "--symbolic-lengths (fk, jacobian and ik can take the lengths as parameters)"
        )
    dm = numeric_model(robot, values)
    n = dm.n
    qs = [sp.Symbol(f"q{k}", **_REAL) for k in range(1, n + 1)]
    vs = [sp.Symbol(f"qd{k}", **_REAL) for k in range(1, n + 1)]
    accs = [sp.Symbol(f"qdd{k}", **_REAL) for k in range(1, n + 1)]
    rename = dict(zip((*dm.variables, *dm.rates, *dm.accelerations), (*qs, *vs, *accs)))
    # the recursion with every entry of every step named as it is computed, the same
    # value under one name (the outward and inward passes share them)
    numbering = _ValueNumbering()
    tau = _rne_recursion(dm, lambda e: numbering(_pythagoras(e.xreplace(rename))))
    exprs = list(tau)
    links = [dm.links[r - 1] for r in dm.joints]
    friction: bool | None = False  # None: the friction is not numeric
    try:
        for k, L in enumerate(links):
            viscous = to_float(L.B * L.G**2)
            up, down = to_float(abs(L.G) * L.Tc[0]), to_float(abs(L.G) * L.Tc[1])
            if viscous:
                exprs[k] += sp.Float(viscous, 17) * vs[k]
            if up or down:
                exprs[k] += Coulomb(vs[k], sp.Float(up, 17), sp.Float(down, 17))
            friction = friction or bool(viscous or up or down)
    except DHError:
        friction = None
    known = set(qs) | set(vs) | set(accs)
    defined = {s.name for s, _ in numbering.lines}
    every = [*exprs, *(e for _, e in numbering.lines)]
    free = sorted({s.name for e in every for s in e.free_symbols} - {s.name for s in known})
    free = [f for f in free if f not in defined]
    if friction is None or free:
        missing = ", ".join(free) if free else "friction (B, Tc, G)"
        raise DHError(
            f"{name}: the dynamics export needs numeric inertial parameters; no number "
            f"for {missing}: give m, r, I (and Jm, G, B, Tc) in the table file"
        )
    taken = {s.name for s in known}
    index = {s: k for k, s in enumerate(qs, start=1)}
    body, reduced = _shared_lines(numbering.lines, exprs, index, taken)
    inputs = tuple(
        (s.name, arr, k)
        for arr, syms in (("q", qs), ("qd", vs), ("qdd", accs))
        for k, s in enumerate(syms)
    )
    scaled = [f"q{k} at {r}" for k, r in enumerate(dm.cell_rates, start=1) if r != 1]
    rated = [
        "A joint whose variable enters its cell at a rate k other than 1 (" + ", ".join(scaled),
        "in this table) turns at k qd and its torque is k times the moment about its axis.",
    ]
    extra = [
        *(rated if scaled else ()),
        "Then the motor inertia Jm G^2 qdd" + ("" if friction else "."),
    ]
    if friction:
        extra.append("and the friction B G^2 qd + |G| Tc (Tc+ when qd > 0, Tc- when qd < 0).")
    passes = (*_PASSES, *extra)
    outputs = tuple(Output(k, 0, e) for k, e in enumerate(reduced))
    return RNEProgram(tuple(s.name for s in qs), inputs, tuple(body), outputs, passes, friction, n)
