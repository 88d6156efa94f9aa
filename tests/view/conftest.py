"""A headless Chromium for the view's tests (Debian's /usr/bin/chromium, driven by
Playwright), one per test module, and a guard that records and refuses every request
that would leave the machine."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    import importlib.util
    import shutil

    from tests.conftest import _need

    _need("Chromium", bool(shutil.which("chromium")), "apt-get install chromium")
    found = importlib.util.find_spec("playwright") is not None
    _need("playwright", found, "pip install -e '.[test]'")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        chromium = p.chromium.launch(
            executable_path="/usr/bin/chromium",
            headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-background-networking"],
        )
        try:
            yield chromium
        finally:
            chromium.close()


class Guarded:
    """A page whose requests outside ``file:``/``data:``/``blob:`` are refused and listed,
    and whose script errors are listed."""

    def __init__(self, browser: Any) -> None:
        self.page = browser.new_page()
        self.outside: list[str] = []
        self.errors: list[str] = []
        self.page.route("**/*", self._guard)
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        self.page.on("console", lambda m: self.errors.append(m.text) if m.type == "error" else None)

    def _guard(self, route: Any) -> None:
        url = route.request.url
        if url.startswith(("file:", "data:", "blob:")):
            route.continue_()
        else:
            self.outside.append(url)
            route.abort()


@pytest.fixture
def guarded(browser: Any) -> Iterator[Guarded]:
    g = Guarded(browser)
    try:
        yield g
    finally:
        g.page.close()
