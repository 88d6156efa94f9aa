"""C99 (``math.h`` only): ``<prefix>.h`` and ``<prefix>.c``, row-major arrays.

::

    void <prefix>_fk(const double q[N], double T[16]);
    void <prefix>_jacobian(const double q[N], double J[6*N]);
    int  <prefix>_ik(const double T[16], double tol, double q[][N], double residual[]);
    /* count; every branch within tol (<= 0: dhsym's rule for poses as they come), a branch
       near a pose that is not exact refined on fk and jacobian first, as robot.ik */

With symbolic lengths each function takes ``const double p[<PREFIX>_NPARAMS]`` last.

Sines, cosines and ``atan2`` are the file's own (``dh_sincos_n``, ``dh_sincos``,
``dh_atan2``: ``templates/export/c_math.j2``, within 2 ulp of libm's, libm itself outside
their range): the fk takes every angle in one call, which gcc -O2 vectorises; the IK
takes those of one level that are known together in one call (:func:`sincos_pairs`), and
where an angle is a sum of ``atan2`` terms (and of angles whose sine and cosine are known),
its sine and cosine come from the ``atan2`` arguments (``y / r``, ``x / r``: the file's
``dh_direction``) and the angle-sum formulas instead (:func:`ik_trig`): no ``atan2`` then
``sin`` and ``cos`` in a row, the longest chain of an analytic IK.

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x", real=True)
>>> CPrinter().doprint(sp.atan2(x, sp.Symbol("y")) + x**2)
'pow(x, 2) + dh_atan2(x, y)'
>>> CPrinter().doprint(sp.atan2(0, x))
'(x != x ? x : (signbit(x) ? 3.141592653589793 : 0.0))'
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import sympy as sp
from sympy.printing.c import C99CodePrinter

from .languages import Language
from .program import Assign

__all__ = [
    "LANGUAGE",
    "CPrinter",
    "Direction",
    "NativePrinter",
    "SinCos",
    "SinCosGroup",
    "TrigPrinting",
    "ik_trig",
    "sincos_pairs",
    "within_turn",
]


@dataclass(frozen=True)
class SinCos:
    """``sin`` and ``cos`` of one angle, named ``sin`` and ``cos`` in the generated code."""

    sin: str
    cos: str
    angle: sp.Expr
    level: int


@dataclass(frozen=True)
class SinCosGroup:
    """Pairs of one level taken together: one call of the file's ``dh_sincos_n`` (two
    angles at a time with SSE2), or of ``dh_sincos`` for one."""

    pairs: tuple[SinCos, ...]
    level: int

    @property
    def size(self) -> int:
        """The length of the call's arrays: the pairs, made even (the last angle again)."""
        return len(self.pairs) + len(self.pairs) % 2


def sincos_pairs(body: Sequence[Assign]) -> list[Assign | SinCosGroup]:
    """``body`` with each ``s = sin(x)``, ``c = cos(x)`` of one angle (at one level, no
    singular value) as one :class:`SinCos`, in the earliest group of its level that comes
    after what its angle reads (a group stands where its first pair stood).

    >>> import sympy as sp
    >>> from dhsym.export.program import Assign
    >>> q1, q2 = sp.symbols("q1 q2", real=True)
    >>> body = [Assign("c1", sp.cos(q1)), Assign("c12", sp.cos(q1 + q2)),
    ...         Assign("s1", sp.sin(q1)), Assign("w0", 2 * q1), Assign("s12", sp.sin(q1 + q2)),
    ...         Assign("q3", q1 - q2), Assign("c3", sp.cos(sp.Symbol("q3", real=True))),
    ...         Assign("s3", sp.sin(sp.Symbol("q3", real=True)))]
    >>> [[(p.sin, p.cos) for p in a.pairs] if isinstance(a, SinCosGroup) else a.name
    ...  for a in sincos_pairs(body)]
    [[('s1', 'c1'), ('s12', 'c12')], 'w0', 'q3', [('s3', 'c3')]]
    """
    trig: dict[tuple[type, sp.Expr, int], Assign] = {}
    for a in body:
        if isinstance(a.expr, (sp.sin, sp.cos)) and a.alt is None:
            trig.setdefault((type(a.expr), a.expr.args[0], a.level), a)
    out: list[Assign | list[SinCos]] = []
    where: dict[str, int] = {}  # a name's place in out
    done: set[str] = set()
    for a in body:
        if a.name in done:
            continue
        if isinstance(a.expr, (sp.sin, sp.cos)) and a.alt is None:
            x = a.expr.args[0]
            s, c = trig.get((sp.sin, x, a.level)), trig.get((sp.cos, x, a.level))
            if s is not None and c is not None:
                pair = SinCos(s.name, c.name, x, a.level)
                done |= {s.name, c.name}
                after = max((where.get(v.name, -1) for v in x.free_symbols), default=-1)
                group = next(
                    (
                        k
                        for k in range(after + 1, len(out))
                        if isinstance(g := out[k], list) and g[0].level == a.level
                    ),
                    None,
                )
                if group is None:
                    group = len(out)
                    out.append([])
                members = out[group]
                assert isinstance(members, list)
                members.append(pair)
                where[s.name] = where[c.name] = group
                continue
        where[a.name] = len(out)
        out.append(a)
    return [SinCosGroup(tuple(g), g[0].level) if isinstance(g, list) else g for g in out]


