"""Prefixes: a name, never a path; a standard name of the language gets a ``_``.

The campaign's prefixes: C++ ``log tan atan pow floor round fmod hypot acos exp printf``
(``namespace log`` meets ``::log``), Python ``os sys errno typing`` (``os.py`` hides the
standard module), and the paths ``../../escaped`` and ``/tmp/abs``.
"""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.export.identifiers import KEYWORDS, RESERVED, checked_name, prefix, reserved

from ..conftest import _need

CPP_PREFIXES = ["log", "tan", "atan", "pow", "floor", "round", "fmod", "hypot", "acos", "exp"]
CPP_PREFIXES += ["printf", "logf", "lgammal_r", "random", "index", "std", "detail"]
PYTHON_PREFIXES = ["os", "sys", "errno", "typing", "math", "numpy", "json", "cprofile"]
PATHS = ["../../escaped", "/tmp/abs", "gen/arm", "..", ".", "a.b", "2r", "", "arm\\x", "arm "]


@pytest.mark.parametrize("text", PATHS)
def test_a_prefix_is_never_a_path(text):
    with pytest.raises(DHError, match="is not a name"):
        checked_name(text)
    for lang in dhsym.export.LANGUAGES:
        with pytest.raises(DHError, match="is not a name"):
            prefix(text, lang)


def test_reserved_prefixes_get_an_underscore_in_their_language_only():
    for name in CPP_PREFIXES:
        assert prefix(name, "cpp") == (name if name in ("detail",) else name + "_")
    assert [prefix(n, "c") for n in ("log", "printf", "math", "stdio")] == [
        "log",
        "printf",
        "math_",
        "stdio_",
    ]
    for name in PYTHON_PREFIXES:
        assert prefix(name, "python") == name + "_"
    assert prefix("os", "c") == "os" and prefix("typing", "rust") == "typing"
    assert [prefix(n, "rust") for n in ("f64", "core", "str", "arm")] == [
        "f64_",
        "core_",
        "str_",
        "arm",
    ]
    assert prefix("for", "matlab") == "for_" and prefix("log", "matlab") == "log"


def test_ordinary_prefixes_are_kept():
    for lang in dhsym.export.LANGUAGES:
        for name in ("arm", "puma", "ur5", "robot", "planar_2r", "puma_560", "stanford_arm"):
            assert prefix(name, lang) == name
        assert prefix("PUMA", lang) == "puma"


def test_python_names_cover_the_standard_library():
    modules = {n.lower() for n in sys.stdlib_module_names if not n.startswith("_")}
    assert modules <= RESERVED["python"]
    assert all(reserved(k, lang) for k in KEYWORDS for lang in RESERVED)


def test_python_prefixes_do_not_hide_the_standard_library(tmp_path):
    robot = dhsym.load("planar2r")
    names = []
    for text in ("os", "sys", "errno", "typing"):
        for name, code in dhsym.export(robot, "python", what="fk", prefix=text).items():
            (tmp_path / name).write_text(code)
            names.append(name.removesuffix(".py"))
    assert names == ["os_", "sys_", "errno_", "typing_"]
    script = (
        "import sys; sys.path.insert(0, '.')\n"
        "import os, errno, typing, os_, sys_, errno_, typing_\n"
        "here = [getattr(m, '__file__', '') or '' for m in (os, errno, typing)]\n"
        "assert not any(f.startswith(os.getcwd()) for f in here), here\n"
        "print(os_.fk([0.1, 0.2])[0, 3])\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], cwd=tmp_path, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    assert abs(float(done.stdout) - robot.fk([0.1, 0.2])[0, 3]) <= 1e-12


def test_cpp_prefixes_compile(tmp_path):
    """Every campaign prefix's header in one translation unit with <cstdio>, <cstdlib>,
    <cstring> (printf, random, index meet the namespace there)."""
    _need("g++", shutil.which("g++") is not None, "apt-get install g++")
    robot = dhsym.load("planar2r")
    lines = ["#include <cstdio>", "#include <cstdlib>", "#include <cstring>"]
    calls = []
    for text in CPP_PREFIXES:
        files = dhsym.export(robot, "cpp", what="fk", prefix=text)
        ((name, code),) = files.items()
        (tmp_path / name).write_text(code)
        lines.append(f'#include "{name}"')
        calls.append(f"    {name.removesuffix('.hpp')}::fk(q, T); s += T[3];")
    main = "\n".join(
        [*lines, "int main()", "{", "    double q[2] = {0.1, 0.2}, T[16], s = 0.0;", *calls]
    )
    main += '\n    std::printf("%.17g\\n", s);\n    return 0;\n}\n'
    (tmp_path / "main.cpp").write_text(main)
    flags = ["-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic"]
    done = subprocess.run(
        ["g++", *flags, "main.cpp", "-o", "prog"], cwd=tmp_path, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    out = subprocess.run([str(tmp_path / "prog")], capture_output=True, text=True, check=True)
    want = len(CPP_PREFIXES) * robot.fk([0.1, 0.2])[0, 3]
    assert abs(float(out.stdout) - want) <= 1e-9
