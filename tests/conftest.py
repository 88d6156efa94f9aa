"""Shared fixtures: symbols named as in the lectures; how pytest-xdist shares the tests
out (a module that builds a fixture once for its tests runs on one worker)."""

from __future__ import annotations

import functools
import gc
import os
import re
from pathlib import Path

import pytest
from hypothesis import settings

# --- sympy's cache (issue 30, item 5) ---------------------------------------------------
# sympy keeps the last SYMPY_CACHE_SIZE results of each cached function (1000 by default),
# a size it reads once, when it is imported: set here, before this file or a test imports
# sympy, it holds for this process, the xdist workers (started after) and every command or
# notebook kernel a test starts. A session of tests meets the same expressions again and
# again (the same robots, room after room). Measured with 1000 and 20000 side by side, one
# worker each (load 11-15): tests/kinematics 56.9 -> 47.7 s of CPU (154 -> 188 MB
# resident), tests/ik 67.4 -> 64.3 s (167 -> 190 MB). Only speed depends on it: a cached
# result is the result. The environment's SYMPY_CACHE_SIZE, if set, is kept.
SYMPY_CACHE_SIZE = "20000"
os.environ.setdefault("SYMPY_CACHE_SIZE", SYMPY_CACHE_SIZE)

# --- Hypothesis's deadline (issue 30, item 5) --------------------------------------------
# Hypothesis fails an example that takes longer than its deadline (200 ms by default): a
# timed assertion, which the suite has none of (speed figures live in benchmarks/), and a
# test that depends on what else runs on the machine (under load, the main session's run
# with coverage failed tests/kinematics/test_simplification.py::
# test_fold_sum_angles_keeps_value as "Flaky": 268 ms once, 100 ms on the rerun). No
# deadline for the suite, as in Hypothesis's own profile for CI (CI=true), which is kept
# otherwise (derandomized); every property is checked on as many examples as before.
settings.register_profile("dhsym-suite", parent=settings.default, deadline=None)
settings.load_profile("dhsym-suite")

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


#: the longest tests of ``make test`` (its ``--durations`` in CI and on this machine, both
#: steps), longest first, by node id or its start: their units of work (:func:`work_unit`)
#: are handed out before all others, so that no worker starts one of them near the end of
#: a run while the other has nothing left. Only the order of the run depends on this list:
#: a test that is not in it runs all the same (``tests/test_conftest.py`` checks that each
#: entry still names a test).
LONGEST_FIRST = (
    # the slow step (-m slow)
    "tests/dynamics/test_compiled_dynamics.py::test_the_jaco_flipped_first_joint_in_the_recursion_the_compiled_program_and_c",
    "tests/docs/test_site.py",
    "tests/checking/platforms/test_otter_example.py",
    "tests/test_installed.py",
    "tests/export/test_compile_all.py",
    "tests/dynamics/test_compact_form.py",
    "tests/test_fuzz.py::test_every_file_loader_gives_a_result_or_a_clear_error",
    "tests/ik/test_accuracy.py::test_every_rounded_pose_is_solved_and_its_branch_found[jaco-",
    "tests/ik/test_kept_derivations.py::test_a_warm_and_a_cold_process_agree_to_the_bit",
    "tests/ik/test_accuracy.py::test_every_rounded_pose_is_solved_and_its_branch_found[panda.urdf-",
    "tests/control/test_controllers.py",
    "tests/dynamics/test_recursive_newton_euler.py::test_lagrange_equals_newton_euler_on_six_joint_robots[puma560_modified]",
    "tests/dynamics/test_recursive_newton_euler.py::test_lagrange_equals_newton_euler_on_six_joint_robots[stanford]",
    "tests/dynamics/test_recursive_newton_euler.py::test_lagrange_equals_newton_euler_on_the_puma560_with_its_published_parameters",
    # the quick step
    "tests/explain/test_notebooks.py::test_notebook_runs_clean[14_control.ipynb]",
    "tests/explain/test_latex.py",
    "tests/kinematics/test_simplification.py::test_inverse_word_composes_to_identity",
    "tests/geometry/test_frames.py::test_measured_geometry_works_through_frames_fk_and_convert",
    "tests/geometry/test_conversion.py::test_round_trip_gives_back_every_table_with_its_base_and_tool",
    "tests/explain/test_notebooks.py::test_notebook_runs_clean[09_inverse_kinematics.ipynb]",
    "tests/kinematics/test_numeric.py::test_numeric_equals_symbolic",
    "tests/explain/test_notebooks.py::test_notebook_runs_clean[01_planar_2R.ipynb]",
    "tests/export/test_languages.py::test_python[jaco]",
    "tests/test_architecture.py::test_imports_point_one_way_without_circles",
    "tests/screws/test_product.py::test_singularities_from_the_determinant",
)


