"""``dhsym list``, ``show``, ``derive`` and ``fk``: a robot's table, closed forms and numbers.

Examples
--------
>>> from dhsym.cli.main import main
>>> main(["fk", "planar2r", "--q", "0,0", "--json"])  # doctest: +ELLIPSIS
{"robot": "Planar 2R", ...}
0
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable

import numpy as np

from dhsym import __version__
from dhsym.errors import DHError
from dhsym.kinematics.robot import Robot, load
from dhsym.model.library import builtin_names, builtin_table
from dhsym.model.parsing import parse_number_list
from dhsym.model.tablefile import dump_table
from dhsym.notation.printers import TrigStyle
from dhsym.notation.tables import table_markdown

from .common import emit

__all__ = ["JSON_SCHEMA_VERSION", "derive_json", "register"]


def _cmd_list(args: argparse.Namespace) -> int:
    for name in builtin_names():
        t = builtin_table(name)
        kinds = "".join(r.joint.value for r in t.rows)
        print(f"{name:20s} {kinds:8s} {t.convention.value:9s} {t.name}")
    print(f"{'planarNr':20s} {'R' * 3 + '…':8s} {'standard':9s} Planar nR chain, any N up to 60")
    return 0


def _cmd_show(args: argparse.Namespace) -> int:
    robot = load(args.robot)
    t = robot.table
    if args.format == "yaml":
        print(dump_table(t), end="")
    else:
        print(f"# {t.name}\n\n{t.convention.value} DH convention; source: {t.source}\n")
        print(table_markdown(t))
        if t.values:
            print("\nvalues: " + ", ".join(f"{k} = {v}" for k, v in t.values))
    return 0


def _frames(robot: Robot, args: argparse.Namespace) -> tuple[int, int]:
    i = 0 if args.frm is None else args.frm
    j = robot.n if args.to is None else args.to
    for k in (i, j):
        if not -1 <= k <= robot.n + 1:
            raise DHError(
                f"frames of {robot.name} are 0 … {robot.n} (-1 world, {robot.n + 1} tool)"
            )
    return i, j


JSON_SCHEMA_VERSION = 1


def derive_json(robot: Robot, i: int = 0, j: int | None = None) -> dict[str, object]:
    """The derivation as a JSON-ready dict (schema documented in the README).

    >>> from dhsym import load
    >>> d = derive_json(load("planar2r"))
    >>> d["compact"][0][3], d["matrix"][0][3]
    ('a1*C1 + a2*C12', 'a1*cos(theta1) + a2*cos(theta1 + theta2)')
    """
    j = robot.n if j is None else j
    pose = robot.transform(i, j)
    full = robot.notation.__class__(robot.notation.labels, compact=False)

    def grid(fn: Callable[[object], str], M: object) -> list[list[str]]:
        return [[fn(M[r, c]) for c in range(4)] for r in range(4)]  # type: ignore[index]

    links = []
    if 0 <= i < j <= robot.n:
        for k in range(i + 1, j + 1):
            L = robot.link_matrix(k)
            links.append(
                {
                    "index": k,
                    "label": L.label_text,
                    "compact": grid(robot.notation.text, L.matrix),
                    "matrix": grid(full.text, L.matrix),
                }
            )
    return {
        "schema": JSON_SCHEMA_VERSION,
        "dhsym": __version__,
        "robot": robot.name,
        "convention": robot.convention.value,
        "from": pose.frm,
        "to": pose.to,
        "variables": [str(v) for v in robot.variables],
        "label": pose.label_text,
        "matrix": grid(full.text, pose.matrix),
        "compact": grid(robot.notation.text, pose.matrix),
        "latex": grid(robot.notation.latex, pose.matrix),
        "links": links,
        "legend": [
            {"abbrev": e.text, "meaning": e.meaning_text}
            for e in robot.notation.legend(list(pose.matrix))
        ],
        "count_ops": pose.count_ops(),
    }


def _cmd_derive(args: argparse.Namespace) -> int:
    robot = load(args.robot, compact=not args.full, style=args.notation)
    what = getattr(args, "what", "fk")
    if what != "fk":
        return _derive_more(robot, what, args)
    i, j = _frames(robot, args)
    if args.format == "json":
        out = json.dumps(derive_json(robot, i, j), indent=2)
    else:
        from dhsym.explain.documents import render_derivation

        out = render_derivation(robot, fmt=args.format, frm=i, to=j)
    emit(out, args.output)
    return 0


def _derive_more(robot: Robot, what: str, args: argparse.Namespace) -> int:
    """``derive --what jacobian|singularities|ik`` (``--from``/``--to`` belong to fk)."""
    if args.frm is not None or args.to is not None:
        raise DHError(f"--from and --to choose ^iT_j of the forward kinematics, not --what {what}")
    if args.format == "json":
        from .derivations import derivation_json

        out = json.dumps(derivation_json(robot, what), indent=2)
    else:
        from dhsym.explain.documents import render_derivation

        out = render_derivation(robot, fmt=args.format, what=what)
    emit(out, args.output)
    return 0


def _parse_q(text: str, n: int) -> list[float]:
    values = parse_number_list(text, "--q")
    if len(values) != n:
        raise DHError(f"--q needs {n} values (one per joint), got {len(values)}")
    if not all(np.isfinite(values)):
        raise DHError("--q values must be finite numbers")
    return values


def _cmd_fk(args: argparse.Namespace) -> int:
    robot = load(args.robot)
    q = _parse_q(args.q, len(robot.variables))
    T = robot.fk(q, deg=args.deg)
    if args.json:
        print(
            json.dumps(
                {
                    "robot": robot.name,
                    "variables": [str(v) for v in robot.variables],
                    "q": q,
                    "deg": bool(args.deg),
                    "matrix": T.round(12).tolist(),
                }
            )
        )
    else:
        with np.printoptions(precision=6, suppress=True):
            print(T)
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    """Add ``list``, ``show``, ``derive`` and ``fk``."""
    sub.add_parser("list", help="built-in robots").set_defaults(func=_cmd_list)

    s = sub.add_parser("show", help="print a DH table")
    s.add_argument("robot", help="built-in name or table file")
    s.add_argument("--format", choices=["markdown", "yaml"], default="markdown")
    s.set_defaults(func=_cmd_show)

    d = sub.add_parser("derive", help="link matrices and the arm matrix in closed form")
    d.add_argument("robot", help="built-in name or table file")
    d.add_argument("--format", choices=["text", "markdown", "latex", "json"], default="text")
    d.add_argument("--from", dest="frm", type=int, default=None, help="frame i of ^iT_j")
    d.add_argument("--to", type=int, default=None, help="frame j of ^iT_j")
    d.add_argument("--full", action="store_true", help="full cos/sin instead of C12/S12")
    d.add_argument(
        "--notation",
        choices=[s.value for s in TrigStyle],
        default=TrigStyle.UPPER.value,
        help="C1: C12, S23 (default); c1: c12, s23 (Craig, Spong); c_theta: c_{θ12} in LaTeX",
    )
    d.add_argument(
        "--what",
        choices=["fk", "jacobian", "singularities", "ik"],
        default="fk",
        help="fk: forward kinematics (default); jacobian: column by column; singularities: "
        "det J factored and named; ik: closed-form inverse kinematics, every branch",
    )
    d.add_argument("-o", "--output", help="write to this file instead of standard output")
    d.set_defaults(func=_cmd_derive)

    f = sub.add_parser("fk", help="numeric forward kinematics")
    f.add_argument("robot", help="built-in name or table file")
    f.add_argument("--q", required=True, help="joint values, comma separated")
    f.add_argument("--deg", action="store_true", help="revolute values in degrees")
    f.add_argument("--json", action="store_true", help="JSON output")
    f.set_defaults(func=_cmd_fk)
