r"""A small LaTeX math reader: student LaTeX into text for the whitelist parser.

Nothing is executed and nothing is handed to ``sympify`` or ``parse_latex``: a
tokenizer and a recursive translator turn the LaTeX that students paste from the
lectures into the plain grammar of :func:`dhsym.model.parsing.parse_expression`, which
then builds the sympy objects.  Supported: ``\cos\theta_1``, ``\cos(\theta_1 +
\theta_2)``, ``\cos^2\theta``, ``C_{12}``, ``\alpha_{i-1}`` (a name ``alpha_im1``),
``\frac{}{}``, ``\sqrt{}``, ``\left( \right)``, ``\cdot``, ``\times``, ``^{}``,
degree signs (``90°``, ``90^\circ``, ``90^{\circ}``, ``90\degree``, ``90^o``: a ``°`` in the
output, which the parser reads with ``textbook=True``), function arguments without brackets
(``\sin\frac{\pi}{2}``, ``\cos\theta_{1}``, ``\sin 90^\circ``, ``\cos{\theta_1}``),
Craig's ``c\theta_i``, Greek letters, the rates ``\dot q_1``, ``\ddot{\theta}_2`` (names
``qdot_1``, ``thetaddot_2``), font commands, the inverse functions (``\arctan``,
``\operatorname{atan2}(y, x)``) and ``\pm``/``\mp`` (left as ``±``/``∓`` for the
inverse-kinematics checker), and the matrix environments
``bmatrix pmatrix matrix Bmatrix vmatrix array``.  Any other command
(``\input``, ``\def``, ``\write18`` …) is refused with a :class:`ParseError`.

Examples
--------
>>> latex_to_text(r"\cos\theta_1 \cos(\theta_1 + \theta_2)")
'cos(theta_1) cos(theta_1 + theta_2)'
>>> latex_to_text(r"p_x = a_1 C_1 + \frac{a_2}{2} S_{12}")
'a_1 C_1 + ((a_2)/(2)) S_12'
>>> latex_to_text(r"-d_i \sin \alpha_{i-1}")
'- d_i sin(alpha_im1)'
>>> latex_matrix_cells(r"\begin{bmatrix} C_1 & -S_1 \\ S_1 & C_1 \end{bmatrix}")
[['C_1', '-S_1'], ['S_1', 'C_1']]
>>> latex_to_text(r"\dot{q}_1 + \ddot\theta_2 \dot{\theta_1}")
'qdot_1 + thetaddot_2 thetadot_1'
>>> flatten_subscripts("c_{alpha_{i-1}} + C_{12}")
'c_alpha_im1 + C_12'
"""

from __future__ import annotations

import re

from dhsym.errors import ParseError

__all__ = [
    "answer_side",
    "flatten_subscripts",
    "is_latex",
    "latex_matrix_cells",
    "latex_to_text",
]

