"""What is asked: a DH table, a transform ``^iT_j``, a link matrix ``A_k`` or one entry; the
Jacobian ``J`` or one entry ``J[r,c]``, its determinant ``det J``, or the inverse kinematics
``ik`` (symbolic in the pose; ``ik all`` asks for every branch, ``ik@q1,…,qn`` for the numbers
of the pose that these joint values reach); a transform at given joint values (``T0_6@q1,…,qn``,
``fk@q1,…,qn`` for ``^0T_n``: the matrix in numbers, graded to the key's digits); the dynamics
``M``, ``M[i,j]``, ``g``, ``C``, Spong's Christoffel symbol ``c_ijk`` (1-based, ``c_112``),
``tau`` (symbolic in q, q̇, q̈) and the statics ``tau_static`` (τ = Jᵀ F); a robot as a
product of exponentials (``kind`` ``screw``, :mod:`~dhsym.checking.reading.screw_questions`):
the screw axes ``S``, ``S3``, ``B``, the home configuration ``Mhome``, ``Js``, ``Jb`` and
``T(theta)``;
of a time profile (kind ``trajectory``, its key a profile
such as ``cubic(q0=0, qf=1, tf=2)``): a coefficient ``traj a<k>``, the blend time ``tb``,
the peak velocity ``vmax``, the position at a time ``q@<t>``, the gains ``kp`` and ``kd``.

Examples
--------
>>> Question.parse("T0_6[0,3]", n=6)
Question(spec='T0_6[0,3]', kind='entry', frm=0, to=6, entry=(0, 3), pose=None, every=False)
>>> Question.parse("A3", n=6).label, Question.parse("arm", n=6).label, Question.parse("px", 6).label
('T2_3', 'T0_6', 'T0_6[0,3]')
>>> Question.parse("^0T_2", n=6).label_latex
'{}^{0}T_{2}'
>>> [Question.parse(s, 2).label for s in ("J", "J[1,0]", "det(J)", "IK", "ik all", "ik@pi/2,0")]
['J', 'J[1,0]', 'det J', 'ik', 'ik all', 'ik@1.5707963267949,0']
>>> [Question.parse(s, 2).label for s in ("T0_2@pi/2,0", "fk@ 0.5, 1", "T0_2[0,3]@0,0")]
['T0_2@1.5707963267949,0', 'T0_2@0.5,1', 'T0_2[0,3]@0,0']
>>> [Question.parse(s, 2).label for s in ("M", "M[0,1]", "g", "C", "c_{112}", "τ", "tau_s")]
['M', 'M[0,1]', 'g', 'C', 'c_112', 'tau', 'tau_static']
>>> [Question.parse(s, 2).label for s in ("S", "S_2", "B", "Mhome", "J_s", "Jb[5,1]", "T(θ)")]
['S', 'S2', 'B', 'Mhome', 'Js', 'Jb[5,1]', 'T(theta)']
>>> [Question.parse(s, 0).label for s in ("traj a2", "t_b", "traj v_max", "q@ 1/2", "K_d")]
['traj a2', 'tb', 'vmax', 'q@1/2', 'kd']
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from dhsym.errors import DHError
from dhsym.model.parsing import parse_number_list

from .screw_questions import parse_screw, screw_label, screw_latex

__all__ = ["Question"]

_TRANSFORM = re.compile(  # frame numbers have at most 4 digits (no 5000-digit int() ever)
    r"^(?:\^\{?(?P<a>\d{1,4})\}?T_\{?(?P<b>\d{1,4})\}?"
    r"|[TH]_?\{?(?P<i>\d{1,4})\}?[_,]\{?(?P<j>\d{1,4})\}?"
    r"|[TH](?P<ij>\d\d)|[AH]_?\{?(?P<k>\d{1,4})\}?|(?P<arm>arm|T0_n|T_?0_?n)|p_?(?P<p>[xyz]))"
    r"(?:\s*\[\s*(?P<r>\d{1,4})\s*,\s*(?P<c>\d{1,4})\s*\])?$"
)
_JACOBIAN = re.compile(r"^(?:J|J0|J_0|jacobian)(?:\[(?P<r>\d+),(?P<c>\d+)\])?$", re.IGNORECASE)
_DET = re.compile(r"^det(?:J|\(J\)|_J|\{J\})$", re.IGNORECASE)
_IK = re.compile(r"^(?:ik|inverse)(?P<all>:?all|\*)?(?:@(?P<q>.+))?$", re.IGNORECASE)
#: a transform at joint values: ``T0_6@q1,…,qn`` (``fk@…`` is ``^0T_n`` there)
_AT = re.compile(r"^(?P<head>[^@]+)@(?P<q>.+)$")
_DYNAMICS = re.compile(
    r"^(?P<part>M|C|g|tau|τ)(?:\[(?P<r>\d{1,2}),(?P<c>\d{1,2})\])?$"
    r"|^c_?\{?(?P<i>\d),?(?P<j>\d),?(?P<k>\d)\}?$"
    r"|^(?P<static>(?:tau|τ)_?(?:static|statics|s|\{s\})|statics)$"
)
_TRAJECTORY = re.compile(
    r"^(?:traj(?:ectory)?\s*(?P<coef>a(?P<k>\d))|(?:traj(?:ectory)?\s*)?(?:(?P<tb>t_?b)"
    r"|(?P<vmax>v_?max|v_?\{max\})|q\s*@\s*(?P<t>[A-Za-z0-9_./*+() -]{1,40})"
    r"|(?P<gain>k_?\{?[pd]\}?)))$",
    re.IGNORECASE,
)
_KINDS = (
    "table, T<i>_<j>, A<k>, arm, px/py/pz, optionally with [row,col] (0-based), e.g. T0_6[0,3]; "
    "T0_6@q1,...,qn or fk@q1,...,qn (the matrix at these joint values); "
    "J, J[row,col], det J, ik, ik all, ik@q1,...,qn; M, M[row,col], g, C, c_ijk, tau, tau_static; "
    "S, S<i>, B, B<i>, Mhome, Js, Jb, T(theta); "
    "of a profile: traj a<k>, tb, vmax, q@<t>, kp, kd"
)


@dataclass(frozen=True)
class Question:
    """One question: ``kind`` is ``table``, ``matrix`` (``^frm T_to``), ``entry`` (0-based),
    ``jacobian`` (``J``, or its ``entry``), ``det`` (``det J``), ``ik``, ``dynamics`` or
    ``trajectory``.

    For ``ik``, ``pose`` holds the joint values whose pose is to be solved (None: a
    symbolic answer in the pose ``n s a p``) and ``every`` asks for every branch.
    For ``matrix`` and ``entry``, ``pose`` holds the joint values the transform is asked at
    (``T0_6@q1,…,qn``; None: symbolic in the joint variables).
    For ``dynamics``, ``part`` is ``M``, ``g``, ``C``, ``tau``, ``tau_static`` or ``c`` (the
    Christoffel symbol ``c_ijk``, its 1-based ``index``); ``entry`` is 0-based.
    For ``screw``, ``part`` is ``S``, ``B``, ``Mhome``, ``Js``, ``Jb`` or ``T`` and ``column``
    the 1-based screw axis asked alone (``S3``).
    For ``trajectory``, ``part`` is ``a<k>``, ``tb``, ``vmax``, ``q@<t>`` (the time as
    written, read with the key's names when the key is prepared), ``kp`` or ``kd``.
    """

    spec: str
    kind: str
    frm: int = 0
    to: int = 0
    entry: tuple[int, int] | None = None
    pose: tuple[float, ...] | None = None
    every: bool = False
    part: str = field(default="", repr=False)
    index: tuple[int, int, int] | None = field(default=None, repr=False)
    column: int | None = field(default=None, repr=False)

    @classmethod
    def parse(cls, spec: str, n: int) -> Question:
        """Read ``table``, ``T0_2``, ``T02``, ``^0T_2``, ``A3``, ``arm``, ``px``, ``…[r,c]``,
        any of these ``@q1,…,qn`` (``fk@q1,…,qn``), ``J``, ``J[r,c]``, ``det J``, ``ik``,
        ``ik all``, ``ik@q1,…,qn``, ``M``, ``M[r,c]``,
        ``g``, ``C``, ``c_ijk``, ``tau``, ``tau_static``; ``traj a<k>``, ``tb``, ``vmax``,
        ``q@<t>``, ``kp`` and ``kd`` (``n`` does not matter for these)."""
        text = str(spec).strip()
        if len(text) > 200:
            raise DHError(f"unknown question {text[:40]!r}…: a question is at most 200 characters")
        if text.lower() in ("table", "dh", "dh table", "dh_table"):
            return cls(text, "table")
        m = _TRAJECTORY.match(text)
        if m is not None:
            return cls(text, "trajectory", part=_trajectory_part(m))
        compact = text.replace(" ", "")
        screw = parse_screw(compact, n)
        if screw is not None:
            return cls(text, "screw", 0, n, screw[1], part=screw[0], column=screw[2])
        m = _JACOBIAN.match(compact)
        if m is not None:
            entry = (int(m["r"]), int(m["c"])) if m["r"] is not None else None
            if entry is not None and not 0 <= entry[0] < 6:
                raise DHError(f"question {text!r}: the rows of J are 0 … 5")
            return cls(text, "jacobian", 0, n, entry)
        m = _DYNAMICS.match(compact)
        if m is not None:
            if m["static"] is not None:
                return cls(text, "dynamics", 0, n, part="tau_static")
            if m["i"] is not None:
                index = (int(m["i"]), int(m["j"]), int(m["k"]))
                if not all(1 <= k <= n for k in index):
                    raise DHError(f"question {text!r}: the indices of c_ijk are 1 … {n}")
                return cls(text, "dynamics", 0, n, part="c", index=index)
            part = "tau" if m["part"] == "τ" else m["part"]
            entry = (int(m["r"]), int(m["c"])) if m["r"] is not None else None
            if entry is not None and not (
                entry[0] < n and entry[1] < (1 if part in ("g", "tau") else n)
            ):
                raise DHError(f"question {text!r}: rows and columns of {part} are 0-based")
            return cls(text, "dynamics", 0, n, entry, part=part)
        if _DET.match(compact):
            return cls(text, "det", 0, n)
        m = _IK.match(compact)
        if m is not None:
            pose = None
            if m["q"] is not None:
                pose = tuple(parse_number_list(m["q"], f"question {text!r}"))
            return cls(text, "ik", 0, n, None, pose, m["all"] is not None)
        at = _AT.match(compact)
        if at is not None:  # a transform at joint values
            head = at["head"]
            if head.lower() == "fk":
                head = "T0_n"
            inner = cls.parse(head, n)
            if inner.kind not in ("matrix", "entry") or inner.pose is not None:
                raise DHError(
                    f"question {text!r}: joint values follow a transform, e.g. T0_{n}@q1,...,qn"
                )
            pose = tuple(parse_number_list(at["q"], f"question {text!r}"))
            return cls(text, inner.kind, inner.frm, inner.to, inner.entry, pose)
        m = _TRANSFORM.match(compact)
        if m is None:
            raise DHError(f"unknown question {text!r}: expected {_KINDS}")
        if m["k"] is not None:
            frm, to = int(m["k"]) - 1, int(m["k"])
        elif m["arm"] is not None or m["p"] is not None:
            frm, to = 0, n
        elif m["ij"] is not None:
            frm, to = int(m["ij"][0]), int(m["ij"][1])
        else:
            frm, to = int(m["a"] or m["i"]), int(m["b"] or m["j"])
        if not (0 <= frm <= n and 0 <= to <= n) or frm == to:
            raise DHError(f"question {text!r}: frames are 0 … {n} and must differ")
        entry = None
        if m["p"] is not None:
            entry = ("xyz".index(m["p"]), 3)
        if m["r"] is not None:
            entry = (int(m["r"]), int(m["c"]))
            if not (0 <= entry[0] < 4 and 0 <= entry[1] < 4):
                raise DHError(f"question {text!r}: row and column are 0 … 3")
        return cls(text, "entry" if entry else "matrix", frm, to, entry)

    @property
    def label(self) -> str:
        """Canonical text: ``table``, ``T0_2``, ``T0_6[0,3]``, ``T0_2@0.5,1``, ``J[1,0]``,
        ``det J``, ``ik``."""
        if self.kind == "table":
            return "table"
        if self.kind == "det":
            return "det J"
        if self.kind == "ik":
            head = "ik all" if self.every else "ik"
            return head + ("@" + ",".join(f"{x:.15g}" for x in self.pose) if self.pose else "")
        if self.kind == "trajectory":
            return f"traj {self.part}" if self.part.startswith("a") else self.part
        if self.kind == "dynamics":
            if self.index is not None:
                return "c_" + "".join(map(str, self.index))
            return self.part + (f"[{self.entry[0]},{self.entry[1]}]" if self.entry else "")
        if self.kind == "screw":
            return screw_label(self.part, self.entry, self.column)
        base = "J" if self.kind == "jacobian" else f"T{self.frm}_{self.to}"
        at = "@" + ",".join(f"{x:.15g}" for x in self.pose) if self.pose is not None else ""
        return (f"{base}[{self.entry[0]},{self.entry[1]}]" if self.entry else base) + at

    @property
    def label_latex(self) -> str:
        """``{}^{0}T_{2}`` (or ``\\text{DH table}``, ``J``, ``\\det J``), for headings."""
        if self.kind == "table":
            return r"\text{DH table}"
        if self.kind == "det":
            return r"\det J"
        if self.kind == "ik":
            return r"\text{inverse kinematics}"
        if self.kind == "dynamics":
            return _dynamics_latex(self)
        if self.kind == "screw":
            return screw_latex(self.part, self.entry, self.column)
        if self.kind == "trajectory":
            return _trajectory_latex(self.part)
        base = "J" if self.kind == "jacobian" else f"{{}}^{{{self.frm}}}T_{{{self.to}}}"
        at = "" if self.pose is None else r" \text{ at the given joint values}"
        if self.entry:
            return f"{base}[{self.entry[0] + 1},{self.entry[1] + 1}]{at}"
        return base + at


def _trajectory_part(m: re.Match[str]) -> str:
    """The canonical part of a trajectory question: ``a2``, ``tb``, ``vmax``, ``q@<t>``
    (the time without spaces), ``kp`` or ``kd``."""
    if m["coef"]:
        return f"a{m['k']}"
    if m["tb"]:
        return "tb"
    if m["vmax"]:
        return "vmax"
    if m["gain"]:
        return "k" + m["gain"].rstrip("}").lower()[-1]
    return "q@" + "".join(m["t"].split())


def _trajectory_latex(part: str) -> str:
    r"""``a_{2}``, ``t_b``, ``\dot q_{\max}``, ``q(1/2)``, ``K_p``, ``K_d``."""
    if part.startswith("q@"):
        return rf"q({part[2:]})"
    fixed = {"tb": "t_b", "vmax": r"\dot q_{\max}", "kp": "K_p", "kd": "K_d"}
    return fixed.get(part, f"a_{{{part[1:]}}}")


def _dynamics_latex(q: Question) -> str:
    """``M(q)``, ``M[1,2]`` (1-based, as a heading), ``c_{112}``, ``\\tau = J^T F``."""
    if q.index is not None:
        return "c_{" + "".join(map(str, q.index)) + "}"
    head = {
        "M": "M(q)",
        "g": "g(q)",
        "C": r"C(q, \dot q)",
        "tau": r"\tau",
        "tau_static": r"\tau = J^T F",
    }[q.part]
    if q.entry is not None:
        return f"{q.part}[{q.entry[0] + 1},{q.entry[1] + 1}]"
    return head
