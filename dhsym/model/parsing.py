"""Whitelist parser: text typed by users into sympy expressions, never ``eval``.

The only way text enters the engine (DH tables, homework answers).  A hand-written
tokenizer and a depth-checked recursive-descent parser build sympy ``Add``, ``Mul``,
``Pow``, ``Rational``, real ``Symbol``, ``pi`` and ``sin cos tan sqrt atan2`` (also spelt
``Atan2``, as Craig, and ``arctan2``, as numpy; and the inverse functions ``atan asin acos``,
also spelt ``arctan arcsin arccos`` and, in textbook mode, ``tan^-1 sin^-1 cos^-1``) only::

    expr   := term (('+' | '-') term)*
    term   := factor (('*' | '/') factor | factor)*      # juxtaposition multiplies
    factor := ('+' | '-') factor | atom ('^' factor)?    # '**' is '^'; -x^2 is -(x^2)
    atom   := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'

With ``textbook=True`` (answers) it also reads what textbooks print: ``atom '°'`` (degrees,
binding to that atom only), ``sin^2(x)`` and ``sin^2 x`` (a power of the function), arguments
without brackets (``sin x``, ``cos 2θ1``, ``sin 90°``: a number, a name, or a number and a
name) and a coefficient glued to a function (``a1cos(q1)``).  Every numeric literal has at most
``max_digits`` digits and a bounded decimal exponent, checked before any arithmetic.
"""

from __future__ import annotations

import keyword
import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, NamedTuple

import sympy

from dhsym.errors import DHError, ParseError

__all__ = [
    "DEFAULT_LIMITS",
    "REAL",
    "ParseLimits",
    "check_count",
    "normalize_name",
    "numeral_problem",
    "parse_expression",
    "parse_number_list",
    "rate_symbols",
    "reserved_symbols",
    "symbol",
]

_GREEK_NAMES = (  # lower case, upper case ('Θ' is 'theta' too), variant forms
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi omicron pi rho sigma "
    "tau upsilon phi chi psi omega " * 2 + "sigma theta phi epsilon rho mu"
).split()
_GREEK_LETTERS = "αβγδεζηθικλμνξοπρστυφχψωΑΒΓΔΕΖΗΘΙΚΛΜΝΞΟΠΡΣΤΥΦΧΨΩςϑϕϵϱµ"
_GREEK = MappingProxyType(dict(zip(map(ord, _GREEK_LETTERS), _GREEK_NAMES, strict=True)))
_LETTERS = "A-Za-z_" + re.escape(_GREEK_LETTERS)
_TOKEN = re.compile(  # explicit ASCII classes: \d and \w would accept any Unicode digit/letter
    r"(?P<space>[ \t\r\n]+)"
    r"|(?P<num>(?=\.?[0-9])(?P<whole>[0-9]*)(?:\.(?P<frac>[0-9]*))?(?:[eE](?P<exp>[+-]?[0-9]+))?)"
    rf"|(?P<name>[{_LETTERS}][{_LETTERS}0-9]*)|(?P<op>\*\*|[-+*/^(),°])"
)
_GLUED_CALL = re.compile(r"^(?P<head>.*[0-9])(?P<func>atan2|cos|sin|sqrt|tan)$")  # a1cos(…)
_FUNCTIONS: MappingProxyType[str, tuple[Callable[..., sympy.Expr], int]] = MappingProxyType(
    {"atan2": (sympy.atan2, 2), "cos": (sympy.cos, 1), "sin": (sympy.sin, 1)}
    | {"sqrt": (sympy.sqrt, 1), "tan": (sympy.tan, 1)}
    # inverse functions: answers to inverse-kinematics questions (atan where atan2 belongs)
    | {"atan": (sympy.atan, 1), "asin": (sympy.asin, 1), "acos": (sympy.acos, 1)}
    | {"arctan": (sympy.atan, 1), "arcsin": (sympy.asin, 1), "arccos": (sympy.acos, 1)}
    # atan2 as Craig (Atan2) and numpy (arctan2) spell it
    | {"Atan2": (sympy.atan2, 2), "arctan2": (sympy.atan2, 2)}
)
#: ``cos^-1 x`` in textbook mode is the inverse function, as textbooks write it
_INVERSE_OF = MappingProxyType({"sin": "asin", "cos": "acos", "tan": "atan"})
_NON_FINITE_NAMES = frozenset({"nan", "inf", "infinity", "oo", "zoo"})
_BUILTINS = "eval exec compile open input globals locals vars getattr setattr delattr breakpoint"
_RESERVED = frozenset([*keyword.kwlist, *_BUILTINS.split()]) - {"lambda"}  # λ is 'lambda'
_NON_FINITE = (sympy.S.ComplexInfinity, sympy.S.NaN, sympy.S.Infinity, sympy.S.NegativeInfinity)
_Resolve = Callable[[str], "sympy.Expr | None"]
_CHARS = "expected a number, name, operator (+ - * / ^ **), '(', ')' or ','"
_ALLOWED = "allowed: " + ", ".join(_FUNCTIONS)
_ATOM = "expected a number, name or '('"
_FINITE = "expected a finite value"
_MINUS = sympy.S.NegativeOne
_DEGREE = sympy.pi / 180
_Literal = Callable[[str, sympy.Rational], sympy.Expr]