_GREEK = frozenset(
    "alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu nu "
    "xi omicron rho varrho sigma varsigma tau upsilon phi varphi chi psi omega "
    "Gamma Delta Theta Lambda Xi Sigma Upsilon Phi Psi Omega".split()
)
_FUNCTIONS = frozenset({"sin", "cos", "tan"})
#: inverse functions, as LaTeX and \operatorname spell them, and what the parser reads
_INVERSE = {"arctan": "atan", "arcsin": "asin", "arccos": "acos"}
_OPERATORS = {"atan2": "atan2", "atan": "atan", "asin": "asin", "acos": "acos"} | _INVERSE
_OPERATORS |= {"Atan2": "atan2", "arctan2": "atan2"}  # Craig's and numpy's spellings
_SIGNS = {"pm": "±", "mp": "∓"}  # ± of an inverse-kinematics answer (both branches)
_FRACTIONS = frozenset({"frac", "dfrac", "tfrac", "cfrac"})
_TIMES = frozenset({"cdot", "times", "ast"})
_SPACES = frozenset({"quad", "qquad", "displaystyle", "textstyle", "hline", "nonumber"})
_FONTS = frozenset(
    "mathbf mathrm mathit mathsf mathtt boldsymbol bm text textrm textit mathnormal".split()
)
_SIZES = frozenset("big Big bigg Bigg bigl bigr Bigl Bigr biggl biggr Biggl Biggr".split())
_DEGREES = frozenset({"degree", "textdegree", "circ"})
_ABBREVIATION_HEADS = frozenset("cCsS")  # Craig's c\theta_i, s\alpha_{i-1}
_NUMBER = re.compile(r"[0-9]+(?:\.[0-9]+)?|\.[0-9]+")  # unambiguous: linear on any text
_ROW_SPACING = re.compile(r"^\s*\[\s*-?[0-9.]+\s*(?:pt|em|ex|mm|cm|in|bp|mu)\s*\]")
_MATRIX_ENVS = "bmatrix|pmatrix|matrix|Bmatrix|vmatrix|Vmatrix|smallmatrix|array|tabular"
_MATRIX = re.compile(  # the body stops at the next \begin: linear on any text
    r"\\begin\{(" + _MATRIX_ENVS + r")\}(?P<body>(?:(?!\\begin\{).)*?)\\end\{\1\}", re.DOTALL
)
# a table's rules: \hline, booktabs' \toprule \midrule \bottomrule, \cline{2-4}
_RULES = re.compile(r"\\(?:hline|toprule|midrule|bottomrule|cline\{[0-9\s-]*\})")
_LETTER = "A-Za-z\u0370-\u03ff"
_TOKEN = re.compile(
    r"(?P<space>\s+)|(?P<cmd>\\[A-Za-z]+)|(?P<esc>\\.)|(?P<num>[0-9]*\.?[0-9]+)"
    rf"|(?P<name>[{_LETTER}][{_LETTER}0-9]*)|(?P<char>.)",
    re.DOTALL,
)
_FLAT_NAME = re.compile(rf"[{_LETTER}_][{_LETTER}0-9_]*")
# a name of at most 64 characters: each start scans a bounded run (linear on any text)
_PLAIN_SUB = re.compile(rf"([{_LETTER}][{_LETTER}0-9_]{{0,63}})_\{{([^{{}}]*)\}}")
_DELIMS = ("$$", "$", r"\[", r"\]", r"\(", r"\)")


def is_latex(text: str) -> bool:
    r"""True when ``text`` looks like LaTeX (a command, or a ``$``, ``\(`` or ``\[`` delimiter).

    >>> is_latex(r"\cos\theta_1"), is_latex("cos(theta1)"), is_latex("$C_1$"), is_latex(r"\(C_1\)")
    (True, False, True, True)
    """
    return "$" in text or re.search(r"\\[A-Za-z(\[]", text) is not None


def _flat(content: str) -> str:
    """A subscript as a name suffix: ``i-1`` → ``im1``, ``i+1`` → ``ip1``, ``1,2`` → ``12``."""
    flat = re.sub(r"[\s\\{}()]", "", content)
    flat = flat.replace("-", "m").replace("+", "p").replace(",", "")
    if not flat or not re.fullmatch(rf"[{_LETTER}0-9_]+", flat):
        raise ParseError(f"cannot read the subscript {content!r}: expected letters and digits")
    return flat


# a sum of joint indices, each a digit or an angle with its digit: 1+2, theta_1 + theta_2
_INDEX_SUM = re.compile(r"(?:theta_?)?([1-9])(?:\+(?:theta_?)?[1-9])+")


def _subscript(name: str, content: str) -> str:
    r"""The subscript of ``name`` as a name suffix; a sine or cosine abbreviation of a sum
    of joint angles takes the joints' digits (``c_{1+2}``, ``C_{\theta_1+\theta_2}`` →
    ``c_12``, as ``c_{12}``).

    >>> _subscript("C", "theta_1 + theta_2"), _subscript("s", "1+2+3"), _subscript("a", "i+1")
    ('12', '123', 'ip1')
    """
    if name in _ABBREVIATION_HEADS:
        flat = re.sub(r"[\s{}]", "", content)
        if _INDEX_SUM.fullmatch(flat):
            return "".join(re.findall(r"[1-9]", flat))
    return _flat(content)


