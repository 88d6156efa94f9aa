"""``dhsym export``: self-contained source code (C, C++, MATLAB/Octave, Rust, NumPy), or a URDF.

``--lang urdf`` writes one file with :func:`dhsym.formats.urdf.write_urdf` (links, joints,
limits, simple visuals and the inertials of rows that have them): ``-o arm.urdf`` names the
file itself; any other ``-o`` is a folder, which gets ``<prefix or robot name>.urdf``.
"""

from __future__ import annotations

import argparse
import shlex
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from .common import add_command, load_robot, note_warnings, wrote

if TYPE_CHECKING:
    from dhsym.robot import Robot

__all__ = ["register"]

#: --lang choices: the export room's languages, and urdf (the formats room's URDF writer)
_LANGS = ("c", "cpp", "matlab", "rust", "python", "urdf")


def _cmd_export(args: argparse.Namespace) -> int:
    from dhsym.export import export

    robot = load_robot(args.robot, args.values)
    note_warnings(robot.table)
    if args.lang == "urdf":
        return _write_urdf(robot, args)
    command = " ".join(
        shlex.quote(a)
        for a in ["dhsym", "export", args.robot, "--lang", args.lang, "--what", args.what]
        + (["--prefix", args.prefix] if args.prefix else [])
        + (["--symbolic-lengths"] if args.symbolic_lengths else [])
        + (["--values", args.values] if args.values else [])
    )
    files = export(
        robot,
        args.lang,
        what=args.what,
        prefix=args.prefix,
        symbolic_lengths=args.symbolic_lengths,
        command=command,
    )
    folder = Path(args.output)
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        path = folder / name
        path.write_text(text, encoding="utf-8")
        wrote(path)
    if not files:
        print("nothing written", file=sys.stderr)
    return 0


def _write_urdf(robot: Robot, args: argparse.Namespace) -> int:
    """``--lang urdf``: one URDF file, ``-o`` itself when it ends in ``.urdf``."""
    from dhsym.errors import DHError
    from dhsym.formats.urdf import write_urdf

    if args.what != "fk,jacobian,ik":
        raise DHError("--what does not apply to --lang urdf (a URDF holds the whole robot)")
    name = args.prefix or Path(args.robot).stem
    text = write_urdf(robot, name=name)
    out = Path(args.output)
    if out.suffix.lower() == ".urdf":
        out.parent.mkdir(parents=True, exist_ok=True)
        path = out
    else:
        out.mkdir(parents=True, exist_ok=True)
        path = out / f"{name}.urdf"
    path.write_text(text, encoding="utf-8")
    wrote(path)
    return 0


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``dhsym export NAME --lang LANG [--what fk,jacobian,ik] [--prefix P] -o DIR``.

    >>> sub = argparse.ArgumentParser().add_subparsers()
    >>> register(sub)
    >>> sorted(sub.choices)
    ['export']
    """
    c = add_command(
        subparsers,
        "export",
        "source code of the fk, Jacobian and closed-form IK: C, C++, MATLAB/Octave, Rust, NumPy",
        epilog="Example: dhsym export puma560 --lang c --prefix puma -o gen/ "
        "(writes gen/puma.h and gen/puma.c; compile with gcc -std=c99 ... -lm); "
        "dhsym export puma560 --lang urdf -o arm.urdf (a URDF for robot viewers)",
    )
    c.add_argument("robot", help="built-in robot name (dhsym list) or table file")
    c.add_argument(
        "--lang",
        required=True,
        choices=_LANGS,
        help="c (C99, math.h), cpp (C++17 header), matlab (Octave too), rust (no crates), "
        "python (NumPy), urdf (one URDF file with limits and inertials)",
    )
    c.add_argument(
        "--what",
        default="fk,jacobian,ik",
        help="comma-separated parts: fk, jacobian, ik, dynamics (or rne: numeric inertial "
        "parameters only)",
    )
    c.add_argument("--prefix", help="name in front of every function (default: the robot's name)")
    c.add_argument(
        "--symbolic-lengths",
        action="store_true",
        help="lengths and offsets as a run-time parameter array p instead of numbers",
    )
    c.add_argument("--values", help="numbers for symbolic lengths, e.g. a1=1,a2=0.8")
    c.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="DIR",
        help="folder for the files (--lang urdf: a folder, or the file itself if it ends in .urdf)",
    )
    c.set_defaults(func=_cmd_export)
