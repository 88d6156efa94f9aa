"""``dhsym convert``: standard <-> modified DH with the base/tool that keep the tool pose;
a URDF file's chain to a DH table, and a DH table to a URDF."""

from __future__ import annotations

import argparse
import os
import sys

from .common import (
    URDF_SUFFIXES,
    add_command,
    add_robot_argument,
    add_urdf_options,
    emit,
    load_table_arg,
    note_warnings,
)

__all__ = ["register"]


def _cmd_convert(args: argparse.Namespace) -> int:
    from dhsym.errors import DHError
    from dhsym.model.parsing import check_count

    check_count(args.samples, "--samples", 0, 100_000)
    is_urdf = os.path.splitext(args.robot)[1].lower() in URDF_SUFFIXES
    like = None if args.like is None else load_table_arg(args.like)
    if like is not None and args.to == "urdf":
        raise DHError("--like chooses among equivalent DH tables: not with --to urdf")
    if is_urdf and args.to != "urdf":
        from dhsym.formats.urdf import import_urdf, table_yaml

        imp = import_urdf(
            args.robot,
            tip=args.tip,
            base=args.base,
            convention=args.to,
            frames="textbook" if like is None else like,
        )
        note_warnings(imp.table)
        _say_mismatches(imp.choice.mismatches if imp.choice else (), args.like)
        emit(table_yaml(imp), args.output)
        err = imp.verify(args.samples)
        print(
            f"fk agrees with the URDF chain {imp.base} -> {imp.tip} at {args.samples} random "
            f"configurations (max difference {err:.2g})",
            file=sys.stderr,
        )
        return 0
    table = load_table_arg(args.robot, args.tip, args.base)
    note_warnings(table)
    if args.to == "urdf":
        from dhsym.formats.urdf import write_urdf

        emit(write_urdf(table), args.output)
        return 0
    from dhsym.geometry.conversion import check_conversion, convert
    from dhsym.model.kinds import Convention
    from dhsym.model.tablefile import dump_table

    target = Convention.parse(args.to)
    if table.convention is target:
        name = table.name or args.robot
        print(f"{name} is already in the {target.value} convention", file=sys.stderr)
    new = convert(table, target)
    if like is not None:
        from dhsym.geometry.frame_choices import match_frames

        choice = match_frames(new, like)
        _say_mismatches(choice.mismatches, args.like)
        new = choice.table
    err = check_conversion(table, new, samples=args.samples)
    emit(dump_table(new), args.output)
    print(
        f"tool pose agrees at {args.samples} random configurations (max difference {err:.2g})",
        file=sys.stderr,
    )
    return 0


def _say_mismatches(mismatches: tuple[str, ...], like: str | None) -> None:
    """The rows ``--like`` could not match, on standard error (the table is still written:
    the nearest choice)."""
    if mismatches:
        print(
            f"dhsym: note: no equivalent choice of frames matches {like} in every row:",
            file=sys.stderr,
        )
        for line in mismatches:
            print(f"  {line}", file=sys.stderr)


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``dhsym convert NAME|FILE --to modified|standard [-o FILE]``.

    >>> sub = argparse.ArgumentParser().add_subparsers()
    >>> register(sub)
    >>> sorted(sub.choices)
    ['convert']
    """
    c = add_command(
        subparsers,
        "convert",
        "standard <-> modified DH (base/tool keep the tool pose); URDF <-> DH table",
        description="Convert a DH table to the other convention, a URDF file's chain (--tip)\n"
        "to a DH table (--to standard|modified, YAML), or a DH table to a URDF (--to urdf).",
    )
    add_robot_argument(c)
    c.add_argument(
        "--to",
        required=True,
        choices=["standard", "modified", "urdf"],
        help="target convention, or urdf",
    )
    c.add_argument(
        "-o", "--output", metavar="FILE", help="write the result to FILE (- or none: stdout)"
    )
    add_urdf_options(c)
    c.add_argument(
        "--like",
        metavar="TABLE",
        help="choose the senses of the x axes that match this table (a built-in name or a "
        "table file), e.g. --like ur5; the rows that cannot match are listed, with why "
        "(default for a URDF: the table a textbook prints)",
    )
    c.add_argument("--samples", type=int, default=20, help="random configurations for the fk check")
    c.set_defaults(func=_cmd_convert)
