r"""Lecture notation: ``C_{12}`` for cos(θ1+θ2), ``S_1`` for sin θ1, in the textbook's order.

The printers are subclasses of sympy's own ``StrPrinter`` and ``LatexPrinter``.
They override ``_print_cos``/``_print_sin`` (the abbreviations) and
``_print_Add``/``_print_Mul`` (the order); both go through one layout pass,
:meth:`Notation.arrange`, so text, LaTeX, Markdown, JSON, notebooks and
feedback pages print every formula in the same order. The sympy expressions
themselves are never rewritten: the order is the printer's job.

The term-order policy
---------------------
1. **Factor before bracket.** A common factor is written before the bracket it
   multiplies: ``C1(…)``, never ``(…)C1``.
2. **Products in lecture order.** Numeric coefficient first, then lengths and
   other plain symbols (``a``, ``d``, ``l`` …) by index, then the sines and
   cosines of joint angles in joint order (``a2C2``, ``S23S5C6``, ``C4S6``; a
   sum angle counts by its joints, ``C23`` before ``S5``), C before S on the
   same joint; then other trigonometric factors (twists, ``c_{α1}``); brackets last.
3. **Sums in joint order, led by a positive term.** Terms are ordered by the
   indices of their factors as they are printed (lengths and joints alike,
   ``C1[…] − d3S1``, ``a2C2 + a3C23 − d4S23``); a bracket counts by its first
   term; a number comes last. If the first term is negative and a positive one
   exists, the first positive term moves to the front (``C4C5C6 − S4S6``).
4. **Signs before brackets.** A minus stands before a bracket rather than in all
   its terms: ``−C1(C23C4S5 + S23C5)``, never ``C1(−C23C4S5 − S23C5)``. A
   bracket with no bracket inside is signed so that its term with the fewest
   sines is positive, as the sum-angle identities read (``C4C5C6 − S4S6``,
   ``C4C6 − S4C5S6``), so the same bracket reads the same in every entry; ties go
   to its first term in the order of rule 3. A bracket that holds brackets is
   signed to show the fewest minus signs (ties as before).
5. **Brackets by level** (LaTeX): ``( )`` around a bracket with no bracket
   inside, ``[ ]`` around one that holds ``( )``, then ``\{ \}``; plain text
   always uses ``( )`` so that it reads back through the project's parser.

Case (:class:`TrigStyle`): ``C1``/``S23`` (the lectures here), ``c1``/``s23``
(Craig, Spong) or ``c_{θ1}`` (LaTeX only; its text is ``c1``).

Examples
--------
>>> import sympy as sp
>>> t1, t2, a1, a2 = sp.symbols("theta1 theta2 a1 a2", real=True)
>>> nota = Notation.from_variables([t1, t2])
>>> e = a2 * sp.cos(t1 + t2) + a1 * sp.cos(t1)
>>> nota.text(e)
'a1*C1 + a2*C12'
>>> nota.latex(e)
'a_{1} C_{1} + a_{2} C_{12}'
>>> nota.text(a2 - (sp.sin(t2) - sp.cos(t2)) * sp.cos(t1))
'C1*(C2 - S2) + a2'
>>> nota.text((sp.sin(t2) - sp.cos(t2)) * sp.cos(t1))
'-C1*(C2 - S2)'
>>> Notation.from_variables([t1, t2], style="c1").latex(-sp.sin(t1) * (a1 + a2 * sp.cos(t2)))
'-s_{1}(a_{1} + a_{2} c_{2})'
>>> print(Notation.from_variables([t1, t2], compact=False).latex(sp.cos(t1 + t2)))
\cos{\left(\theta_{1} + \theta_{2} \right)}
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from enum import Enum
from functools import cached_property
from itertools import product as _combinations
from typing import TYPE_CHECKING, Any

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.str import StrPrinter

from dhsym.errors import DHError
from dhsym.model.entries import as_expr, exact_decimal

__all__ = [
    "LegendEntry",
    "Notation",
    "Product",
    "Sum",
    "Token",
    "TrigStyle",
    "angle_label",
    "decimal_lengths",
    "format_angle",
    "uses_decimals",
]


def angle_label(arg: sp.Expr, labels: dict[sp.Symbol, str]) -> str | None:
    """The index label of a sum of joint angles: θ1+θ2 → ``12``, θ1+θ2−θ4 → ``12-4``.

    Returns None when ``arg`` is not a ±1 combination of joint angles.

    >>> t = sp.symbols("theta1:4", real=True)
    >>> angle_label(t[0] + t[1], {t[0]: "1", t[1]: "2"})
    '12'
    >>> angle_label(t[1] - t[0], {t[0]: "1", t[1]: "2"})
    '2-1'
    """
    coeffs = arg.as_coefficients_dict()
    if sp.S.One in coeffs:
        return None
    pos: list[sp.Expr] = []
    neg: list[sp.Expr] = []
    for term, c in coeffs.items():
        if term not in labels or c not in (1, -1):
            return None
        (pos if c == 1 else neg).append(labels[term])
    if not pos:
        return None
    key = lambda lab: [int(t) if t.isdigit() else t for t in lab.split(",")]  # noqa: E731
    pos.sort(key=key)
    neg.sort(key=key)
    wide = any(len(lab) > 1 for lab in pos + neg)
    sep = "," if wide else ""
    text = sep.join(pos)
    if neg:
        text += "-" + "-".join(neg)
    return text


class TrigStyle(str, Enum):
    """How sin and cos of joint angles print.

    >>> TrigStyle.parse("craig"), TrigStyle.parse("C1"), TrigStyle.parse("theta")
    (<TrigStyle.LOWER: 'c1'>, <TrigStyle.UPPER: 'C1'>, <TrigStyle.THETA: 'c_theta'>)
    """

    UPPER = "C1"  # C_1, S_{23}: the lectures here (IRob2305)
    LOWER = "c1"  # c_1, s_{23}: Craig, Spong
    THETA = "c_theta"  # c_{θ_1}, s_{θ_{23}} in LaTeX; c1, s23 in text

    @classmethod
    def parse(cls, value: object) -> TrigStyle:
        """Read ``C1``/``upper``/``lecture``, ``c1``/``lower``/``craig``/``spong`` or
        ``c_theta``/``theta``."""
        if isinstance(value, cls):
            return value
        text = str(value).strip()
        if text in ("C1", "c1"):
            return cls(text)
        synonyms = dict.fromkeys(("upper", "lecture", "lectures"), "C1")
        synonyms.update(dict.fromkeys(("lower", "craig", "spong"), "c1"))
        synonyms.update(dict.fromkeys(("c_theta", "ctheta", "theta", "c_θ"), "c_theta"))
        key = text.lower()
        if key not in synonyms:
            raise DHError(
                f"unknown notation {value!r}: expected C1 (C1, S23), c1 (c1, s23, Craig) "
                "or c_theta (c_{θ1})"
            )
        return cls(synonyms[key])


@dataclass(frozen=True)
class LegendEntry:
    """One abbreviation and what it stands for, in LaTeX and plain text."""

    latex: str
    meaning_latex: str
    text: str
    meaning_text: str


# --- the layout of one formula: signed products and brackets ----------------------------------


@dataclass(frozen=True)
class Product:
    """One term as printed: its sign, its coefficient and its factors in the policy's order.

    ``factors`` holds sympy leaves (symbols, cos/sin, powers) and bracketed
    :class:`Sum` s; ``whole`` is a term sympy prints itself (a fraction), positive.
    """

    negative: bool
    coeff: sp.Expr = sp.S.One
    factors: tuple[sp.Expr | Sum, ...] = ()
    whole: sp.Expr | None = None
    key: tuple[Any, ...] = field(default=(), compare=False)
    sines: int = 0

    def flipped(self) -> Product:
        """The same term with the opposite sign."""
        return replace(self, negative=not self.negative)

    @property
    def minus_signs(self) -> int:
        """How many minus signs the term shows (its own and its brackets')."""
        return int(self.negative) + sum(f.minus_signs for f in self.factors if isinstance(f, Sum))


@dataclass(frozen=True)
class Sum:
    """Terms in printed order; as a factor, a bracket of ``level`` (1 = innermost)."""

    terms: tuple[Product, ...]

    @cached_property
    def level(self) -> int:
        """1 for a bracket with no bracket inside, 2 around those, …"""
        inner = [f.level for t in self.terms for f in t.factors if isinstance(f, Sum)]
        return 1 + max(inner, default=0)

    @property
    def minus_signs(self) -> int:
        """How many minus signs the sum shows."""
        return sum(t.minus_signs for t in self.terms)

    @property
    def canonical(self) -> bool:
        """True when the term with the fewest sines (then the first in order) is positive."""
        return not min(self.terms, key=lambda t: (t.sines, t.key)).negative

    def negated(self) -> Sum:
        """The sum with every sign flipped, re-led by a positive term."""
        return _lead(t.flipped() for t in self.terms)


def _lead(terms: Iterable[Product]) -> Sum:
    """Terms in key order, the first positive one moved to the front (rule 3)."""
    ordered = sorted(terms, key=lambda t: t.key)
    if ordered[0].negative:
        pos = next((k for k, t in enumerate(ordered) if not t.negative), None)
        if pos is not None:
            ordered.insert(0, ordered.pop(pos))
    return Sum(tuple(ordered))


@dataclass(frozen=True)
class Token:
    """A piece of a printed formula.

    ``kind`` is ``atom``, ``sign`` (a leading minus), ``op`` (``+`` or ``-``, with a
    space each side, between terms: a line may break before it), ``open`` or ``close`` (a bracket
    of ``level``, ``tall`` when it holds a fraction or root); ``depth`` counts the
    brackets around the piece.
    """

    kind: str
    text: str
    depth: int
    level: int = 0
    tall: bool = False


_DELIMS = (("(", ")"), ("[", "]"), (r"\{", r"\}"))


def delimiter(tok: Token, latex: bool, broken: bool = False) -> str:
    r"""The bracket a token prints as: by level in LaTeX (``( [ \{``), ``(`` in text.

    A tall bracket is ``\left(``…``\right)`` on one line and ``\Bigl(`` when it
    spans lines (``\left`` cannot).
    """
    if not latex:
        return "(" if tok.kind == "open" else ")"
    pair = _DELIMS[(tok.level - 1) % 3]
    d = pair[0] if tok.kind == "open" else pair[1]
    if not tok.tall:
        return d
    side = "l" if tok.kind == "open" else "r"
    return f"\\Big{side}{d}" if broken else f"\\{'left' if side == 'l' else 'right'}{d}"


def render(tokens: Sequence[Token], latex: bool) -> str:
    """The tokens joined on one line."""
    return "".join(
        delimiter(t, latex) if t.kind in ("open", "close") else t.text for t in tokens
    ).strip()


# --- the notation -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Notation:
    """How to print: which symbols are joint angles, their labels, the case of C/S.

    Parameters
    ----------
    labels
        ``(symbol, label)`` pairs: cos of a sum of these prints as ``C_{label…}``.
    compact
        False prints the full ``cos``/``sin`` form.
    style
        :class:`TrigStyle` (or its name): ``C1`` (default), ``c1`` or ``c_theta``.
    decimals
        True for a table whose lengths are decimals: every finite decimal prints as
        one (``0.25*C12``, ``(p_x**2 + p_y**2 - 0.185)/0.175``), never as a fraction.
        A formula that holds a decimal (``0.35``) prints so anyway.
    """

    labels: tuple[tuple[sp.Symbol, str], ...] = ()
    compact: bool = True
    style: TrigStyle = TrigStyle.UPPER
    decimals: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "style", TrigStyle.parse(self.style))

    @classmethod
    def from_variables(
        cls,
        variables: Sequence[sp.Symbol],
        labels: Sequence[str] | None = None,
        **kw: Any,  # the other fields: compact, style
    ) -> Notation:
        """Notation whose joint angles are ``variables``, labelled 1, 2, … by default."""
        labs = (
            list(labels) if labels is not None else [str(i) for i in range(1, len(variables) + 1)]
        )
        return cls(tuple(zip(variables, labs)), **kw)

    @cached_property
    def label_map(self) -> dict[sp.Symbol, str]:
        """The labels as a dict."""
        return dict(self.labels)

    @cached_property
    def _joint_index(self) -> dict[sp.Symbol, int]:
        """Joint number of each angle: its label when it is a number, else its position."""
        return {s: int(lab) if lab.isdigit() else k for k, (s, lab) in enumerate(self.labels, 1)}

    def latex(self, expr: object) -> str:
        """LaTeX of ``expr`` (an expression or matrix) in this notation."""
        return _DHLatexPrinter(self).doprint(expr)

    def text(self, expr: object) -> str:
        """Plain text of ``expr`` in this notation."""
        return _DHStrPrinter(self).doprint(expr)

    def markdown(self, expr: object) -> str:
        """Inline Markdown math: ``$…$``."""
        return f"${self.latex(expr)}$"

    def tokens(self, expr: sp.Expr, latex: bool) -> list[Token]:
        """``expr`` printed as :class:`Token` s (what line breaking works on).

        >>> t1, a1 = sp.symbols("theta1 a1", real=True)
        >>> [t.text for t in Notation.from_variables([t1]).tokens(-a1 * sp.cos(t1) + 1, False)]
        ['1', ' - ', 'a1', '*C1']
        """
        printer = _DHLatexPrinter(self) if latex else _DHStrPrinter(self)
        expr = expr if isinstance(expr, sp.Basic) else as_expr(expr)  # text: whitelist parser
        printer._decimals = self.decimals or uses_decimals(expr)
        return printer.tokens(self.arrange(expr))

    def legend(self, exprs: Iterable[object]) -> list[LegendEntry]:
        """The abbreviations used in ``exprs``, in order of first appearance (sorted).

        >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
        >>> [e.text + " = " + e.meaning_text for e in
        ...  Notation.from_variables([t1, t2]).legend([sp.cos(t1 + t2) * sp.sin(t1)])]
        ['S1 = sin(theta1)', 'C12 = cos(theta1 + theta2)']
        """
        if not self.compact:
            return []
        atoms: set[sp.Expr] = set()
        for e in exprs:
            if isinstance(e, sp.Basic):
                atoms |= e.atoms(sp.cos, sp.sin)
        full = replace(self, compact=False)
        entries = {}
        for f in atoms:
            short = self.text(f)
            if short == full.text(f):
                continue
            entries[short] = LegendEntry(self.latex(f), full.latex(f), short, full.text(f))

        def order(item: tuple[str, LegendEntry]) -> tuple[bool, int, str]:
            name = item[0]
            return ("_" in name, len(name), name)

        return [entries[k] for k, _ in sorted(entries.items(), key=order)]

    # how one cos/sin prints -------------------------------------------------------
    def _short(self, func: sp.Expr, latex: bool) -> str | None:
        if not self.compact:
            return None
        arg = func.args[0]
        cos = isinstance(func, sp.cos)
        lab = angle_label(arg, self.label_map)
        if lab is not None:
            upper = self.style is TrigStyle.UPPER
            letter = ("C" if cos else "S") if upper else ("c" if cos else "s")
            if latex and self.style is TrigStyle.THETA:
                return f"{letter}_{{{_angle_head(arg)}_{{{lab}}}}}"
            if latex:
                return f"{letter}_{{{lab}}}"
            return f"{letter}[{lab}]" if "-" in lab else f"{letter}{lab}"
        if isinstance(arg, sp.Symbol):
            small = "c" if cos else "s"
            if latex:
                return f"{small}_{{{sp.latex(arg)}}}"
            return f"{small}_{arg.name}"
        return None

    # the order of the policy -------------------------------------------------------
    def arrange(self, expr: sp.Expr) -> Sum:
        """``expr`` laid out by the term-order policy (the module docstring): a :class:`Sum`.

        >>> t = sp.symbols("theta1:4", real=True)
        >>> c, s = [sp.cos(x) for x in t], [sp.sin(x) for x in t]
        >>> tree = Notation.from_variables(t).arrange((s[1] * s[2] - c[1] * c[2]) * s[0])
        >>> [(p.negative, len(p.factors)) for p in tree.terms]
        [(True, 2)]
        """
        if expr.is_Add:
            return _lead(self._term(t) for t in expr.args)
        return Sum((self._term(expr),))

    def _index(self, s: sp.Symbol) -> int:
        if s in self._joint_index:
            return self._joint_index[s]
        digits = s.name[len(s.name.rstrip("0123456789")) :]  # a trailing index, linear time
        return int(digits[-18:]) if digits else 0

    def _angle(self, arg: sp.Expr) -> tuple[int, ...] | None:
        """Joint numbers of a sum of joint angles (``θ2 + θ3`` → (2, 3)), None otherwise."""
        if angle_label(arg, self.label_map) is None:
            return None
        coeffs = arg.as_coefficients_dict()
        pos = sorted(self._joint_index[s] for s, c in coeffs.items() if c == 1)
        neg = sorted(self._joint_index[s] for s, c in coeffs.items() if c == -1)
        return tuple(pos + neg)

    @cached_property
    def _factor_keys(self) -> dict[sp.Expr, tuple[Any, ...]]:
        return {}  # a memo of _factor_key: the same few leaves recur in every entry

    def _factor_key(self, f: sp.Expr) -> tuple[Any, ...]:
        """(group, index, letter, name): number, symbol, joint trig, other trig, other, bracket."""
        key = self._factor_keys.get(f)
        if key is None:
            key = self._factor_keys[f] = self._compute_factor_key(f)
        return key

    def _compute_factor_key(self, f: sp.Expr) -> tuple[Any, ...]:
        base, exp = (f.base, f.exp) if f.is_Pow else (f, 1)
        name = (getattr(base, "name", ""), str(exp))  # ties: a2 before d2, S1 before S1**2
        if f.is_number:
            return (0, (), 0, name)
        if isinstance(base, (sp.cos, sp.sin)):
            letter = 0 if isinstance(base, sp.cos) else 1
            joints = self._angle(base.args[0])
            if joints is not None:
                return (2, joints, letter, name)
            index = tuple(sorted(self._index(s) for s in base.free_symbols))
            return (3, index, letter, name)
        if isinstance(base, sp.Symbol):
            return (1, (self._index(base),), 0, name)
        if base.is_Add:
            return (5, (), 0, name)
        return (4, tuple(sorted(self._index(s) for s in f.free_symbols)), 0, name)

    def _term_key(self, factors: Sequence[sp.Expr | Sum], whole: sp.Expr | None) -> tuple[Any, ...]:
        """Rule 3: the indices of the printed factors, a bracket by its first term."""
        index: list[tuple[int, ...]] = []
        letters: list[tuple[int, int]] = []
        if whole is not None:
            syms = sorted(whole.free_symbols, key=lambda s: (self._index(s), s.name))
            return (not syms, [(self._index(s),) for s in syms], [], str(whole))
        for f in factors:
            if isinstance(f, Sum):
                first = f.terms[0].key
                index += first[1]
                letters += first[2]
                continue
            k = self._factor_key(f)
            if k[0] == 0:
                continue
            index.append(k[1])
            letters.append((k[0], k[2]))
        return (not index, index, letters, "")

    def _term(self, term: sp.Expr) -> Product:
        coeff, rest = term.as_coeff_Mul()
        negative = bool(coeff.is_negative)
        coeff = -coeff if negative else coeff
        factors = list(sp.Mul.make_args(rest)) if rest != 1 else []
        plain = (
            not factors
            or not term.is_commutative
            or any(f.is_Pow and f.exp.is_negative for f in factors)
        )
        if plain:
            whole = -term if negative else term
            return Product(negative, whole=whole, key=self._term_key((), whole))
        brackets = [self.arrange(f) for f in factors if f.is_Add]
        leaves = sorted((f for f in factors if not f.is_Add), key=self._factor_key)
        negative, brackets = _orient(negative, brackets)
        brackets.sort(key=lambda b: b.terms[0].key)
        ordered = (*leaves, *brackets)
        sines = sum(isinstance(f.base if f.is_Pow else f, sp.sin) for f in leaves)
        return Product(negative, coeff, ordered, key=self._term_key(ordered, None), sines=sines)


