"""``dhsym convert``: standard <-> modified DH with the base/tool that keep the tool pose."""

from __future__ import annotations

import argparse
import sys

from .common import add_command, emit, note_warnings

__all__ = ["register"]


def _cmd_convert(args: argparse.Namespace) -> int:
    from dhsym.geometry.conversion import check_conversion, convert
    from dhsym.model.kinds import Convention
    from dhsym.model.library import load_table
    from dhsym.model.parsing import check_count
    from dhsym.model.tablefile import dump_table

    check_count(args.samples, "--samples", 0, 100_000)
    table = load_table(args.robot)
    note_warnings(table)
    target = Convention.parse(args.to)
    if table.convention is target:
        print(
            f"{table.name or args.robot} is already in the {target.value} convention",
            file=sys.stderr,
        )
    new = convert(table, target)
    err = check_conversion(table, new, samples=args.samples)
    emit(dump_table(new), args.output)
    print(
        f"tool pose agrees at {args.samples} random configurations (max difference {err:.2g})",
        file=sys.stderr,
    )
    return 0


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``dhsym convert NAME|FILE --to modified|standard [-o FILE]``.

    >>> sub = argparse.ArgumentParser().add_subparsers()
    >>> register(sub)
    >>> sorted(sub.choices)
    ['convert']
    """
    c = add_command(
        subparsers,
        "convert",
        "standard <-> modified DH, with base/tool transforms that keep the tool pose",
    )
    c.add_argument("robot", help="built-in robot name (dhsym list) or table file")
    c.add_argument(
        "--to", required=True, choices=["standard", "modified"], help="target convention"
    )
    c.add_argument(
        "-o", "--output", metavar="FILE", help="write the YAML table to FILE (- or none: stdout)"
    )
    c.add_argument("--samples", type=int, default=20, help="random configurations for the fk check")
    c.set_defaults(func=_cmd_convert)
