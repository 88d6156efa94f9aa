"""How the suite shares work (conftest.py, tests/conftest.py): one disk cache for a run
and its xdist workers, and the tests of a module's shared fixture on one worker."""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path
from types import SimpleNamespace

import pytest

from tests.conftest import LONGEST_FIRST, longest_first, program_modules_first, work_unit

ROOT = Path(__file__).resolve().parent.parent


def _root_conftest():
    spec = importlib.util.spec_from_file_location("_root_conftest", ROOT / "conftest.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize(
    "nodeid",
    [
        "tests/docs/test_site.py::test_the_site_builds_without_a_warning",
        "tests/test_installed.py::test_handout_pdf",
        "tests/export/test_compile_all.py::test_every_robot_is_exported",
        "tests/explain/test_latex.py::test_every_builtin_robot_compiles_without_errors_or_overfull_boxes",
    ],
)
def test_a_module_that_builds_a_shared_fixture_is_one_unit(nodeid):
    assert work_unit(nodeid, ROOT) == nodeid.split("::")[0]


@pytest.mark.parametrize(
    "nodeid",
    [
        "tests/model/test_parsing.py::test_whitelist_refuses_calls",
        "dhsym/model/table.py::dhsym.model.table.DHTable",
        "tests/ik/test_decoupled.py::test_x[puma560]",
        # a session-scoped fixture (built once per worker) does not tie a module's tests
        "tests/explain/test_notebooks.py::test_notebook_runs_clean[03_puma560.ipynb]",
    ],
)
def test_any_other_test_is_a_unit_by_itself(nodeid):
    assert work_unit(nodeid, ROOT) == nodeid


def test_a_worker_keeps_the_cache_folder_of_its_controller(tmp_path, monkeypatch):
    conftest = _root_conftest()
    folder = tmp_path / f"{conftest.PREFIX}abc"
    folder.mkdir()
    monkeypatch.delenv("DHSYM_TEST_CACHE", raising=False)
    monkeypatch.setenv("DHSYM_CACHE", str(folder))
    worker, controller = SimpleNamespace(workerinput={}), SimpleNamespace()
    assert conftest._given_folder(worker) == str(folder)
    assert conftest._given_folder(controller) is None  # the controller makes its own
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))  # not a session folder: the user's
    assert conftest._given_folder(worker) is None


def test_make_test_names_one_folder_for_both_steps(tmp_path, monkeypatch):
    conftest = _root_conftest()
    monkeypatch.setenv("DHSYM_TEST_CACHE", str(tmp_path))
    assert conftest._given_folder(SimpleNamespace()) == str(tmp_path)
    assert conftest._given_folder(SimpleNamespace(workerinput={})) == str(tmp_path)
    monkeypatch.setenv("DHSYM_TEST_CACHE", str(tmp_path / "missing"))
    assert conftest._given_folder(SimpleNamespace()) is None


def test_the_session_cache_is_private_and_not_the_users():
    folder = os.environ["DHSYM_CACHE"]
    assert Path(folder).is_dir() and os.stat(folder).st_mode & 0o077 == 0
    assert (
        Path(folder).name.startswith(_root_conftest().PREFIX)
        or os.environ.get("DHSYM_TEST_CACHE") == folder
    )


def test_modules_that_start_a_program_come_first_and_stay_together():
    def item(path: str, *fixtures: str) -> SimpleNamespace:
        return SimpleNamespace(path=Path(path), fixturenames=("tmp_path", *fixtures))

    items = [
        item("a.py"),
        item("b.py", "need_tex"),
        item("a.py"),
        item("c.py"),
        item("b.py"),
        item("d.py", "browser"),
        SimpleNamespace(path=Path("dhsym/x.py")),  # a doctest: no fixture names
    ]
    order = [items[1], items[4], items[5], items[0], items[2], items[3], items[6]]
    program_modules_first(items)
    assert items == order


def test_then_the_modules_whose_tests_are_one_unit():
    def item(path: str, *fixtures: str) -> SimpleNamespace:
        return SimpleNamespace(path=ROOT / path, fixturenames=("tmp_path", *fixtures))

    items = [
        item("tests/model/test_parsing.py"),
        item("tests/checking/judging/test_ik_branches.py"),  # a module-scoped fixture
        item("tests/explain/test_notebooks.py", "need_jupyter"),
        item("tests/model/test_parsing.py"),
        item("tests/checking/judging/test_ik_branches.py"),
    ]
    order = [items[2], items[1], items[4], items[0], items[3]]
    program_modules_first(items)
    assert items == order


def test_the_longest_tests_go_first_with_their_units():
    def item(nodeid: str) -> SimpleNamespace:
        return SimpleNamespace(nodeid=nodeid)

    six = "tests/dynamics/test_recursive_newton_euler.py::test_lagrange_equals_newton_euler_on_"
    items = [
        item("tests/model/test_parsing.py::test_a"),
        item("tests/docs/test_site.py::test_b"),  # a unit: the module (a shared fixture)
        item(six + "six_joint_robots[stanford]"),
        item("tests/docs/test_site.py::test_a"),
        item(six + "six_joint_robots[puma560_modified]"),
        item(six + "built_in_robots[planar2r]"),
    ]
    order = [items[1], items[3], items[4], items[2], items[0], items[5]]
    longest_first(items, ROOT)
    assert items == order


def test_each_of_the_longest_tests_is_a_test():
    for entry in LONGEST_FIRST:
        path, _, name = entry.partition("::")
        assert (ROOT / path).is_file(), entry
        if name:
            assert f"def {name.split('[')[0]}(" in (ROOT / path).read_text(), entry


def test_this_session_runs_the_modules_that_start_a_program_first(request):
    from tests.conftest import STARTS_A_PROGRAM, _builds_once, _rank

    # after the longest tests' units (LONGEST_FIRST), which go before all others
    items = [i for i in request.session.items if _rank(i.nodeid) == len(LONGEST_FIRST)]
    first = {i.path for i in items if STARTS_A_PROGRAM & set(getattr(i, "fixturenames", ()))}
    flags = [item.path in first for item in items]
    assert flags == sorted(flags, reverse=True)  # all of them, then the others
    rest = [item for item in items if item.path not in first]
    units = [_builds_once(Path(item.path)) for item in rest]
    assert units == sorted(units, reverse=True)  # then the modules that are one unit


def test_what_earlier_tests_and_the_collection_left_is_frozen():
    import gc

    import dhsym

    # dhsym was imported by the collection phase, before this test: its module object
    # is in the permanent generation (tests/conftest.py), which full collections skip
    assert gc.get_freeze_count() > 0
    assert gc.is_tracked(dhsym)
    assert not any(obj is dhsym for obj in gc.get_objects(generation=2))


def test_sympy_was_imported_with_the_cache_size_of_the_suite():
    import os

    from sympy.core import cache

    # set (tests/conftest.py: SYMPY_CACHE_SIZE, unless the environment names another)
    # before sympy was imported, or it would not hold
    assert str(cache.SYMPY_CACHE_SIZE) == os.environ["SYMPY_CACHE_SIZE"]


def test_hypothesis_has_no_deadline_in_the_suite():
    from hypothesis import settings

    # no example fails for its time (tests/conftest.py), a test's own settings aside
    assert settings.default.deadline is None
    assert settings().deadline is None
    assert settings.default.max_examples == 100  # as many examples as Hypothesis's own