def _orient(negative: bool, brackets: list[Sum]) -> tuple[bool, list[Sum]]:
    """Rule 4: sign the brackets of one product (inner ones canonical, outer ones frugal)."""
    options = [
        [b if b.canonical else b.negated()] if b.level == 1 else [b, b.negated()] for b in brackets
    ]
    if len(options) > 4:  # more brackets than anyone writes: inner ones only
        options = [o[:1] for o in options]
    best: tuple[Any, ...] | None = None
    choice: tuple[bool, list[Sum]] = (negative, brackets)
    for bs in _combinations(*options):
        flips = sum(b is not orig for b, orig in zip(bs, brackets))
        neg = negative ^ (flips % 2 == 1)
        score = (int(neg) + sum(b.minus_signs for b in bs), -sum(b.canonical for b in bs), flips)
        if best is None or score < best:
            best, choice = score, (neg, list(bs))
    return choice


def _coefficient(c: sp.Expr, decimals: bool = False) -> str | None:
    """A coefficient as printed before its factors: ``2``, ``0.15005``; None for 1/3.

    With ``decimals`` (a formula whose lengths are decimals) every finite decimal prints
    as one (``0.25``, not ``1/4``), so that fractions and decimals never mix.
    """
    if c.is_Integer:
        return str(c)
    if c.is_Rational:
        return exact_decimal(c) if decimals or c.q % 10 == 0 else None
    return None


