r"""Homework on trajectories and gains: a key (a profile's data, exact or symbolic), the
questions it answers, and the judge that names the typical mistakes
(:mod:`dhsym.checking.mistakes.trajectory_mistakes`).

Questions: ``traj a<k>`` (a coefficient of a cubic or quintic), ``tb`` (the blend time of
a linear segment with parabolic blends or of the minimum-time profile), ``vmax`` (the
peak velocity), ``q@<t>`` (the position at time ``t``), ``kp`` and ``kd`` (the gains for
a natural frequency ``omega`` and damping ``zeta``, 1 for critical damping). Answers are
read by the whitelist reader (plain math or LaTeX, never ``sympify``), with the names
``q0``, ``qf``, ``tf``, ``v0``, ``vf``, ``V``, ``a``, ``omega``, ``zeta``.

Examples
--------
>>> key = TrajectoryKey.of("cubic", q0=0, qf=1, tf=2)
>>> check_trajectory_answer(key, "traj a2", "3/4").correct
True
>>> r = check_trajectory_answer(key, "traj a2", "3/2")
>>> r.verdict.value, r.kinds
('incorrect', ('tf_for_tf_squared',))
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.entries import as_expr
from dhsym.trajectory import Profile, cubic, lspb, minimum_time, quintic

from ..comparing.verdict import CheckResult, Diagnosis, Verdict
from ..mistakes.trajectory_mistakes import TRAJECTORY_MISTAKES
from ..reading.answer_names import NameContext
from ..reading.answers import read_expression

__all__ = ["TrajectoryKey", "check_trajectory_answer"]

#: the symbols of symbolic keys and the names a student may use for them
SYMBOLS = {
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
_PARAMS = {
    "cubic": ("q0", "qf", "tf", "v0", "vf"),
    "quintic": ("q0", "qf", "tf", "v0", "vf"),
    "lspb": ("q0", "qf", "tf", "V", "a"),
    "minimum_time": ("q0", "qf", "vmax", "amax"),
    "gains": ("omega", "zeta"),
}
_QUESTION = re.compile(
    r"^(?:traj\s+)?(?:(?P<coef>a(?P<k>\d))|(?P<tb>t_?b|blend)|(?P<vmax>v_?max|peak)"
    r"|q@(?P<t>[0-9./ ]{1,20})|(?P<gain>k_?p|k_?d))$",
    re.IGNORECASE,
)


@dataclass(frozen=True)
class TrajectoryKey:
    """A profile's data (``kind``: ``cubic``, ``quintic``, ``lspb``, ``minimum_time``, or
    ``gains``), exact: numbers, or the symbols ``q_0``, ``q_f``, ``t_f``, … when a value
    is given as its name (``TrajectoryKey.of("quintic", q0="q0", qf="qf", tf="tf")``)."""

    kind: str
    params: tuple[tuple[str, sp.Expr], ...]

    @classmethod
    def of(cls, kind: str, **params: object) -> TrajectoryKey:
        """The key of a ``kind`` profile with ``params`` (names of :data:`_PARAMS`)."""
        if kind not in _PARAMS:
            raise DHError(f"trajectory key: unknown kind {kind!r}: expected {', '.join(_PARAMS)}")
        unknown = set(params) - set(_PARAMS[kind])
        if unknown:
            raise DHError(f"trajectory key: {kind} takes no {', '.join(sorted(unknown))}")
        values = []
        for name, v in params.items():
            if v is None:
                continue
            if isinstance(v, str) and v in SYMBOLS:
                values.append((name, SYMBOLS[v]))
            else:
                values.append((name, as_expr(v, field=name)))
        return cls(kind, tuple(values))

    @property
    def values(self) -> dict[str, sp.Expr]:
        """The parameters by name."""
        return dict(self.params)

    def profile(self, at_rest: bool = False) -> Profile:
        """The key's profile (``at_rest``: with the end velocities 0)."""
        v = self.values
        if self.kind in ("cubic", "quintic"):
            make = cubic if self.kind == "cubic" else quintic
            zero = sp.Integer(0)
            ends = (zero, zero) if at_rest else (v.get("v0", zero), v.get("vf", zero))
            return make(v["q0"], v["qf"], v["tf"], *ends)
        if self.kind == "lspb":
            return lspb(v["q0"], v["qf"], v["tf"], v=v.get("V"), a=v.get("a"))
        if self.kind == "minimum_time":
            return minimum_time(v["q0"], v["qf"], v["vmax"], v["amax"])
        raise DHError(f"a {self.kind} key has no profile")

    def expected(self, question: str) -> dict[str, sp.Expr]:
        """What the question's answer is (``key``) and what the mistakes need."""
        m = _QUESTION.match(question.strip())
        if m is None:
            raise DHError(
                f"unknown trajectory question {question!r}: expected traj a<k>, tb, vmax, "
                "q@<t>, kp or kd"
            )
        v = self.values
        if m["gain"]:
            if self.kind != "gains":
                raise DHError(f"{question}: a gains question needs a gains key")
            w, z = v["omega"], v.get("zeta", sp.Integer(1))
            kp = m["gain"].lower().replace("_", "") == "kp"
            return {"key": w**2 if kp else 2 * z * w, "omega": w}
        p = self.profile()
        out: dict[str, sp.Expr] = {}
        if "tf" in v:
            out["t_f"] = v["tf"]
        if m["coef"]:
            if len(p.joints[0]) != 1:
                raise DHError(f"{question}: coefficients belong to a cubic or quintic key")
            k = int(m["k"])
            coeffs = p.coefficients
            if k >= len(coeffs):
                raise DHError(f"{question}: a {self.kind} has a0 … a{len(coeffs) - 1}")
            out["key"] = coeffs[k]
            tf = SYMBOLS["tf"]
            symbolic = TrajectoryKey(
                self.kind, tuple((n, tf if n == "tf" else x) for n, x in self.params)
            )
            out["key_tf"], out["tf_symbol"] = symbolic.profile().coefficients[k], tf
            if any(v.get(e, 0) != 0 for e in ("v0", "vf")):
                out["key_at_rest"] = self.profile(at_rest=True).coefficients[k]
        elif m["tb"]:
            if self.kind not in ("lspb", "minimum_time"):
                raise DHError(f"{question}: a blend time belongs to an lspb or minimum_time key")
            seg = p.joints[0][0]
            out["key"] = seg.end
            out["blend_other"] = _other_blend(self, seg.end)
        elif m["vmax"]:
            mid = p.duration / 2  # every profile of a key is symmetric from rest to rest
            if any(v.get(e, 0) != 0 for e in ("v0", "vf")):
                raise DHError(f"{question}: the peak velocity is asked of rest-to-rest motions")
            t = sp.Symbol("t", nonnegative=True)
            first = p.joints[0][0]
            if len(p.joints[0]) > 1:  # the end of the first blend: the line's velocity
                out["key"] = sp.simplify(sp.diff(first.position(t), t).subs(t, first.end))
            else:
                out["key"] = sp.factor(sp.diff(first.position(t), t).subs(t, mid))
        else:
            out["key"] = p.at(as_expr(m["t"].strip(), field="question"))[0]
        return out