@dataclass(frozen=True)
class ParseLimits:
    """Resource limits of :func:`parse_expression`; each one is a positive ``int``."""

    max_length: int = 20_000  # characters of input
    max_depth: int = 60  # nesting of parentheses, signs, powers and calls
    max_nodes: int = 5_000  # tokens
    max_digits: int = 40  # digits in one numeric literal
    max_exponent: int = 64  # |p| and q of any exponent p/q, after sympy merges powers
    max_symbols: int = 100  # distinct names
    max_result_digits: int = 400  # digits of any number computed on the way

    def __post_init__(self) -> None:
        for name, value in vars(self).items():
            if type(value) is not int or value < 1:
                raise ValueError(f"ParseLimits.{name} must be a positive int, got {value!r}")


DEFAULT_LIMITS = ParseLimits()


_NUMERAL = re.compile(r"(?P<whole>[0-9]*)(?:\.(?P<frac>[0-9]*))?(?:[eE](?P<exp>[+-]?[0-9]+))?")


def numeral_problem(text: str, limits: ParseLimits = DEFAULT_LIMITS) -> tuple[str, str] | None:
    """(what was found, what was expected) when a decimal literal is too long or too large.

    Every literal -- in tables, answers and on the command line -- has at most
    ``max_digits`` digits (exponent included) and a decimal exponent small enough that its
    exact value has at most ``max_result_digits`` digits, whatever its mantissa (``0e99999``
    too).  Checked on the text, before any arithmetic.

    >>> numeral_problem("0.4318") is None, numeral_problem("1e-300") is None
    (True, True)
    >>> numeral_problem("0e99999999999")
    ("number '0e99999999999' with exponent 99999999999", 'expected an exponent between -399 and 399 (max_result_digits=400)')
    >>> numeral_problem("9" * 41)[1]
    'expected at most max_digits=40'
    """  # noqa: E501
    m = _NUMERAL.fullmatch(text.strip().lstrip("+-"))
    if m is None or not (m["whole"] or m["frac"]):
        return (f"invalid number {text!r}", "expected digits, a point and an exponent")
    whole, frac, exp = m["whole"], m["frac"] or "", m["exp"] or "0"
    digits = len(whole + frac + m["exp"].lstrip("+-") if m["exp"] else whole + frac)
    if digits > limits.max_digits:
        return (f"number with {digits} digits", f"expected at most max_digits={limits.max_digits}")
    bound = limits.max_result_digits - len(whole + frac)
    if abs(int(exp) - len(frac)) > bound:
        return (
            f"number {text.strip()!r} with exponent {exp.lstrip('+')}",
            f"expected an exponent between {-bound} and {bound} "
            f"(max_result_digits={limits.max_result_digits})",
        )
    return None