def flatten_subscripts(text: str) -> str:
    """Rewrite plain-text subscripts ``name_{…}`` as names (``alpha_{i-1}`` → ``alpha_im1``)."""
    for _ in range(8):  # nested subscripts, innermost first
        new = _PLAIN_SUB.sub(lambda m: f"{m[1]}_{_subscript(m[1], m[2])}", text)
        if new == text:
            return new
        text = new
    return text


def _tokens(src: str) -> list[tuple[str, str]]:
    out = []
    for m in _TOKEN.finditer(src):
        kind = m.lastgroup or "char"
        if kind != "space":
            out.append((kind, m.group()))
    return out


class _Translator:
    """One translation: the tokens and a cursor."""

    def __init__(self, src: str) -> None:
        self.src = src
        self.toks = _tokens(src)
        self.i = 0

    # -- cursor -------------------------------------------------------------------
    def error(self, found: str, expected: str) -> ParseError:
        shown = self.src if len(self.src) <= 60 else self.src[:57] + "…"
        return ParseError(f"LaTeX: {found} in {shown!r}: {expected}")

    def peek(self) -> tuple[str, str]:
        return self.toks[self.i] if self.i < len(self.toks) else ("end", "")

    def take(self) -> tuple[str, str]:
        tok = self.peek()
        self.i += 1
        return tok

    def expect(self, text: str) -> None:
        kind, value = self.take()
        if value != text:
            raise self.error(f"unexpected {value or 'end of text'!r}", f"expected {text!r}")

    # -- grammar ------------------------------------------------------------------
    def run(self) -> str:
        out = self.seq(None)
        if self.peek()[0] != "end":
            raise self.error(f"unbalanced {self.peek()[1]!r}", "expected matching brackets")
        return out

    def seq(self, until: str | None) -> str:
        parts: list[str] = []
        while self.peek()[0] != "end" and self.peek()[1] != until:
            if until is None and self.peek()[1] in (")", "}", "]", r"\right"):
                break
            piece = self.item()
            if piece:
                parts.append(piece)
        return " ".join(parts)

    def group(self, close: str) -> str:
        inner = self.seq(close)
        self.expect(close)
        return f"({inner})"

    def item(self) -> str:
        kind, tok = self.take()
        if tok == "{":
            return self.postfix(self.group("}"))
        if tok == "(":
            return self.postfix(self.group(")"))
        if tok == "[":
            return self.postfix(self.group("]"))
        if kind == "num":
            return self.postfix(tok)
        if kind == "name":
            if tok in _ABBREVIATION_HEADS and self.peek()[1][1:] in _GREEK:  # c\theta_1
                greek = self.take()[1][1:].lower().removeprefix("var")
                return self.postfix(f"{tok}_{self.subscripted(greek)}")
            return self.postfix(self.subscripted(tok))
        if tok in ("+", "-", "*", "/", ","):
            return tok
        if tok in ("°", "º", "˚"):
            return "°"
        if tok == "^" and self.degree_mark(after_hat=True):  # 90\,^{\circ}
            return "°"
        if tok in ("&", "~"):
            return ""
        if kind == "esc":
            if tok in (r"\,", r"\;", r"\:", r"\!", "\\ ", r"\\"):
                return ""
            if tok in (r"\{", r"\}"):
                return self.postfix(self.group(r"\}")) if tok == r"\{" else ""
            raise self.error(f"unsupported {tok!r}", "expected math")
        if kind == "cmd":
            return self.command(tok[1:])
        raise self.error(f"unexpected {tok!r}", "expected a number, name, command or bracket")

    def command(self, name: str) -> str:
        if name in _GREEK:
            return self.postfix(self.subscripted(name.lower().removeprefix("var")))
        if name == "ell":  # Spong's link lengths: \ell_1, \ell_{c2}
            return self.postfix(self.subscripted("l"))
        if name == "pi":
            return self.postfix("pi")
        if name in _FUNCTIONS:
            return self.function(name)
        if name in _INVERSE:
            return self.function(_INVERSE[name])
        if name in _SIGNS:
            return _SIGNS[name]
        if name == "operatorname":
            inner = re.sub(r"[\s()]", "", self.argument())
            if inner in _FUNCTIONS:
                return self.function(inner)
            if inner in _OPERATORS:
                return self.function(_OPERATORS[inner])
            raise self.error(
                f"unknown operator {inner!r}", "expected sin, cos, tan, atan2, atan, asin or acos"
            )
        if name in _FRACTIONS:
            num, den = self.argument(), self.argument()
            return self.postfix(f"(({num})/({den}))")
        if name == "sqrt":
            if self.peek()[1] == "[":
                self.take()
                root = self.seq("]")
                self.expect("]")
                return self.postfix(f"({self.argument()})^(1/({root}))")
            return self.postfix(f"sqrt({self.argument()})")
        if name == "left":
            return self.postfix(self.left())
        if name in _TIMES:
            return "*"
        if name == "div":
            return "/"
        if name in _SPACES:
            return ""
        if name in _SIZES:
            return ""
        if name in _FONTS:
            return self.postfix(self.subscripted_group(self.argument()))
        if name in _DEGREES:
            return "°"
        if name in ("dot", "ddot"):  # \dot q_1, \ddot{\theta}_2: the names qdot_1, thetaddot_2
            inner = re.sub(r"\s", "", self.argument())
            if not _FLAT_NAME.fullmatch(inner):
                raise self.error(f"unsupported \\{name}{{{inner}}}", "expected a joint variable")
            head, _, sub = inner.partition("_")
            word = head + name
            return self.postfix(f"{word}_{sub}" if sub else self.subscripted(word))
        raise self.error(
            f"unsupported command \\{name}", "expected math (\\cos, \\frac, \\theta …)"
        )

    def left(self) -> str:
        kind, tok = self.take()
        closers = {"(": ")", "[": "]", r"\{": r"\}", ".": None}
        if tok not in closers:
            raise self.error(f"unsupported \\left{tok}", "expected \\left( or \\left[")
        inner = self.seq(r"\right")
        self.expect(r"\right")
        self.take()  # the closing delimiter, whatever it is
        return f"({inner})"

    def argument(self) -> str:
        """A macro argument: a ``{group}`` or a single token (first digit of a number)."""
        kind, tok = self.peek()
        if tok == "{":
            self.take()
            return self.group("}")[1:-1]
        if kind == "num" and len(tok) > 1:
            self.toks[self.i] = ("num", tok[1:])
            return tok[0]
        if kind in ("num", "name"):
            self.take()
            return self.subscripted(tok) if kind == "name" else tok
        if kind == "cmd" and tok[1:] in _GREEK | {"pi"}:
            self.take()
            return self.command(tok[1:])
        raise self.error(f"unexpected {tok or 'end of text'!r}", "expected an argument {…}")

    def subscripted(self, name: str) -> str:
        """A name and its subscript as one parser name: ``alpha`` ``_{i-1}`` → ``alpha_im1``."""
        if self.peek()[1] != "_":
            return name
        self.take()
        kind, tok = self.peek()
        if tok == "{":
            self.take()
            sub = self.seq("}")
            self.expect("}")
        elif kind == "num":
            sub = self.argument()
        else:
            sub = self.argument()
        return f"{name}_{_subscript(name, sub)}"

    def subscripted_group(self, inner: str) -> str:
        """``\\mathbf{T}_2``: a font group that is a single name may take a subscript."""
        if _FLAT_NAME.fullmatch(inner):
            return self.subscripted(inner)
        return f"({inner})"

    def degree_mark(self, after_hat: bool = False, number: bool = False) -> bool:
        r"""Take a degree mark if one comes next: ``^\circ``, ``^{\circ}``, ``\degree``,
        ``°``, and ``^o``/``^{o}`` after a number (``after_hat``: the ``^`` is already taken)."""
        ahead = self.toks[self.i : self.i + 4]
        marks = [[("cmd", r"\circ")], [("char", "{"), ("cmd", r"\circ"), ("char", "}")]]
        if number:
            marks += [[("name", "o")], [("char", "{"), ("name", "o"), ("char", "}")]]
        if not after_hat:
            if ahead[:1] in ([("char", "°")], [("char", "º")], [("char", "˚")]) or (
                ahead[:1] and ahead[0][0] == "cmd" and ahead[0][1][1:] in ("degree", "textdegree")
            ):
                self.i += 1
                return True
            if ahead[:1] != [("char", "^")]:
                return False
            ahead = ahead[1:]
        for mark in marks:
            if ahead[: len(mark)] == mark:
                self.i += len(mark) + (not after_hat)
                return True
        return False

    def postfix(self, base: str) -> str:
        number = _NUMBER.fullmatch(base) is not None
        while self.peek()[1] in ("^", "'", "°", "º", "˚", r"\degree", r"\textdegree"):
            if self.degree_mark(number=number):
                base, number = f"{base}°", False
                continue
            if self.peek()[1] not in ("^", "'"):
                break
            self.take()
            base = f"{base}^({self.argument()})"
        if self.peek()[1] == "_":
            raise self.error("a subscript after something that is not a name", "expected x_{…}")
        return base

    def function(self, name: str) -> str:
        r"""``\sin`` and its argument: bracketed, braced, a fraction, or a number and/or symbol."""
        power = None
        if self.peek()[1] == "^":
            self.take()
            power = self.argument()
            if re.fullmatch(r"\s*-\s*1\s*", power) and name in _FUNCTIONS:  # \cos^{-1}: arccos
                return self.function(_INVERSE["arc" + name])
            if re.fullmatch(r"\s*-.*", power):
                raise self.error(
                    f"\\{name}^{{{power}}}",
                    f"expected a positive power, or ^{{-1}} for the inverse function (write "
                    f"1/\\{name}(x) for the reciprocal)",
                )
        while self.peek()[0] == "cmd" and self.peek()[1][1:] in _SIZES:  # \bigl(
            self.take()
        kind, tok = self.peek()
        if tok in ("(", "[", "{"):
            self.take()
            arg = self.group({"(": ")", "[": "]", "{": "}"}[tok])
        elif tok == r"\left":
            self.take()
            arg = self.left()
        elif kind == "cmd" and tok[1:] in _FRACTIONS:
            self.take()
            arg = f"({self.command(tok[1:])})"
        elif kind in ("num", "name") or (kind == "cmd" and tok[1:] in _GREEK | {"pi"}):
            parts = []
            if kind == "num":
                parts.append(self.postfix(self.take()[1]))
                kind, tok = self.peek()
            if kind == "name":
                self.take()
                parts.append(self.postfix(self.subscripted(tok)))
            elif kind == "cmd" and tok[1:] in _GREEK | {"pi"}:
                self.take()
                parts.append(self.command(tok[1:]))
            arg = "(" + " ".join(parts) + ")"
        else:
            raise self.error(
                f"\\{name} followed by {tok or 'end of text'!r}", "expected its argument"
            )
        base = f"{name}{arg}"
        out = self.postfix(base)
        if power is None:
            return out
        return f"({base}^({power})){out[len(base) :]}" if out != base else f"{base}^({power})"


