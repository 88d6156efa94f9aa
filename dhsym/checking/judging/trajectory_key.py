r"""The key of a trajectory or gain question: the profile as the instructor writes it, and
its part prepared once for checking many answers.

The key is a profile written as a call, ``cubic(q0=0, qf=1, tf=2)``, the values read by
the whitelist parser (never ``sympify``): numbers and exact expressions (``pi/2``,
``0.25``), or the names below, which keep the key symbolic (``quintic(q0=q0, qf=qf,
tf=tf)``); a name drawn per student (``variants:``) is the student's number.

=================  ======================================  ================================
profile            parameters (the trajectory room's)      questions
=================  ======================================  ================================
``cubic``          ``q0, qf, tf, v0=0, vf=0``              ``traj a0`` … ``a3``, ``vmax``,
                                                           ``q@<t>``
``quintic``        ``q0, qf, tf, v0=0, vf=0``              ``traj a0`` … ``a5``, ``vmax``,
                                                           ``q@<t>``
``lspb``           ``q0, qf, tf`` and ``V`` or ``a``       ``tb``, ``vmax``, ``q@<t>``
``minimum_time``   ``q0, qf, vmax, amax``                  ``tb``, ``vmax``, ``q@<t>``
``gains``          ``omega, zeta=1``                       ``kp``, ``kd``
=================  ======================================  ================================

Every expected value comes from the rooms that own the mathematics
(:func:`dhsym.trajectory.cubic`, :func:`~dhsym.trajectory.quintic`,
:func:`~dhsym.trajectory.lspb`, :func:`~dhsym.trajectory.minimum_time`,
:func:`dhsym.control.gains`); so do the values under each catalogued mistake
(:mod:`~dhsym.checking.mistakes.trajectory_mistakes`), computed here once per key.

Examples
--------
>>> key = TrajectoryKey.load("cubic(q0=0, qf=1, tf=2)", "traj a2")
>>> part = prepare_trajectory(key).part
>>> part.expected, [(kind, str(value)) for kind, value in part.wrong]
(3/4, [('tf_for_tf_squared', '3/2')])
>>> TrajectoryKey.load("quintic(q0=q0, qf=qf, tf=tf)", "traj a3").name
'quintic(q0=q0, qf=qf, tf=tf)'
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import sympy as sp

from dhsym.control import gains
from dhsym.errors import DHError
from dhsym.model.parsing import normalize_name, parse_expression
from dhsym.trajectory import Profile, cubic, lspb, minimum_time, quintic

from ..comparing.equivalence import POINTS, Sample, values
from ..mistakes.trajectory_mistakes import TRAJECTORY_MISTAKES
from ..reading.answer_names import NameContext
from ..reading.limits import echoed
from ..reading.questions import Question
from .rounding import DEFAULT_ROUNDING, Rounding

__all__ = [
    "PreparedTrajectory",
    "SYMBOLS",
    "TrajectoryKey",
    "TrajectoryPart",
    "Motion",
    "is_profile_spec",
    "prepare_trajectory",
    "spec_names",
    "trajectory_sample",
]

#: the symbols of symbolic keys, by the name an instructor and a student write
SYMBOLS: Mapping[str, sp.Symbol] = {
    "q0": sp.Symbol("q_0", real=True),
    "qf": sp.Symbol("q_f", real=True),
    "tf": sp.Symbol("t_f", positive=True),
    "v0": sp.Symbol("v_0", real=True),
    "vf": sp.Symbol("v_f", real=True),
    "V": sp.Symbol("V", positive=True),
    "a": sp.Symbol("a", positive=True),
    "vmax": sp.Symbol("v_max", positive=True),
    "amax": sp.Symbol("a_max", positive=True),
    "omega": sp.Symbol("omega", positive=True),
    "zeta": sp.Symbol("zeta", positive=True),
}
#: each profile's parameters, required first (the names of :data:`SYMBOLS`)
_PARAMS: Mapping[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "cubic": (("q0", "qf", "tf"), ("v0", "vf")),
    "quintic": (("q0", "qf", "tf"), ("v0", "vf")),
    "lspb": (("q0", "qf", "tf"), ("V", "a")),
    "minimum_time": (("q0", "qf", "vmax", "amax"), ()),
    "gains": (("omega",), ("zeta",)),
}
_KIND_ALIASES = {"trapezoidal": "lspb", "minimumtime": "minimum_time", "mintime": "minimum_time"}
_SPEC = re.compile(r"^\s*(?P<kind>[A-Za-z_]{1,20})\s*\((?P<args>[^()]*(?:\([^()]*\)[^()]*)*)\)\s*$")
_ARG = re.compile(r"^\s*(?P<name>[A-Za-z_][A-Za-z0-9_]{0,20})\s*=\s*(?P<value>.+?)\s*$", re.S)
_MAX_SPEC = 400
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_TRIES, _MIN_POINTS = 8, 16


def _canon(name: str) -> str:
    return normalize_name(name).replace("_", "").lower()


_BY_CANON = {_canon(k): k for k in SYMBOLS}


def is_profile_spec(ref: object) -> bool:
    """True when ``ref`` is written as a profile (``cubic(…)``), not a robot or a table file.

    >>> is_profile_spec("cubic(q0=0, qf=1, tf=2)"), is_profile_spec("puma560")
    (True, False)
    """
    if not isinstance(ref, str) or len(ref) > _MAX_SPEC:
        return False
    m = _SPEC.match(ref)
    return m is not None and _kind(m["kind"]) in _PARAMS


def _kind(name: str) -> str:
    low = name.lower()
    return _KIND_ALIASES.get(low.replace("_", ""), low)


def spec_names(spec: str, ask: str = "") -> set[str]:
    """The names a profile's values and the time of a ``q@<t>`` question use (what a
    variant may draw).

    >>> sorted(spec_names("cubic(q0=0, qf=Q, tf=tf)", "q@T/2"))
    ['Q', 'T', 'tf']
    """
    m = _SPEC.match(spec) if len(spec) <= _MAX_SPEC else None
    if m is None:
        return set()
    texts = [a["value"] for a in map(_ARG.match, m["args"].split(",")) if a is not None]
    texts += [ask.split("@", 1)[1]] if "@" in ask[:_MAX_SPEC] else []
    return {n for t in texts for n in _NAME.findall(t) if n not in ("pi", "sqrt")}


@dataclass(frozen=True)
class Motion:
    """A profile's data: ``kind`` (``cubic``, ``quintic``, ``lspb``, ``minimum_time`` or
    ``gains``) and its parameters, exact (numbers, or the symbols of :data:`SYMBOLS`)."""

    kind: str
    params: tuple[tuple[str, sp.Expr], ...]

    @classmethod
    def parse(cls, spec: str, drawn: Mapping[str, sp.Expr] | None = None) -> Motion:
        """Read ``cubic(q0=0, qf=1, tf=2)``; a name in ``drawn`` is that value.

        >>> Motion.parse("lspb(q0=0, qf=1, tf=2, v=3/4)")
        Motion(kind='lspb', params=(('q0', 0), ('qf', 1), ('tf', 2), ('V', 3/4)))
        >>> Motion.parse("cubic(q0=0, tf=2)")
        Traceback (most recent call last):
        ...
        dhsym.errors.DHError: field key: cubic needs qf (its parameters: q0, qf, tf, v0, vf)
        """
        text = str(spec)
        m = _SPEC.match(text) if len(text) <= _MAX_SPEC else None
        if m is None or _kind(m["kind"]) not in _PARAMS:
            raise DHError(
                f"expected a profile like cubic(q0=0, qf=1, tf=2) ({', '.join(_PARAMS)}), "
                f"got {echoed(spec)}",
                field="key",
            )
        kind = _kind(m["kind"])
        required, optional = _PARAMS[kind]
        known = required + optional
        given: dict[str, sp.Expr] = {}
        args = [a for a in m["args"].split(",") if a.strip()]
        for arg in args:
            a = _ARG.match(arg)
            if a is None:
                raise DHError(
                    f"{kind}: expected name=value, got {echoed(arg.strip())}", field="key"
                )
            name = _BY_CANON.get(_canon(a["name"]), a["name"])
            if kind == "lspb" and name == "v":
                name = "V"
            if name not in known:
                raise DHError(
                    f"{kind} takes no {echoed(a['name'])} (its parameters: {', '.join(known)})",
                    field="key",
                )
            if name in given:
                raise DHError(f"{kind}: {name} is given twice", field="key")
            given[name] = _value(a["value"], name, drawn or {})
        missing = [n for n in required if n not in given]
        if missing:
            raise DHError(
                f"{kind} needs {', '.join(missing)} (its parameters: {', '.join(known)})",
                field="key",
            )
        if kind == "lspb" and "V" in given and "a" in given:
            raise DHError(
                "lspb: give the line's velocity V or the acceleration a, not both", field="key"
            )
        return cls(kind, tuple((n, given[n]) for n in known if n in given))

    @property
    def values(self) -> dict[str, sp.Expr]:
        """The parameters by name."""
        return dict(self.params)

    @property
    def text(self) -> str:
        """``cubic(q0=0, qf=1, tf=2)``, the symbols as the key prints them."""
        plain = {s: sp.Symbol(n) for n, s in SYMBOLS.items()}
        shown = (f"{n}={sp.sstr(v.xreplace(plain))}" for n, v in self.params)
        return f"{self.kind}(" + ", ".join(shown) + ")"

    def profile(self, at_rest: bool = False) -> Profile:
        """The profile of the trajectory room (``at_rest``: its end velocities 0)."""
        v, zero = self.values, sp.Integer(0)
        if self.kind in ("cubic", "quintic"):
            make = cubic if self.kind == "cubic" else quintic
            ends = (zero, zero) if at_rest else (v.get("v0", zero), v.get("vf", zero))
            return make(v["q0"], v["qf"], v["tf"], *ends)
        if self.kind == "lspb":
            return lspb(v["q0"], v["qf"], v["tf"], v=v.get("V"), a=v.get("a"))
        if self.kind == "minimum_time":
            return minimum_time(v["q0"], v["qf"], v["vmax"], v["amax"])
        raise DHError(f"a {self.kind} key has no profile: ask kp or kd")


def _value(text: str, name: str, drawn: Mapping[str, sp.Expr]) -> sp.Expr:
    """One parameter: the whitelist parser, with the trajectory names and the drawn ones."""
    by_name = {normalize_name(k): v for k, v in drawn.items()}

    def resolve(word: str) -> sp.Expr | None:
        if normalize_name(word) in by_name:
            return by_name[normalize_name(word)]
        c = _canon(word)
        return SYMBOLS[_BY_CANON[c]] if c in _BY_CANON else None

    expr = parse_expression(text, resolve=resolve, field=f"key.{name}")
    unknown = expr.free_symbols - set(SYMBOLS.values())
    if unknown:
        shown = ", ".join(sorted(str(s) for s in unknown))
        raise DHError(
            f"{name}: unknown name {shown}: use numbers, the names {', '.join(SYMBOLS)} or a "
            "name drawn in variants:",
            field=f"key.{name}",
        )
    return expr


@dataclass(frozen=True)
class TrajectoryKey:
    """The key of one trajectory or gain question: the profile as written (``spec``,
    re-read with a student's ``drawn`` values), its data (``motion``), the question, its
    name (the profile as printed) and the accepted rounding of decimals."""

    spec: str
    motion: Motion
    question: Question
    name: str = ""
    rounding: Rounding = DEFAULT_ROUNDING
    #: a student's drawn values of names in the profile or the question's time
    drawn: tuple[tuple[str, sp.Expr], ...] = ()

    @classmethod
    def load(
        cls,
        spec: str,
        question: str | Question,
        *,
        rounding: object = None,
        drawn: Mapping[str, sp.Expr] | None = None,
    ) -> TrajectoryKey:
        """The key of ``question`` (``traj a2``, ``tb``, ``vmax``, ``q@1``, ``kp``, ``kd``)
        about the profile ``spec``; ``drawn``: a student's values of names in it.  The
        key is prepared once here to check it (a question it cannot answer, or a key
        with no real value, raises)."""
        motion = Motion.parse(spec, drawn)
        try:
            q = question if isinstance(question, Question) else Question.parse(question, 0)
        except DHError:
            q = None
        if q is None or q.kind != "trajectory":
            raise DHError(
                f"question {echoed(str(question))} is not one a profile answers: its questions "
                "are traj a<k>, tb, vmax, q@<t>, kp and kd",
                field="ask",
            )
        mine = tuple((n, v) for n, v in (drawn or {}).items() if n in spec_names(spec, q.spec))
        key = cls(str(spec), motion, q, motion.text, Rounding.parse(rounding), mine)
        try:
            prepare_trajectory(key)  # a key that cannot be checked against stops here
        except DHError as err:  # the profile's own check (a duration, a blend that fits)
            raise DHError(err.message, field=err.field or "key") from None
        return key

    def with_drawn(self, drawn: Mapping[str, sp.Expr]) -> TrajectoryKey:
        """This key with a student's drawn values of the names in its profile."""
        return TrajectoryKey.load(self.spec, self.question, rounding=self.rounding, drawn=drawn)


@dataclass(frozen=True, eq=False)
class TrajectoryPart:
    """A trajectory key prepared: the ``expected`` value, as text and LaTeX, and the key
    under each catalogued mistake that applies (``wrong``: kind and value), derived once."""

    expected: sp.Expr
    text: str
    latex: str
    wrong: tuple[tuple[str, sp.Expr], ...]


@dataclass(frozen=True, eq=False)
class PreparedTrajectory:
    """What checking many answers to one trajectory key shares: the key, the names an
    answer may use (:data:`SYMBOLS`) and the prepared part."""

    key: TrajectoryKey
    names: NameContext
    part: TrajectoryPart


def trajectory_sample(symbols: set[sp.Symbol], key: sp.Expr, size: int = POINTS) -> Sample:
    """Fresh random points for ``symbols``, positive ones in ``(0.25, 2.75)``, keeping only
    points where ``key`` has a finite real value; at least 16 of them, else the key has
    no real value to compare with (a :class:`~dhsym.errors.DHError`).

    >>> tf = sp.Symbol("t_f", positive=True)
    >>> s = trajectory_sample({tf}, 1 / tf)
    >>> s.size >= 16, bool((s.table > 0).all())
    (True, True)
    """
    syms = tuple(sorted(symbols, key=sp.default_sort_key))
    kept = np.empty((len(syms), 0))
    origin = 0
    for _ in range(_TRIES):
        s = Sample.random(syms, size)
        table = s.table.copy()
        for k, sym in enumerate(syms):
            if sym.is_positive:
                table[k] = np.abs(table[k]) + 0.25
        s = Sample(syms, table, s.origin)
        with np.errstate(all="ignore"):
            ok = np.isfinite(np.broadcast_to(values(key, s), (s.size,)))
        kept = np.hstack([kept, table[:, ok]])
        origin = s.origin
        if kept.shape[1] >= size:
            break
    if kept.shape[1] < _MIN_POINTS:
        raise DHError(f"the key {key} has no real value at random points: check its profile")
    return Sample(syms, kept[:, :size], origin)


def prepare_trajectory(key: TrajectoryKey) -> PreparedTrajectory:
    """Prepare ``key``: its expected value and its value under each mistake."""
    values = expected_values(key)
    expected = values["key"]
    wrong = []
    for m in TRAJECTORY_MISTAKES:
        w = m.wrong(key.question.part, values)
        if w is not None and sp.simplify(w - expected) != 0:
            wrong.append((m.kind, w))
    trajectory_sample(expected.free_symbols, expected)  # a key with no real value stops here
    names = NameContext(aliases=tuple((_canon(k), s) for k, s in SYMBOLS.items()))
    part = TrajectoryPart(expected, sp.sstr(expected), sp.latex(expected), tuple(wrong))
    return PreparedTrajectory(key, names, part)


def expected_values(key: TrajectoryKey) -> dict[str, sp.Expr]:
    """What the question's answer is (``key``) and what the mistakes need: ``t_f`` (the
    key's duration), ``key_tf`` and ``tf_symbol`` (a coefficient with ``t_f`` a symbol),
    ``key_at_rest`` (with the end velocities 0), ``blend_other`` (the blend time of the
    other limit or root), ``omega`` (of a gains key)."""
    motion, part = key.motion, key.question.part
    v = motion.values
    if part in ("kp", "kd"):
        if motion.kind != "gains":
            raise DHError(
                f"{part}: the gains are asked of a gains(omega=…, zeta=…) key", field="ask"
            )
        kp, kd = gains(v["omega"], v.get("zeta", sp.Integer(1)))
        return {"key": kp if part == "kp" else kd, "omega": v["omega"]}
    if motion.kind == "gains":
        raise DHError(f"{part}: a gains key answers kp and kd", field="ask")
    p = motion.profile()
    out: dict[str, sp.Expr] = {"t_f": v["tf"]} if "tf" in v else {}
    if part.startswith("a"):
        coeffs = _coefficients(p, part)
        k = int(part[1:])
        out["key"] = coeffs[k]
        tf = SYMBOLS["tf"]
        symbolic = Motion(motion.kind, tuple((n, tf if n == "tf" else x) for n, x in motion.params))
        out["key_tf"], out["tf_symbol"] = symbolic.profile().coefficients[k], tf
        if any(v.get(e, 0) != 0 for e in ("v0", "vf")):
            out["key_at_rest"] = motion.profile(at_rest=True).coefficients[k]
    elif part == "tb":
        if motion.kind not in ("lspb", "minimum_time"):
            raise DHError("tb: a blend time belongs to an lspb or minimum_time key", field="ask")
        segments = p.joints[0]
        if len(segments) == 1:
            raise DHError("tb: the motion has no blend (q0 = qf)", field="key")
        out["key"] = segments[0].end
        other = _other_blend(motion, segments[0].end)
        if other is not None:
            out["blend_other"] = other
    elif part == "vmax":
        out["key"] = _peak_velocity(motion, p)
    else:
        out["key"] = _position(motion, p, part[2:], key.drawn)
    return out


def _coefficients(p: Profile, part: str) -> tuple[sp.Expr, ...]:
    if len(p.joints[0]) != 1:
        raise DHError(f"traj {part}: coefficients belong to a cubic or quintic key", field="ask")
    coeffs = p.coefficients
    if int(part[1:]) >= len(coeffs):
        raise DHError(f"traj {part}: a {p.kind} has a0 … a{len(coeffs) - 1}", field="ask")
    return coeffs


def _peak_velocity(motion: Motion, p: Profile) -> sp.Expr:
    """The peak velocity of a rest-to-rest profile: at ``t_f/2`` for a polynomial (the
    profile is symmetric), the line's (the end of the first blend) for a blended one."""
    v = motion.values
    if any(v.get(e, 0) != 0 for e in ("v0", "vf")):
        raise DHError("vmax: the peak velocity is asked of rest-to-rest motions", field="ask")
    t = sp.Symbol("t", nonnegative=True)
    first = p.joints[0][0]
    at = first.end if len(p.joints[0]) > 1 else p.duration / 2
    return sp.factor(sp.diff(first.position(t), t).subs(t, at))


def _position(
    motion: Motion, p: Profile, written: str, drawn: tuple[tuple[str, sp.Expr], ...]
) -> sp.Expr:
    """The position at the time ``written`` (a number, or in the key's names: ``tf/2``,
    or the names drawn for a student)."""
    t = _value(written, "t", {**dict(motion.params), **dict(drawn)})
    end = p.duration
    if t.is_number and end.is_number and not (bool(t >= 0) and bool(t <= end)):
        raise DHError(f"q@{written}: the time is outside the motion, 0 … {end}", field="ask")
    return sp.factor(p.at(t)[0]) if t.free_symbols else p.at(t)[0]


def _other_blend(motion: Motion, tb: sp.Expr) -> sp.Expr | None:
    """The blend time of the other case (see the mistakes): the velocity limit's ``v/a``
    where the motion never reaches it and ``√(D/a)`` where it does; the larger root of
    ``a t_b² − a t_f t_b + D = 0``."""
    v = motion.values
    D = v["qf"] - v["q0"]
    if motion.kind == "minimum_time":
        cruise, triangle = v["vmax"] / v["amax"], sp.sqrt(sp.Abs(D) / v["amax"])
        return triangle if sp.simplify(tb - cruise) == 0 else cruise
    if "a" in v:
        return v["tf"] - tb
    return None
