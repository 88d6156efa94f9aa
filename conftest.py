"""The test session's own disk cache (dhsym.cache.store): set before any test or doctest
runs, inherited by the command-line processes the tests start, removed at the end. No
test reads or writes the user's cache; a test that needs an empty cache sets
``DHSYM_CACHE`` to a folder of its own."""

from __future__ import annotations

import os
import shutil
import tempfile

_SAVED: dict[str, str | None] = {}


def pytest_configure(config: object) -> None:
    for name in ("DHSYM_CACHE", "DHSYM_NO_CACHE"):
        _SAVED[name] = os.environ.get(name)
    os.environ["DHSYM_CACHE"] = tempfile.mkdtemp(prefix="dhsym-test-cache-")
    os.environ.pop("DHSYM_NO_CACHE", None)


def pytest_unconfigure(config: object) -> None:
    folder = os.environ.get("DHSYM_CACHE")
    if folder and os.path.basename(folder).startswith("dhsym-test-cache-"):
        shutil.rmtree(folder, ignore_errors=True)
    for name, value in _SAVED.items():
        if value is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = value
