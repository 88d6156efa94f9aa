"""``dhsym plot``: a picture of the arm with its DH frames, or its workspace."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from dhsym.errors import DHError

__all__ = ["register"]


def _cmd_plot(args: argparse.Namespace) -> int:
    from dhsym.kinematics.robot import load
    from dhsym.model.parsing import parse_number_list
    from dhsym.plot.figures import plot_robot, plot_workspace

    out = Path(args.output)
    if out.suffix.lower() not in (".png", ".pdf", ".svg"):
        raise DHError(f"-o {out}: the picture must be .png, .pdf or .svg")
    robot = load(args.robot)
    if args.workspace:
        fig = plot_workspace(robot, args.samples, view=args.view)
    else:
        q = None if args.q is None else parse_number_list(args.q, "--q")
        fig = plot_robot(robot, q, deg=args.deg, view=args.view or "3d")
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=args.dpi)
    print(f"wrote {out}", file=sys.stderr)
    return 0


def register(subparsers: Any) -> None:
    """Add ``dhsym plot NAME|FILE [--q …] [--deg] [--view 2d|3d] [--workspace] -o FILE``."""
    p = subparsers.add_parser("plot", help="draw the arm with its DH frames (PNG, PDF or SVG)")
    p.add_argument("robot", help="built-in name or table file")
    p.add_argument("--q", help="joint values, comma separated (default: all zero)")
    p.add_argument("--deg", action="store_true", help="revolute values in degrees")
    p.add_argument("--view", choices=["2d", "3d"], help="3d (default) or a 2d top view")
    p.add_argument("--workspace", action="store_true", help="reachable points instead of the arm")
    p.add_argument("--samples", type=int, default=4000, help="workspace samples (default 4000)")
    p.add_argument("--dpi", type=int, default=150, help="resolution of a PNG (default 150)")
    p.add_argument("-o", "--output", required=True, help="picture file: .png, .pdf or .svg")
    p.set_defaults(func=_cmd_plot)
