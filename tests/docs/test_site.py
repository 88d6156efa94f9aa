"""The documentation site: built clean, complete, linked, and typeset offline.

The site is built once per module (``scripts/build_docs.py``, the code of ``make docs``)
into a temporary folder: Sphinx with warnings as errors, every internal link and anchor of
the HTML checked, nothing loaded from another host. Then: every public name, command,
mistake kind, file key and notebook has its page; and headless Chromium opens pages and
finds the mathematics typeset by the local MathJax with no request leaving the machine.
The Python examples of every page run as doctests (fast, without the build).
"""

from __future__ import annotations

import doctest
import functools
import html
import importlib
import inspect
import re
import sys
import textwrap
import threading
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from tests.conftest import _need

ROOT = Path(__file__).resolve().parent.parent.parent
DOCS = ROOT / "docs"
PAGES = sorted(p for p in DOCS.rglob("*.md") if "_build" not in p.parts)
BLOCKS = {p: re.findall(r"```python\n(.*?)```", p.read_text(encoding="utf-8"), re.S) for p in PAGES}
#: pages whose Python examples are doctests (``>>>`` with their output): they are run
EXAMPLES = [p for p, blocks in BLOCKS.items() if any(">>> " in b for b in blocks)]
#: code listings without output (a how-to's recipe): they must at least be valid Python
LISTINGS = [(p, b) for p, blocks in BLOCKS.items() for b in blocks if ">>> " not in b]


def _build_docs_module():
    sys.path.insert(0, str(ROOT / "scripts"))
    try:
        return importlib.import_module("build_docs")
    finally:
        sys.path.remove(str(ROOT / "scripts"))


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    ok = all(
        importlib.util.find_spec(m) for m in ("sphinx", "myst_nb", "numpydoc", "sphinx_copybutton")
    ) and importlib.util.find_spec("pydata_sphinx_theme")
    _need("Sphinx and its extensions", bool(ok), "pip install -e '.[docs]'")
    _need(
        "MathJax",
        Path("/usr/share/javascript/mathjax/MathJax.js").is_file(),
        "apt-get install libjs-mathjax",
    )
    report = _build_docs_module().build(tmp_path_factory.mktemp("docs") / "site")
    return report


def _text(path: Path) -> str:
    return path.read_text(encoding="utf-8")


def _ids(path: Path) -> set[str]:
    return set(re.findall(r'id="([^"]+)"', _text(path)))


# --------------------------------------------------------------------------- the build


@pytest.mark.slow
def test_the_site_builds_without_a_warning(site):
    assert site.status == 0
    assert site.warnings == ()
    assert site.pages > 50


@pytest.mark.slow
def test_internal_links_and_anchors_resolve(site):
    assert site.broken_links == ()


@pytest.mark.slow
def test_nothing_is_loaded_from_another_host(site):
    assert site.remote_resources == ()
    assert (site.outdir / "_static/mathjax/MathJax.js").is_file()
    assert (site.outdir / "_static/mathjax/config/TeX-AMS_CHTML-full.js").is_file()


@pytest.mark.slow
def test_every_page_of_the_sources_is_built(site):
    for page in PAGES:
        rel = page.relative_to(DOCS).with_suffix(".html")
        assert (site.outdir / rel).is_file(), rel


@pytest.mark.slow
def test_every_public_name_has_its_documentation(site):
    import dhsym

    ext = _load_extension()
    homes = ext._home(ext._walk("dhsym"))
    all_ids = set().union(*(_ids(p) for p in (site.outdir / "api").glob("*.html")))
    for name in dhsym.__all__:
        obj = getattr(dhsym, name)
        if inspect.ismodule(obj) or name.startswith("_"):
            continue
        if id(obj) in homes:  # a class or function: on the page of the room that defines it
            home = homes[id(obj)][0]
            assert f"{home}.{name}" in _ids(site.outdir / "api" / f"{home}.html"), (name, home)
        else:  # a constant: on the page of a module that exports it
            assert any(i.endswith(f".{name}") for i in all_ids), name


@pytest.mark.slow
def test_every_public_module_has_a_page(site):
    ext = _load_extension()
    for module in ext._walk("dhsym")[1:]:
        assert (site.outdir / "api" / f"{module}.html").is_file(), module
    assert "dhsym.__main__" not in ext._walk("dhsym")