def uses_decimals(expr: object) -> bool:
    """True when ``expr`` (an expression or matrix) holds a number written as a decimal
    (a denominator divisible by 10: ``0.35`` is 7/20): then the whole formula prints its
    finite decimals as decimals.

    >>> uses_decimals(sp.Rational(7, 20) * sp.Symbol("x") + sp.Rational(1, 4))
    True
    >>> uses_decimals(sp.Symbol("x") / 4)
    False
    """
    atoms = expr.atoms(sp.Rational) if isinstance(expr, sp.Basic) else set()
    if isinstance(expr, sp.MatrixBase):
        atoms = set().union(*(e.atoms(sp.Rational) for e in expr))
    return any(r.q % 10 == 0 for r in atoms)


def decimal_lengths(values: Iterable[sp.Expr]) -> bool:
    """True when a length is a number that is not whole but a finite decimal (``0.25``):
    the table's lengths were written as decimals, so its formulas print decimals.

    >>> decimal_lengths([sp.Rational(7, 20), sp.Symbol("d3")]), decimal_lengths([sp.Integer(1)])
    (True, False)
    """
    return any(
        not r.is_Integer and exact_decimal(r) is not None
        for v in values
        for r in (v.atoms(sp.Rational) if isinstance(v, sp.Basic) else ())
    )