@dataclass(frozen=True)
class Direction:
    """``sin`` and ``cos`` of ``angle = atan2(y, x)`` as ``y / r`` and ``x / r``,
    ``r = sqrt(x² + y²)`` (the file's ``dh_direction``; the angle's own ``dh_sincos``
    when ``r`` is 0 or not finite)."""

    sin: str
    cos: str
    y: sp.Expr
    x: sp.Expr
    angle: sp.Expr
    level: int
    joint: str = ""  # the joint whose atan2 term it is


_Pair = tuple[sp.Expr, sp.Expr]  # (sin, cos) of an angle, as names or numbers


def ik_trig(body: Sequence[Assign]) -> list[Assign | SinCosGroup | Direction]:
    """:func:`sincos_pairs` of an IK ``body``, the sines and cosines of angles that are
    sums of ``atan2`` terms taken from the terms' arguments: a joint ``q = ±atan2(y1, x1)
    ± atan2(y2, x2) + k`` (no singular value) gets its terms named (``q_a``, ``q_b``; a
    single term is ``q`` itself) with their arguments (``q_ay``, ``q_ax``), each term's
    sine and cosine a :class:`Direction`, and the pair of ``q`` by the angle-sum formulas
    (``sin(a ± b) = sa cb ± ca sb``, ``cos(a ± b) = ca cb ∓ sa sb``, ``k``'s sine and
    cosine as numbers); a pair of a sum of such joints (``q2 + q3``) from those already
    known. Mathematically the same values; in floating point within a few ulp of the
    sine and cosine of the summed angle (the ``atan2`` and the sum rounded away), and
    ``atan2``, ``sin``, ``cos`` no longer one after the other. Pairs that decide a
    branch (a square root's radicand or a singular guard reads them, see
    :func:`_decisions`) stay the angle's own, and so does a group whose call would be as
    long without the pairs derived (``dh_sincos_n`` takes two angles at a time). The rest
    stays as :func:`sincos_pairs` has it.

    >>> import sympy as sp
    >>> from dhsym.export.program import Assign
    >>> x, y, k = sp.symbols("x y k", real=True)
    >>> q1, q2 = sp.symbols("q1 q2", real=True)
    >>> body = [Assign("q1", sp.atan2(y, x) - sp.atan2(k, 2 * x), 1),
    ...         Assign("s1", sp.sin(q1), 1), Assign("c1", sp.cos(q1), 1),
    ...         Assign("q2", sp.atan2(2 * y, x), 1),
    ...         Assign("s12", sp.sin(q1 + q2), 1), Assign("c12", sp.cos(q1 + q2), 1)]
    >>> for a in ik_trig(body):
    ...     if isinstance(a, Direction):
    ...         print(f"{a.sin}, {a.cos} of atan2({a.y}, {a.x})")
    ...     else:
    ...         print(f"{a.name} = {a.expr}")
    q1_ax = 2*x
    q1_a = atan2(k, q1_ax)
    q1_b = atan2(y, x)
    q1 = -q1_a + q1_b
    sq1_a, cq1_a of atan2(k, q1_ax)
    sq1_b, cq1_b of atan2(y, x)
    s1 = cq1_a*sq1_b - cq1_b*sq1_a
    c1 = cq1_a*cq1_b + sq1_a*sq1_b
    q2_y = 2*y
    q2 = atan2(q2_y, x)
    sq2, cq2 of atan2(q2_y, x)
    s12 = c1*sq2 + cq2*s1
    c12 = c1*cq2 - s1*sq2
    """
    decides = _decisions(body)
    candidates = {
        v.name
        for a in body
        if isinstance(a.expr, (sp.sin, sp.cos)) and a.alt is None and a.name not in decides
        for v in a.expr.args[0].free_symbols
    }
    used = _ik_trig(body, decides, candidates)[1]  # the joints whose terms are read
    return _ik_trig(body, decides, used)[0]


