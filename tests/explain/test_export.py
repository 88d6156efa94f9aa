"""Exporting a notebook: HTML whose math MathJax typesets offline (checked in headless Chromium),
and Markdown with its pictures beside it."""

from __future__ import annotations

import os
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import pytest

from dhsym.cli import main
from dhsym.explain.notebooks import export_notebook, local_mathjax_url

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOK = ROOT / "notebooks" / "01_planar_2R.ipynb"
ARTIFACTS = ROOT / "test-artifacts"

pytestmark = pytest.mark.jupyter


@pytest.fixture
def need_mathjax():
    """Require Debian's libjs-mathjax (CI installs it): the export must render math offline."""
    if local_mathjax_url() is None:
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail("MathJax is required in CI but missing: apt-get install libjs-mathjax")
        pytest.skip("libjs-mathjax not installed (apt-get install libjs-mathjax)")


class _VisibleText(HTMLParser):
    """Text a reader sees (outside script/style) and the classes used in the page."""

    def __init__(self) -> None:
        super().__init__()
        self.hidden = 0
        self.parts: list[str] = []
        self.classes: set[str] = set()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.classes.update((dict(attrs).get("class") or "").split())
        self.hidden += tag in ("script", "style")

    def handle_endtag(self, tag: str) -> None:
        self.hidden -= tag in ("script", "style")

    def handle_data(self, data: str) -> None:
        if not self.hidden:
            self.parts.append(data)


def _chromium(page: Path, profile: Path, *extra: str) -> str:
    cmd = [
        "chromium",
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-background-networking",
        "--disable-component-update",
        "--no-first-run",
        f"--user-data-dir={profile}",
        "--virtual-time-budget=10000",
        *extra,
        page.as_uri(),
    ]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


def _render(page: Path, profile: Path) -> _VisibleText:
    parser = _VisibleText()
    parser.feed(_chromium(page, profile, "--dump-dom"))
    return parser


def test_markdown_and_html_files(tmp_path, need_jupyter):
    written = export_notebook(NOTEBOOK, tmp_path)
    assert [p.name for p in written] == ["01_planar_2R.html", "01_planar_2R.md"]
    md = (tmp_path / "01_planar_2R.md").read_text()
    pictures = sorted((tmp_path / "01_planar_2R_files").glob("*.png"))
    assert len(pictures) >= 3
    for pic in pictures:
        assert f"01_planar_2R_files/{pic.name}" in md
    assert r"\begin{bmatrix}C_{12}" in md  # the arm matrix, as LaTeX for the Markdown viewer
    html = (tmp_path / "01_planar_2R.html").read_text()
    assert "data:image/png;base64," in html and "data:image/gif;base64," in html
    url = local_mathjax_url()
    if url is not None:
        assert f'src="{url}"' in html
    assert (
        main(
            ["notebooks", "export", str(NOTEBOOK), "-o", str(tmp_path / "cli"), "--to", "markdown"]
        )
        == 0
    )
    assert (tmp_path / "cli" / "01_planar_2R.md").is_file()
    assert main(["notebooks", "export", str(NOTEBOOK), "-o", str(tmp_path), "--to", "pdf"]) == 2


def test_html_math_is_typeset_offline(tmp_path, need_jupyter, need_chromium, need_mathjax):
    (page,) = export_notebook(NOTEBOOK, tmp_path / "ok", formats=("html",))
    seen = _render(page, tmp_path / "profile1")
    assert {"MathJax_CHTML", "mjx-chtml", "mjx-mtable"} <= seen.classes
    text = "".join(seen.parts)
    assert r"\begin{bmatrix}" not in text and "$$" not in text
    assert "C_{12}" not in text  # typeset, not raw TeX
    ARTIFACTS.mkdir(exist_ok=True)
    shot = ARTIFACTS / "export_01_planar_2R.png"
    shot.unlink(missing_ok=True)
    _chromium(
        page,
        tmp_path / "profile2",
        f"--screenshot={shot}",
        "--window-size=1200,2400",
        "--hide-scrollbars",
    )
    assert shot.read_bytes().startswith(b"\x89PNG") and shot.stat().st_size > 50_000


def test_without_mathjax_the_raw_tex_shows(tmp_path, need_jupyter, need_chromium):
    """The check above can fail: with MathJax missing, the raw matrices stay visible."""
    (page,) = export_notebook(
        NOTEBOOK, tmp_path, formats=("html",), mathjax_url=(tmp_path / "no" / "MathJax.js").as_uri()
    )
    seen = _render(page, tmp_path / "profile")
    assert r"\begin{bmatrix}" in "".join(seen.parts)
    assert "MathJax_CHTML" not in seen.classes