def _number(t: Product) -> sp.Expr:
    """The number of a term: its coefficient, or the term itself when it is a number."""
    return t.whole if t.whole is not None and not t.factors else t.coeff


def _scaled(t: Product, k: sp.Rational) -> Product:
    if t.whole is not None and not t.factors:
        return replace(t, whole=t.whole * k)
    return replace(t, coeff=t.coeff * k)


def _decimal_terms(p: Product) -> tuple[Sum, sp.Rational] | None:
    """A number times a bracket, written with decimals: the bracket with the number
    multiplied in (``0.05*(5*C2 + 7)`` is ``0.25*C2 + 0.35``), divisor 1; or the bracket led
    by 1 and a decimal divisor (``(200x + 200y - 37)/35`` is ``(x + y - 0.185)/0.175``)."""
    c = p.coeff
    if not (c.is_Rational and len(p.factors) == 1 and isinstance(p.factors[0], Sum)):
        return None
    terms = p.factors[0].terms
    if any(not _number(t).is_Rational for t in terms):
        return None
    for m, divisor in [(1 / c, sp.Integer(1))] + [(_number(t), None) for t in terms]:
        inner = [_scaled(t, 1 / m) for t in terms]
        outer = divisor if divisor is not None else 1 / (c * m)
        if all(exact_decimal(_number(t)) is not None for t in inner) and exact_decimal(outer):
            return Sum(tuple(inner)), outer
    return None