def _other_blend(key: TrajectoryKey, tb: sp.Expr) -> sp.Expr | None:
    """The blend time of the wrong limit (see the mistakes)."""
    v = key.values
    D = v["qf"] - v["q0"]
    if key.kind == "minimum_time":
        vmax, amax = v["vmax"], v["amax"]
        cruise, triangle = vmax / amax, sp.sqrt(sp.Abs(D) / amax)
        return triangle if tb == cruise else cruise
    if key.kind == "lspb" and "a" in v:  # the larger root
        return v["tf"] - tb
    return None


def _same(a: sp.Expr, b: sp.Expr) -> bool:
    if sp.simplify(a - b) == 0:
        return True
    if a.is_number and b.is_number:  # decimals as written: three significant digits
        x, y = complex(a), complex(b)
        return abs(x - y) <= 5e-4 * max(abs(y), 1e-12)
    return False


def check_trajectory_answer(key: TrajectoryKey, question: str, answer: str) -> CheckResult:
    """The verdict on ``answer`` (text) to ``question`` under ``key``, with the typical
    mistake named when the answer is one of them."""
    values = key.expected(question)
    expected = values["key"]
    ctx = NameContext(aliases=tuple(SYMBOLS.items()))
    try:
        got = read_expression(answer, ctx)
    except DHError as err:
        return CheckResult(
            question,
            Verdict.UNREADABLE,
            f"The answer could not be read: {err.message}",
            reason=err.message,
            key=key.kind,
        )
    if _same(got, expected):
        return CheckResult(
            question, Verdict.CORRECT, f"Correct: {sp.sstr(expected)}.", key=key.kind
        )
    name = re.sub(r"[\s_]", "", question.lower()).removeprefix("traj")
    found = []
    for m in TRAJECTORY_MISTAKES:
        wrong = m.wrong(name, values)
        if wrong is not None and _same(got, wrong):
            found.append(Diagnosis(m.kind, m.title, m.detail))
    message = (
        f"Not the expected value: {found[0].title}. {found[0].detail}"
        if found
        else "Not the expected value: write the conditions of the profile and solve them again."
    )
    return CheckResult(question, Verdict.INCORRECT, message, diagnoses=tuple(found), key=key.kind)
