"""The checking room's sub-rooms: one order, no import circle, no private name across them.

Every import counts: at module level, inside functions and under ``if TYPE_CHECKING:``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import dhsym.checking

ROOT = Path(dhsym.checking.__file__).parent
#: each sub-room imports only those before it
ORDER = ("reading", "comparing", "mistakes", "judging", "grading", "platforms")


def _modules() -> dict[str, Path]:
    out = {}
    for p in sorted(ROOT.rglob("*.py")):
        parts = list(p.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(["dhsym", "checking", *parts])] = p
    return out


def _imports(name: str, path: Path, known: dict[str, Path]) -> set[tuple[str, tuple[str, ...]]]:
    """(module imported, names taken from it) for every import of the module at ``path``."""
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            target = ".".join([*base, *([node.module] if node.module else [])])
            for alias in node.names:
                full = f"{target}.{alias.name}"
                if full in known:  # ``from . import module``
                    out.add((full, ()))
                else:
                    out.add((target, (alias.name,)))
        elif isinstance(node, ast.Import):
            out |= {(alias.name, ()) for alias in node.names}
    return {(t, names) for t, names in out if t in known and t != name}


def _edges() -> dict[str, set[tuple[str, tuple[str, ...]]]]:
    known = _modules()
    return {name: _imports(name, path, known) for name, path in known.items()}


def _room(module: str) -> str:
    parts = module.split(".")
    return parts[2] if len(parts) > 2 else ""


def test_no_import_circle_among_the_modules():
    graph = {a: {b for b, _ in targets} for a, targets in _edges().items()}
    state: dict[str, int] = {}

    def visit(node: str, path: list[str]) -> None:
        state[node] = 1
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                raise AssertionError(" -> ".join([*path[path.index(nxt) :], nxt]))
            if nxt not in state:
                visit(nxt, [*path, nxt])
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])


def test_sub_rooms_import_only_those_before_them_and_no_private_name():
    assert {_room(m) for m in _modules()} - {""} == set(ORDER)
    wrong = []
    for a, targets in _edges().items():
        for b, names in targets:
            ra, rb = _room(a), _room(b)
            if not ra or not rb or ra == rb:
                continue
            if ORDER.index(rb) > ORDER.index(ra):
                wrong.append(f"{a} imports {b} (a later sub-room)")
            private = [p for p in (*b.split("."), *names) if p.startswith("_")]
            if private:
                wrong.append(f"{a} imports the private {', '.join(private)} of {b}")
    assert wrong == []


def test_the_check_sees_an_upward_import():
    # the parser resolves relative imports: judging's ``from ..mistakes.registry import …``
    key = _edges()["dhsym.checking.judging.matrix_judge"]
    assert ("dhsym.checking.mistakes.registry", ("diagnose_matrix",)) in key
    assert any(b.startswith("dhsym.checking.judging") for b, _ in key)
