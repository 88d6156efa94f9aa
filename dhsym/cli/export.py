"""``dhsym export``: self-contained source code (C, C++, MATLAB/Octave, Rust, NumPy), or a URDF.

``--lang urdf`` writes one file with :func:`dhsym.formats.urdf.write_urdf` (links, joints,
limits, simple visuals and the inertials of rows that have them): ``-o arm.urdf`` names the
file itself; any other ``-o`` is a folder, which gets ``<prefix or robot name>.urdf``.

``--prefix`` is a name, never a path (:func:`dhsym.export.identifiers.checked_name`). The
``-o`` folder is made when missing (it may itself be a link to a folder: the user named
it); inside it each file is written through the folder's descriptor without following a
symbolic link (``O_NOFOLLOW``): a file name that is a link, or anything but a plain file
with one name (a hard link, a pipe), is refused before anything is written, with the
file named (exit code 2).
"""

from __future__ import annotations

import argparse
import os
import shlex
import stat
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from .common import add_command, add_output_option, load_robot, note_warnings, wrote

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
    for path in _write_files(Path(args.output), files):
        wrote(path)
    if not files:
        print("nothing written", file=sys.stderr)
    return 0


def _refusal(path: Path, st: os.stat_result) -> str | None:
    """Why the existing ``path`` (its ``lstat``) is not overwritten, or ``None``."""
    if stat.S_ISLNK(st.st_mode):
        return "is a symbolic link (links are never followed)"
    if not stat.S_ISREG(st.st_mode):
        return "is not a plain file"
    if st.st_nlink > 1:
        return "has other names (a hard link: writing it would change them too)"
    return None


def _write_files(folder: Path, files: Mapping[str, str]) -> list[Path]:
    """Write ``files`` (name → text, UTF-8) into ``folder`` without following a link.

    The folder is made when missing; every name is checked before any is written (a link,
    a hard link or anything but a plain file: a :class:`~dhsym.errors.DHError` naming it),
    and each file is opened relative to the folder's descriptor with ``O_NOFOLLOW``, so a
    link planted between the check and the write is refused too.
    """
    from dhsym.errors import DHError

    if folder.exists() and not folder.is_dir():
        raise DHError(f"{folder} is not a folder: give a folder with -o")
    folder.mkdir(parents=True, exist_ok=True)
    for name in files:
        if name in (".", "..") or os.sep in name or (os.altsep and os.altsep in name):
            raise DHError(f"{name!r} is not a file name")  # the names are prefixes: never
    nofollow = getattr(os, "O_NOFOLLOW", 0)
    flags = os.O_WRONLY | os.O_CREAT | nofollow | getattr(os, "O_NONBLOCK", 0)
    flags |= getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0)
    relative = os.open in os.supports_dir_fd and os.stat in os.supports_dir_fd
    dir_fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0)) if relative else None
    written = []
    try:
        for name in files:
            path = folder / name
            try:
                st = os.stat(name if relative else path, dir_fd=dir_fd, follow_symlinks=False)
            except FileNotFoundError:
                continue
            why = _refusal(path, st)
            if why:
                raise DHError(f"{path} {why}: nothing written; remove it or choose another -o")
        for name, text in files.items():
            path = folder / name
            try:
                fd = os.open(name if relative else path, flags, 0o644, dir_fd=dir_fd)
            except OSError as err:
                raise DHError(f"{path} cannot be written safely ({err.strerror})") from None
            try:
                why = _refusal(path, os.fstat(fd))
                if why:
                    raise DHError(f"{path} {why}: not written")
                os.ftruncate(fd, 0)
                data = memoryview(text.encode("utf-8"))
                while data:
                    data = data[os.write(fd, data) :]
            finally:
                os.close(fd)
            written.append(path)
    finally:
        if dir_fd is not None:
            os.close(dir_fd)
    return written


def _write_urdf(robot: Robot, args: argparse.Namespace) -> int:
    """``--lang urdf``: one URDF file, ``-o`` itself when it ends in ``.urdf``."""
    from dhsym.errors import DHError
    from dhsym.export.identifiers import checked_name
    from dhsym.formats.urdf import write_urdf

    if args.what != "fk,jacobian,ik":
        raise DHError("--what does not apply to --lang urdf (a URDF holds the whole robot)")
    name = checked_name(args.prefix) if args.prefix else Path(args.robot).stem
    text = write_urdf(robot, name=name)
    out = Path(args.output)
    if out.suffix.lower() == ".urdf":
        folder, file = out.parent, out.name
    else:
        folder, file = out, f"{name}.urdf"
    for path in _write_files(folder, {file: text}):
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
        "parameters only), trajectory (cubic and quintic profiles), control (computed "
        "torque on rne: numeric inertial parameters only), screws (the product of "
        "exponentials: fk_space, jacobian_space, jacobian_body)",
    )
    c.add_argument(
        "--prefix",
        help="name in front of every function and file: letters, digits and _, never a path "
        "(default: the robot's name; a keyword or standard name such as log or os gets a _)",
    )
    c.add_argument(
        "--symbolic-lengths",
        action="store_true",
        help="lengths and offsets as a run-time parameter array p instead of numbers",
    )
    c.add_argument("--values", help="numbers for symbolic lengths, e.g. a1=1,a2=0.8")
    add_output_option(
        c,
        "folder for the files (--lang urdf: a folder, or the file itself if it ends in .urdf)",
        metavar="DIR",
    )
    c.set_defaults(func=_cmd_export)