def _strip_delimiters(src: str) -> str:
    text = src.strip()
    for d in _DELIMS:
        text = text.replace(d, " ")
    text = re.sub(r"\\(begin|end)\{(equation|align|aligned|gather|displaymath)\*?\}", " ", text)
    return text


# a label: one name, with subscripts, braces, a LaTeX command or an index ``[0,3]``, and
# a LaTeX superscript prefix of one character ``{}^0T_2``; no operator, no space between
# two names. Its parts cannot match the same characters twice: linear on any text.
_LABEL = re.compile(r"\s*(?:\{\}\^\{?[0-9A-Za-z]\}?)?\\?[A-Za-z][\w{}\\]*(?:\[[\d,\s]*\])?\s*")


def answer_side(text: str) -> str:
    r"""The side of an equation that is the answer: the part after the last top-level
    ``=`` (a label such as ``p_x =`` or ``{}^0T_2 =`` dropped), or the part before the
    first when the answer is written first and the label last (``a_1 C_1 = p_x``).

    >>> answer_side("p_x = a1 C1"), answer_side("a1 C1 + a2 C12 = px"), answer_side("a1 C1")
    (' a1 C1', 'a1 C1 + a2 C12 ', 'a1 C1')
    >>> answer_side("T0_2[0,3] = x = a1 C1"), answer_side("d = d3"), answer_side("0 = d3")
    (' a1 C1', ' d3', ' d3')
    """
    depth, cuts = 0, [-1]
    for k, ch in enumerate(text):
        if ch in "{([":
            depth += 1
        elif ch in "})]":
            depth -= 1
        elif ch == "=" and depth == 0:
            cuts.append(k)
    last = text[cuts[-1] + 1 :]
    first = text[: cuts[1]] if len(cuts) > 1 else last
    if _LABEL.fullmatch(last) and not _LABEL.fullmatch(first) and _is_expression(first):
        return first
    return last


