"""What every command shares: the shell's conventions, in one place.

* ``-o -`` means standard output for every command that writes a file
  (:func:`emit`, :func:`emit_bytes`); a binary picture goes to standard output only
  when it is not a terminal.
* A closed pipe (``dhsym derive puma560 | head -1``) ends the command quietly with
  status 141 (128 + SIGPIPE, as the shell reports a program killed by it): no message,
  no traceback, not even at the interpreter's last flush (:func:`run_quietly`).
* Help is plain text with the defaults and choices shown (:class:`HelpFormatter`,
  :func:`add_command`).
* Every "wrote" line names the path the way the user gave it (:func:`wrote`).
* ``--values a2=0.43,d3=0.15`` gives numbers to a table's symbols (:func:`load_robot`).
* What the reader did to the input (decimal angles read as exact) is a note on standard
  error (:func:`note_warnings`).

Only the standard library is imported here: ``dhsym --help`` must start fast.

Examples
--------
>>> parse_values("a2=0.43, d3 = pi/20", "--values")
{'a2': 0.43, 'd3': 0.15707963267948966}
>>> emit("hello", "-")
hello
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the table loads when a command runs
    from dhsym.model.table import DHTable
    from dhsym.robot import Robot

__all__ = [
    "EXIT_BROKEN_PIPE",
    "JSON_SCHEMA_VERSION",
    "ROBOT_HELP",
    "STDOUT",
    "HelpFormatter",
    "add_angle_options",
    "add_command",
    "add_notation_options",
    "add_output_option",
    "add_robot_argument",
    "add_values_option",
    "json_head",
    "q_in_degrees",
    "emit",
    "emit_bytes",
    "URDF_SUFFIXES",
    "add_urdf_options",
    "load_robot",
    "load_table_arg",
    "note_warnings",
    "parse_values",
    "progress_line",
    "run_quietly",
    "wrote",
]

#: The file name that means standard output.
STDOUT = "-"

#: The version of the JSON the commands write (``dhsym derive --format json``; the schema
#: in docs/reference/json.md).
JSON_SCHEMA_VERSION = 1

#: Exit status after a closed pipe: 128 + SIGPIPE, what the shell shows for ``yes | head``.
EXIT_BROKEN_PIPE = 141


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Plain help: descriptions and epilogs as written, ``(default: …)`` after each option
    whose default is a value (not for flags, nor when the help already says it)."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        default = action.default
        if (
            action.option_strings
            and default not in (None, False, True, argparse.SUPPRESS)
            and "default" not in text
            and action.nargs != 0
        ):
            text += " (default: %(default)s)"
        return text


def add_command(
    subparsers: argparse._SubParsersAction[argparse.ArgumentParser],
    name: str,
    help: str,  # noqa: A002 - argparse's own word
    *,
    description: str | None = None,
    epilog: str | None = None,
) -> argparse.ArgumentParser:
    """A sub-command with plain help, defaults shown, and ``help`` as its description."""
    return subparsers.add_parser(
        name,
        help=help,
        description=description or help[:1].upper() + help[1:] + ".",
        epilog=epilog,
        formatter_class=HelpFormatter,
    )


def add_notation_options(parser: argparse.ArgumentParser) -> None:
    """``--full`` and ``--notation``: how cosines and sines are written (derive, handout)."""
    parser.add_argument("--full", action="store_true", help="full cos/sin instead of C12/S12")
    parser.add_argument(
        "--notation",
        choices=("C1", "c1", "c_theta"),
        default="C1",
        help="C1: C12, S23; c1: c12, s23 (Craig, Spong); c_theta: c_{θ12} in LaTeX",
    )


def wrote(path: str | os.PathLike[str]) -> None:
    """Say on standard error that ``path`` was written (as the user wrote it: no resolving)."""
    print(f"wrote {os.fspath(path)}", file=sys.stderr)


def emit(text: str, output: str | None) -> None:
    """Print ``text``, or write it to the file ``output`` and say so (``-`` is stdout)."""
    if not output or output == STDOUT:
        print(text if not text.endswith("\n") else text[:-1])
        return
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    Path(output).write_text(text if text.endswith("\n") else text + "\n", encoding="utf-8")
    wrote(output)


def emit_bytes(data: bytes, output: str, what: str) -> None:
    """Write binary ``data`` to the file ``output``, or to standard output for ``-``.

    Refuses to print binary data (``what``, e.g. ``a PNG picture``) on a terminal.
    """
    from dhsym.errors import DHError

    if output == STDOUT:
        if sys.stdout.isatty():
            raise DHError(
                f"-o - would print {what} on the terminal: pipe it (| display), or give a file name"
            )
        sys.stdout.flush()
        sys.stdout.buffer.write(data)
        sys.stdout.buffer.flush()
        return
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    Path(output).write_bytes(data)
    wrote(output)


def _silence_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's last flush cannot fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # stdout without a file descriptor
        pass


def run_quietly(command: Callable[[], int]) -> int:
    """Run ``command`` and flush stdout; a closed pipe gives :data:`EXIT_BROKEN_PIPE` quietly.

    Python ignores SIGPIPE and raises :class:`BrokenPipeError` instead, at the write
    that found the pipe closed or at the final flush. Both are caught here (the flush
    is done here, inside the handler), and stdout is then pointed at ``/dev/null``.
    SIGPIPE itself stays ignored: worker processes of ``grade`` talk through pipes,
    and a dead worker must be an error the batch survives, not a silent kill.
    """
    try:
        try:
            status = command()
        except SystemExit:  # --help, --version and usage errors end through sys.exit
            sys.stdout.flush()
            raise
        sys.stdout.flush()
        return status
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_BROKEN_PIPE


def parse_values(text: str, option: str = "--values") -> dict[str, float]:
    """``a2=0.43,d3=0.15`` as ``{"a2": 0.43, "d3": 0.15}``; numbers through the safe parser."""
    from dhsym.errors import DHError
    from dhsym.model.parsing import parse_number_list

    out: dict[str, float] = {}
    for part in text.split(","):
        name, sep, value = part.partition("=")
        name = name.strip()
        if not sep or not name or not value.strip():
            raise DHError(f"{option}: expected NAME=NUMBER pairs separated by commas, got {part!r}")
        if not name.replace("_", "").isalnum() or not name[0].isalpha():
            raise DHError(f"{option}: {name!r} is not a symbol name")
        out[name] = parse_number_list(value, f"{option} {name}")[0]
    return out


URDF_SUFFIXES = (".urdf", ".xacro")


def json_head(robot: Robot) -> dict[str, object]:
    """What every JSON a command writes about a robot starts with: the schema's version,
    dhsym's, the robot's name and its convention."""
    from dhsym._version import __version__

    return {
        "schema": JSON_SCHEMA_VERSION,
        "dhsym": __version__,
        "robot": robot.name,
        "convention": robot.convention.value,
    }


ROBOT_HELP = "built-in robot name (dhsym list), table file, or URDF file (with --tip)"


def add_robot_argument(parser: argparse.ArgumentParser) -> None:
    """The positional ``robot``: a built-in name, a table file or a URDF file (``--tip``)."""
    parser.add_argument("robot", help=ROBOT_HELP)


def add_values_option(parser: argparse.ArgumentParser, example: str = "a2=0.43,d3=0.15") -> None:
    """``--values NAME=NUMBER,...``: numbers for the table's symbolic lengths (read by
    :func:`parse_values`), with an ``example``."""
    parser.add_argument(
        "--values",
        metavar="NAME=NUMBER,...",
        help=f"numbers for the table's symbolic lengths, e.g. {example}",
    )


def add_output_option(parser: argparse.ArgumentParser, help: str, metavar: str = "FILE") -> None:
    """``-o/--output FILE``, required: where the command writes (``help`` says what)."""
    parser.add_argument("-o", "--output", required=True, metavar=metavar, help=help)


def add_urdf_options(parser: argparse.ArgumentParser) -> None:
    """``--tip LINK`` and ``--base LINK`` for a robot given as a URDF file."""
    parser.add_argument(
        "--tip", metavar="LINK", help="URDF file: the link the chain ends at (the tool)"
    )
    parser.add_argument(
        "--base", metavar="LINK", help="URDF file: the link the chain starts at (default: root)"
    )


def load_table_arg(
    name: str, tip: str | None = None, base: str | None = None, convention: str = "standard"
) -> DHTable:
    """The DH table of ``name``: a built-in name, a table file, a URDF file (``--tip``) or a
    product of exponentials (``*.poe.yaml``, :mod:`dhsym.screws.poefile`)."""
    from dhsym.errors import DHError, echoed

    if os.path.splitext(name)[1].lower() in URDF_SUFFIXES:
        from dhsym.formats.urdf import import_urdf

        return import_urdf(name, tip=tip, base=base, convention=convention).table
    if tip is not None or base is not None:
        raise DHError(f"--tip and --base choose a chain in a URDF file; {echoed(name)} is not one")
    from dhsym.screws.poefile import is_poe_path

    if is_poe_path(name):  # a product of exponentials: its axes given DH frames
        from dhsym.screws.poe_to_dh import to_dh
        from dhsym.screws.poefile import read_poe

        return to_dh(read_poe(name), convention).table
    from dhsym.model.library import load_table

    return load_table(name)


def load_robot(
    name: str,
    values: str | None = None,
    *,
    need_numbers: bool = False,
    tip: str | None = None,
    base: str | None = None,
) -> Robot:
    """The robot ``name`` (built-in, table file or URDF file) with ``--values`` applied.

    With ``need_numbers`` every symbolic length must have a number, from the table's
    ``values:`` or from ``--values``; the error names both ways.
    """
    from dhsym.errors import DHError
    from dhsym.robot import Robot

    table = load_table_arg(name, tip, base)
    if values:
        given = parse_values(values)
        known = {str(s) for s in table.constants}
        unknown = sorted(set(given) - known)
        if unknown:
            have = ", ".join(sorted(known)) or "none"
            raise DHError(
                f"--values: {table.name or name} has no symbol {', '.join(unknown)} "
                f"(its symbolic lengths: {have})"
            )
        table = table.with_values(given)
    if need_numbers:
        missing = sorted(str(s) for s in set(table.constants) - set(table.value_map))
        if missing:
            example = ",".join(f"{m}=…" for m in missing)
            raise DHError(
                f"{table.name or name} has no numbers for {', '.join(missing)}: give them in "
                f"the table file's values: (values: {{{missing[0]}: …}}) or on the command "
                f"line with --values {example}"
            )
    return Robot(table)


def progress_line(task: str, *, after: float = 2.0) -> Callable[[str], None]:
    """A callback printing ``dhsym: <task>: <stage> (N s)`` on standard error, from the first
    stage reached ``after`` seconds into the work (quick work prints nothing)."""
    start = time.perf_counter()

    def say(stage: str) -> None:
        elapsed = time.perf_counter() - start
        if elapsed >= after:
            print(f"dhsym: {task}: {stage} ({elapsed:.0f} s)", file=sys.stderr, flush=True)

    return say


def note_warnings(table: object) -> None:
    """Print what the reader did to the input (``table.warnings``) on standard error, once."""
    for text in getattr(table, "warnings", ()):
        print(f"dhsym: note: {text}", file=sys.stderr)


def add_angle_options(parser: argparse.ArgumentParser) -> None:
    """``--deg`` / ``--rad``: the unit of ``--q``'s revolute values (default: the table's)."""
    unit = parser.add_mutually_exclusive_group()
    unit.add_argument(
        "--deg", action="store_true", help="revolute values in degrees (default: the table's unit)"
    )
    unit.add_argument(
        "--rad", action="store_true", help="revolute values in radians (default: the table's unit)"
    )


def q_in_degrees(args: argparse.Namespace, table: object) -> tuple[bool, str]:
    """Whether ``--q`` is in degrees (``--deg``, ``--rad``, else the table's ``angles``),
    and the sentence that says so.

    >>> from types import SimpleNamespace as NS
    >>> q_in_degrees(NS(deg=False, rad=False), NS(angles=NS(value="deg")))
    (True, "--q read in degrees (the table's angles: deg; --rad to override)")
    """
    if args.deg or args.rad:
        deg = bool(args.deg)
        why = "--deg" if deg else "--rad"
    else:
        deg = getattr(getattr(table, "angles", None), "value", "rad") == "deg"
        unit, other = ("deg", "--rad") if deg else ("rad", "--deg")
        why = f"the table's angles: {unit}; {other} to override"
    return deg, f"--q read in {'degrees' if deg else 'radians'} ({why})"
