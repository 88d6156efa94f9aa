"""The test session's own disk cache (dhsym.cache.store): set before any test or doctest
runs, inherited by the command-line processes the tests start, removed at the end. No
test reads or writes the user's cache; a test that needs an empty cache sets
``DHSYM_CACHE`` to a folder of its own.

The folder is shared, never per test: under pytest-xdist the controller makes it before
it starts its workers and every worker keeps the one it inherits, so a robot derived by
one worker is read by the others; ``make test`` makes one folder for its two steps and
names it in ``DHSYM_TEST_CACHE`` (the steps then leave it for ``make`` to remove). The
store is made to be shared (atomic writes, every entry checked against its HMAC; an
entry that fails the check is rebuilt, never used). Only the process that made a folder
removes it."""

from __future__ import annotations

import os
import shutil
import tempfile

PREFIX = "dhsym-test-cache-"
_SAVED: dict[str, str | None] = {}
_MADE: list[str] = []


def _given_folder(config: object) -> str | None:
    """The folder this session is given: ``DHSYM_TEST_CACHE`` (``make test``), else the
    one an xdist worker inherits from its controller; ``None`` for a new one."""
    given = os.environ.get("DHSYM_TEST_CACHE", "")
    if given and os.path.isdir(given):
        return given
    if not hasattr(config, "workerinput"):
        return None
    folder = os.environ.get("DHSYM_CACHE", "")
    ok = os.path.basename(folder).startswith(PREFIX) and os.path.isdir(folder)
    return folder if ok else None


def pytest_configure(config: object) -> None:
    for name in ("DHSYM_CACHE", "DHSYM_NO_CACHE"):
        _SAVED[name] = os.environ.get(name)
    folder = _given_folder(config)
    if folder is None:
        folder = tempfile.mkdtemp(prefix=PREFIX)
        _MADE.append(folder)
    os.environ["DHSYM_CACHE"] = folder
    os.environ.pop("DHSYM_NO_CACHE", None)


def pytest_unconfigure(config: object) -> None:
    for folder in _MADE:
        shutil.rmtree(folder, ignore_errors=True)
    _MADE.clear()
    for name, value in _SAVED.items():
        if value is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = value