def _rank(nodeid: str) -> int:
    """The place of the test ``nodeid`` in :data:`LONGEST_FIRST` (its length if absent)."""
    for k, start in enumerate(LONGEST_FIRST):
        if nodeid.startswith(start):
            return k
    return len(LONGEST_FIRST)


def longest_first(items: list, root: Path) -> None:
    """Put first, in place, the units of work (:func:`work_unit`) of the tests named in
    :data:`LONGEST_FIRST`, in its order; the others keep their order (stable)."""
    rank: dict[str, int] = {}
    for item in items:
        unit = work_unit(item.nodeid, root)
        rank[unit] = min(rank.get(unit, len(LONGEST_FIRST)), _rank(item.nodeid))
    items.sort(key=lambda item: rank[work_unit(item.nodeid, root)])


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    # last: after ``-m``/``-k`` have deselected, so a module whose only program-starting
    # tests are deselected (``-m "not slow"``) is not put first
    program_modules_first(items)
    longest_first(items, config.rootpath)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: object) -> object:
    """Under ``pytest -n N`` (the default ``--dist load``): share the tests out one by one,
    except that the tests of a module defining a module-, class- or package-scoped
    fixture (the docs site, the wheel and its venv, the exports of every robot, a grading
    key, ...) go to one worker together (:func:`work_unit`), so that the fixture is built
    once, not once by each worker that gets one of its tests; the units are handed out in
    the order of the items (:func:`longest_first`). Another ``--dist`` is left as asked."""
    if config.getoption("dist") != "load":
        return None
    from xdist.scheduler import LoadScopeScheduling

    # the units go out in the order of the items (pytest_collection_modifyitems: the
    # longest first), not re-sorted by their number of tests (xdist's loadscope reorder)
    config.option.loadscopereorder = False
    root = config.rootpath

    class SharedFixtureScheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return work_unit(nodeid, root)

    return SharedFixtureScheduling(config, log)


# --- Python's garbage collector (issue 30, item 5) -----------------------------------------
# A full collection walks every object the process keeps: the modules the collection phase
# imported (sympy, numpy, dhsym, ...), the robots and keys of the session fixtures, sympy's
# caches. None of them is garbage. After the collection phase and after each test, the
# young garbage is collected and what is left is moved to the permanent generation
# (gc.freeze), so that later full collections walk only what later tests make. Measured
# with gc.callbacks (thread CPU), one worker, load 9-15: the collector's time in
# tests/kinematics 4.1 -> 2.0 s (of 61 s), in tests/ik 3.8 -> 1.2 s (of 70-84 s). A frozen
# object is still freed when its last reference goes; only a cycle among frozen objects
# stays, and the resident size of a room grew by less than 10 %.


def pytest_collection_finish(session: pytest.Session) -> None:
    gc.collect()
    gc.freeze()


@pytest.hookimpl(trylast=True)
def pytest_runtest_logfinish(nodeid: str, location: tuple) -> None:
    # after the test's teardown: its function-scoped fixtures are gone
    gc.collect(1)
    gc.freeze()


@pytest.fixture
def sym():
    """Real symbols by name: ``sym("theta1")``."""
    import sympy as sp

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