def _angle_head(arg: sp.Expr) -> str:
    r"""``\theta`` for angles θ1, θ2…, ``q`` for q1, q2… (the letter of the joint variables)."""
    names = {re.match(r"[A-Za-z]*", s.name).group(0) for s in arg.free_symbols}  # type: ignore[union-attr]  # `*`: always a match
    return sp.latex(sp.Symbol(names.pop())) if len(names) == 1 and "" not in names else r"\theta"


if TYPE_CHECKING:  # the mixin's methods call sympy's printer, next in the MRO
    from sympy.printing.printer import Printer as _PrinterBase
else:
    _PrinterBase = object


class _LayoutMixin(_PrinterBase):
    """Tokens of an arranged formula; shared by the LaTeX and the text printer."""

    _nota: Notation
    _latex: bool
    _print: Callable[..., str]  # sympy's Printer._print
    _decimals: bool = False

    def doprint(self, expr: object) -> str:
        """Print ``expr``; a formula with decimal lengths prints every finite decimal as one."""
        self._decimals = self._nota.decimals or uses_decimals(expr)
        return str(super().doprint(expr))

    def _print_Rational(self, expr: sp.Rational) -> str:
        dec = exact_decimal(expr) if expr.q > 1 else None
        return dec if dec is not None else str(super()._print_Rational(expr))

    def _print_Add(self, expr: sp.Add, order: object = None) -> str:
        return self._layout(expr)

    def _print_Mul(self, expr: sp.Mul) -> str:
        return self._layout(expr)

    def _print_whole(self, expr: sp.Expr) -> str:
        """A term sympy prints itself (a fraction): sympy's own ``_print_Mul``."""
        return str(super()._print_Mul(expr)) if expr.is_Mul else self._print(expr)

    def tokens(self, tree: Sum, depth: int = 0) -> list[Token]:
        """The tokens of ``tree`` (from :meth:`Notation.arrange`)."""
        out: list[Token] = []
        for k, term in enumerate(tree.terms):
            if k == 0:
                if term.negative:
                    out.append(Token("sign", "-", depth))
            else:
                out.append(Token("op", " - " if term.negative else " + ", depth))
            out += self._product_tokens(term, depth)
        return out

    def _product_tokens(self, p: Product, depth: int) -> list[Token]:
        if p.whole is not None:
            return [Token("atom", self._print_whole(p.whole), depth)]
        c = p.coeff
        if self._decimals and (dec := _decimal_terms(p)) is not None:
            inner, divisor = dec
            if divisor == 1:
                return self.tokens(inner, depth)
            bracket = [Token("open", "(", depth, inner.level, False)]
            bracket += self.tokens(inner, depth + 1)
            bracket.append(Token("close", ")", depth, inner.level, False))
            below = exact_decimal(divisor)
            if self._latex:
                top = render(self.tokens(inner, depth), True)
                return [Token("atom", rf"\frac{{{top}}}{{{below}}}", depth)]
            return [*bracket, Token("atom", f"/{below}", depth)]
        if c.is_Rational and not c.is_Integer and _coefficient(c, self._decimals) is None:
            top = render(
                self._product_tokens(replace(p, coeff=sp.Integer(c.p)), depth), self._latex
            )
            q = int(c.q)
            return [
                Token("atom", rf"\frac{{{top}}}{{{q}}}" if self._latex else f"{top}/{q}", depth)
            ]
        out: list[Token] = []
        sep = " " if self._latex else "*"
        lead = _coefficient(c, self._decimals) if c.is_Rational else None
        if c != 1:
            out.append(Token("atom", lead if lead is not None else self._print(c), depth))
        for f in p.factors:
            joint = sep if out else ""
            if isinstance(f, Sum):
                pieces = self.tokens(f, depth + 1)
                tall = self._latex and any(r"\frac" in t.text or r"\sqrt" in t.text for t in pieces)
                if out:  # the same pieces in both formats; in LaTeX a space after a
                    gap = " " if out[-1].kind == "close" else ""  # bracket: no Markdown ](
                    out.append(Token("atom", gap if self._latex else "*", depth))
                out.append(Token("open", "(", depth, f.level, tall))
                out += pieces
                out.append(Token("close", ")", depth, f.level, tall))
            else:
                out.append(Token("atom", joint + self._print(f), depth))
        return out

    def _layout(self, expr: sp.Expr) -> str:
        return render(self.tokens(self._nota.arrange(expr)), self._latex)


