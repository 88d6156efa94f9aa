"""The import graph of dhsym's rooms: every edge, those against the order, and circles.

Reads every module with ``ast`` (module-level and lazy imports inside functions alike)
and prints the room-to-room edges. Exit status 1 when

- an edge points up the order model → cache → notation → kinematics → ik/dynamics/geometry/plot/
  trajectory → screws/export → formats → control → robot (the facade, ``dhsym.robot.Robot``) →
  explain → checking → cli,
  except the documented exceptions in ``ALLOWED``;
- any imports, counted all (module level and inside functions; only ``if TYPE_CHECKING:``
  blocks are left out), form a circle anywhere in the package;
- the modules of one room form a circle among themselves (a room's sub-rooms, such as
  ``checking.grading``, belong to it). In the rooms of ``ANNOTATED_ROOMS`` (``ik`` and
  ``checking``) the imports made only for type annotations (``if TYPE_CHECKING:``) count
  too: their modules are layered even on paper. Elsewhere run-time imports count.

Each circle is printed by name, as its modules (a strongly connected component).

    python scripts/import_graph.py
"""

from __future__ import annotations

import ast
import sys
from collections import defaultdict
from dataclasses import dataclass, field
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
    "screws",
    "plot",
    "formats",
    "export",
    "view",
    "trajectory",
    "control",
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
RANK["export"] = RANK["screws"]  # a sibling of screws: it prints the product of exponentials
RANK["dynamics"] = RANK["geometry"]  # a sibling: model, notation, kinematics below it
RANK["trajectory"] = RANK["geometry"]  # a sibling: the export prints its profiles
#: Upward edges with a documented reason: a table's display hooks reach the printer at
#: call time (as sympy's own Basic._repr_latex_ does). ALLOWED excuses the direction only:
#: every import, module level or inside a function, counts when looking for circles.
#: Imports under ``if TYPE_CHECKING:`` are annotations only and are not counted.
ALLOWED = {
    ("model.table", "notation.tables"),
}
#: Rooms whose modules form no circle even counting the imports made for annotations only.
ANNOTATED_ROOMS = frozenset({"ik", "checking"})


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


def imports(
    name: str, path: Path, *, annotations: bool = False, known: frozenset[str] = frozenset()
) -> set[str]:
    """The dhsym modules that module ``name`` (file ``path``) imports.

    With ``annotations`` the imports under ``if TYPE_CHECKING:`` are counted too. A name
    imported from a package that is itself a module of ``known`` (``from dhsym.ik import
    steps``) counts as an import of that module, not of the package.
    """
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
        if id(node) in typing_only and not annotations:  # no import at run time
            continue
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg[: len(pkg) - (node.level - 1)] if node.level > 1 else pkg
                target = ".".join(base + ([node.module] if node.module else []))
            elif node.module and node.module.startswith("dhsym"):
                target = node.module[len("dhsym.") :] if node.module != "dhsym" else "__init__"
            else:
                continue
            target = target or "__init__"
            prefix = "" if target == "__init__" else target + "."
            submodules = {f"{prefix}{a.name}" for a in node.names} & known
            found |= submodules
            if len(submodules) < len(node.names):  # names defined by the package itself
                found.add(target)
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


@dataclass(frozen=True)
class Report:
    """What the check found: room-to-room edges, edges against the order, circles."""

    edges: dict[str, set[str]]
    against_order: list[str]
    circles: list[list[str]]  # run-time circles anywhere in the package
    room_circles: dict[str, list[list[str]]] = field(default_factory=dict)  # by room

    @property
    def ok(self) -> bool:
        return not (self.against_order or self.circles or any(self.room_circles.values()))


def _graph(
    mods: dict[str, Path], *, annotations: bool, known: frozenset[str]
) -> dict[str, set[str]]:
    graph: dict[str, set[str]] = defaultdict(set)
    for name, path in sorted(mods.items()):
        for target in imports(name, path, annotations=annotations, known=known):
            if target != name:  # every import: ALLOWED excuses direction, never a circle
                graph[name].add(target)
    # a package's __init__ re-exports its modules: that is not a circle
    for m, p in mods.items():
        if p.name == "__init__.py" and m != "__init__":
            graph[m] = {t for t in graph[m] if not t.startswith(m + ".")}
    return graph


def room_circles(
    graph: dict[str, set[str]], rooms: list[str] | None = None
) -> dict[str, list[list[str]]]:
    """The circles among the modules of each room (sub-rooms included), by room."""
    by_room: dict[str, list[list[str]]] = {}
    for r in rooms if rooms is not None else sorted({room(m) for m in graph}):
        inside = {m: {t for t in ts if room(t) == r} for m, ts in graph.items() if room(m) == r}
        by_room[r] = cycles(inside)
    return by_room


def check() -> Report:
    """Read the package and check its imports (see the module's docstring)."""
    mods = modules()
    known = frozenset(mods)
    graph = _graph(mods, annotations=False, known=known)
    edges: dict[str, set[str]] = defaultdict(set)
    bad = []
    for name, targets in sorted(graph.items()):
        for target in sorted(targets):
            a, b = room(name), room(target)
            if a != b:
                edges[a].add(b)
                if RANK.get(b, 0) > RANK.get(a, 0) and (name, target) not in ALLOWED:
                    bad.append(f"{name} -> {target}")
    circles = [c for c in cycles(graph) if set(c) - {"__init__"}]
    annotated = _graph(mods, annotations=True, known=known)
    rooms = sorted({room(m) for m in mods} - {"__init__", "__main__"})
    found = room_circles(graph, [r for r in rooms if r not in ANNOTATED_ROOMS])
    found.update(room_circles(annotated, [r for r in rooms if r in ANNOTATED_ROOMS]))
    return Report(dict(edges), bad, circles, {r: found[r] for r in rooms})


def main() -> int:
    report = check()
    for a in ORDER:
        if a in report.edges:
            targets = sorted(report.edges[a], key=lambda r: RANK.get(r, 0))
            print(f"{a:11s} -> {', '.join(targets)}")
    bad = list(report.against_order)
    bad += ["circle: " + " <-> ".join(c) for c in report.circles]
    for r, circles in report.room_circles.items():
        counted = "annotations counted" if r in ANNOTATED_ROOMS else "run time"
        bad += [f"circle in room {r} ({counted}): " + " <-> ".join(c) for c in circles]
    if bad:
        print("\nimports against the order or in a circle:\n  " + "\n  ".join(bad))
        return 1
    print(
        "\nno import points against the order; no import circles, "
        "none inside a room (ik, checking: annotations counted)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
