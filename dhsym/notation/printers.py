"""Lecture notation: ``C_{12}`` for cos(θ1+θ2), ``S_1`` for sin θ1, ``c_{α_1}`` for cos α1.

The printers are subclasses of sympy's own ``StrPrinter`` and ``LatexPrinter``
that override only ``_print_cos`` and ``_print_sin``; everything else (sums,
products, fractions, matrices) is sympy's printing.

Examples
--------
>>> import sympy as sp
>>> t1, t2, a1, a2 = sp.symbols("theta1 theta2 a1 a2", real=True)
>>> nota = Notation.from_variables([t1, t2])
>>> e = a1 * sp.cos(t1) + a2 * sp.cos(t1 + t2)
>>> nota.text(e)
'a1*C1 + a2*C12'
>>> nota.latex(e)
'a_{1} C_{1} + a_{2} C_{12}'
>>> print(Notation.from_variables([t1, t2], compact=False).latex(sp.cos(t1 + t2)))
\\cos{\\left(\\theta_{1} + \\theta_{2} \\right)}
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.str import StrPrinter

from dhsym.model.entries import exact_decimal

__all__ = [
    "LegendEntry",
    "Notation",
    "angle_label",
    "format_angle",
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
    pos, neg = [], []
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


@dataclass(frozen=True)
class LegendEntry:
    """One abbreviation and what it stands for, in LaTeX and plain text."""

    latex: str
    meaning_latex: str
    text: str
    meaning_text: str


@dataclass(frozen=True)
class Notation:
    """How to print trigonometric terms: which symbols are joint angles, and their labels.

    Parameters
    ----------
    labels
        ``(symbol, label)`` pairs: cos of a sum of these prints as ``C_{label…}``.
    compact
        False prints the full ``cos``/``sin`` form.
    upper
        ``C_1``/``S_1`` (IRob2305 Lecture 5) when True, ``c_1``/``s_1`` (Craig) when False.
    """

    labels: tuple[tuple[sp.Symbol, str], ...] = ()
    compact: bool = True
    upper: bool = True

    @classmethod
    def from_variables(
        cls, variables: Sequence[sp.Symbol], labels: Sequence[str] | None = None, **kw: bool
    ) -> Notation:
        """Notation whose joint angles are ``variables``, labelled 1, 2, … by default."""
        labs = (
            list(labels) if labels is not None else [str(i) for i in range(1, len(variables) + 1)]
        )
        return cls(tuple(zip(variables, labs)), **kw)

    @property
    def label_map(self) -> dict[sp.Symbol, str]:
        """The labels as a dict."""
        return dict(self.labels)

    def latex(self, expr: object) -> str:
        """LaTeX of ``expr`` (an expression or matrix) in this notation."""
        return _DHLatexPrinter(self).doprint(expr)

    def text(self, expr: object) -> str:
        """Plain text of ``expr`` in this notation."""
        return _DHStrPrinter(self).doprint(expr)

    def markdown(self, expr: object) -> str:
        """Inline Markdown math: ``$…$``."""
        return f"${self.latex(expr)}$"

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
        full = Notation(self.labels, compact=False, upper=self.upper)
        entries = {}
        for f in atoms:
            short = self.text(f)
            if short == full.text(f):
                continue
            entries[short] = LegendEntry(self.latex(f), full.latex(f), short, full.text(f))

        def order(item: tuple[str, LegendEntry]) -> tuple[int, int, str]:
            name = item[0]
            return (name[:1].islower(), len(name), name)

        return [entries[k] for k, _ in sorted(entries.items(), key=order)]

    # how one cos/sin prints -------------------------------------------------------
    def _short(self, func: sp.Expr, latex: bool) -> str | None:
        if not self.compact:
            return None
        arg = func.args[0]
        letter = "C" if isinstance(func, sp.cos) else "S"
        lab = angle_label(arg, self.label_map)
        if lab is not None:
            letter = letter if self.upper else letter.lower()
            if latex:
                return f"{letter}_{{{lab}}}"
            return f"{letter}[{lab}]" if "-" in lab else f"{letter}{lab}"
        if isinstance(arg, sp.Symbol):
            small = letter.lower()
            if latex:
                return f"{small}_{{{sp.latex(arg)}}}"
            return f"{small}_{arg.name}"
        return None


class _DHLatexPrinter(LatexPrinter):
    def __init__(self, notation: Notation) -> None:
        settings = {"mat_str": "bmatrix", "mat_delim": ""}
        super().__init__(settings)
        self._nota = notation
        self._plain = LatexPrinter(settings)

    def _print_trig(self, expr: sp.Expr, exp: str | None) -> str:
        short = self._nota._short(expr, latex=True)
        if short is None:
            return self._plain._print(expr, exp=exp)
        return f"{short}^{{{exp}}}" if exp else short

    def _print_cos(self, expr: sp.Expr, exp: str | None = None) -> str:
        return self._print_trig(expr, exp)

    def _print_sin(self, expr: sp.Expr, exp: str | None = None) -> str:
        return self._print_trig(expr, exp)

    def _print_Rational(self, expr: sp.Rational) -> str:
        dec = exact_decimal(expr) if expr.q > 1 else None
        return dec if dec is not None else super()._print_Rational(expr)

    def _print_Mul(self, expr: sp.Mul) -> str:
        return _decimal_mul(self, expr, " ") or super()._print_Mul(expr)


def _decimal(r: sp.Rational) -> str | None:
    """Decimal text of a lecture number like 3001/20000 (denominator a multiple of 10)."""
    return exact_decimal(r) if r.q > 1 and r.q % 10 == 0 else None


def _decimal_mul(printer: StrPrinter | LatexPrinter, expr: sp.Mul, sep: str) -> str | None:
    """``0.15005*theta1`` instead of ``3001*theta1/20000``; None when not applicable."""
    coeff, rest = expr.as_coeff_Mul()
    dec = _decimal(coeff) if isinstance(coeff, sp.Rational) else None
    if dec is None or rest == 1:
        return None
    body = printer._print(rest)
    if rest.is_Add:
        body = rf"\left({body}\right)" if sep == " " else f"({body})"
    return f"{dec}{sep}{body}"


class _DHStrPrinter(StrPrinter):
    def __init__(self, notation: Notation) -> None:
        super().__init__()
        self._nota = notation
        self._plain = StrPrinter()

    def _print_trig(self, expr: sp.Expr) -> str:
        short = self._nota._short(expr, latex=False)
        return short if short is not None else self._plain._print(expr)

    _print_cos = _print_trig
    _print_sin = _print_trig

    def _print_Rational(self, expr: sp.Rational) -> str:
        dec = exact_decimal(expr) if expr.q > 1 else None
        return dec if dec is not None else super()._print_Rational(expr)

    def _print_Mul(self, expr: sp.Mul) -> str:
        return _decimal_mul(self, expr, "*") or super()._print_Mul(expr)


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
        return sp.latex(value) if latex else sp.sstr(value)
    sym_part = sp.Add(*[t for t in sp.Add.make_args(value) if t.free_symbols])
    const = sp.nsimplify(sp.expand((value - sym_part) * 180 / sp.pi))
    deg = exact_decimal(const) if isinstance(const, sp.Rational) and const.q > 1 else None
    deg = deg or str(const)
    unit = "^{\\circ}" if latex else "°"
    head = sp.latex(sym_part) if latex else sp.sstr(sym_part)
    if sym_part == 0:
        return f"{deg}{unit}" if const != 0 else "0"
    if const == 0:
        return head
    sign = "-" if str(deg).startswith("-") else "+"
    return f"{head} {sign} {str(deg).lstrip('-')}{unit}"
