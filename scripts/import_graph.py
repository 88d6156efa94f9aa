"""The import graph of dhsym's rooms: every edge, and those that point against the order.

Reads every module with ``ast`` (module-level and lazy imports inside functions alike)
and prints the room-to-room edges. Exit status 1 when an edge points up the order
model → cache → notation → kinematics → ik/dynamics/geometry/plot/export → formats → robot (the
facade, ``dhsym.robot.Robot``) → explain → checking → cli, except the documented
exceptions in ``ALLOWED``, or when any imports, counted all (module level and inside
functions; only ``if TYPE_CHECKING:`` blocks are left out), form a circle.

    python scripts/import_graph.py
"""

from __future__ import annotations

import ast
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1] / "dhsym"
ORDER = [
    "errors",
    "_lazy",
    "_version",
    "model",
    "cache",
    "notation",
    "kinematics",
    "ik",
    "dynamics",
    "geometry",
    "plot",
    "formats",
    "export",
    "robot",
    "explain",
    "checking",
    "__init__",
    "cli",
    "__main__",
]
RANK = {room: k for k, room in enumerate(ORDER)}
RANK["plot"] = RANK["geometry"]  # siblings
RANK["ik"] = RANK["geometry"]
RANK["export"] = RANK["geometry"]  # a sibling too: it reads model, notation, kinematics, ik
RANK["dynamics"] = RANK["geometry"]  # a sibling: model, notation, kinematics below it
#: Upward edges with a documented reason: a table's display hooks reach the printer at
#: call time (as sympy's own Basic._repr_latex_ does). ALLOWED excuses the direction only:
#: every import, module level or inside a function, counts when looking for circles.
#: Imports under ``if TYPE_CHECKING:`` are annotations only and are not counted.
ALLOWED = {
    ("model.table", "notation.tables"),
}


def room(module: str) -> str:
    return module.split(".")[0]


def modules() -> dict[str, Path]:
    out = {}
    for p in ROOT.rglob("*.py"):
        parts = list(p.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__" and len(parts) > 1:
            parts = parts[:-1]
        out[".".join(parts)] = p
    return out


def imports(name: str, path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    is_pkg = path.name == "__init__.py"
    pkg = name.split(".") if is_pkg else name.split(".")[:-1]
    found = set()
    typing_only = {
        id(n)
        for block in ast.walk(tree)
        if isinstance(block, ast.If) and "TYPE_CHECKING" in ast.unparse(block.test)
        for n in ast.walk(block)
    }
    for node in ast.walk(tree):
        if id(node) in typing_only:  # annotations only: no import at run time
            continue
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg[: len(pkg) - (node.level - 1)] if node.level > 1 else pkg
                target = ".".join(base + ([node.module] if node.module else []))
            elif node.module and node.module.startswith("dhsym"):
                target = node.module[len("dhsym.") :] if node.module != "dhsym" else "__init__"
            else:
                continue
            found.add(target or "__init__")
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("dhsym."):
                    found.add(a.name[len("dhsym.") :])
    return found


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (import circles)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main() -> int:
    mods = modules()
    bad = []
    edges = defaultdict(set)
    graph: dict[str, set[str]] = defaultdict(set)
    for name, path in sorted(mods.items()):
        for target in imports(name, path):
            if target != name:  # every import: ALLOWED excuses direction, never a circle
                graph[name].add(target)
            a, b = room(name), room(target)
            if a != b:
                edges[a].add(b)
                if RANK.get(b, 0) > RANK.get(a, 0) and (name, target) not in ALLOWED:
                    bad.append(f"{name} -> {target}")
    for a in ORDER:
        if a in edges:
            print(f"{a:11s} -> {', '.join(sorted(edges[a], key=lambda r: RANK.get(r, 0)))}")
    # a package's __init__ re-exports its modules: that is not a circle
    inits = {m for m, p in mods.items() if p.name == "__init__.py"}
    for m in inits:
        graph[m] = {t for t in graph[m] if not t.startswith(m + ".") or m == "__init__"}
    circles = [c for c in cycles(graph) if set(c) - {"__init__"}]
    for c in circles:
        bad.append("circle: " + " <-> ".join(c))
    if bad:
        print("\nimports against the order:\n  " + "\n  ".join(bad))
        return 1
    print("\nno import points against the order; no import circles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