#: ``lc1``, ``lc_2``: the distance to a link's centre of mass (Spong's ℓ_{ci})
_CENTRE_LENGTH = re.compile(r"^lc_?(\d+)$")


class _OrderedLatexPrinter(_LayoutMixin, LatexPrinter):
    """sympy's LaTeX in the policy's order (cos and sin in full)."""

    _latex = True

    def __init__(self, notation: Notation) -> None:
        super().__init__({"mat_str": "bmatrix", "mat_delim": ""})
        self._nota = notation

    def _print_Symbol(self, expr: sp.Symbol, style: str = "plain") -> str:
        """``lc1`` (a centre-of-mass length, Spong's ℓ_{c1}) as ``l_{c1}``, not ``lc_{1}``,
        which reads as ``l·c₁`` beside the C/S notation; other names as sympy prints them."""
        m = _CENTRE_LENGTH.match(expr.name)
        if m:
            expr = sp.Symbol(f"l_c{m.group(1)}", **expr.assumptions0)
        return str(super()._print_Symbol(expr, style))

    def _print_atan2(self, expr: sp.atan2, exp: str | None = None) -> str:
        y, x = (self._print(a) for a in expr.args)
        head = r"\operatorname{atan2}" + (f"^{{{exp}}}" if exp else "")
        return rf"{head}\left({y}, {x}\right)"


