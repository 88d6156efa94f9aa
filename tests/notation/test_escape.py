"""Escaping untrusted text: LaTeX that prints it literally, Markdown that shows it as is."""

from __future__ import annotations

import html as html_module
import re
import subprocess
import unicodedata

import pytest
from hypothesis import given
from hypothesis import strategies as st
from markdown_it import MarkdownIt

from dhsym.notation.escape import TeX, clean_text, escape_latex, escape_markdown

HOSTILE = [
    r"\input{/etc/passwd}",
    r"\write18{rm -rf /}",
    r"}\end{document}",
    "100% sure",
    "$x$ and $$y$$",
    r"# $ % & _ { } ~ ^ \ < > | \"",
    "a--b---c ?` !`",
    "Übung — Müller, Łódź, Straße, α/β → θ",
    "中文 🤖",
    "bidi\u202eevil\x00\x1b[31m",
]

#: The control sequences escape_latex may write, and nothing else: escaped specials,
#: the typewriter glyphs, text accents and symbols, Greek letters in math.
ALLOWED_COMMANDS = {
    *"{}#$%&'`^~=.\"",
    *"uvrHdc",
    *("textbackslash", "ttfamily", "char", "ensuremath", "texttt", "ldots"),
    *("i", "j", "ss", "ae", "AE", "oe", "OE", "o", "O", "l", "L", "aa", "AA"),
    *("S", "P", "copyright", "pounds", "circ", "times", "cdot", "pm", "leq", "geq"),
    *("rightarrow", "infty", "varsigma", "varepsilon"),
    *(
        "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi pi rho "
        "sigma tau upsilon phi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Upsilon "
        "Phi Psi Omega"
    ).split(),
}

_COMMAND = re.compile(r"\\([A-Za-z]+|.)")


def _commands(tex: str) -> set[str]:
    return set(_COMMAND.findall(tex))


def _braces_balance(tex: str) -> bool:
    depth, k = 0, 0
    while k < len(tex):  # escaped braces \{ \} do not count
        if tex[k] == "\\" and k + 1 < len(tex) and tex[k + 1] in "{}":
            k += 2
            continue
        depth += {"{": 1, "}": -1}.get(tex[k], 0)
        if depth < 0:
            return False
        k += 1
    return depth == 0


# --- LaTeX ------------------------------------------------------------------------------


@pytest.mark.parametrize("text", HOSTILE)
def test_escaped_text_has_no_live_commands_or_specials(text):
    out = escape_latex(text)
    assert isinstance(out, TeX) and out.isascii()
    assert _commands(out) <= ALLOWED_COMMANDS, (text, out)
    for cmd in ("input", "write", "end", "include", "openin", "catcode", "def", "csname"):
        assert cmd not in _commands(out)
    rest = out
    for safe in (r"\textbackslash{}", r"\{", r"\}", r"\#", r"\$", r"\%", r"\&"):
        rest = rest.replace(safe, "")
    rest = re.sub(r"\{\\ttfamily\\char[0-9]+\}", "", rest)
    for ch in "#$%&_^~":
        assert ch not in rest, (text, out)


def test_escaping_of_each_special_character():
    assert escape_latex("#$%&") == r"\#\$\%\&"
    assert escape_latex("a_b") == r"a{\ttfamily\char95}b"
    assert escape_latex("{x}") == r"\{x\}"
    assert escape_latex("\\") == r"\textbackslash{}"
    assert escape_latex("~^") == r"{\ttfamily\char126}{\ttfamily\char94}"
    assert escape_latex("<|>") == r"{\ttfamily\char60}{\ttfamily\char124}{\ttfamily\char62}"
    assert escape_latex("--") == "-{}-{}"
    assert escape_latex("?`!`") == "?{}`!{}`"  # no Spanish ligatures
    assert escape_latex("line\nbreak\ttab\rcr") == "line break tab cr"


def test_commands_are_printed_as_text():
    assert escape_latex(r"\input{/etc/passwd}") == r"\textbackslash{}input\{/etc/passwd\}"
    assert escape_latex(r"\write18{rm -rf /}") == r"\textbackslash{}write18\{rm -{}rf /\}"
    assert escape_latex("^^5cinput") == r"{\ttfamily\char94}{\ttfamily\char94}5cinput"


def test_escaping_of_unicode():
    assert escape_latex("é") == r"\'{e}"
    assert escape_latex("ï") == r"\"{\i{}}"
    assert escape_latex("Ł ß") == r"\L{} \ss{}"
    assert (
        escape_latex("θ Ω ς") == r"\ensuremath{\theta} \ensuremath{\Omega} \ensuremath{\varsigma}"
    )
    assert escape_latex("Α") == "A"  # a capital alpha is drawn as a Latin A
    assert escape_latex("中") == r"\texttt{[U+4E2D]}"
    assert escape_latex("🤖") == r"\texttt{[U+1F916]}"
    assert escape_latex("a\u00a0b\u2003c") == "a~b c"  # no-break space, em space


def test_control_and_format_characters_are_dropped():
    assert escape_latex("\u202e\u200b\x07\x1b\x00") == ""  # bidi, zero width, bell, ESC, NUL
    assert escape_latex("a\u2028b") == "ab"  # a line separator is dropped, not a break