def _ik_trig(
    body: Sequence[Assign], decides: set[str], wanted: set[str]
) -> tuple[list[Assign | SinCosGroup | Direction], set[str]]:
    """:func:`ik_trig` with the joints in ``wanted`` split into their atan2 terms; and
    the joints whose terms the derived pairs read."""
    used: set[str] = set()
    taken = {a.name for a in body} | {
        s.name for a in body for e in a.expressions() for s in e.free_symbols
    }

    def fresh(name: str) -> str:
        while name in taken:
            name += "_"
        taken.add(name)
        return name

    # a joint's atan2 terms: (sign, angle, y, x); its constant part
    terms: dict[sp.Symbol, tuple[list[tuple[int, sp.Expr, sp.Expr, sp.Expr]], sp.Expr]] = {}
    known: dict[sp.Expr, _Pair] = {}
    out: list[Assign | SinCosGroup | Direction] = []

    def split(a: Assign) -> list[Assign] | None:
        """``a`` with its atan2 terms and their arguments named, or ``None``."""
        if a.alt is not None or not a.expr.has(sp.atan2) or a.name not in wanted:
            return None
        parts, const = [], sp.Integer(0)
        for t in sp.Add.make_args(a.expr):
            if t.is_number:
                const += t
                continue
            sign, f = (-1, -t) if t.could_extract_minus_sign() else (1, t)
            if not isinstance(f, sp.atan2):
                return None
            parts.append((sign, f))
        single = len(parts) == 1 and parts[0][0] == 1 and const == 0
        made: list[Assign] = []
        found = []
        for k, (sign, f) in enumerate(parts):
            tag = "" if single else "abcdefgh"[k]
            args = []
            for arg, end in zip(f.args, "yx"):
                if arg.is_Atom or (-arg).is_Atom:
                    args.append(arg)
                else:
                    name = fresh(f"{a.name}_{tag}{end}")
                    made.append(Assign(name, arg, a.level))
                    args.append(sp.Symbol(name, real=True))
            angle = sp.atan2(*args)
            if not single:
                name = fresh(f"{a.name}_{tag}")
                made.append(Assign(name, angle, a.level))
                angle = sp.Symbol(name, real=True)
            found.append((sign, angle, args[0], args[1]))
        whole = sp.Add(*(s * t[1] for s, t in zip((p[0] for p in found), found)), const)
        if single:
            whole = found[0][1]
            found = [(1, sp.Symbol(a.name, real=True), found[0][2], found[0][3])]
        made.append(Assign(a.name, whole, a.level))
        made[0] = replace(made[0], comment=a.comment)  # the step's sentence first
        terms[sp.Symbol(a.name, real=True)] = (found, const)
        return made

    def combine(p: _Pair, r: _Pair, sign: int) -> _Pair:
        (sa, ca), (sb, cb) = p, r
        return (sa * cb + sign * ca * sb, ca * cb - sign * sa * sb)

    def number(k: sp.Expr) -> _Pair:
        return (sp.Float(sp.sin(k).evalf(30), 17), sp.Float(sp.cos(k).evalf(30), 17))

    def joint(v: sp.Symbol, level: int, made: list[Assign | Direction]) -> _Pair | None:
        """The pair of a joint of atan2 terms, its directions appended to ``made``."""
        if v not in terms:
            return None
        found, const = terms[v]
        pair: _Pair | None = None
        for sign, angle, y, x in found:
            tag = angle.name if isinstance(angle, sp.Symbol) else v.name
            d = Direction(fresh(f"s{tag}"), fresh(f"c{tag}"), y, x, angle, level, v.name)
            made.append(d)
            here: _Pair = (sp.Symbol(d.sin, real=True), sp.Symbol(d.cos, real=True))
            if pair is None:
                pair = here if sign == 1 else (-here[0], here[1])
            else:
                pair = combine(pair, here, sign)
        assert pair is not None
        return combine(pair, number(-const), -1) if const != 0 else pair

    def derive(angle: sp.Expr, level: int, made: list[Assign | Direction]) -> _Pair | None:
        """The pair of ``angle`` from known pairs and joints of atan2 terms, or ``None``."""
        if angle in known:
            return known[angle]
        if isinstance(angle, sp.Symbol):
            return joint(angle, level, made)
        if angle.is_number:
            return number(angle)
        rest = [(b, angle - b) for b in known if len(sp.Add.make_args(angle - b)) == 1]
        for b, r in rest + [(angle - t, t) for t in reversed(sp.Add.make_args(angle))]:
            sign, f = (-1, -r) if r.could_extract_minus_sign() else (1, r)
            if not (isinstance(f, sp.Symbol) or f.is_number):
                continue
            first = derive(b, level, made)
            if first is None:
                return None
            second = derive(f, level, made)
            if second is None:
                return None
            return combine(first, second, sign)
        return None

    for a in sincos_pairs(body):
        if isinstance(a, Assign):
            out.extend(split(a) or [a])
            continue
        rest: list[SinCos] = []
        made: list[Assign | Direction] = []
        reads: set[str] = set()
        for p in sorted(a.pairs, key=lambda p: len(sp.Add.make_args(p.angle))):
            trial: list[Assign | Direction] = []
            decided = p.sin in decides or p.cos in decides
            pair = None if decided else derive(p.angle, a.level, trial)
            names = (sp.Symbol(p.sin, real=True), sp.Symbol(p.cos, real=True))
            if pair is None:
                rest.append(p)
            else:
                reads.update(x.joint for x in trial if isinstance(x, Direction))
                last = trial[-1] if trial else None
                if isinstance(last, Direction) and pair == (
                    sp.Symbol(last.sin, real=True),
                    sp.Symbol(last.cos, real=True),
                ):  # one atan2: its direction under the pair's own names
                    made.extend([*trial[:-1], replace(last, sin=p.sin, cos=p.cos)])
                else:
                    made.extend([*trial, Assign(p.sin, pair[0], a.level)])
                    made.append(Assign(p.cos, pair[1], a.level))
            known[p.angle] = names
        if rest and SinCosGroup(tuple(rest), a.level).size == a.size:
            out.append(a)  # the call would take as long (two angles at a time): kept whole
            continue
        used |= reads
        if rest:
            out.append(SinCosGroup(tuple(rest), a.level))
        out.extend(made)
    return out, used


