"""The ``dhsym`` command line: the parser and the explicit list of command groups.

Each group lives in its own module of this room and adds its sub-commands with
``register(subparsers)``; the group modules import only the standard library at
the top, and each command imports what it needs when it runs, so ``dhsym --help``
starts without sympy. Bad input exits with status 2 and one line
``dhsym: error: …`` (no traceback); the shell conventions are in :mod:`.common`.

Examples
--------
>>> sorted(build_parser()._subparsers._group_actions[0].choices)  # doctest: +NORMALIZE_WHITESPACE
['autograder', 'cache', 'check', 'check-assignment', 'convert', 'derive', 'export', 'fk', 'grade',
 'handout', 'ik', 'list', 'new-assignment', 'notebooks', 'plot', 'show', 'variants',
 'view']
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence

from . import cache, checking, export, geometry, handouts, plots, robots
from .common import HelpFormatter, run_quietly

__all__ = ["COMMAND_GROUPS", "build_parser", "main"]

#: The command groups, in the order ``dhsym --help`` lists them.
COMMAND_GROUPS = (robots, handouts, plots, geometry, checking, export, cache)

_DESCRIPTION = """\
Denavit-Hartenberg tables to closed-form kinematics in lecture notation
(C12, S23, a1C1 + a2C12), lecture-style derivations and handouts, pictures,
and homework checking.

A robot is a built-in name (dhsym list), a YAML table file, or a URDF file with
--tip LINK (dhsym convert robot.urdf --tip tool0 --to standard -o table.yaml)."""

_EPILOG = """\
Options -o FILE write to FILE; -o - writes to standard output.
Exit status: 0 success, 1 an incorrect answer (check), 2 bad input or an error,
141 the output pipe was closed (e.g. | head), 130 interrupted.
'dhsym COMMAND --help' describes each command."""


class _VersionAction(argparse.Action):
    """``--version``: reads the installed version only when asked (it costs an import)."""

    def __init__(self, option_strings: Sequence[str], dest: str, **kw: object) -> None:
        super().__init__(option_strings, dest, nargs=0, help="print the version and exit")

    def __call__(self, parser: argparse.ArgumentParser, *args: object) -> None:
        from dhsym._version import __version__

        print(f"dhsym {__version__}")
        parser.exit()


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every command group's sub-commands."""
    p = argparse.ArgumentParser(
        prog="dhsym", description=_DESCRIPTION, epilog=_EPILOG, formatter_class=HelpFormatter
    )
    p.add_argument("--version", action=_VersionAction)
    p.add_argument(
        "--no-cache",
        action="store_true",
        help="neither read nor write the disk cache of derived results (as DHSYM_NO_CACHE=1)",
    )
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
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


def _run(args: argparse.Namespace) -> int:
    from dhsym.errors import DHError

    try:
        return int(args.func(args))
    except BrokenPipeError:
        raise  # handled by run_quietly
    except DHError as err:
        print(f"dhsym: error: {_one_line(err)}", file=sys.stderr)
        return 2
    except (OSError, IndexError) as err:
        print(f"dhsym: error: {_one_line(err)}", file=sys.stderr)
        return 2
    except (RecursionError, MemoryError) as err:
        print(
            f"dhsym: error: the input is too large or too deeply nested ({type(err).__name__})",
            file=sys.stderr,
        )
        return 2
    except Exception as err:  # noqa: BLE001 - a user never sees a traceback
        print(
            f"dhsym: internal error: {type(err).__name__}: {_one_line(err)} "
            "(please report this with the command that caused it)",
            file=sys.stderr,
        )
        return 70


def _one_line(err: BaseException) -> str:
    """The error's message on one line, at most 2,000 characters."""
    text = " ".join(str(err).split())
    return text if len(text) <= 2000 else text[:1999] + "…"


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    argv = _glue_negative_values(list(sys.argv[1:] if argv is None else argv))
    before = os.environ.get("DHSYM_NO_CACHE")
    try:
        return run_quietly(lambda: _run(_cache_switch(parser.parse_args(argv))))
    except KeyboardInterrupt:
        print(file=sys.stderr)
        return 130
    finally:  # main() may run inside another program (the tests): leave its switch as found
        if before is None:
            os.environ.pop("DHSYM_NO_CACHE", None)
        else:
            os.environ["DHSYM_NO_CACHE"] = before


def _cache_switch(args: argparse.Namespace) -> argparse.Namespace:
    """``--no-cache``: the library reads ``DHSYM_NO_CACHE`` (:mod:`dhsym.cache.store`)."""
    if args.no_cache:
        os.environ["DHSYM_NO_CACHE"] = "1"
    return args


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