class _DHLatexPrinter(_OrderedLatexPrinter):
    """The lecture's LaTeX: ``C_{12}``, ``s_{\alpha_{1}}``."""

    def _print_trig(self, expr: sp.Expr, exp: str | None) -> str:
        short = self._nota._short(expr, latex=True)
        if short is None:  # sympy's _print_Function would call _print_cos again
            return _OrderedLatexPrinter(self._nota)._print(expr, exp=exp)
        return f"{short}^{{{exp}}}" if exp else short

    def _print_cos(self, expr: sp.Expr, exp: str | None = None) -> str:
        return self._print_trig(expr, exp)

    def _print_sin(self, expr: sp.Expr, exp: str | None = None) -> str:
        return self._print_trig(expr, exp)


class _DHStrPrinter(_LayoutMixin, StrPrinter):
    _latex = False

    def __init__(self, notation: Notation) -> None:
        super().__init__()
        self._nota = notation

    def _print_trig(self, expr: sp.Expr) -> str:
        short = self._nota._short(expr, latex=False)
        return short if short is not None else StrPrinter._print_Function(self, expr)

    _print_cos = _print_trig
    _print_sin = _print_trig

    def _print_Equality(self, expr: sp.Equality) -> str:
        return f"{self._print(expr.lhs)} = {self._print(expr.rhs)}"

    def _print_Abs(self, expr: sp.Abs) -> str:
        return f"|{self._print(expr.args[0])}|"


