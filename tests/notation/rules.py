"""An independent reader of printed entries that checks the textbook rules of issue 11.

It reads the *text* the printers produce (``C1*(C23*(C4*C5*C6 - S4*S6) - S23*S5*C6)``),
not the printer's own data, so a test built on it can fail when the printer is wrong.
The three rules:

* ``factor``: in a product, every factor is written before the bracket(s) it multiplies;
* ``order``: in a product, lengths (and other plain symbols) come before trig factors,
  lengths by index, trig factors by joint (``S23*S5*C6``), C before S on the same joint;
* ``lead``: a sum that has a positive term starts with one.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

_TOKEN = re.compile(
    r"\s*(\*\*|[-+*/()]|[A-Za-z_][A-Za-z0-9_]*(?:\{[^}]*\}|\[[0-9,\-]+\]|(?:,[0-9]+)+)?|[0-9.]+)"
)
_TRIG = re.compile(r"^(?P<f>[CScs])(?:_theta)?(?P<lab>[0-9,]+|\[[0-9,\-]+\])$")
_INDEX = re.compile(r"([0-9]+)$")


@dataclass
class Sum:
    """Terms as (negative, Product)."""

    terms: list[tuple[bool, Product]] = field(default_factory=list)


@dataclass
class Product:
    """Factors: atom strings or bracketed Sums."""

    factors: list[object] = field(default_factory=list)


class _Reader:
    def __init__(self, text: str) -> None:
        self.toks = [m.group(1) for m in _TOKEN.finditer(text)]
        if "".join(self.toks) != re.sub(r"\s+", "", text):
            raise ValueError(f"cannot read {text!r}")
        self.k = 0

    def peek(self) -> str | None:
        return self.toks[self.k] if self.k < len(self.toks) else None

    def take(self) -> str:
        self.k += 1
        return self.toks[self.k - 1]

    def sum(self) -> Sum:
        s = Sum()
        neg = False
        if self.peek() == "-":
            self.take()
            neg = True
        s.terms.append((neg, self.product()))
        while self.peek() in ("+", "-"):
            neg = self.take() == "-"
            s.terms.append((neg, self.product()))
        return s

    def product(self) -> Product:
        p = Product([self.factor()])
        while self.peek() in ("*", "/"):
            op = self.take()
            f = self.factor()
            p.factors.append(f if op == "*" else ("/", f))
        return p

    def factor(self) -> object:
        tok = self.take()
        if tok == "(":
            inner = self.sum()
            if self.take() != ")":
                raise ValueError("unbalanced")
            out: object = inner
        elif tok == "-":  # a minus inside a product: -(…)*x never appears, but be safe
            out = ("neg", self.factor())
        else:
            out = tok
            if self.peek() == "(":  # a function call: cos(…)
                self.take()
                args = self.sum()
                self.take()
                out = (tok, args)
        if self.peek() == "**":
            self.take()
            out = ("pow", out, self.factor())
        return out


def read(text: str) -> Sum:
    """The printed text as a tree of sums and products."""
    r = _Reader(text)
    s = r.sum()
    if r.peek() is not None:
        raise ValueError(f"trailing {r.peek()!r} in {text!r}")
    return s


def _atom(f: object) -> str | None:
    if isinstance(f, tuple) and f and f[0] == "pow":
        return _atom(f[1])
    return f if isinstance(f, str) else None


def _key(name: str) -> tuple[int, tuple[int, ...], int] | None:
    """(group, index, letter) of a factor; None for numbers and calls."""
    if re.fullmatch(r"[0-9.]+", name):
        return None
    m = _TRIG.match(name)
    if m:
        lab = m["lab"].strip("[]")
        parts = re.split(r"[,\-]", lab) if "," in lab else list(lab.replace("-", ""))
        nums = tuple(int(x) for x in parts if x)
        return (2, nums, 0 if m["f"] in "Cc" else 1)
    if re.match(r"^[cs]_", name):  # c_alpha1: a twist, after the joint angles
        idx = _INDEX.search(name)
        return (3, (int(idx.group(1)),) if idx else (), 0 if name[0] == "c" else 1)
    idx = _INDEX.search(name)
    return (1, (int(idx.group(1)),) if idx else (0,), 0)


def violations(text: str) -> list[str]:
    """The rules that ``text`` breaks, one message per place."""
    out: list[str] = []

    def visit_sum(s: Sum) -> None:
        if s.terms[0][0] and not all(neg for neg, _ in s.terms):
            out.append("lead")
        for _, p in s.terms:
            visit_product(p)

    def visit_product(p: Product) -> None:
        seen_bracket = False
        keys = []
        for f in p.factors:
            if isinstance(f, Sum):
                seen_bracket = True
                visit_sum(f)
                continue
            if isinstance(f, tuple) and f[0] == "/":
                continue
            if seen_bracket:
                out.append("factor")
            name = _atom(f)
            k = _key(name) if name else None
            if k is not None:
                keys.append(k)
            if isinstance(f, tuple) and len(f) == 2 and isinstance(f[1], Sum):
                visit_sum(f[1])  # the argument of a call
        if keys != sorted(keys):
            out.append("order")

    visit_sum(read(text))
    return out


def nontrivial(text: str) -> bool:
    """An entry worth checking: a product or a sum, not a lone (signed) atom."""
    return bool(re.search(r"[*+]| - ", text.lstrip("-")))
