r"""User text made safe to print: LaTeX that prints it literally, Markdown that shows it as is.

* :func:`escape_latex` turns *any* user string (robot name, title, author,
  course, a table's source) into LaTeX that prints that string literally:
  ``\input{/etc/passwd}``, ``\write18{…}``, ``}\end{document}``, ``%``,
  ``$x$`` and the ten special characters ``# $ % & _ { } ~ ^ \`` all come out
  as text. Output is pure ASCII and works with the default OT1 font encoding
  (no ``lmodern``/``cm-super`` needed): accented Latin letters become accent
  commands, Greek letters ``\ensuremath{\alpha}``, and any other character a
  visible ``[U+XXXX]``.
* :func:`escape_markdown` shows a string literally in Markdown (no emphasis,
  links, HTML or math), control and format characters removed.
* :class:`TeX` marks a string as trusted LaTeX (printer output); the Jinja2
  environments print it verbatim and escape every other string.

Examples
--------
>>> print(escape_latex(r"\input{/etc/passwd} 100% of $x$"))
\textbackslash{}input\{/etc/passwd\} 100\% of \$x\$
>>> print(escape_latex("Übung: α_1"))
\"{U}bung: \ensuremath{\alpha}{\ttfamily\char95}1
>>> print(escape_markdown("a_1 *b* <script>"))
a\_1 \*b\* &lt;script&gt;
"""

from __future__ import annotations

import re
import unicodedata

__all__ = ["TeX", "clean_text", "escape_latex", "escape_markdown"]


class TeX(str):
    """A string of trusted LaTeX (from sympy's printers or dhsym), printed verbatim.

    >>> TeX("C_{12}") == "C_{12}", isinstance(TeX("x"), str)
    (True, True)
    """

    __slots__ = ()


# ASCII characters with a special meaning in LaTeX. The ones that OT1 text fonts lack
# (or draw as a rule, so that they vanish from copied text) come from the typewriter
# font, which has every ASCII glyph.
_ASCII = {
    "\\": r"\textbackslash{}",
    "{": r"\{",
    "}": r"\}",
    "#": r"\#",
    "$": r"\$",
    "%": r"\%",
    "&": r"\&",
    "_": r"{\ttfamily\char95}",
    "~": r"{\ttfamily\char126}",
    "^": r"{\ttfamily\char94}",
    "<": r"{\ttfamily\char60}",
    ">": r"{\ttfamily\char62}",
    "|": r"{\ttfamily\char124}",
    '"': r"{\ttfamily\char34}",
    "-": "-{}",  # no -- / --- ligatures: a literal "--" stays two dashes
    "!": "!{}",  # no !` ligature
    "?": "?{}",  # no ?` ligature
    "\t": " ",
    "\n": " ",
    "\r": " ",
}


_SPECIAL = {
    "ß": r"\ss{}",
    "æ": r"\ae{}",
    "Æ": r"\AE{}",
    "œ": r"\oe{}",
    "Œ": r"\OE{}",
    "ø": r"\o{}",
    "Ø": r"\O{}",
    "ł": r"\l{}",
    "Ł": r"\L{}",
    "ı": r"\i{}",
    "å": r"\aa{}",
    "Å": r"\AA{}",
    "–": "--",
    "—": "---",
    "‘": "`",
    "’": "'",
    "“": "``",
    "”": "''",
    "„": ",,",
    "…": r"\ldots{}",
    "°": r"\ensuremath{^\circ}",
    "×": r"\ensuremath{\times}",
    "·": r"\ensuremath{\cdot}",
    "±": r"\ensuremath{\pm}",
    "−": r"\ensuremath{-}",
    "≤": r"\ensuremath{\leq}",
    "≥": r"\ensuremath{\geq}",
    "→": r"\ensuremath{\rightarrow}",
    "∞": r"\ensuremath{\infty}",
    "§": r"\S{}",
    "¶": r"\P{}",
    "©": r"\copyright{}",
    "£": r"\pounds{}",
    "¿": "?`",
    "¡": "!`",
    "\u00a0": "~",
}


# combining marks -> OT1 accent commands
_ACCENTS = {
    0x300: "`",
    0x301: "'",
    0x302: "^",
    0x303: "~",
    0x304: "=",
    0x306: "u",
    0x307: ".",
    0x308: '"',
    0x30A: "r",
    0x30B: "H",
    0x30C: "v",
    0x323: "d",
    0x327: "c",
}