# --- tables ---------------------------------------------------------------------------


def format_angle(value: sp.Expr, degrees: bool, latex: bool = True) -> str:
    """An angle entry for display, in degrees (``90^\\circ``) or radians.

    >>> q = sp.Symbol("q3", real=True)
    >>> format_angle(q + sp.pi / 2, degrees=True)
    'q_{3} + 90^{\\\\circ}'
    >>> format_angle(-sp.pi / 2, degrees=True, latex=False)
    '-90°'
    """
    if not degrees:
        return str(sp.latex(value) if latex else sp.sstr(value))
    sym_part = sp.Add(*[t for t in sp.Add.make_args(value) if t.free_symbols])
    const = sp.nsimplify(sp.expand((value - sym_part) * 180 / sp.pi))
    deg = exact_decimal(const) if isinstance(const, sp.Rational) and const.q > 1 else None
    deg = deg or str(const)
    unit = "^{\\circ}" if latex else "°"
    head = str(sp.latex(sym_part) if latex else sp.sstr(sym_part))
    if sym_part == 0:
        return f"{deg}{unit}" if const != 0 else "0"
    if const == 0:
        return head
    sign = "-" if str(deg).startswith("-") else "+"
    return f"{head} {sign} {str(deg).lstrip('-')}{unit}"