#: The assumptions of every symbol dhsym makes (joint variables, lengths, the names of a
#: derivation's steps and of generated code): real. ``sympy.Symbol(name, **REAL)``.
REAL: Mapping[str, bool] = MappingProxyType({"real": True})


def normalize_name(name: str) -> str:
    """Spell Greek letters in ``name`` as ASCII names; other characters are kept.

    Examples
    --------
    >>> normalize_name("θ1"), normalize_name("α"), normalize_name("Θ"), normalize_name("q_2")
    ('theta1', 'alpha', 'theta', 'q_2')
    """
    return name.translate(_GREEK)


def symbol(name: str) -> sympy.Symbol:
    """Return the canonical real symbol for ``name``: ``Symbol(normalize_name(name), real=True)``.

    Raise `ParseError` for names not ``[A-Za-z_][A-Za-z0-9_]*``, with ``__``, ``nan`` or keywords.

    Examples
    --------
    >>> symbol("θ1"), symbol("θ1") == symbol("theta1"), symbol("q").is_real
    (theta1, True, True)
    """
    norm = normalize_name(name) if isinstance(name, str) else ""
    if problem := _name_problem(norm):
        raise ParseError(f"{problem[0]} {name!r}: {problem[1]}")
    return sympy.Symbol(norm, **REAL)


def _indexed(name: str) -> tuple[str, str] | None:
    """``(stem, index)`` of a name ending in digits (``theta_12`` → ``("theta", "12")``),
    else None; one pass from the end (a pattern with a lazy stem is quadratic on long names)."""
    end = len(name)
    while end and name[end - 1].isdecimal():
        end -= 1
    if end == len(name):
        return None
    stem = name[:end]
    return (stem[:-1] if stem.endswith("_") else stem), name[end:]


def rate_symbols(variables: Sequence[sympy.Symbol], order: int = 1) -> tuple[sympy.Symbol, ...]:
    """The symbols of the joint rates (``order=1``) or accelerations (``order=2``).

    ``theta1`` gives ``thetadot1`` and ``thetaddot1``, which sympy prints as
    :math:`\\dot\\theta_1`, :math:`\\ddot\\theta_1`. A table reserves these names: no
    length, offset or inertial parameter may be called so (:class:`~dhsym.model.table.DHTable`).

    Examples
    --------
    >>> rate_symbols(sympy.symbols("theta1 d3")), rate_symbols(sympy.symbols("q2,"), 2)
    ((thetadot1, ddot3), (qddot2,))
    """
    suffix = {1: "dot", 2: "ddot"}[order]
    out = []
    for v in variables:
        m = _indexed(v.name)
        name = f"{m[0]}{suffix}{m[1]}" if m else f"{v.name}{suffix}"
        out.append(sympy.Symbol(name, **REAL))
    return tuple(out)


def reserved_symbols(variables: Sequence[sympy.Symbol]) -> dict[sympy.Symbol, str]:
    """The joint variables with their rates and accelerations, each with what it is.

    A table's constants (lengths, offsets, inertial parameters, gravity) may not use
    these names: ``a: thetaddot2`` would be read as the acceleration of joint 2.

    Examples
    --------
    >>> for name, what in reserved_symbols(sympy.symbols("theta1,")).items():
    ...     print(name, "is", what)
    theta1 is the joint variable theta1
    thetadot1 is the rate of the joint variable theta1
    thetaddot1 is the acceleration of the joint variable theta1
    """
    out: dict[sympy.Symbol, str] = {}
    for v, rate, acc in zip(variables, rate_symbols(variables), rate_symbols(variables, 2)):
        out[v] = f"the joint variable {v}"
        out[rate] = f"the rate of the joint variable {v}"
        out[acc] = f"the acceleration of the joint variable {v}"
    return out


