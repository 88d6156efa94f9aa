"""Feedback and summary pages in headless Chromium: mathematics typeset, nothing fetched.

A small class is graded into a report folder; Debian's Chromium (driven by Playwright,
no browser download) opens each page from ``file://`` with every request routed through
the test, which refuses and records anything that is not a local file. The key's
entries must be laid out as mathematics (a subscript sits lower and smaller than its
base), and no raw LaTeX delimiters may be left in the text a student reads.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsym.checking import grade

pytestmark = [pytest.mark.browser, pytest.mark.slow]

RIGHT = (
    "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0], [0, 0, 0, 1]]"
)
WRONG = RIGHT.replace("a1*C1 + a2*C12", "a1*C1 - a2*C12")

SUBSCRIPT = """() => {
  const sub = document.querySelector("td math msub");
  const [base, index] = [sub.children[0], sub.children[1]];
  const b = base.getBoundingClientRect(), i = index.getBoundingClientRect();
  const size = (e) => parseFloat(getComputedStyle(e).fontSize);
  return {lower: i.bottom > b.bottom, smaller: size(index) < size(base),
          width: sub.getBoundingClientRect().width};
}"""


def _class(root: Path) -> tuple[Path, Path]:
    (root / "assignment.yaml").write_text(
        "title: browser check\nkey: planar2r\nquestions:\n  - {id: q1, ask: T0_2, points: 2}\n",
        encoding="utf-8",
    )
    for student, answer in (("ann", RIGHT), ("bo", WRONG)):
        (root / "subs" / student).mkdir(parents=True)
        (root / "subs" / student / "q1.txt").write_text(answer, encoding="utf-8")
    return root / "assignment.yaml", root / "subs"


def test_feedback_is_typeset_offline(tmp_path, need_chromium, need_playwright):
    from playwright.sync_api import sync_playwright

    assignment, subs = _class(tmp_path)
    report = grade(assignment, subs, tmp_path / "report", workers=1, progress=False)
    assert report is not None
    pages = sorted((tmp_path / "report" / "feedback").glob("*.html"))
    pages.append(tmp_path / "report" / "summary.html")
    outside: list[str] = []

    def guard(route) -> None:  # noqa: ANN001 - a Playwright Route
        if route.request.url.startswith("file://"):
            route.continue_()
        else:
            outside.append(route.request.url)
            route.abort()

    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path="/usr/bin/chromium",
            headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-background-networking"],
        )
        try:
            page = browser.new_page()
            page.route("**/*", guard)
            typeset = 0
            for path in pages:
                page.goto(path.as_uri())
                page.wait_for_load_state("networkidle")
                text = page.inner_text("body")
                assert "\\(" not in text and "\\)" not in text, path.name
                if page.locator("td math msub").count():
                    typeset += 1
                    got = page.evaluate(SUBSCRIPT)
                    assert got["lower"] and got["smaller"] and got["width"] > 0, got
            assert page.locator("script").count() == 0
        finally:
            browser.close()
    assert typeset == 1  # bo's page shows the key's entry a1 C1 + a2 C12 typeset
    assert outside == []
