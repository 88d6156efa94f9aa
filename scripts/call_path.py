"""The path of a robot from its table file to the PDF handout: which modules call which.

Traces ``write_handout(["puma560"], …, pdf=True)`` with :func:`sys.setprofile` and prints
the modules crossed, the distinct module-to-module calls ("moves") and those that go
back up the rooms' order (a lower room calling a higher one, which only callbacks can do).

    python scripts/call_path.py
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from import_graph import RANK, room  # noqa: E402


def main() -> int:
    import dhsym
    from dhsym.explain.documents import write_handout

    dhsym.load("planar2r")  # warm imports so that the trace shows the path, not loading
    edges: dict[tuple[str, str], int] = {}

    def module_of(frame) -> str | None:
        name = frame.f_globals.get("__name__", "")
        return name[len("dhsym.") :] if name.startswith("dhsym.") else None

    def profile(frame, event, arg):  # noqa: ANN001
        if event != "call":
            return
        callee = module_of(frame)
        caller = module_of(frame.f_back) if frame.f_back else None
        if callee and caller and callee != caller:
            edges[(caller, callee)] = edges.get((caller, callee), 0) + 1

    with tempfile.TemporaryDirectory() as tmp:
        sys.setprofile(profile)
        try:
            write_handout(["puma560"], Path(tmp) / "puma560.tex", pdf=True)
        finally:
            sys.setprofile(None)
    modules = sorted({m for e in edges for m in e})
    up = [(a, b) for a, b in edges if RANK.get(room(b), 0) > RANK.get(room(a), 0)]
    print(f"{len(modules)} modules, {len(edges)} moves, {len(up)} back up the order")
    for a, b in sorted(edges):
        mark = "  <- up" if (a, b) in up else ""
        print(f"  {a:28s} -> {b}{mark}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
