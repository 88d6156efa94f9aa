"""The ``dhsym`` command line: the parser and the explicit list of command groups.

Each group lives in its own module of this room and adds its sub-commands with
``register(subparsers)``. Bad input exits with status 2 and one line
``dhsym: error: …`` (no traceback).

Examples
--------
>>> sorted(build_parser()._subparsers._group_actions[0].choices)  # doctest: +NORMALIZE_WHITESPACE
['check', 'convert', 'derive', 'fk', 'grade', 'handout', 'list', 'notebooks', 'plot', 'show']
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from dhsym import __version__
from dhsym.errors import DHError

from . import checking, documents, geometry, plots, robots

__all__ = ["COMMAND_GROUPS", "build_parser", "main"]

#: The command groups, in the order ``dhsym --help`` lists them.
COMMAND_GROUPS = (robots, documents, plots, geometry, checking)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every command group's sub-commands."""
    p = argparse.ArgumentParser(
        prog="dhsym", description="Denavit-Hartenberg tables to lecture-style kinematics."
    )
    p.add_argument("--version", action="version", version=f"dhsym {__version__}")
    sub = p.add_subparsers(dest="command", required=True)
    for group in COMMAND_GROUPS:
        group.register(sub)
    return p


def _glue_negative_values(argv: list[str]) -> list[str]:
    """``--q -30,45`` would read as an option: glue it to ``--q=-30,45``."""
    out: list[str] = []
    k = 0
    while k < len(argv):
        tok = argv[k]
        nxt = argv[k + 1] if k + 1 < len(argv) else ""
        if tok == "--q" and nxt.startswith("-") and nxt[1:2].isdigit() | (nxt[1:2] == "."):
            out.append(f"--q={nxt}")
            k += 2
            continue
        out.append(tok)
        k += 1
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(_glue_negative_values(list(sys.argv[1:] if argv is None else argv)))
    try:
        return int(args.func(args))
    except DHError as err:
        print(f"dhsym: error: {err}", file=sys.stderr)
        return 2
    except (OSError, IndexError) as err:
        print(f"dhsym: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
