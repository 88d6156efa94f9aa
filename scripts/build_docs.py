"""Build dhsym's documentation site (``make docs``), warnings as errors, links checked.

Copies ``docs/`` into a staging folder (the API pages and the notebooks are generated
there, never in the source tree), runs Sphinx with ``-W --keep-going``, then checks every
internal link and resource of the built HTML (files and ``#anchors``), that no page
loads anything from another host, and that no page shows Markdown or LaTeX as raw text
(``$…$``, a ``|`` table row or a backtick in its prose: a notebook output or a table cell
that was not parsed). Usage::

    python scripts/build_docs.py [OUTDIR]      # default build/docs

Exit status 0 when the site built clean, 1 otherwise (the problems are printed).
"""

from __future__ import annotations

import os
import re
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

ROOT = Path(__file__).resolve().parent.parent


@dataclass(frozen=True)
class SiteReport:
    """What a build produced: Sphinx's warnings, broken internal links, remote loads."""

    outdir: Path
    status: int
    warnings: tuple[str, ...]
    broken_links: tuple[str, ...]
    remote_resources: tuple[str, ...]
    pages: int
    seconds: float
    raw_markup: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        return self.status == 0 and not (
            self.warnings or self.broken_links or self.remote_resources or self.raw_markup
        )


@dataclass
class _Page(HTMLParser):
    links: list[tuple[str, str]] = field(default_factory=list)  # (attribute, url)
    ids: set[str] = field(default_factory=set)

    def __post_init__(self) -> None:
        super().__init__()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if value is None:
                continue
            if name in ("id", "name") and (name == "id" or tag == "a"):
                self.ids.add(value)
            if name in ("href", "src") and not (tag == "link" and ("rel", "canonical") in attrs):
                self.links.append((f"{tag}.{name}", value))


def check_links(outdir: Path) -> tuple[list[str], list[str], int]:
    """Broken internal links and remote resources of a built HTML site, and its page count.

    A link is internal when it has no scheme; it must name an existing file and, with a
    ``#fragment``, an id of that page. Scripts, stylesheets, images and fonts must all be
    internal (``<a href>`` to other sites is allowed: it loads nothing).
    """
    pages = {p: _Page() for p in outdir.rglob("*.html") if "_static" not in p.parts}
    for path, page in pages.items():
        page.feed(path.read_text(encoding="utf-8", errors="replace"))
    broken, remote = [], []
    for path, page in sorted(pages.items()):
        rel = path.relative_to(outdir)
        for where, url in page.links:
            parts = urlsplit(url)
            if parts.scheme or url.startswith("//"):
                if where != "a.href" and parts.scheme not in ("data",):
                    remote.append(f"{rel}: {where} {url}")
                continue
            target = path if not parts.path else (path.parent / unquote(parts.path)).resolve()
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                broken.append(f"{rel}: {url}")
                continue
            if parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else set()
                if unquote(parts.fragment) not in ids:
                    broken.append(f"{rel}: {url} (no such anchor)")
    return broken, remote, len(pages)


#: elements whose text is not prose: code, scripts, and maths typeset by MathJax
_NOT_PROSE = {"script", "style", "pre", "code", "kbd", "samp", "textarea", "head", "title"}
_VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source",
         "track", "wbr"}  # fmt: skip
#: elements that end a line of prose
_BLOCKS = {"p", "div", "li", "td", "th", "tr", "dt", "dd", "h1", "h2", "h3", "h4", "h5", "h6",
           "blockquote", "section", "table"}  # fmt: skip
#: inline maths left as text (``$...$`` or ``$…$`` alone names the notation, it is no maths)
_DOLLARS = re.compile(r"\$(?!(?:\.\.\.|…)\$)[^\s$][^$\n]*?\$")


@dataclass
class _Prose(HTMLParser):
    """The text of a page that a reader sees as prose (outside code and typeset maths)."""

    chunks: list[str] = field(default_factory=list)
    open: list[bool] = field(default_factory=list)  # per open element: is it not prose?

    def __post_init__(self) -> None:
        super().__init__()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag not in _VOID:
            classes = (dict(attrs).get("class") or "").split()
            self.open.append(tag in _NOT_PROSE or "math" in classes)

    def handle_endtag(self, tag: str) -> None:
        if tag not in _VOID and self.open:
            self.open.pop()
        if tag in _BLOCKS:
            self.chunks.append("\n")

    def handle_data(self, data: str) -> None:
        if not any(self.open):
            self.chunks.append(data)


