"""The public face: ``dir()`` shows what a room exports (and ``dhsym`` its rooms), loaded lazily."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

import dhsym
from dhsym._lazy import lazy_exports, public_dir

ROOMS = {
    "checking",
    "cli",
    "dynamics",
    "explain",
    "export",
    "formats",
    "geometry",
    "ik",
    "kinematics",
    "model",
    "notation",
    "plot",
    "screws",
}
#: Every room's ``__init__`` lists its names through ``lazy_exports`` or ``public_dir``.
LAZY_ROOMS = sorted(ROOMS)


def _public(names: list[str]) -> set[str]:
    return {n for n in names if not (n.startswith("__") and n.endswith("__"))}


def test_dir_of_dhsym_is_its_all_and_its_rooms():
    assert _public(dir(dhsym)) == (set(dhsym.__all__) | ROOMS) - {"__version__"}
    for detail in ("annotations", "lazy_exports", "_lazy", "importlib"):
        assert detail not in dir(dhsym)
    assert "__version__" in dir(dhsym) and "__doc__" in dir(dhsym)


@pytest.mark.parametrize("room", LAZY_ROOMS)
def test_dir_of_a_room_is_its_all(room):
    module = importlib.import_module(f"dhsym.{room}")
    assert _public(dir(module)) == set(module.__all__)


@pytest.mark.parametrize("room", LAZY_ROOMS)
def test_every_exported_name_of_a_room_loads(room):
    module = importlib.import_module(f"dhsym.{room}")
    for name in module.__all__:
        assert getattr(module, name) is not None, name


def test_every_room_is_reachable_from_dhsym():
    for room in ROOMS:
        assert getattr(dhsym, room) is importlib.import_module(f"dhsym.{room}")


def test_import_and_dir_stay_cheap():
    code = (
        "import sys, dhsym; dir(dhsym); dir(dhsym.model); "
        "print(sorted(m for m in sys.modules if m.startswith(('dhsym.kinematics', 'jinja2', "
        "'numpy', 'matplotlib', 'dhsym.checking'))))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_lazy_exports_refuses_unknown_names():
    getattr_, dir_ = lazy_exports("dhsym.model", {"parse_expression": "parsing"})
    with pytest.raises(AttributeError, match="module 'dhsym.model' has no attribute 'nope'"):
        getattr_("nope")
    assert "parse_expression" in dir_() and "nope" not in dir_()


def test_public_dir_adds_names_to_all_and_dunders():
    names = public_dir("dhsym.notation", ["extra"])
    assert "extra" in names and "TeX" in names and "__name__" in names
    assert "lazy_exports" not in names and names == sorted(names)
