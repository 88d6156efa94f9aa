"""What the names in a student's answer mean for one key robot.

Students write ``theta1``, ``θ_1``, ``q1``, the lecture abbreviations ``C12``,
``S23``, ``c1``, ``C_{12}``, ``c_{alpha}``, ``c_alpha1``, ``c_{\\theta_i}``, Craig's
``cθ1``, or glued products like ``c1s2``, ``a_1c_1``, ``s_23c_4``, ``a1C1`` and
``cosθ1``.  :class:`NameContext` turns each name into the key robot's symbol or into
``cos``/``sin`` of its joint angles; it is the ``resolve`` hook of
:func:`dhsym.model.parsing.parse_expression`.  A glued name is read whole when it can be
(the longest match), else split into known factors; when two splits give different
products the name is refused as ambiguous.

Examples
--------
>>> from dhsym import load_table
>>> ctx = NameContext.from_table(load_table("puma560"))
>>> ctx.resolve("C23"), ctx.resolve("s1"), ctx.resolve("q4"), ctx.resolve("a_2")
(cos(theta2 + theta3), sin(theta1), theta4, a2)
>>> ctx.resolve("c_alpha1"), ctx.resolve("c1s2"), ctx.resolve("banana") is None
(cos(alpha1), sin(theta2)*cos(theta1), True)
>>> ctx.resolve("a_2c_23"), ctx.resolve("s_23c_4"), ctx.resolve("costheta1")
(a2*cos(theta2 + theta3), sin(theta2 + theta3)*cos(theta4), cos(theta1))
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cached_property

import sympy as sp

from dhsym.errors import ParseError
from dhsym.model.parsing import normalize_name, symbol
from dhsym.model.table import DHTable, JointType

__all__ = ["ANGLE_DIFFERENCE", "NameContext", "angle_difference_name"]

_ABBREV = re.compile(r"^(?P<f>[CcSs])_?(?P<rest>[A-Za-z0-9_]+)$")
_GLUED = re.compile(r"^(?:[CcSs][0-9]+){2,}$")
_GLUED_PART = re.compile(r"[CcSs][0-9]+")
_GREEK_HEAD = re.compile(
    r"^(alpha|beta|gamma|delta|theta|phi|psi|omega|sigma|tau|rho|lambda|mu|nu|xi|eta|zeta|"
    r"epsilon|kappa|chi|iota|upsilon|omicron|pi)[A-Za-z0-9_]*$"
)
_VAR_PREFIXES = ("theta", "th", "q", "d")
_FUNCTION_HEAD = re.compile(r"^(sin|cos|tan)(?P<rest>[A-Za-z][A-Za-z0-9_]*)$")  # cosθ1
_TRIG_OF = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan}
#: An angle difference as dhsym prints it in text: ``C[12-4]`` is cos(θ1 + θ2 − θ4), with
#: ``,`` between labels longer than one character (``S[10,11-12]``); joint numbers only, so
#: ``S[1-x]`` stays a product.
ANGLE_DIFFERENCE = re.compile(
    r"(?<![A-Za-z0-9_])(?P<f>[CcSs])\[(?P<pos>[0-9]+(?:,[0-9]+)*)(?P<neg>(?:-[0-9]+)+)\]"
)
_DIFFERENCE_NAME = re.compile(
    r"^(?P<f>[CcSs])_angle_(?P<pos>[A-Za-z0-9_]+?)(?P<neg>(?:_minus_[A-Za-z0-9]+)+)$"
)
_SPLIT_LONGEST = 48  # longest glued name that is split into factors
_PIECE_LONGEST = 20  # longest factor in it


def angle_difference_name(match: re.Match[str]) -> str:
    """The one name that stands for a printed angle difference (:data:`ANGLE_DIFFERENCE`),
    which :meth:`NameContext.resolve` reads back: ``C[12-4]`` → ``C_angle_12_minus_4``.

    >>> ANGLE_DIFFERENCE.sub(angle_difference_name, "a1*C[12-4] + S[10,11-12]")
    'a1*C_angle_12_minus_4 + S_angle_10_and_11_minus_12'
    """
    pos = match["pos"].replace(",", "_and_")
    negs = "".join(f"_minus_{label}" for label in match["neg"][1:].split("-"))
    return f"{match['f']}_angle_{pos}{negs}"


def _canon(name: str) -> str:
    return normalize_name(name).replace("_", "")


@dataclass(frozen=True)
class NameContext:
    """Aliases of a key's symbols and the labels of its revolute joint angles.

    Parameters
    ----------
    aliases
        ``(alias, symbol)`` pairs; an alias is compared without underscores.
    labels
        ``(label, variable)`` pairs: ``C12`` is cos of the sum of labels 1 and 2.
    """

    aliases: tuple[tuple[str, sp.Symbol], ...] = ()
    labels: tuple[tuple[str, sp.Symbol], ...] = ()

    @classmethod
    def from_table(cls, table: DHTable) -> NameContext:
        """Names of a DH table: its symbols, ``q<k>``/``theta<k>``/``d<k>`` and joint labels."""
        aliases: dict[str, sp.Symbol] = {}
        for s in (*table.variables, *table.constants):
            aliases[_canon(s.name)] = s
        labels: dict[str, sp.Symbol] = {}
        for k, row in enumerate(table.rows, start=1):
            var = row.variable
            if var is None:
                continue
            extra = [f"q{k}"] + ([f"theta{k}", f"th{k}"] if row.joint is JointType.REVOLUTE else [])
            extra += [f"d{k}"] if row.joint is JointType.PRISMATIC else []
            for alias in extra:
                aliases.setdefault(alias, var)
            if row.joint is JointType.REVOLUTE:
                labels.setdefault(str(k), var)
                low = _canon(var.name)
                for prefix in _VAR_PREFIXES:
                    if low.startswith(prefix) and len(low) > len(prefix):
                        labels.setdefault(low[len(prefix) :], var)
                        break
        return cls(tuple(aliases.items()), tuple(labels.items()))

    def extended(self, names: Iterable[tuple[str, sp.Symbol]]) -> NameContext:
        """This context with more names (``p_x``, a helper ``D`` of an answer); they win
        over the abbreviations (a helper ``c2`` is not ``cos θ2``).

        >>> from dhsym import load_table
        >>> px = sp.Symbol("p_x", real=True)
        >>> ctx = NameContext.from_table(load_table("planar2r")).extended([("p_x", px)])
        >>> ctx.resolve("px"), ctx.resolve("p_x") == px, ctx.resolve("C1")
        (p_x, True, cos(theta1))
        """
        extra = tuple((_canon(name), s) for name, s in names)
        return NameContext(self.aliases + extra, self.labels)  # later names win in the dict

    @cached_property
    def _aliases(self) -> dict[str, sp.Symbol]:
        return dict(self.aliases)

    @cached_property
    def _labels(self) -> dict[str, sp.Symbol]:
        return dict(self.labels)

    @property
    def symbols(self) -> frozenset[sp.Symbol]:
        """Every symbol of the key."""
        return frozenset(self._aliases.values())

    def symbol(self, name: str) -> sp.Symbol | None:
        """The key symbol that ``name`` spells (``theta_1``, ``θ1``, ``q1`` …), or None."""
        return self._aliases.get(_canon(name))

    def angle_sum(self, rest: str) -> sp.Expr | None:
        """Sum of the joint angles whose labels make up ``rest`` (``"12"`` → θ1 + θ2)."""
        if rest in self._labels:
            return self._labels[rest]
        if len(rest) > 1 and all(ch in self._labels for ch in rest) and len(set(rest)) == len(rest):
            return sp.Add(*(self._labels[ch] for ch in rest))
        return None

    def resolve(self, name: str) -> sp.Expr | None:
        """The expression a name stands for, or None (a new symbol of that name).

        A name that is not one symbol or abbreviation is split into factors that are
        (``a_1c_1`` is a_1·c_1); two splits with different products raise ParseError.
        """
        whole = self._single(name, guess=False)
        if whole is not None:
            return whole
        splittable = len(name) <= _SPLIT_LONGEST and any(c.isdigit() or c == "_" for c in name)
        readings = self._splits(name) if splittable else {}
        if not readings:
            return self._single(name)  # c_alpha: cos of a new symbol alpha
        if len(readings) > 1:
            shown = [" ".join(pieces) for pieces in list(readings.values())[:2]]
            raise ParseError(
                f"ambiguous name {name!r}: it reads as {shown[0]!r} or as {shown[1]!r}; "
                f"write the factors apart, e.g. {shown[0]!r} or "
                f"{shown[0].replace(' ', '*')!r}"
            )
        return next(iter(readings))

    def _splits(self, name: str) -> dict[sp.Expr, tuple[str, ...]]:
        """Products of the ways ``name`` splits into known factors (at most two found)."""
        memo: dict[int, dict[sp.Expr, tuple[str, ...]]] = {len(name): {sp.Integer(1): ()}}

        def rest(i: int) -> dict[sp.Expr, tuple[str, ...]]:
            if i in memo:
                return memo[i]
            found: dict[sp.Expr, tuple[str, ...]] = {}
            for j in range(i + 1, min(len(name), i + _PIECE_LONGEST) + 1):
                if j < len(name) and not name[j].isalpha():
                    continue  # a factor starts with a letter
                whole_name = j - i == len(name) or name[j - 1] == "_"
                piece = None if whole_name else self._single(name[i:j], guess=False)
                if piece is None:
                    continue
                for product, pieces in rest(j).items():
                    found.setdefault(piece * product, (name[i:j], *pieces))
                    if len(found) > 1:
                        break
                if len(found) > 1:
                    break
            memo[i] = found
            return found

        return rest(0) if name[:1].isalpha() else {}

    def _single(self, name: str, guess: bool = True) -> sp.Expr | None:
        """One symbol, abbreviation (``C12``, ``c_alpha``), ``cosθ1``, or ``c1s2``.

        ``guess``: ``c_<Greek name>…`` may be cos of a symbol the key does not have."""
        own = self.symbol(name)
        if own is not None:
            return own
        if _GLUED.match(name):
            parts = [self._single(p) for p in _GLUED_PART.findall(name)]
            if all(p is not None for p in parts):
                return sp.Mul(*parts)
            return None
        d = _DIFFERENCE_NAME.match(name)
        if d is not None:
            return self._difference(d)
        f = _FUNCTION_HEAD.match(name)
        if f is not None and self.symbol(f["rest"]) is not None:  # cosθ1: cos of a key symbol
            return _TRIG_OF[f[1]](self.symbol(f["rest"]))
        m = _ABBREV.match(name)
        if m is None:
            return None
        trig = sp.cos if m["f"] in "Cc" else sp.sin
        rest = m["rest"].lstrip("_")
        if not rest:
            return None
        target = self.symbol(rest)
        if target is None:
            target = self.angle_sum(rest.replace("_", ""))
        if target is None and guess and _GREEK_HEAD.match(normalize_name(rest)):
            try:
                target = symbol(rest.replace("__", "_"))
            except ParseError:
                return None
        return trig(target) if target is not None else None

    def _difference(self, d: re.Match[str]) -> sp.Expr | None:
        """cos/sin of the labels before ``_minus_`` less those after (None: unknown label)."""
        pos = d["pos"]
        if pos in self._labels:
            first = [pos]
        else:
            first = pos.split("_and_") if "_and_" in pos else list(pos)
        rest = d["neg"].split("_minus_")[1:]
        if any(label not in self._labels for label in (*first, *rest)):
            return None
        arg = sp.Add(*(self._labels[k] for k in first)) - sp.Add(*(self._labels[k] for k in rest))
        return (sp.cos if d["f"] in "Cc" else sp.sin)(arg)

    def table_resolve(self, name: str) -> sp.Expr | None:
        """Resolve for table cells: only symbol aliases (no ``C12`` abbreviations)."""
        return self.symbol(name)