def _name_problem(name: str) -> tuple[str, str] | None:
    """Return (what was found, what was expected) if ``name`` may not be used."""
    problems = [
        (not (name.isascii() and name.isidentifier()), "invalid name", "expected [A-Za-z0-9_]"),
        ("__" in name, "name", "names with double underscores are not allowed"),
        (name.lower() in _NON_FINITE_NAMES, "non-finite number", "expected a finite number"),
        (name in _RESERVED, "reserved name", "expected a variable, not a keyword or builtin"),
    ]
    return next(((found, expected) for bad, found, expected in problems if bad), None)


class _Token(NamedTuple):
    kind: str  # "num", "name", "op" or "end"
    text: str  # normalized name; "^" for "**"
    pos: int  # 0-based index into the text
    value: sympy.Expr | None = None  # value of a number


def _digits(value: sympy.Expr) -> float:
    """Decimal digits of the larger of numerator and denominator of a rational, else 0."""
    bits = max(abs(value.p).bit_length(), value.q.bit_length()) if value.is_Rational else 0
    return bits * 0.30103


def _merged_digits(args: tuple[Any, ...], add: bool) -> float:
    """Bound the digits of the numbers sympy computes when it flattens ``Add``/``Mul(*args)``."""
    parts = [p for a in args for p in (a.args if (a.is_Add if add else a.is_Mul) else (a,))]
    if add:  # coefficients of like terms are added over a common denominator
        coeffs = [p.as_coeff_Mul()[0] for p in parts]
        lcm = math.lcm(*(c.q for c in coeffs if c.is_Rational))
        return lcm.bit_length() * 0.30103 + max(map(_digits, coeffs))
    pairs = (p.as_base_exp() for p in parts)  # numbers; bases of equal exponents multiply
    return sum(_digits(b) * (abs(e.p) if e.is_Rational else 1) for b, e in pairs)


