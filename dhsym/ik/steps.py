r"""The pieces every closed-form derivation is made of: steps, branches, and the solver of
equations one unknown at a time.

A derivation (one module per family of arms in :mod:`dhsym.ik`) is a list of
:class:`Step` (``symbol = exact expression``, with the sentence that explains it) and of
:class:`Branch` (a sign ``σ = ±1`` chosen by a ``±√``). :class:`Builder` collects them;
:func:`solve_equations` takes equations ``expr = 0`` and solves them one unknown at a
time as the lectures do (Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*,
§5.3): two equations linear in ``cos θ`` and ``sin θ`` give one ``atan2``; one equation
``A cos θ + B sin θ = K`` gives two solutions, ``atan2(B, A) ± atan2(√(A² + B² − K²), K)``;
a prismatic joint comes from a linear or quadratic equation.

Examples
--------
>>> pose_symbols()[:3, 2].T
Matrix([[a_x, a_y, a_z]])
>>> rot_z(sp.pi / 2)
Matrix([
[0, -1, 0],
[1,  0, 0],
[0,  0, 1]])
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, TypeAlias

import sympy as sp

from dhsym.kinematics.decoupling import Decoupling, StructureError
from dhsym.kinematics.jacobian import compact
from dhsym.kinematics.simplification import trig_coefficients
from dhsym.model.parsing import REAL
from dhsym.model.table import JointType
from dhsym.notation.layout import Sentence, sentence

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "BRANCH_NAMES",
    "REAL",
    "ROOT_WORDS",
    "Branch",
    "Builder",
    "Equation",
    "Step",
    "branch_word",
    "capital",
    "pose_symbols",
    "rot_x",
    "root_words",
    "rot_z",
    "solve_equations",
    "solve_joint_from_entry",
    "step_latex",
    "step_text",
    "undo_prefix",
]

Matrix: TypeAlias = sp.ImmutableMatrix

#: The one list of branch names, by the role of the branch: (first, second). For
#: ``"arm"``, ``"wrist"`` and ``"shoulder"`` the first is the sign +1; for ``"elbow"`` the
#: first is the elbow above the shoulder-to-wrist line (found from the geometry, not from
#: the sign). ``"shoulder"`` is the flip of three axes that meet at the base (the chain read
#: backwards: its wrist is the arm's shoulder).
BRANCH_NAMES: Mapping[str, tuple[str, str]] = MappingProxyType(
    {
        "arm": ("right arm", "left arm"),
        "elbow": ("elbow up", "elbow down"),
        "wrist": ("wrist not flipped", "wrist flipped"),
        "shoulder": ("shoulder not flipped", "shoulder flipped"),
    }
)

#: A branch with no geometric name of its own (the sign of a ``±√`` that solves one
#: joint's equation) is named by its root: the sign +1 is the first root, −1 the second.
ROOT_WORDS = ("first root of the", "second root of the")


def root_words(first: bool) -> tuple[str, str]:
    """The words around the variable in the name of a branch without a geometric name:
    ``("first root of the", "equation")`` (the derivations typeset the variable between).

    >>> root_words(False)
    ('second root of the', 'equation')
    """
    return ROOT_WORDS[0 if first else 1], "equation"


def branch_word(role: str, first: bool, variable: object = "") -> str:
    """The name of one branch: derivations, IK results, feedback and notebooks all use it.

    ``first`` is the sign +1 for the arm, the wrist and the shoulder, the elbow up for the
    elbow; a branch of another role (the sign of a square root) is named by its root and
    the equation of its variable (the sign itself stays in ``IKSolution.signs``).

    >>> branch_word("elbow", True), branch_word("arm", False)
    ('elbow up', 'left arm')
    >>> branch_word("reach", True, "d3"), branch_word("sign", False, "theta4")
    ('first root of the d3 equation', 'second root of the θ4 equation')
    """
    if role in BRANCH_NAMES:
        return BRANCH_NAMES[role][0 if first else 1]
    before, after = root_words(first)
    return " ".join(w for w in (before, _plain_name(str(variable)), after) if w)


def _plain_name(name: str) -> str:
    """A variable's name as a student reads it: ``theta4`` as ``θ4``, ``d3`` as it is."""
    letters = name.rstrip("0123456789")
    greek = sp.pretty(sp.Symbol(letters), use_unicode=True) if letters else ""
    return (greek if len(greek) == 1 else letters) + name[len(letters) :]


