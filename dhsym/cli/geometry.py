"""``dhsym convert``: standard <-> modified DH with the base/tool that keep the tool pose."""

from __future__ import annotations

import argparse
import sys

from dhsym.model.kinds import Convention

from .common import note_warnings

__all__ = ["register"]


def _cmd_convert(args: argparse.Namespace) -> int:
    from pathlib import Path

    from dhsym.geometry.conversion import check_conversion, convert
    from dhsym.model.library import load_table
    from dhsym.model.tablefile import dump_table

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
    text = dump_table(new)
    if args.output:
        Path(args.output).parent.mkdir(parents=True, exist_ok=True)
        Path(args.output).write_text(text, encoding="utf-8")
        print(f"wrote {args.output}", file=sys.stderr)
    else:
        print(text, end="")
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
    c = subparsers.add_parser(
        "convert",
        help="standard <-> modified DH, with base/tool transforms that keep the tool pose",
    )
    c.add_argument("robot", help="built-in name or table file")
    c.add_argument(
        "--to", required=True, choices=["standard", "modified"], help="target convention"
    )
    c.add_argument("-o", "--output", help="write the YAML table here instead of standard output")
    c.add_argument(
        "--samples",
        type=int,
        default=20,
        help="random configurations for the fk check (default 20)",
    )
    c.set_defaults(func=_cmd_convert)