_GREEK_CAPITALS = {
    "GAMMA",
    "DELTA",
    "THETA",
    "LAMBDA",
    "XI",
    "PI",
    "SIGMA",
    "UPSILON",
    "PHI",
    "PSI",
    "OMEGA",
}


_GREEK_AS_LATIN = {
    "ALPHA": "A",
    "BETA": "B",
    "EPSILON": "E",
    "ZETA": "Z",
    "ETA": "H",
    "IOTA": "I",
    "KAPPA": "K",
    "MU": "M",
    "NU": "N",
    "OMICRON": "O",
    "RHO": "P",
    "TAU": "T",
    "CHI": "X",
}


def _greek(ch: str) -> str | None:
    name = unicodedata.name(ch, "")
    m = re.fullmatch(r"GREEK (SMALL|CAPITAL) LETTER (FINAL )?([A-Z]+)", name)
    if not m:
        return None
    small, final, letter = m.group(1) == "SMALL", m.group(2), m.group(3)
    if small:
        word = "varsigma" if final else ("o" if letter == "OMICRON" else letter.lower())
        return rf"\ensuremath{{\{word}}}" if word != "o" else "o"
    if letter in _GREEK_CAPITALS:
        return rf"\ensuremath{{\{letter.capitalize()}}}"
    return _GREEK_AS_LATIN.get(letter)


def _accented(ch: str) -> str | None:
    decomposed = unicodedata.normalize("NFD", ch)
    base, marks = decomposed[0], decomposed[1:]
    if not (base.isascii() and base.isalpha()) or not marks:
        return None
    out = {"i": r"\i{}", "j": r"\j{}"}.get(base, base)
    for mark in marks:
        cmd = _ACCENTS.get(ord(mark))
        if cmd is None:
            return None
        out = rf"\{cmd}{{{out}}}"
    return out


def _char(ch: str) -> str:
    if ch in _ASCII:
        return _ASCII[ch]
    if " " <= ch <= "~":
        return ch
    if ch in _SPECIAL:
        return _SPECIAL[ch]
    if unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp"):
        return ""  # control and format characters (bidi overrides, zero-width) are dropped
    if unicodedata.category(ch) == "Zs":
        return " "
    found = _accented(ch) or _greek(ch) or _greek(unicodedata.normalize("NFD", ch)[0])
    return found if found is not None else rf"\texttt{{[U+{ord(ch):04X}]}}"


def escape_latex(text: object) -> TeX:
    r"""LaTeX text-mode source that prints ``text`` literally (ASCII output).

    >>> print(escape_latex(r"}\end{document}"))
    \}\textbackslash{}end\{document\}
    >>> print(escape_latex(r"\write18{rm -rf /} #&~^"))
    \textbackslash{}write18\{rm -{}rf /\} \#\&{\ttfamily\char126}{\ttfamily\char94}
    >>> print(escape_latex("Müller — 90° 中"))
    M\"{u}ller --- 90\ensuremath{^\circ} \texttt{[U+4E2D]}
    """
    return TeX("".join(_char(ch) for ch in unicodedata.normalize("NFC", str(text))))


_MD_SPECIAL = re.compile(r"([\\`*_\[\]#|$~{}!])")
_MD_ENTITIES = str.maketrans({"&": "&amp;", "<": "&lt;", ">": "&gt;"})


def escape_markdown(text: object) -> str:
    r"""Markdown inline text that shows ``text`` literally (no emphasis, links, HTML or math).

    ``< > &`` become entities, the other Markdown specials get a backslash, control and
    format characters (terminal escapes, bidi overrides) are dropped and line breaks
    become spaces. The one Markdown escaper of dhsym (derivations, handouts, feedback).

    >>> print(escape_markdown("a_1 *b* <script> $x$ [a](b)"))
    a\_1 \*b\* &lt;script&gt; \$x\$ \[a\](b)
    """
    s = clean_text(text).translate(_MD_ENTITIES)
    return " ".join(_MD_SPECIAL.sub(r"\\\1", s).splitlines())


_ASCII_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f]")


def clean_text(text: object) -> str:
    """Drop control and format characters (terminal escapes, bidi overrides).

    >>> clean_text("ok\x1b[31m red\u202e")
    'ok[31m red'
    """
    text = str(text)
    if text.isprintable():  # no Cc or Cf character (nor a line break or another space)
        return text
    if text.isascii():  # the ASCII control characters, the only Cc or Cf ones in ASCII
        return _ASCII_CONTROL.sub("", text)
    return "".join(
        ch for ch in text if ch in "\n\t" or unicodedata.category(ch) not in ("Cc", "Cf")
    )