def pose_symbols() -> Matrix:
    """The symbolic pose ``[n s a p; 0 0 0 1]`` (normal, sliding, approach, position).

    >>> pose_symbols()[:3, 3].T
    Matrix([[p_x, p_y, p_z]])
    """
    cols = []
    for v in "nsap":
        cols.append([sp.Symbol(f"{v}_{c}", **REAL) for c in "xyz"])
    M = sp.Matrix(3, 4, lambda i, j: cols[j][i])
    return Matrix(M.col_join(sp.Matrix([[0, 0, 0, 1]])))


# --- plain data ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Branch:
    """A choice of sign ``symbol = ±1`` made by one step.

    ``role`` is ``"arm"`` (left/right), ``"elbow"`` (up/down), ``"reach"`` (the sign of
    a prismatic ``±√``) or ``"wrist"`` (flip); ``joint`` is the joint it decides;
    ``sentence`` says what each sign means (a :class:`~dhsym.notation.layout.Sentence`).
    """

    symbol: sp.Symbol
    role: str
    joint: int
    sentence: Sentence

    @property
    def text(self) -> str:
        """The sentence in plain text."""
        return self.sentence.text()


@dataclass(frozen=True)
class Step:
    """One line of the derivation: ``lhs = rhs``, exact, with the sentence that explains it.

    ``part`` is ``"wrist centre"``, ``"position"`` or ``"orientation"``; ``sentence``
    the words with their math (a :class:`~dhsym.notation.layout.Sentence`, printed by
    each format); ``equation`` is the equation this step solves (when it solves one);
    ``branch`` the sign it introduces; ``singular`` the value used instead when the
    wrist is singular (``sin θ5 = 0``: only ``θ4 + θ6`` is determined, so ``θ4`` is set
    to 0).
    """

    part: str
    sentence: Sentence
    lhs: sp.Symbol
    rhs: sp.Expr
    equation: sp.Eq | None = None
    branch: Branch | None = None
    singular: sp.Expr | None = None

    @property
    def text(self) -> str:
        """The sentence in plain text."""
        return self.sentence.text()


# --- equations of the position sub-problem ------------------------------------------------