@pytest.mark.slow
def test_every_command_and_option_is_in_the_cli_reference(site):
    from dhsym.cli.main import build_parser

    ext = _load_extension()
    page = html.unescape(_text(site.outdir / "reference" / "cli.html"))

    def walk(parser, prefix):
        for name, _, sub in ext._subcommands(parser):
            title = f"{prefix} {name}"
            assert f">{title}<" in page, title
            for action in sub._actions:
                for option in action.option_strings:
                    assert option in page, (title, option)
            walk(sub, title)

    walk(build_parser(), "dhsym")


@pytest.mark.slow
def test_every_mistake_kind_is_in_the_catalogue(site):
    from dhsym.checking.mistakes import registry as mistakes

    page = _text(site.outdir / "reference" / "mistakes.html")
    detectors = [
        cls.kind
        for cls in vars(mistakes).values()
        if inspect.isclass(cls) and isinstance(getattr(cls, "kind", None), str) and cls.kind
    ] + [
        m.kind
        for m in (
            *mistakes.dynamics_mistakes(),
            *mistakes.SCREW_MISTAKES,
            *mistakes.TRAJECTORY_MISTAKES,
        )
    ]
    kinds = set(detectors)
    assert len(kinds) >= 15
    # the header, one row a detector (two detectors may find one kind: a whole matrix or
    # one 3×3 block transposed)
    assert len(re.findall(r"<tr", page)) == len(detectors) + 1
    assert ":class:" not in page and "{py:class}" not in page  # the links were resolved
    for kind in kinds:
        assert f'<code class="docutils literal notranslate"><span class="pre">{kind}' in page


@pytest.mark.slow
def test_every_notebook_is_a_tutorial_with_its_pictures(site):
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    assert len(notebooks) >= 9
    for nb in notebooks:
        page = site.outdir / "tutorials" / "notebooks" / f"{nb.stem}.html"
        assert page.is_file(), nb.name
        if '"image/png"' in _text(nb):
            assert re.search(r'<img [^>]*src="\.\./\.\./_images/', _text(page)), nb.name


@pytest.mark.slow
def test_no_page_shows_markdown_or_latex_as_text(site):
    # outside code and typeset maths, no `$…$`, no `|` table row, no stray backtick
    assert site.raw_markup == ()


@pytest.mark.slow
def test_the_tutorials_typeset_their_outputs(site):
    # dhsym's objects show themselves as Markdown (pipe tables, $…$ maths): MyST parses them
    page = _text(site.outdir / "tutorials" / "notebooks" / "01_planar_2R.html")
    outputs = "".join(re.findall(r'<div class="cell_output.*?(?=<div class="cell |\Z)', page, re.S))
    assert "<table" in outputs and '<span class="math' in outputs
    assert "\\(\\theta_i\\)" in outputs  # the table's header, typeset


@pytest.mark.slow
def test_every_tutorial_is_listed_by_its_title(site):
    index = html.unescape(_text(site.outdir / "tutorials" / "index.html"))
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        label = re.search(rf'href="notebooks/{nb.stem}\.html">([^<]*)<', index)
        assert label and label.group(1).startswith(f"{int(nb.stem[:2])} · "), nb.stem
        assert label.group(1) in _text(nb), nb.stem  # its title, the notebook's first heading


@pytest.mark.slow
def test_a_pipe_inside_a_table_cell_stays_in_its_cell(site):
    page = html.unescape(_text(site.outdir / "guide" / "dynamics.html"))
    cells = re.findall(r"<td><p>(.*?)</p></td>", page, re.S)
    code = [
        re.sub(r"<[^>]+>", "", c) for cell in cells for c in re.findall(r"<code.*?</code>", cell)
    ]
    assert "B·G²·q̇ + |G|·Tc" in code


def test_the_check_finds_raw_markup():
    check = _build_docs_module().raw_markup
    shown = "<p>| $i$ | joint |</p><p>gains `B·G²·q̇ + </p>"
    assert check(shown) == ["$i$", "| $i$ | joint |", "`B·G²·q̇ + "]
    typeset = (
        '<table><tr><td><span class="math">\\(\\theta_i\\)</span></td></tr></table>'
        "<p><code>$x$ | y</code> the <code>--format markdown</code> ($...$ maths)</p>"
        '<div class="highlight"><pre>print("$a$")\n| b</pre></div>'
    )
    assert check(typeset) == []