def _show(text: str, pos: int | None, width: int = 60) -> str:
    """Quote ``text`` on one line, cut to ``width`` characters around ``pos``."""
    start = max(0, min((pos or 0) - width // 2, len(text) - width))
    head, tail = "…" * (start > 0), "…" * (start + width < len(text))
    return repr(head + text[start : start + width] + tail)


class _Parser:
    """One parse: tokens, cursor, nesting depth and the names seen so far."""

    def __init__(
        self,
        text: str,
        resolve: _Resolve | None,
        limits: ParseLimits,
        where: dict[str, Any],
        textbook: bool = False,
        literal: _Literal | None = None,
    ):
        self.text, self.resolve, self.limits, self.where = text, resolve, limits, where
        self.textbook, self.literal = textbook, literal
        self.i = self.depth = self.in_exponent = 0
        self.names: dict[str, sympy.Expr | None] = {}
        self.tokens = self.tokenize()

    def error(self, found: str, pos: int | None, expected: str) -> ParseError:
        at = f" at column {pos + 1}" if pos is not None else ""
        return ParseError(f"{found}{at} in {_show(self.text, pos)}: {expected}", **self.where)

    def over(self, found: str, pos: int | None, limit: str) -> ParseError:
        return self.error(found, pos, f"expected at most {limit}={getattr(self.limits, limit)}")

    def unexpected(self, tok: _Token, expected: str) -> ParseError:
        what = {"num": f"number {tok.text!r}", "name": f"name {tok.text!r}", "end": "end of text"}
        return self.error(f"unexpected {what.get(tok.kind, repr(tok.text))}", tok.pos, expected)

    def tokenize(self) -> list[_Token]:
        text, i = self.text, 0
        tokens: list[_Token] = []
        while i < len(text):
            m = _TOKEN.match(text, i)
            if m is None:
                c = text[i]
                shown = repr(c).replace("\\\\", "\\") if c.isprintable() else f"U+{ord(c):04X}"
                raise self.error(f"unexpected character {shown}", i, _CHARS)
            if m["space"] is None and len(tokens) >= self.limits.max_nodes:
                raise self.over("too many tokens", i, "max_nodes")
            if m["num"] is not None:
                tokens.append(_Token("num", m["num"], i, self.number(m)))
            elif m["name"] is not None:
                name = normalize_name(m["name"])
                glued = _GLUED_CALL.match(name) if self.textbook else None
                if glued:  # a1cos(q1): the coefficient, then the function
                    tokens.append(_Token("name", glued["head"], i))
                    name, i = glued["func"], i + len(glued["head"])
                if problem := _name_problem(name):
                    raise self.error(f"{problem[0]} {m['name']!r}", i, problem[1])
                tokens.append(_Token("name", name, i))
            elif m["op"] is not None:
                if m["op"] == "°" and not self.textbook:
                    raise self.error("unexpected character '°'", i, _CHARS)
                tokens.append(_Token("op", m["op"].replace("**", "^"), i))
            i = m.end()
        return [*tokens, _Token("end", "", len(text))]

    def number(self, m: re.Match[str]) -> sympy.Expr:
        """Exact value of a decimal literal: ``0.4318`` is ``Rational(4318, 10000)``."""
        whole, frac, exp = m["whole"], m["frac"] or "", m["exp"] or ""
        if problem := numeral_problem(m["num"], self.limits):
            raise self.error(problem[0], m.start(), problem[1])
        mantissa, scale = int(whole + frac), int(exp or "0") - len(frac)
        return sympy.Rational(mantissa * 10 ** max(scale, 0), 10 ** max(-scale, 0))

    def take(self) -> _Token:
        self.i += 1
        return self.tokens[self.i - 1]

    def is_op(self, *ops: str) -> bool:
        return self.tokens[self.i].kind == "op" and self.tokens[self.i].text in ops

    def enter(self, tok: _Token) -> None:
        self.depth += 1
        if self.depth > self.limits.max_depth:
            raise self.over("too deeply nested", tok.pos, "max_depth")

    def nested(self, tok: _Token, parse: Callable[[], sympy.Expr], close: str = "") -> sympy.Expr:
        """Run ``parse`` one level deeper (``max_depth``), then take ')' if ``close``."""
        self.enter(tok)
        value = parse()
        if close and not self.is_op(")"):
            raise self.unexpected(self.tokens[self.i], close)
        self.i += bool(close)
        self.depth -= 1
        return value

    def make(self, tok: _Token, build: Callable[..., sympy.Expr], *args: sympy.Expr) -> sympy.Expr:
        """Build a node with sympy, then refuse non-finite or oversized results."""
        limit = self.limits.max_result_digits
        if build in (sympy.Add, sympy.Mul) and _merged_digits(args, build is sympy.Add) > limit:
            raise self.over("too large numbers", tok.pos, "max_result_digits")
        try:
            value = build(*args)
        except (ArithmeticError, ValueError, TypeError) as exc:
            raise self.error(f"cannot evaluate ({type(exc).__name__})", tok.pos, _FINITE) from None
        if value in _NON_FINITE:
            raise self.error("division by zero or undefined value", tok.pos, _FINITE)
        parts = [value, *value.args, *(a for arg in value.args for a in arg.args)]
        if max(map(_digits, parts)) > limit:  # sympy may have merged numbers
            raise self.over("too large number", tok.pos, "max_result_digits")
        return value

    def parse(self) -> sympy.Expr:
        if self.tokens[self.i].kind == "end":
            raise self.error("empty expression", None, _ATOM)
        value = self.expr()
        if self.tokens[self.i].kind != "end":
            raise self.unexpected(self.tokens[self.i], "expected an operator or end of text")
        if value.has(*_NON_FINITE):
            raise self.error("non-finite result", None, _FINITE)
        return value

    def expr(self) -> sympy.Expr:
        first, terms = self.tokens[self.i], [self.term()]
        while self.is_op("+", "-"):
            tok, term = self.take(), self.term()
            terms.append(term if tok.text == "+" else self.make(tok, sympy.Mul, _MINUS, term))
        return terms[0] if len(terms) == 1 else self.make(first, sympy.Add, *terms)

    def term(self) -> sympy.Expr:
        first = self.tokens[self.i]
        factors: list[sympy.Expr] = []
        while not factors or self.is_op("*", "/", "(") or self.tokens[self.i].kind == "name":
            tok = self.take() if factors and self.is_op("*", "/") else self.tokens[self.i]
            sign, value = self.factor()  # a sign applies to the product: -(a+b)*c stays so
            if tok.text == "/" and value == 0:
                raise self.error("division by zero", tok.pos, "expected a non-zero divisor")
            value = self.make(tok, sympy.Pow, value, _MINUS) if tok.text == "/" else value
            factors += [value] if sign > 0 else [_MINUS, value]
        return factors[0] if len(factors) == 1 else self.make(first, sympy.Mul, *factors)

    def factor(self) -> tuple[int, sympy.Expr]:
        """Leading signs (counted, not recursed) and the power after them."""
        sign, depth = 1, self.depth
        while self.is_op("+", "-"):
            self.enter(tok := self.take())
            sign = -sign if tok.text == "-" else sign
        value = self.degrees(self.atom())
        if self.is_op("^"):  # right-associative; the exponent may have signs: x^-2
            self.enter(tok := self.take())
            value = self.pow(tok, value, self.exponent())
        self.depth = depth
        return sign, value

    def exponent(self) -> sympy.Expr:
        """The factor after '^' (literals in it stay exact numbers)."""
        self.in_exponent += 1
        value = sympy.Mul(*self.factor())
        self.in_exponent -= 1
        return value

    def degrees(self, value: sympy.Expr) -> sympy.Expr:
        """``value°`` is ``value·π/180`` (textbook mode; the sign binds to that atom only)."""
        while self.is_op("°"):
            value = self.make(self.take(), sympy.Mul, value, _DEGREE)
        return value

    def pow(self, tok: _Token, base: sympy.Expr, exponent: sympy.Expr) -> sympy.Expr:
        """Check the limits on ``base**exponent`` before sympy evaluates it."""
        if not exponent.is_Rational:
            raise self.error("non-numeric exponent", tok.pos, "expected an integer or fraction")
        if base == 0 and exponent.is_negative:
            raise self.error("division by zero", tok.pos, "expected a non-zero base")
        digits, todo = 0.0, [(base, exponent)]
        while todo:  # sympy merges (b**x)**y into b**(x*y) and distributes (a*b)**y
            b, x = todo.pop()
            if max(abs(x.p), x.q) > self.limits.max_exponent:
                raise self.over(f"exponent {x}", tok.pos, "max_exponent")  # for |p| and q of p/q
            digits += abs(x.p) * _digits(b)
            if b.is_Pow and b.exp.is_Rational:
                todo.append((b.base, b.exp * x))
            elif b.is_Mul:
                todo.extend((arg, x) for arg in b.args)
        if digits > self.limits.max_result_digits:
            raise self.over(f"power with about {digits:.0f} digits", tok.pos, "max_result_digits")
        return self.make(tok, sympy.Pow, base, exponent)

    def atom(self) -> sympy.Expr:
        tok = self.take()
        if tok.value is not None:  # a number
            if self.literal is not None and not self.in_exponent:
                return self.literal(tok.text, tok.value)
            return tok.value
        if tok.kind == "name":
            return self.name(tok)
        if tok.text == "(":
            return self.nested(tok, self.expr, close="expected an operator or ')'")
        raise self.unexpected(tok, _ATOM)

    def name(self, tok: _Token) -> sympy.Expr:
        name, call = tok.text, self.is_op("(")
        if name in _FUNCTIONS and call:
            return self.call(tok)
        if name in _FUNCTIONS and self.textbook and _FUNCTIONS[name][1] == 1:
            return self.textbook_call(tok)
        if name in _FUNCTIONS:
            raise self.unexpected(self.tokens[self.i], f"expected '(' after function {name!r}")
        if name == "pi" and not call:
            return sympy.pi
        if name not in self.names and name != "pi":  # ask resolve once per distinct name
            if len(self.names) >= self.limits.max_symbols:
                raise self.over(f"name {name!r}", tok.pos, "max_symbols")
            value = self.resolve(name) if self.resolve is not None else None
            if value is not None and not isinstance(value, sympy.Expr):
                raise TypeError(f"resolve({name!r}) gave {type(value).__name__}, not sympy.Expr")
            self.names[name] = value
        value = self.names.get(name)
        if call and value is None:  # a resolved name before '(' multiplies
            raise self.error(f"unknown function {name!r}", tok.pos, _ALLOWED)
        return symbol(name) if value is None else value

    def textbook_call(self, tok: _Token) -> sympy.Expr:
        """``sin^2(x)``, ``sin^2 x``, ``sin x``, ``cos 2θ1``, ``sin 90°`` (textbook mode)."""
        power = None
        if self.is_op("^"):
            self.enter(hat := self.take())
            power = self.exponent()
            if power == -1 and tok.text in _INVERSE_OF:  # cos^-1(x): arccos, as textbooks
                tok, power = _Token(tok.kind, _INVERSE_OF[tok.text], tok.pos), None
            elif not (power.is_Integer and power > 0):
                found = f"{tok.text}^{power}" if power.is_number else f"{tok.text}^…"
                raise self.error(
                    found,
                    hat.pos,
                    f"expected a positive whole power, or ^-1 for the inverse function"
                    f" (the reciprocal is written 1/{tok.text}(x) or {tok.text}(x)^-1)",
                )
            self.depth -= 1
        if self.is_op("("):
            value = self.call(tok)
        else:  # an argument without brackets: a number, a name, or a number and a name
            first = self.tokens[self.i]
            if first.kind not in ("num", "name") or first.text in _FUNCTIONS:
                raise self.unexpected(first, f"expected '(' or an argument after {tok.text!r}")
            self.enter(tok)
            sign, arg = self.factor()
            nxt = self.tokens[self.i]
            if first.kind == "num" and nxt.kind == "name" and nxt.text not in _FUNCTIONS:
                arg = self.make(nxt, sympy.Mul, arg, sympy.Mul(*self.factor()))
            self.depth -= 1
            arg = arg if sign > 0 else self.make(first, sympy.Mul, _MINUS, arg)
            if tok.text == "sqrt":
                value = self.pow(tok, arg, sympy.S.Half)
            else:
                value = self.make(tok, _FUNCTIONS[tok.text][0], arg)
        return value if power is None else self.pow(tok, value, power)

    def call(self, tok: _Token) -> sympy.Expr:
        build, arity = _FUNCTIONS[tok.text]
        args: list[sympy.Expr] = []
        while not args or self.is_op(","):  # take '(' or ','
            args.append(self.nested(self.take(), self.expr))
        if self.take().text != ")":
            raise self.unexpected(self.tokens[self.i - 1], "expected an operator, ',' or ')'")
        if len(args) != arity:
            raise self.error(
                f"{tok.text}() with {len(args)} argument(s)", tok.pos, f"expected {arity}"
            )
        if tok.text == "sqrt":
            return self.pow(tok, args[0], sympy.S.Half)
        return self.make(tok, build, *args)


def parse_expression(
    text: str,
    *,
    resolve: _Resolve | None = None,
    limits: ParseLimits = DEFAULT_LIMITS,
    file: str | None = None,
    row: int | None = None,
    field: str | None = None,
    textbook: bool = False,
    literal: _Literal | None = None,
) -> sympy.Expr:
    """Turn user text into a finite sympy expression with a whitelist grammar, never ``eval``.

    Parameters
    ----------
    text
        Decimals become exact rationals, names real symbols (Greek letters in ASCII);
        ``pi``/``π`` is π, ``e``/``E`` are plain symbols.
    resolve
        Called once per distinct normalized name (not ``pi``, not functions); returns
        the expression to use or ``None``.  A resolved name before ``(`` multiplies.
    limits, file, row, field
        Resource limits (:class:`ParseLimits`); where the text came from, for errors.
    textbook
        Also read degree signs, ``sin^2 x`` and arguments without brackets (see the module
        docstring); for answers, where a student writes what the textbook prints.
    literal
        Called with the text and exact value of each numeric literal outside exponents;
        returns the expression to use in its place (the checker puts symbols there to see
        how rounding a decimal moves the result).

    Raises
    ------
    ParseError
        One line: what was found, at which 1-based column, in which text, what was expected.

    Examples
    --------
    >>> parse_expression("a1*cos(theta1) + 1/2")
    a1*cos(theta1) + 1/2
    >>> parse_expression("2^3^2"), parse_expression("-x^2"), parse_expression("2a1 + 0.4318 pi")
    (512, -x**2, 2*a1 + 2159*pi/5000)
    >>> parse_expression("theta1 + pi/2"), parse_expression("1e-3"), parse_expression("θ1 + α")
    (theta1 + pi/2, 1/1000, alpha + theta1)
    >>> parse_expression("x^70", limits=ParseLimits(max_exponent=70))
    x**70
    >>> parse_expression("a1 C1", resolve=lambda n: sympy.cos(symbol("q1")) if n == "C1" else None)
    a1*cos(q1)
    >>> parse_expression("sin^2 θ1 + cos 90°", textbook=True), parse_expression("a1cos(q1)", textbook=True)
    (sin(theta1)**2, a1*cos(q1))
    >>> parse_expression("q1 + )", file="arm.yaml", row=2, field="theta")
    Traceback (most recent call last):
    ...
    dhsym.errors.ParseError: arm.yaml: row 2, field theta: unexpected ')' at column 6 in 'q1 + )': expected a number, name or '('
    """  # noqa: E501
    where: dict[str, Any] = {"file": file, "row": row, "field": field}
    if not isinstance(text, str):
        raise ParseError(f"expected text (str), got {type(text).__name__}", **where)
    if len(text) > limits.max_length:  # before looking at the characters
        found = f"text of {len(text)} characters in {_show(text, 0)}"
        raise ParseError(f"{found}: expected at most max_length={limits.max_length}", **where)
    try:
        return _Parser(text, resolve, limits, where, textbook, literal).parse()
    except RecursionError:  # only possible with a max_depth far above the default
        message = f"expression too deeply nested in {_show(text, 0)}: lower max_depth"
        raise ParseError(message, **where) from None


def parse_number_list(text: str, option: str) -> list[float]:
    """The numbers of ``text`` (comma separated) as floats; ``option`` names them in errors.

    Used for command-line values such as ``--q 90,-45`` or ``--check pi/2,0``.

    >>> parse_number_list("pi/2, 0.5", "--q")
    [1.5707963267948966, 0.5]
    """
    values = []
    for k, part in enumerate(text.split(","), start=1):
        expr = parse_expression(part, field=f"{option} value {k}")
        if expr.free_symbols or not expr.is_number or not expr.is_real:
            raise DHError(f"{option} value {k} ({part.strip()}) must be a real number")
        values.append(float(expr))
    return values


def check_count(value: int, option: str, low: int, high: int) -> int:
    """``value`` if ``low <= value <= high``; otherwise a one-line error naming ``option``.

    Counts the user chooses (samples, dots per inch) size arrays and pictures: an
    unbounded one is gigabytes of memory or an hour of work.

    >>> check_count(20, "--samples", 0, 100_000)
    20
    >>> check_count(10**11, "--samples", 0, 100_000)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: --samples must be from 0 to 100000, got 100000000000
    """
    if not low <= value <= high:
        raise DHError(f"{option} must be from {low} to {high}, got {value}")
    return value