def raw_markup(page: str) -> list[str]:
    r"""Markdown or LaTeX that a page shows as text: ``$…$``, ``|`` rows, stray backticks.

    Only prose counts: code, ``<pre>`` blocks and the maths MathJax typesets (elements of
    class ``math``) are left out.

    >>> raw_markup(r'<p>| $i$ | $\theta_i$ |</p><span class="math">\(x\)</span>')
    ['$i$', '$\\theta_i$', '| $i$ | $\\theta_i$ |']
    >>> raw_markup('<p>gains `B + </p><p>$...$ maths, <code>$x$</code></p>')
    ['`B + ']
    """
    prose = _Prose()
    prose.feed(page)
    text = "".join(prose.chunks)
    found = [m.group(0) for m in _DOLLARS.finditer(text)]
    found += [line.strip() for line in text.splitlines() if line.lstrip().startswith("|")]
    found += [text[k : k + 40].split("\n")[0] for k in range(len(text)) if text[k] == "`"]
    return found


def check_prose(outdir: Path) -> list[str]:
    """Pages of the site that show raw Markdown or LaTeX, and what (see :func:`raw_markup`).

    The API pages (numpydoc's rendering of the docstrings) and Sphinx's index pages are
    left out.
    """
    out = []
    for path in sorted(outdir.rglob("*.html")):
        rel = path.relative_to(outdir)
        if rel.parts[0] in ("_static", "_modules", "api", "_sources") or rel.name in (
            "genindex.html", "search.html", "py-modindex.html"
        ):  # fmt: skip
            continue
        for snippet in raw_markup(path.read_text(encoding="utf-8", errors="replace")):
            out.append(f"{rel}: {snippet}")
    return out


def build(outdir: Path, *, quiet: bool = True) -> SiteReport:
    """Build the site into ``outdir`` and check it (see the module's docstring)."""
    from sphinx.cmd.build import build_main

    start = time.perf_counter()
    outdir = outdir.resolve()
    with tempfile.TemporaryDirectory(prefix="dhsym-docs-") as tmp:
        src, warnfile = Path(tmp) / "src", Path(tmp) / "warnings.txt"
        shutil.copytree(ROOT / "docs", src, ignore=shutil.ignore_patterns("_build", "__pycache__"))
        os.environ["DHSYM_DOCS_ROOT"] = str(ROOT)
        args = ["-b", "html", "-W", "--keep-going", "-w", str(warnfile), "-j", "1"]
        args += ["-d", str(Path(tmp) / "doctrees"), str(src), str(outdir)]
        status = build_main([*args, "-q"] if quiet else args)
        warnings = (
            tuple(line for line in warnfile.read_text().splitlines() if line.strip())
            if warnfile.exists()
            else ()
        )
    broken, remote, count = check_links(outdir)
    raw = tuple(check_prose(outdir))
    return SiteReport(
        outdir, status, warnings, tuple(broken), tuple(remote), count,
        time.perf_counter() - start, raw,
    )  # fmt: skip


def main(argv: list[str]) -> int:
    outdir = Path(argv[0]) if argv else ROOT / "build" / "docs"
    report = build(outdir, quiet=False)
    for line in report.warnings:
        print(f"warning: {line}", file=sys.stderr)
    for line in report.broken_links:
        print(f"broken link: {line}", file=sys.stderr)
    for line in report.remote_resources:
        print(f"loads from another host: {line}", file=sys.stderr)
    for line in report.raw_markup:
        print(f"shows raw markup: {line}", file=sys.stderr)
    verdict = "built" if report.ok else "FAILED"
    print(
        f"docs {verdict}: {report.pages} pages in {report.outdir} "
        f"({report.seconds:.1f} s; open {report.outdir / 'index.html'})"
    )
    return 0 if report.ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