def within_turn(body: Sequence[Assign]) -> set[str]:
    """The names whose value is an ``atan2`` (and a number in ``[-π, π]`` at a singular
    wrist): in ``[-π, π]`` already, so that the IK keeps them as they are (``wrap`` would
    return them unchanged).

    >>> import sympy as sp
    >>> from dhsym.export.program import Assign
    >>> x, y = sp.symbols("x y", real=True)
    >>> sorted(within_turn([Assign("q1", sp.atan2(y, x)), Assign("q2", sp.atan2(y, x) + 1),
    ...                     Assign("q3", sp.atan2(y, x), 1, (), ("s_5", 1e-12, sp.Float(0)))]))
    ['q1', 'q3']
    """

    def inside(e: sp.Expr) -> bool:
        return isinstance(e, sp.atan2) or (e.is_number and abs(float(e)) <= 3.141592653589793)

    return {a.name for a in body if inside(a.expr) and (a.alt is None or inside(a.alt[2]))}


def _decisions(body: Sequence[Assign]) -> set[str]:
    """The names whose values decide something beyond rounding: what a square root's
    radicand (its sign: a branch or none) or a singular value's guard reads, directly or
    through other names. Their sines and cosines stay those of the angle (as every other
    language computes them), so that a pose on a singularity (a radicand exactly 0, as at
    a lecture's home pose) keeps its branches bit for bit."""
    from dhsym.ik.rewriting import SafeSqrt

    defs = {a.name: a for a in body}
    out: set[str] = set()
    todo = [
        s.name
        for a in body
        for e in a.expressions()
        for f in e.atoms(SafeSqrt)
        for s in f.free_symbols
    ] + [a.alt[0] for a in body if a.alt is not None]
    while todo:
        name = todo.pop()
        if name in out:
            continue
        out.add(name)
        if name in defs:
            todo.extend(s.name for e in defs[name].expressions() for s in e.free_symbols)
    return out


