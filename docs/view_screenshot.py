"""Take the docs' screenshot of the 3D view: docs/view-puma560.png, the page of
``dhsym view puma560`` in headless Chromium with the link matrices shown, θ3 just moved.

Run from the repository root: ``.venv/bin/python docs/view_screenshot.py`` (needs Debian's
chromium and Playwright, the ``test`` extra).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import dhsym
from dhsym.view import view_page

OUT = Path(__file__).resolve().parent / "view-puma560.png"
MOVE = """([joint, value]) => {
  const input = document.querySelector(`input[data-joint="${joint}"]`);
  input.value = String(value);
  input.dispatchEvent(new Event("input"));
}"""


def main(path: Path = OUT) -> Path:
    """Write the screenshot."""
    from playwright.sync_api import sync_playwright

    with tempfile.TemporaryDirectory() as tmp:
        page_file = Path(tmp) / "puma560.html"
        page_file.write_text(view_page(dhsym.load("puma560"), workspace=0), encoding="utf-8")
        with sync_playwright() as p:
            browser = p.chromium.launch(
                executable_path="/usr/bin/chromium",
                args=["--no-sandbox", "--disable-gpu", "--disable-background-networking"],
            )
            page = browser.new_page(viewport={"width": 1100, "height": 760})
            page.goto(page_file.as_uri())
            page.wait_for_function("() => window.dhsymView && window.dhsymView.redraws > 0")
            for joint, value in ((2, -0.6), (5, 0.8), (3, 0.4)):
                page.evaluate(MOVE, [joint, value])
            page.get_by_role("button", name="link matrices").click()
            page.screenshot(path=str(path), full_page=True)
            browser.close()
    return path


if __name__ == "__main__":
    print(f"wrote {main()}")
