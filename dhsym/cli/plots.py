"""``dhsym plot``: a picture of the arm with its DH frames, or its workspace."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from dhsym.errors import DHError

from .common import (
    STDOUT,
    add_angle_options,
    add_command,
    add_output_option,
    add_robot_argument,
    add_urdf_options,
    add_values_option,
    emit_bytes,
    load_robot,
    q_in_degrees,
)

__all__ = ["register"]

_FORMATS = ("png", "pdf", "svg")


def _format(args: argparse.Namespace) -> str:
    """The picture format: ``--format``, else the suffix of ``-o``, else SVG for ``-o -``."""
    if args.format:
        return str(args.format)
    if args.output == STDOUT:
        return "svg"
    suffix = Path(args.output).suffix.lower().lstrip(".")
    if suffix not in _FORMATS:
        raise DHError(f"-o {args.output}: the picture must be .png, .pdf or .svg (or use --format)")
    return suffix


def _cmd_plot(args: argparse.Namespace) -> int:
    import io

    from dhsym.model.parsing import check_count, parse_number_list
    from dhsym.plot.figures import plot_robot, plot_workspace

    fmt = _format(args)
    check_count(args.samples, "--samples", 1, 1_000_000)
    check_count(args.dpi, "--dpi", 10, 1200)
    robot = load_robot(args.robot, args.values, need_numbers=True, tip=args.tip, base=args.base)

    if args.workspace:
        fig = plot_workspace(robot, args.samples, view=args.view)
    else:
        q = None if args.q is None else parse_number_list(args.q, "--q")
        deg, unit = q_in_degrees(args, robot.table) if q is not None else (False, "")
        if unit:
            print(f"dhsym: note: {unit}", file=sys.stderr)
        fig = plot_robot(robot, q, deg=deg, view=args.view or "3d")
    buffer = io.BytesIO()
    fig.savefig(buffer, format=fmt, dpi=args.dpi)
    emit_bytes(buffer.getvalue(), args.output, f"a {fmt.upper()} picture")
    return 0


def _cmd_view(args: argparse.Namespace) -> int:
    from dhsym.model.parsing import check_count, parse_number_list
    from dhsym.plot.figures import joint_values
    from dhsym.view.page import view_page

    check_count(args.workspace, "--workspace", 0, 100_000)
    robot = load_robot(args.robot, args.values, need_numbers=True, tip=args.tip, base=args.base)
    q = None
    if args.q is not None:
        values = parse_number_list(args.q, "--q")
        deg, unit = q_in_degrees(args, robot.table)
        if unit:
            print(f"dhsym: note: {unit}", file=sys.stderr)
        q = list(joint_values(robot, values, deg=deg))
    page = view_page(robot, q, workspace=args.workspace)
    emit_bytes(page.encode("utf-8"), args.output, "an HTML page")
    return 0


def register(subparsers: Any) -> None:
    """Add ``dhsym plot NAME|FILE [--q …] [--deg] [--view 2d|3d] [--workspace] -o FILE``."""
    p = add_command(subparsers, "plot", "draw the arm with its DH frames (PNG, PDF or SVG)")
    add_robot_argument(p)
    add_urdf_options(p)
    p.add_argument("--q", help="joint values, comma separated (default: all zero)")
    add_angle_options(p)
    add_values_option(p)
    p.add_argument("--view", choices=["2d", "3d"], help="3d (default) or a 2d top view")
    p.add_argument("--workspace", action="store_true", help="reachable points instead of the arm")
    p.add_argument("--samples", type=int, default=4000, help="workspace samples")
    p.add_argument("--dpi", type=int, default=150, help="resolution of a PNG")
    add_output_option(p, "picture file: .png, .pdf or .svg; - writes to standard output")
    p.add_argument(
        "--format",
        choices=_FORMATS,
        default=None,
        help="picture format (default: from the file name; svg for -o -)",
    )
    p.set_defaults(func=_cmd_plot)

    p = add_command(
        subparsers,
        "view",
        "a 3D view of the arm in one HTML page: a slider per joint, its frames, ^0T_n live",
    )
    add_robot_argument(p)
    add_urdf_options(p)
    p.add_argument("--q", help="joint values to start at, comma separated (default: all zero)")
    add_angle_options(p)
    add_values_option(p, "a1=1,a2=0.8")
    p.add_argument(
        "--workspace",
        type=int,
        default=4000,
        metavar="N",
        help="points of the workspace cloud the page can show (0: none; default 4000)",
    )
    add_output_option(
        p, "the page (.html); it opens offline, from a file; - writes to standard output"
    )
    p.set_defaults(func=_cmd_view)