class TrigPrinting:
    """The printing of ``sin``, ``cos`` and ``atan2`` as the functions named ``trig`` +
    ``sin`` (``dh_sin``: the file's own, ``templates/export/c_math.j2``; ``""``: libm's)."""

    trig = "dh_"
    _print: Callable[[object], str]  # the code printer's own (declared for the type checker)

    def _print_sin(self, expr: sp.Expr) -> str:
        return f"{self.trig}sin({self._print(expr.args[0])})"

    def _print_cos(self, expr: sp.Expr) -> str:
        return f"{self.trig}cos({self._print(expr.args[0])})"

    def _print_atan2(self, expr: sp.Expr) -> str:
        y, x = (self._print(a) for a in expr.args)
        return f"{self.trig}atan2({y}, {x})"


class CPrinter(TrigPrinting, C99CodePrinter):
    """sympy's C99 printer, with the solver's ``SafeSqrt`` as a helper of the file (its
    ``stretch``: a local of the IK function, set for a pose that is not exact) and the
    file's own ``dh_sin``, ``dh_cos``, ``dh_atan2``."""

    def _print_atan2(self, expr: sp.Expr) -> str:
        """``atan2(0, x)`` of a name ``x`` as the half turn it is (``dh_atan2``'s and
        libm's very value: 0 for ``x`` > 0 or +0, π for ``x`` < 0 or -0, NaN for NaN);
        any other ``atan2`` as :class:`TrigPrinting` prints it."""
        y, x = expr.args
        if self.trig == "dh_" and y.is_zero and isinstance(x, sp.Symbol):
            v = self._print(x)
            return f"({v} != {v} ? {v} : (signbit({v}) ? 3.141592653589793 : 0.0))"
        return super()._print_atan2(expr)

    def _print_SafeSqrt(self, expr: sp.Expr) -> str:
        return f"safe_sqrt({self._print(expr.args[0])}, stretch)"

    def _print_Coulomb(self, expr: sp.Expr) -> str:
        v, up, down = (self._print(a) for a in expr.args)
        return f"({v} > 0.0 ? {up} : ({v} < 0.0 ? {down} : 0.0))"

    def _print_Clamp(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"fmin(fmax({t}, 0.0), {tf})"

    def _print_Inside(self, expr: sp.Expr) -> str:
        t, tf = (self._print(a) for a in expr.args)
        return f"({t} >= 0.0 && {t} <= {tf} ? 1.0 : 0.0)"

    def _print_Pick(self, expr: sp.Expr) -> str:
        c, a, b = (self._print(x) for x in expr.args)
        return f"({c} ? {a} : {b})"


class NativePrinter(CPrinter):
    """The C printer of the solver's program for one pose
    (:func:`dhsym.export.shared_library.native_source`) and of the numeric dynamics' rows
    (libm's ``sin``, ``cos``, ``atan2``, as NumPy evaluates them): ``SafeSqrt`` with the
    function's ``stretch`` (as :class:`CPrinter`), ``remainder`` of C99, and a
    ``Residual`` as nested ``nan_max`` of its magnitudes (NaN when any difference is).

    >>> import sympy as sp
    >>> from dhsym.ik.rewriting import Residual
    >>> x, y = sp.symbols("x y", real=True)
    >>> NativePrinter().doprint(Residual(x, y - 1))
    'nan_max(fabs(x), fabs(y - 1))'
    """

    trig = ""

    def _print_remainder(self, expr: sp.Expr) -> str:
        x, y = (self._print(a) for a in expr.args)
        return f"remainder({x}, {y})"

    _print_Remainder = _print_remainder

    def _print_Residual(self, expr: sp.Expr) -> str:
        out = f"fabs({self._print(expr.args[0])})"
        for a in expr.args[1:]:
            out = f"nan_max({out}, fabs({self._print(a)}))"
        return out


LANGUAGE = Language(
    name="c",
    printer=CPrinter,
    files=(("c_header.h.j2", "{prefix}.h", None), ("c_source.c.j2", "{prefix}.c", None)),
    comment=" *",
    note="gcc -std=c99 -O2 -c {prefix}.c (link with -lm)",
    extra={"sincos_pairs": sincos_pairs, "ik_trig": ik_trig, "within_turn": within_turn},
)
