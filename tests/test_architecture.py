"""The rooms' imports point one way and form no circles (scripts/import_graph.py)."""

import importlib.util
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[1] / "scripts" / "import_graph.py"


def _graph():
    if "import_graph" not in sys.modules:  # its dataclass looks its module up there
        spec = importlib.util.spec_from_file_location("import_graph", SCRIPT)
        sys.modules["import_graph"] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(sys.modules["import_graph"])
    return sys.modules["import_graph"]


def test_imports_point_one_way_without_circles():
    report = _graph().check()
    assert report.against_order == []
    assert report.circles == []
    assert _graph().main() == 0


def test_no_room_has_a_circle_inside():
    """ik and checking count the imports made for annotations only; other rooms run time."""
    report = _graph().check()
    assert {r: c for r, c in report.room_circles.items() if c} == {}


def test_the_check_finds_a_circle():
    graph = _graph()
    assert graph.cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert graph.cycles({"a": {"b"}, "b": set()}) == []


def test_the_check_finds_a_circle_inside_a_room_only():
    graph = _graph()
    modules = {"ik.a": {"ik.b", "model.x"}, "ik.b": {"ik.a"}, "model.x": {"ik.a"}, "ik": set()}
    assert graph.room_circles(modules) == {"ik": [["ik.a", "ik.b"]], "model": []}


def test_annotation_imports_count_only_when_asked(tmp_path):
    graph = _graph()
    source = tmp_path / "a.py"
    source.write_text(
        "from typing import TYPE_CHECKING\n"
        "from dhsym.ik import steps, solve\n"
        "if TYPE_CHECKING:\n"
        "    from dhsym.ik.results import Solution\n"
        "def f():\n"
        "    from . import b\n"
    )
    known = frozenset({"ik", "ik.steps", "ik.results", "ik.b"})
    run_time = graph.imports("ik.a", source, known=known)
    assert run_time == {"ik.steps", "ik", "ik.b"}
    assert graph.imports("ik.a", source, annotations=True, known=known) == run_time | {"ik.results"}


# --- no code reads text by evaluating it ----------------------------------------------------

EVALUATING = {"eval", "exec", "sympify", "parse_expr", "S", "lambdastr"}


def _evaluating_calls(source: str) -> list[str]:
    import ast

    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call):
            f = node.func
            name = getattr(f, "id", None) or getattr(f, "attr", "")
            if name in EVALUATING:
                found.append(f"{name} (line {node.lineno})")
    return found


def test_no_module_evaluates_text():
    package = SCRIPT.parents[1] / "dhsym"
    hits = {
        str(p.relative_to(package)): calls
        for p in sorted(package.rglob("*.py"))
        if (calls := _evaluating_calls(p.read_text(encoding="utf-8")))
    }
    assert hits == {}, "text is read by the whitelist parser, never evaluated"


def test_the_scan_sees_an_evaluating_call():
    assert _evaluating_calls("import sympy as sp\nsp.sympify(x)\neval(y)") == [
        "sympify (line 2)",
        "eval (line 3)",
    ]


def test_builders_and_printers_refuse_text_or_parse_it_safely():
    import pytest

    from dhsym.errors import ParseError
    from dhsym.kinematics.transforms import Rx, Tz, cos_sin
    from dhsym.notation.printers import Notation

    hostile = "__import__('os').system('echo owned')"
    for build in (Rx, Tz, cos_sin):
        with pytest.raises(TypeError, match="got str"):
            build(hostile)
    with pytest.raises(ParseError, match="double underscores"):
        Notation().tokens(hostile, latex=False)
    import dhsym

    rows = [[hostile, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    with pytest.raises(TypeError, match="got str"):
        dhsym.Pose(rows)
    link = dhsym.load("planar2r").link_matrix(1)
    for call in (lambda: link.subs({"a1": hostile}), lambda: link.evalf({"a1": hostile})):
        with pytest.raises(ParseError):
            call()
    assert [t.text for t in Notation().tokens("a1 + 1", latex=False)] == ["a1", " + ", "1"]


# --- one name, one module -------------------------------------------------------------------


def _shared_module_names(files: list[Path]) -> dict[str, list[str]]:
    """File names (a leading ``_`` ignored) that more than one module under dhsym/ has."""
    by_name: dict[str, list[str]] = {}
    for p in files:
        if p.stem in ("__init__", "__main__"):
            continue
        by_name.setdefault(p.stem.lstrip("_"), []).append(p.as_posix())
    return {name: paths for name, paths in sorted(by_name.items()) if len(paths) > 1}


def test_no_two_modules_share_a_name():
    package = SCRIPT.parents[1] / "dhsym"
    files = [p.relative_to(package.parent) for p in sorted(package.rglob("*.py"))]
    shared = _shared_module_names(files)
    listing = "; ".join(f"{name}: {', '.join(paths)}" for name, paths in shared.items())
    assert shared == {}, f"modules that share a name: {listing}"


def test_the_scan_sees_modules_that_share_a_name():
    files = [Path(p) for p in ("a/x.py", "b/_x.py", "a/__init__.py", "b/__init__.py", "c/y.py")]
    assert _shared_module_names(files) == {"x": ["a/x.py", "b/_x.py"]}