def _reduce(expr: sp.Expr, revolute: Sequence[sp.Symbol]) -> sp.Expr:
    """Expand into sines and cosines of single joint angles; ``sin² = 1 − cos²``."""
    e = sp.expand(sp.expand_trig(expr))
    for x in revolute:
        s, c = sp.sin(x), sp.cos(x)

        def is_power(t: sp.Expr, s: sp.Expr = s) -> bool:
            return bool(t.is_Pow and t.base == s and t.exp.is_Integer and t.exp >= 2)

        def lower(t: sp.Pow, s: sp.Expr = s, c: sp.Expr = c) -> sp.Expr:
            k = int(t.exp)
            return (1 - c**2) ** (k // 2) * s ** (k % 2)

        e = sp.expand(e.replace(is_power, lower))
    return e


def _poly_coefficients(e: sp.Expr, d: sp.Symbol) -> list[sp.Expr] | None:
    """Coefficients (highest first) of ``e`` as a polynomial of degree ≤ 2 in ``d``."""
    poly = sp.Poly(e, d)
    if poly.degree() > 2 or poly.degree() < 1:
        return None
    coeffs: list[sp.Expr] = poly.all_coeffs()
    if any(d in c.free_symbols for c in coeffs):
        return None
    return coeffs


@dataclass(frozen=True)
class Equation:
    """One equation ``expr = 0`` of a sub-problem, as shown (``shown``) and named (``name``).

    ``role`` names the branch a ``±√`` solving it opens (``"elbow"``: the law of
    cosines; ``"arm"``: the shoulder, left or right; ``"wrist"``: the flip).
    """

    expr: sp.Expr  # = 0
    shown: sp.Eq
    name: str
    role: str = "elbow"


# --- the derivation --------------------------------------------------------------------------


#: what the two signs of a ``±√`` mean, by the role of the branch, in the words of
#: :data:`BRANCH_NAMES` (the names the IK results and the feedback use)
_BRANCH_WORDS = {
    role: f"{{plus}} and {{minus}}: the two {part} configurations ({first} and {second})"
    for role, part in (("elbow", "elbow"), ("arm", "shoulder"), ("wrist", "wrist"))
    for first, second in (BRANCH_NAMES[role],)
}


class Builder:
    """Collects steps and branches while the structure is solved."""

    def __init__(self, robot: KinematicChain, dec: Decoupling) -> None:
        self.robot = robot
        self.dec = dec
        self.steps: list[Step] = []
        self.branches: list[Branch] = []
        rows = robot.table.rows
        self.variables = robot.variables
        self.number = {v: i for i, v in enumerate(self.variables, start=1)}
        self.revolute = [r.variable for r in rows if r.joint is JointType.REVOLUTE]
        self.kind = {r.variable: r.joint for r in rows if r.variable is not None}
        #: the part of the derivation that :func:`solve_equations` writes its steps in
        self.part = "position"

    def add(
        self, part: str, text: Sentence | str, lhs: sp.Symbol, rhs: sp.Expr, **kw: Any
    ) -> sp.Symbol:  # kw: the optional fields of Step
        words = text if isinstance(text, Sentence) else Sentence(text)
        self.steps.append(Step(part, words, lhs, rhs, **kw))
        return lhs

    def branch(self, role: str, var: sp.Symbol, template: str, **math: object) -> Branch:
        """A new sign σ_j; ``template`` may use ``{s}`` (σ_j), ``{plus}``, ``{minus}``."""
        j = self.number[var]
        sigma = sp.Symbol(f"sigma_{j}", **REAL)
        words = sentence(template, s=sigma, plus=sp.Eq(sigma, 1), minus=sp.Eq(sigma, -1), **math)
        b = Branch(sigma, role, j, words)
        self.branches.append(b)
        return b

    def tidy(self, e: sp.Expr) -> sp.Expr:
        return compact(sp.factor_terms(e))


def undo_prefix(b: Builder, part: str, text: str, point: Matrix, prefix: sp.Matrix) -> Matrix:
    """``point`` in the frame before joint 1: the constant transform ``prefix`` that precedes
    joint 1 undone, ``u = Rᵀ (point − t)``, as three steps ``u_x, u_y, u_z`` of ``part``
    explained by ``text`` (``point`` itself when there is no such transform).
    """
    if prefix == sp.eye(4):
        return point
    local = (prefix[:3, :3].T * (point - prefix[:3, 3])).applyfunc(sp.expand)
    names = [sp.Symbol(f"u_{c}", **REAL) for c in "xyz"]
    for name, value in zip(names, local):
        b.add(part, text, name, value)
    return Matrix(names)


def step_text(robot: KinematicChain, step: Step) -> str:
    """``lhs = rhs`` of one step in plain text, in the robot's notation."""
    nota = robot.notation
    return f"{nota.text(step.lhs)} = {nota.text(step.rhs)}"


def step_latex(robot: KinematicChain, step: Step) -> str:
    """``lhs = rhs`` of one step in LaTeX, in the robot's notation."""
    nota = robot.notation
    return f"{nota.latex(step.lhs)} = {nota.latex(step.rhs)}"


def capital(words: str) -> str:
    return words[:1].upper() + words[1:]


def solve_joint_from_entry(value: sp.Expr, x: sp.Expr, var: sp.Symbol) -> sp.Expr:
    """``var`` from ``x = value`` where ``x`` is a joint's DH argument ``rate·var + offset``."""
    rate = sp.diff(x, var)
    offset = sp.expand(x - rate * var)
    return (value - offset) / rate


def solve_equations(b: Builder, equations: list[Equation], unknowns: list[sp.Symbol]) -> None:
    """Solve the position equations one unknown at a time (pairs first, then ±√)."""
    pending = list(unknowns)
    used: set[int] = set()
    while pending:
        reduced = [_reduce(eq.expr, b.revolute) for eq in equations]
        single: dict[sp.Symbol, list[int]] = {}
        for i, e in enumerate(reduced):
            if i in used:
                continue
            present = [v for v in pending if v in e.free_symbols]
            if len(present) == 1:
                single.setdefault(present[0], []).append(i)
        done = _try_pair(b, equations, reduced, single) or _try_single(
            b, equations, reduced, single
        )
        if done is not None:
            var, rows = done
            used.update(rows)
            pending.remove(var)
            continue
        names = ", ".join(str(v) for v in pending)
        raise StructureError(
            f"the position sub-problem has no equation in one unknown left ({names} appear "
            "together): no closed form by decoupling — a redundant arm, or joints 2 and 3 "
            "do not move the point in a plane through the axis of joint 1"
        )


_Solved = tuple[sp.Symbol, tuple[int, ...]] | None  # the joint solved and the equations used


def _try_pair(
    b: Builder,
    equations: list[Equation],
    reduced: list[sp.Expr],
    single: dict[sp.Symbol, list[int]],
) -> _Solved:
    """One revolute joint from two equations linear in its cos and sin: a single atan2."""
    for var, idx in single.items():
        if b.kind[var] is not JointType.REVOLUTE or len(idx) < 2:
            continue
        for i, j in itertools.combinations(idx, 2):
            c1, c2 = trig_coefficients(reduced[i], var), trig_coefficients(reduced[j], var)
            if c1 is None or c2 is None:
                continue
            (A1, B1, C1), (A2, B2, C2) = c1, c2
            det = sp.expand(A1 * B2 - A2 * B1)
            if det == 0:
                continue
            R1, R2 = -C1, -C2
            t = b.tidy
            if sp.expand(A2 + B1) == 0 and sp.expand(B2 - A1) == 0:
                value = sp.atan2(t(R2), t(R1)) - sp.atan2(t(A2), t(A1))
            elif sp.expand(A2 - B1) == 0 and sp.expand(B2 + A1) == 0:
                value = sp.atan2(t(-R2), t(R1)) - sp.atan2(t(-A2), t(A1))
            else:
                delta = sp.Symbol(f"Delta_{b.number[var]}", **REAL)
                b.add(
                    b.part,
                    sentence(
                        "The determinant of the two linear equations in {c} and {s}:",
                        c=sp.cos(var),
                        s=sp.sin(var),
                    ),
                    delta,
                    t(det),
                )
                value = sp.atan2(t(A1 * R2 - A2 * R1) / delta, t(R1 * B2 - R2 * B1) / delta)
            text = sentence(
                "With the joints before known, {one} and {two} are linear in {c} and {s}: "
                "one atan2.",
                one=equations[i].name,
                two=equations[j].name,
                c=sp.cos(var),
                s=sp.sin(var),
            )
            b.add(b.part, text, var, value, equation=sp.Eq(_show(A1, B1, var), b.tidy(R1)))
            return var, (i, j)
    return None


def _show(A: sp.Expr, B: sp.Expr, var: sp.Symbol) -> sp.Expr:
    return compact(A) * sp.cos(var) + compact(B) * sp.sin(var)


def _try_single(
    b: Builder,
    equations: list[Equation],
    reduced: list[sp.Expr],
    single: dict[sp.Symbol, list[int]],
) -> _Solved:
    """One joint from one equation: linear prismatic ones first (no branch), then ±√."""
    order = sorted(single.items(), key=lambda kv: b.kind[kv[0]] is JointType.REVOLUTE)
    for two_branch in (False, True):
        for var, idx in order:
            for i in idx:
                if _solve_single(b, equations[i], reduced[i], var, two_branch):
                    return var, (i,)
    return None


def _solve_single(b: Builder, eq: Equation, e: sp.Expr, var: sp.Symbol, two: bool) -> bool:
    j = b.number[var]
    if b.kind[var] is JointType.PRISMATIC:
        coeffs = _poly_coefficients(e, var)
        if coeffs is None:
            return False
        if len(coeffs) == 2 and not two:
            A, C = coeffs
            b.add(
                b.part,
                sentence("{eq} is linear in {v}:", eq=capital(eq.name), v=var),
                var,
                b.tidy(-C / A),
                equation=eq.shown,
            )
            return True
        if len(coeffs) == 3 and two:
            A, B, C = coeffs
            br = b.branch("reach", var, "{s} = ±1: the sign of the square root for {v}", v=var)
            if B == 0:
                value = br.symbol * sp.sqrt(b.tidy(-C / A))
            else:
                value = (-B + br.symbol * sp.sqrt(b.tidy(B**2 - 4 * A * C))) / (2 * A)
            b.add(
                b.part,
                sentence("{eq} is quadratic in {v}:", eq=capital(eq.name), v=var),
                var,
                value,
                equation=eq.shown,
                branch=br,
            )
            return True
        return False
    if not two:
        return False
    abc = trig_coefficients(e, var)
    if abc is None:
        return False
    A, B, C = abc
    K = -C
    g = sp.gcd(A, B) if A != 0 and B != 0 else (A if B == 0 else B)
    if g != 0 and not (g.free_symbols & set(b.variables)):
        A, B, K = (sp.cancel(v / g) for v in (A, B, K))
    br = b.branch(eq.role, var, _BRANCH_WORDS[eq.role])
    s = br.symbol
    text = (
        "{eq} leaves {v} alone (the law of cosines): {name} with"
        if eq.role == "elbow"
        else "{eq} leaves {v} alone: {name} with"
    )
    if B == 0 or A == 0:
        D = sp.Symbol(f"D_{j}", **REAL)
        trig = sp.cos(var) if B == 0 else sp.sin(var)
        b.add(
            b.part,
            sentence(text, eq=capital(eq.name), v=var, name=sp.Eq(trig, D)),
            D,
            b.tidy(K / (A if B == 0 else B)),
            equation=sp.Eq(_show(A, B, var), b.tidy(K)),
        )
        root = s * sp.sqrt(1 - D**2)
        value = sp.atan2(root, D) if B == 0 else sp.atan2(D, root)
        b.add(b.part, "Two solutions, one for each sign of the root:", var, value, branch=br)
        return True
    Ks = sp.Symbol(f"K_{j}", **REAL)
    b.add(
        b.part,
        sentence(text, eq=capital(eq.name), v=var, name=sp.Eq(_show(A, B, var), Ks)),
        Ks,
        b.tidy(K),
        equation=sp.Eq(_show(A, B, var), b.tidy(K)),
    )
    value = sp.atan2(B, A) + sp.atan2(s * sp.sqrt(A**2 + B**2 - Ks**2), Ks)
    b.add(b.part, "Two solutions, one for each sign of the root:", var, value, branch=br)
    return True


def rot_z(a: sp.Expr) -> sp.Matrix:
    """3×3 rotation about z (exact)."""
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rot_x(a: sp.Expr) -> sp.Matrix:
    """3×3 rotation about x (exact)."""
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