def test_the_result_is_trusted_tex_and_text_is_read_with_str():
    out = escape_latex(12.5)
    assert out == "12.5" and isinstance(out, TeX)
    assert escape_latex(TeX(r"\alpha")) == r"\textbackslash{}alpha"  # escaping never trusts


@given(st.text(max_size=60))
def test_any_text_gives_balanced_ascii_with_only_harmless_commands(text):
    out = escape_latex(text)
    assert out.isascii()
    assert _braces_balance(out)
    assert _commands(out) <= ALLOWED_COMMANDS
    assert "\n" not in out and "%" not in out.replace(r"\%", "")


@given(st.text(alphabet="abcxyzABC0123456789 .,:;()+=/*'@", max_size=40))
def test_plain_text_is_left_as_it_is(text):
    assert escape_latex(text) == text


@given(st.text(max_size=40))
def test_composed_and_decomposed_text_escape_alike(text):
    nfd = unicodedata.normalize("NFD", text)
    assert escape_latex(nfd) == escape_latex(unicodedata.normalize("NFC", text))


@given(st.text(max_size=30), st.sampled_from(["\x00", "\x1b", "\u202e", "\u200b", "\x7f"]))
def test_inserted_control_characters_change_nothing(text, control):
    for k in (0, len(text) // 2, len(text)):
        assert escape_latex(text[:k] + control + text[k:]) == escape_latex(text)


def test_escaped_text_compiles_and_prints_literally(tmp_path, need_tex):
    from dhsym.explain.latex import compile_pdf

    lines = [*HOSTILE[:-2], "".join(chr(c) for c in range(33, 127)), "Straße Ærø øre"]
    body = "\n\n".join(escape_latex(line) for line in lines)
    tex = tmp_path / "escaped.tex"
    tex.write_text(
        "\\documentclass{article}\n\\begin{document}\n\\raggedright\n"
        + body
        + "\n\\end{document}\n",
        encoding="ascii",
    )
    pdf = compile_pdf(tex)
    text = subprocess.run(
        ["pdftotext", str(pdf), "-"], capture_output=True, text=True, check=True
    ).stdout
    flat = " ".join(unicodedata.normalize("NFC", text).replace("’", "'").split())
    for line in (r"\input{/etc/passwd}", "100% sure", "$x$ and $$y$$", "Straße Ærø øre"):
        assert line in flat, line
    assert "root:" not in flat


# --- Markdown ---------------------------------------------------------------------------


def _unescape_markdown(md: str) -> str:
    """The text a reader sees: backslash escapes and the three entities undone."""
    plain = re.sub(r"\\(.)", r"\1", md)
    return plain.replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&")


def test_markdown_specials_html_and_math_are_escaped():
    assert escape_markdown("a_1 *b* <script>") == r"a\_1 \*b\* &lt;script&gt;"
    assert escape_markdown("[x](javascript:1)") == r"\[x\](javascript:1)"
    assert escape_markdown("$\\input$") == r"\$\\input\$"
    assert escape_markdown("# h | c ~~s~~ `c` {a} !x &") == (
        r"\# h \| c \~\~s\~\~ \`c\` \{a\} \!x &amp;"
    )
    assert escape_markdown("two\nlines\x1b[31m\u202e") == r"two lines\[31m"


def test_markdown_html_comes_out_as_text():
    html = MarkdownIt().render(escape_markdown('<img src=x onerror="alert(1)"> <b>b</b>'))
    assert "<img" not in html and "<b>" not in html
    assert "&lt;img src=x onerror=&quot;alert(1)&quot;&gt;" in html


@given(st.text(max_size=60))
def test_markdown_shows_exactly_the_cleaned_text(text):
    out = escape_markdown(text)
    assert "\n" not in out and "<" not in out and ">" not in out
    assert re.search(r"(?<!\\)[`*_\[\]#|$~{}!]", out.replace("\\\\", "")) is None
    assert _unescape_markdown(out) == " ".join(clean_text(text).splitlines())


@given(st.text(alphabet="ab _*[]()#<>&`|$!~ ", max_size=40).map(str.strip))
def test_a_markdown_renderer_shows_the_text_without_markup(text):
    html = MarkdownIt("commonmark").render(escape_markdown(text))
    if not text.strip():
        return
    inner = re.fullmatch(r"<p>(.*)</p>\n", html, flags=re.S)
    assert inner is not None, html
    shown = html_module.unescape(inner.group(1))
    assert "<" not in inner.group(1)  # no tag: no emphasis, code, link or HTML
    assert shown == text


# --- plain text -------------------------------------------------------------------------


def test_clean_text_drops_terminal_escapes_and_bidi_but_keeps_layout():
    assert clean_text("a\x1b[2Jb\u202ec\u200bd\x00") == "a[2Jbcd"
    assert clean_text("x\ty\nz") == "x\ty\nz"
    assert clean_text(3) == "3"


def test_clean_text_of_printable_text_is_the_text_for_every_character():
    """A printable text (no Cc or Cf character) comes back as it is: the per-character
    filter gives the same for every character of the Basic Multilingual Plane."""

    def reference(text: str) -> str:
        return "".join(
            ch for ch in text if ch in "\n\t" or unicodedata.category(ch) not in ("Cc", "Cf")
        )

    for code in range(0x10000):
        for text in (chr(code), f"a·π{chr(code)}b", f"x{chr(code)}"):
            assert clean_text(text) == reference(text), hex(code)