# --------------------------------------------------------------------------- schemas


def test_every_table_file_key_is_in_its_reference():
    from dhsym.model import tablefile

    page = _text(DOCS / "reference" / "table-file.md")
    for key in (*tablefile._TOP_KEYS, *tablefile._ROW_KEYS):
        assert re.search(rf"^\| `{key}` \|", page, re.M), key


def test_every_assignment_key_is_in_its_reference():
    from dhsym.checking.grading.assignment import Assignment

    source = inspect.getsource(Assignment.load)
    keys = set(re.findall(r"""(?:data|q)(?:\.get\(|\[)["'](\w+)["']""", source))
    assert {"questions", "key", "time_limit", "id", "ask", "points", "tool"} <= keys
    page = _text(DOCS / "reference" / "assignment-file.md")
    for key in keys:
        assert re.search(rf"^\| `{key}` \|", page, re.M), key


# --------------------------------------------------------------------------- examples


@pytest.mark.parametrize("page", EXAMPLES, ids=[str(p.relative_to(DOCS)) for p in EXAMPLES])
def test_the_python_examples_of_every_page_run(page):
    blocks = re.findall(r"```python\n(.*?)```", _text(page), re.S)
    parser = doctest.DocTestParser()
    test = parser.get_doctest("\n".join(blocks), {}, page.name, str(page), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    runner.run(test)
    assert runner.tries > 0 and runner.failures == 0


@pytest.mark.parametrize(
    "page, block", LISTINGS, ids=[f"{p.relative_to(DOCS)}:{k}" for k, (p, _) in enumerate(LISTINGS)]
)
def test_every_code_listing_is_valid_python(page, block):
    compile(textwrap.dedent(block), str(page), "exec")  # a listing may sit in a list item


# --------------------------------------------------------------------------- the browser


def _load_extension():
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        return importlib.import_module("dhsym_docs")
    finally:
        sys.path.remove(str(DOCS / "_ext"))


class _QuietHandler(SimpleHTTPRequestHandler):
    def log_message(self, *args: object) -> None:
        pass


@pytest.fixture(scope="module")
def served(site):
    handler = functools.partial(_QuietHandler, directory=str(site.outdir))
    server = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]
MATH = "document.querySelectorAll('span.math, div.math')"
UNTYPESET = f"Array.from({MATH}).filter(e => !e.querySelector('.MathJax_CHTML')).length"
MATHJAX_DONE = (
    "() => window.MathJax && MathJax.Hub && MathJax.Hub.queue.pending === 0 "
    f"&& {MATH}.length > 0 && {UNTYPESET} === 0"
)


@pytest.mark.slow
@pytest.mark.browser
def test_pages_typeset_their_mathematics_offline(served, need_chromium, need_playwright):
    from playwright.sync_api import sync_playwright

    pages = {
        "index.html": "dhsym",
        "tutorials/notebooks/03_puma560.html": "PUMA 560",
        # Markdown outputs: pipe tables, $…$ and $$…$$ inside a paragraph (MyST parses them)
        "tutorials/notebooks/08_jacobian_singularities.html": "Jacobian",
        "api/dhsym.robot.html": "Robot",
    }
    outside: list[str] = []
    local = urlsplit(served).netloc

    def route(r):
        if urlsplit(r.request.url).netloc == local:
            r.continue_()
        else:
            outside.append(r.request.url)
            r.abort()

    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS
        )
        try:
            context = browser.new_context()
            context.route("**/*", route)
            page = context.new_page()
            failed: list[str] = []
            page.on("requestfailed", lambda req: failed.append(req.url))
            for path, words in pages.items():
                page.goto(f"{served}/{path}", wait_until="load")
                assert words in page.title() + page.inner_text("main"), path
                if path.startswith("api/"):
                    assert page.locator("[id='dhsym.robot.Robot']").count() == 1
                page.wait_for_function(MATHJAX_DONE, timeout=120_000)
                assert page.evaluate(f"{MATH}.length") > 0 and page.evaluate(UNTYPESET) == 0
                errors = page.evaluate("document.querySelectorAll('.MathJax_Error, merror').length")
                assert errors == 0, path
            assert failed == [] and outside == [], (failed, outside)
        finally:
            browser.close()
