"""The ``dhsym`` command line.

Sub-commands: ``list``, ``show``, ``derive``, ``fk`` (and, from the other
modules, ``handout``, ``plot``, ``check``, ``grade``, ``convert``). Bad input
exits with status 2 and one line ``dhsym: error: …`` (no traceback).

Examples
--------
>>> main(["fk", "planar2r", "--q", "0,0", "--json"])  # doctest: +ELLIPSIS
{"robot": "Planar 2R", ...}
0
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from . import __version__
from ._number_list import parse_number_list
from .errors import DHError
from .library import builtin_names, builtin_table, load
from .notation import table_markdown
from .robot import Robot
from .tablefile import dump_table

__all__ = ["build_parser", "derive_json", "main"]

JSON_SCHEMA_VERSION = 1


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
    robot = load(args.robot, compact=not args.full)
    i, j = _frames(robot, args)
    if args.format == "json":
        out = json.dumps(derive_json(robot, i, j), indent=2)
    else:
        from .rendering import render_derivation

        out = render_derivation(robot, fmt=args.format, frm=i, to=j)
    _emit(out, args.output)
    return 0


def _emit(text: str, output: str | None) -> None:
    if output:
        Path(output).parent.mkdir(parents=True, exist_ok=True)
        Path(output).write_text(text if text.endswith("\n") else text + "\n", encoding="utf-8")
        print(f"wrote {output}", file=sys.stderr)
    else:
        print(text)


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


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (sub-commands register themselves here)."""
    p = argparse.ArgumentParser(prog="dhsym", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"dhsym {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

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
    d.add_argument("-o", "--output", help="write to this file instead of standard output")
    d.set_defaults(func=_cmd_derive)

    f = sub.add_parser("fk", help="numeric forward kinematics")
    f.add_argument("robot", help="built-in name or table file")
    f.add_argument("--q", required=True, help="joint values, comma separated")
    f.add_argument("--deg", action="store_true", help="revolute values in degrees")
    f.add_argument("--json", action="store_true", help="JSON output")
    f.set_defaults(func=_cmd_fk)

    for register in _extensions():
        register(sub)
    return p


def _extensions() -> list[Callable[[argparse._SubParsersAction], None]]:
    """Sub-commands contributed by other modules (handout, plot, check, grade, convert)."""
    found = []
    here = Path(__file__).parent
    for module in ("rendering", "plotting", "notebooks", "checking.cli", "conversion"):
        if not (here / (module.replace(".", "/") + ".py")).exists():
            continue
        mod = importlib.import_module(f"dhsym.{module}")
        if hasattr(mod, "register_cli"):
            found.append(mod.register_cli)
    return found


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


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(_glue_negative_values(list(sys.argv[1:] if argv is None else argv)))
    try:
        return int(args.func(args))
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
    except KeyboardInterrupt:
        print("dhsym: interrupted", file=sys.stderr)
        return 130
    except Exception as err:  # noqa: BLE001 - a user never sees a traceback
        print(
            f"dhsym: internal error: {type(err).__name__}: {_one_line(err)} "
            "(please report this with the command that caused it)",
            file=sys.stderr,
        )
        return 70


def _one_line(err: BaseException) -> str:
    text = " ".join(str(err).split())
    return text if len(text) <= 2000 else text[:1999] + "…"


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