def _is_expression(text: str) -> bool:
    """Whether ``text`` combines terms (an operator, a call or a product of names), which
    a bare number or name does not."""
    return bool(re.search(r"[-+*/^()\\·]|\w\s+\w", text.strip()))


def latex_to_text(src: str) -> str:
    r"""Translate one LaTeX math expression into whitelist-parser text.

    Text left of the last top-level ``=`` is dropped (``p_x = …``).

    >>> latex_to_text(r"\cos^2\theta + 90^\circ"), latex_to_text(r"\sin\frac{\pi}{2} c\theta_1")
    ('cos(theta)^(2) + 90°', 'sin(((pi)/(2))) c_theta_1')
    >>> latex_to_text(r"\input{/etc/passwd}")
    Traceback (most recent call last):
    ...
    dhsym.errors.ParseError: LaTeX: unsupported command \input in '\\input{/etc/passwd}': expected math (\cos, \frac, \theta …)
    """  # noqa: E501
    text = answer_side(_strip_delimiters(src))
    return _Translator(text).run()


def latex_matrix_cells(src: str) -> list[list[str]] | None:
    r"""The cells (LaTeX) of the last matrix environment (or ``tabular``) in ``src``, or None
    if there is none.

    >>> latex_matrix_cells(r"\begin{array}{cc} 1 & 0 \\ 0 & 1 \\ \end{array}")
    [['1', '0'], ['0', '1']]
    >>> latex_matrix_cells(r"\begin{tabular}{c|c} \toprule $a_i$ & $d_i$ \\ \midrule"
    ...                    r" a_1 & 0 \end{tabular}")
    [['$a_i$', '$d_i$'], ['a_1', '0']]
    """
    found = list(_MATRIX.finditer(src))
    if not found:
        return None
    m = found[-1]
    body = m["body"]
    if m[1] in ("array", "tabular"):  # the column specification {c|c|c}
        body = re.sub(r"^\s*\{[^{}]*\}", "", body)
    body = _RULES.sub(" ", body)
    rows = [_ROW_SPACING.sub("", r) for r in re.split(r"\\\\", body)]  # \\[2pt]
    if rows and not rows[-1].strip():
        rows.pop()
    return [[cell.strip() for cell in row.split("&")] for row in rows]
