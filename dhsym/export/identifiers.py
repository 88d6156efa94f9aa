"""Identifiers and comments for generated code that no robot name can break.

A robot's name, its variable names and a prefix come from a user: in generated code
they become identifiers only through :func:`identifier` (ASCII letters, digits and
``_``, starting with a letter, never a keyword of any target language) and text only
through :func:`comment_lines` (printable ASCII, no sequence that ends or opens a
comment in C, C++, Rust, MATLAB/Octave or Python).

Examples
--------
>>> identifier("PUMA 560")
'puma_560'
>>> identifier("*/ int main(){")
'int_main'
>>> identifier("for")
'for_'
>>> comment_lines("θ1 */ evil\\n%{ more ??/")
['theta1 * / evil', '% { more ? ?/']
"""

from __future__ import annotations

import re
import unicodedata

__all__ = ["KEYWORDS", "comment_lines", "identifier"]

#: Words no generated identifier may equal: keywords and reserved words of C99, C++17,
#: Rust, MATLAB/Octave and Python, and the names the templates themselves use.
KEYWORDS = frozenset(
    """
    auto break case char const continue default do double else enum extern float for goto if
    inline int long register restrict return short signed sizeof static struct switch typedef
    union unsigned void volatile while alignas alignof and and_eq asm bitand bitor bool catch
    class compl constexpr const_cast decltype delete dynamic_cast explicit export false friend
    mutable namespace new noexcept not not_eq nullptr operator or or_eq private protected public
    reinterpret_cast static_assert static_cast template this thread_local throw true try typeid
    typename using virtual wchar_t xor xor_eq as crate dyn fn impl in let loop match mod move mut
    pub ref self Self super trait type unsafe use where async await abstract become box final
    macro override priv typeof unsized yield end endfor endif endwhile endfunction function
    global persistent elseif otherwise parfor spmd unwind_protect None True False assert def del
    elif except finally from import is lambda nonlocal pass raise with print main std math
    numpy np q T J p sol count b k i j f64 usize isize i32 u32 pi e inf nan sqrt sin cos atan2
    remainder fabs abs max min
    """.split()
)

_ASCII = {
    "θ": "theta",
    "α": "alpha",
    "σ": "sigma",
    "π": "pi",
    "−": "-",
    "–": "-",
    "—": "-",
    "…": "...",
    "√": "sqrt",
    "·": "*",
    "×": "x",
    "²": "^2",
    "ⁿ": "^n",
    "≤": "<=",
    "≥": ">=",
    "→": "->",
    "↔": "<->",
    "±": "+/-",
}


def _ascii(text: str) -> str:
    out = []
    for ch in text:
        if ch in _ASCII:
            out.append(_ASCII[ch])
            continue
        plain = unicodedata.normalize("NFKD", ch).encode("ascii", "ignore").decode()
        out.append(plain if plain else ("?" if ch.isprintable() else " "))
    return "".join(out)


def identifier(
    text: str, *, taken: frozenset[str] | set[str] = frozenset(), limit: int = 40
) -> str:
    """A safe identifier for ``text``: lower-case ASCII words joined by ``_``.

    It starts with a letter (``r_`` is put before a leading digit), is at most
    ``limit`` characters, and differs from every keyword and from ``taken`` (a number
    or a ``_`` is added).

    >>> identifier("2R arm"), identifier(""), identifier("a2", taken={"a2"})
    ('r_2r_arm', 'robot', 'a2_2')
    """
    words = re.findall(r"[a-z0-9]+", _ascii(text).lower())
    name = "_".join(words)[:limit].strip("_") or "robot"
    if not name[0].isalpha():
        name = f"r_{name}"
    if name in KEYWORDS:
        name += "_"
    base, k = name, 2
    while name in taken or name in KEYWORDS:
        name = f"{base}_{k}"
        k += 1
    return name


def comment_lines(text: str) -> list[str]:
    """``text`` as lines safe inside a comment of every target language.

    Printable ASCII only; ``*/`` and ``/*`` (C block comments), ``??`` (trigraphs), a
    backslash (line splices), ``%{`` and ``%}`` (Octave block comments) are broken
    apart; each line of ``text`` is one line (the caller prefixes each).

    >>> comment_lines("a\\\\\\nb */")
    ['a/', 'b * /']
    """
    lines = []
    for raw in _ascii(text).splitlines() or [""]:
        line = "".join(ch if " " <= ch <= "~" else " " for ch in raw)
        line = line.replace("\\", "/")
        for bad, good in (("*/", "* /"), ("/*", "/ *"), ("??", "? ?"), ("%{", "% {")):
            while bad in line:
                line = line.replace(bad, good)
        line = line.replace("%}", "% }")
        lines.append(line.rstrip())
    return lines
