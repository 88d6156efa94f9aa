"""Shared fixtures: symbols named as in the lectures; how pytest-xdist shares the tests
out (a module that builds a fixture once for its tests runs on one worker)."""

from __future__ import annotations

import functools
import re
from pathlib import Path

import pytest
import sympy as sp

#: a fixture built once for the tests of a module (or class, or package)
_SHARED_FIXTURE = re.compile(
    r"""@pytest\.fixture\(\s*scope\s*=\s*["'](?:module|class|package)["']"""
)


@functools.cache
def _builds_once(path: Path) -> bool:
    """Whether the test module at ``path`` defines a module-, class- or package-scoped
    fixture."""
    if not (path.name.startswith("test_") and path.suffix == ".py" and path.is_file()):
        return False
    return bool(_SHARED_FIXTURE.search(path.read_text(encoding="utf-8")))


def work_unit(nodeid: str, root: Path) -> str:
    """What pytest-xdist gives one worker at a time: the whole file of a test module
    that builds a shared fixture (:func:`_builds_once`), any other test by itself."""
    file = nodeid.split("::", 1)[0]
    return file if _builds_once(root / file) else nodeid


#: fixtures of the tests that start an outside program: TeX, Chromium, a Jupyter kernel
STARTS_A_PROGRAM = frozenset(
    {"need_tex", "need_chromium", "need_jupyter", "need_playwright", "need_otter", "browser"}
)


def program_modules_first(items: list) -> None:
    """Put first, in place and otherwise in order, the test modules with a test that starts
    TeX, Chromium or a Jupyter kernel (:data:`STARTS_A_PROGRAM`), then the modules that
    build a shared fixture (:func:`_builds_once`: all their tests are one unit of work, the
    largest units pytest-xdist hands out): the long units are handed out first and the
    short ones last, so that no worker is left alone with a long one at the end of a run
    while the other waits. A module's tests stay together (a module-scoped fixture is built
    once)."""
    first = {
        item.path for item in items if STARTS_A_PROGRAM & set(getattr(item, "fixturenames", ()))
    }
    units = {item.path for item in items if _builds_once(Path(item.path))}
    items.sort(key=lambda item: (item.path not in first, item.path not in units))  # stable


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    # last: after ``-m``/``-k`` have deselected, so a module whose only program-starting
    # tests are deselected (``-m "not slow"``) is not put first
    program_modules_first(items)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: object) -> object:
    """Under ``pytest -n N`` (the default ``--dist load``): share the tests out one by one,
    except that the tests of a module defining a module-, class- or package-scoped
    fixture (the docs site, the wheel and its venv, the exports of every robot, a grading
    key, ...) go to one worker together (:func:`work_unit`), so that the fixture is built
    once, not once by each worker that gets one of its tests. Another ``--dist`` is left
    as asked."""
    if config.getoption("dist") != "load":
        return None
    from xdist.scheduler import LoadScopeScheduling

    root = config.rootpath

    class SharedFixtureScheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return work_unit(nodeid, root)

    return SharedFixtureScheduling(config, log)


@pytest.fixture
def sym():
    """Real symbols by name: ``sym("theta1")``."""

    def make(name: str) -> sp.Symbol:
        return sp.Symbol(name, real=True)

    return make


def _need(what: str, found: bool, hint: str) -> None:
    """Skip a test whose tool is missing, except in CI (CI=true) where it must run."""
    if found:
        return
    import os

    if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
        pytest.fail(f"{what} is required in CI but missing: {hint}")
    pytest.skip(f"{what} not installed ({hint})")


@pytest.fixture
def need_tex():
    """Require latexmk/pdflatex and pdftoppm (Debian: texlive-latex-* latexmk poppler-utils)."""
    import shutil

    ok = all(shutil.which(t) for t in ("latexmk", "pdflatex", "pdftoppm"))
    _need(
        "TeX",
        ok,
        "apt-get install texlive-latex-base texlive-latex-recommended "
        "texlive-latex-extra latexmk poppler-utils",
    )


@pytest.fixture
def need_chromium():
    """Require headless Chromium (Debian: chromium)."""
    import shutil

    _need("Chromium", bool(shutil.which("chromium")), "apt-get install chromium")


@pytest.fixture
def need_jupyter():
    """Require nbclient, nbconvert and a python3 Jupyter kernel."""
    try:
        import nbclient  # noqa: F401
        import nbconvert  # noqa: F401
        from jupyter_client.kernelspec import KernelSpecManager

        ok = "python3" in KernelSpecManager().find_kernel_specs()
    except Exception:  # noqa: BLE001 - any import/kernel problem means "not available"
        ok = False
    _need("Jupyter", ok, "pip install -e '.[test]' (nbclient, nbconvert, ipykernel)")


def _importable(name: str) -> bool:
    import importlib.util

    return importlib.util.find_spec(name) is not None


@pytest.fixture
def need_ipywidgets():
    """Require ipywidgets (the self-check widget; extra ``widgets``)."""
    _need("ipywidgets", _importable("ipywidgets"), "pip install -e '.[widgets]'")


@pytest.fixture
def need_playwright():
    """Require Playwright for Python (drives Debian's /usr/bin/chromium; extra ``test``)."""
    _need("playwright", _importable("playwright"), "pip install -e '.[test]'")


@pytest.fixture
def need_otter():
    """Require otter-grader (the notebook-grader example; extra ``graders``)."""
    _need("otter-grader", _importable("otter"), "pip install -e '.[graders]'")
