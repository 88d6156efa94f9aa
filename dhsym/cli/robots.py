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
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING

from .common import (
    JSON_SCHEMA_VERSION,
    add_angle_options,
    add_command,
    add_notation_options,
    add_robot_argument,
    add_urdf_options,
    add_values_option,
    emit,
    json_head,
    load_robot,
    load_table_arg,
    note_warnings,
    progress_line,
    q_in_degrees,
)

if TYPE_CHECKING:  # sympy, numpy and the robot load when a command runs
    import sympy as sp

    from dhsym.model.table import Elementary
    from dhsym.robot import Robot

__all__ = ["JSON_SCHEMA_VERSION", "derive_json", "register"]


def _cmd_list(args: argparse.Namespace) -> int:
    from dhsym.model.library import builtin_names, builtin_table

    for name in builtin_names():
        t = builtin_table(name)
        kinds = "".join(r.joint.value for r in t.rows)
        print(f"{name:20s} {kinds:8s} {t.convention.value:9s} {t.name}")
    print(f"{'planarNr':20s} {'R' * 3 + '…':8s} {'standard':9s} Planar nR chain, any N up to 60")
    return 0


def _cmd_show(args: argparse.Namespace) -> int:
    from dhsym.model.entries import exact_decimal
    from dhsym.model.tablefile import dump_table
    from dhsym.notation.escape import escape_markdown
    from dhsym.notation.tables import table_markdown
    from dhsym.robot import Robot

    robot = Robot(load_table_arg(args.robot, args.tip, args.base))
    t = robot.table
    note_warnings(t)
    if args.format == "yaml":
        print(dump_table(t), end="")
    else:
        name, source = escape_markdown(t.name), escape_markdown(t.source)  # from files: text
        print(f"# {name}\n\n{t.convention.value} DH convention; source: {source}\n")
        print(table_markdown(t))
        if t.values:
            print("\nvalues: " + ", ".join(f"{k} = {exact_decimal(v) or v}" for k, v in t.values))
        for label, word in (("base", t.base), ("tool", t.tool)):
            if word:  # the table alone is not the arm: what stands before and after it
                print(f"\n{label} transform: {_word_markdown(word)}")
    return 0


def _word_markdown(word: tuple[Elementary, ...]) -> str:
    r"""A word of elementary transforms in Markdown math: ``$R_z(180^{\circ})\,T_z(0.107)$``."""
    import sympy as sp

    from dhsym.model.entries import exact_decimal
    from dhsym.notation.printers import format_angle

    parts = []
    for e in word:
        nice = e.kind == "R" and ((e.value / sp.pi).is_rational is True or e.value == 0)
        if e.kind == "R":
            value = format_angle(e.value, degrees=nice, latex=True)
        else:
            value = exact_decimal(e.value) or sp.latex(e.value)
        parts.append(f"{e.kind}_{e.axis}({value})")
    return "$" + r"\,".join(parts) + "$"


def _frames(robot: Robot, args: argparse.Namespace) -> tuple[int, int]:
    from dhsym.errors import DHError

    i = 0 if args.frm is None else args.frm
    j = robot.n if args.to is None else args.to
    for k in (i, j):
        if not -1 <= k <= robot.n + 1:
            raise DHError(
                f"frames of {robot.name} are 0 … {robot.n} (-1 world, {robot.n + 1} tool)"
            )
    return i, j


def derive_json(robot: Robot, i: int = 0, j: int | None = None) -> dict[str, object]:
    """The derivation as a JSON-ready dict (schema in docs/reference/json.md).

    >>> from dhsym import load
    >>> d = derive_json(load("planar2r"))
    >>> d["compact"][0][3], d["matrix"][0][3]
    ('a1*C1 + a2*C12', 'a1*cos(theta1) + a2*cos(theta1 + theta2)')
    """
    j = robot.n if j is None else j
    pose = robot.transform(i, j)
    full = robot.notation.__class__(robot.notation.labels, compact=False)

    def grid(fn: Callable[[object], str], M: sp.MatrixBase) -> list[list[str]]:
        return [[fn(M[r, c]) for c in range(4)] for r in range(4)]

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
        **json_head(robot),
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
    from dhsym.robot import Robot

    table = load_table_arg(args.robot, args.tip, args.base)
    robot = Robot(table, compact=not args.full, style=args.notation)
    note_warnings(robot.table)
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
    """``derive --what jacobian|singularities|ik|dynamics`` (``--from``/``--to`` belong to fk)."""
    from dhsym.errors import DHError

    if args.frm is not None or args.to is not None:
        raise DHError(f"--from and --to choose ^iT_j of the forward kinematics, not --what {what}")
    if args.format == "json":
        from .derivations import derivation_json

        out = json.dumps(derivation_json(robot, what), indent=2)
    else:
        from dhsym.explain.documents import render_derivation

        try:
            if what == "dynamics":
                say = progress_line(f"{robot.name or 'robot'}: {what}")
                out = render_derivation(robot, fmt=args.format, what=what, progress=say)
            else:
                out = render_derivation(robot, fmt=args.format, what=what)
        except DHError as err:
            nxt = _next_step(what, args.robot)
            if nxt is None:
                raise
            raise type(err)(f"{err.message}. {nxt}") from None
    emit(out, args.output)
    return 0


def _next_step(what: str, name: str) -> str | None:
    """The command that goes on where ``derive --what`` finds no closed form."""
    if what == "ik":
        return f"A numeric solution: {_numeric_command(name)}"
    if what == "singularities":
        return (
            "The measure to use: the manipulability w = sqrt(det(J Jᵀ)) (Yoshikawa), zero "
            f"exactly at a singular configuration: dhsym fk {name} --q Q --manipulability"
        )
    return None


def _parse_q(text: str, n: int, option: str = "--q") -> list[float]:
    import math

    from dhsym.errors import DHError
    from dhsym.model.parsing import parse_number_list

    values = parse_number_list(text, option)
    if len(values) != n:
        raise DHError(f"{option} needs {n} values (one per joint), got {len(values)}")
    if not all(math.isfinite(v) for v in values):
        raise DHError(f"{option} values must be finite numbers")
    return values


def _cmd_fk(args: argparse.Namespace) -> int:
    import numpy as np

    robot = load_robot(args.robot, args.values, need_numbers=True, tip=args.tip, base=args.base)
    q = _parse_q(args.q, len(robot.variables))
    deg, unit = q_in_degrees(args, robot.table)
    T = robot.fk(q, deg=deg)
    extra: dict[str, object] = {}
    if args.manipulability:
        rows = [r for r in robot.table.rows if r.variable is not None]
        turns = [deg and r.variable_field == "theta" for r in rows]  # only angles convert
        J = robot.jacob0(np.where(turns, np.radians(q), q))
        wide = J if J.shape[0] <= J.shape[1] else J.T  # det(J Jᵀ), or det(Jᵀ J) for a tall J
        extra["manipulability"] = float(np.sqrt(max(np.linalg.det(wide @ wide.T), 0.0)))
    if args.json:
        print(
            json.dumps(
                {
                    "robot": robot.name,
                    "variables": [str(v) for v in robot.variables],
                    "q": q,
                    "deg": deg,
                    "matrix": T.round(12).tolist(),
                    **extra,
                }
            )
        )
    else:
        with np.printoptions(precision=6, suppress=True):
            print(f"{unit}:\n{T}")
        if extra:
            print(f"manipulability w = sqrt(det(J Jᵀ)) = {extra['manipulability']:.6g}")
    return 0


def _pose(args: argparse.Namespace, robot: Robot) -> object:
    """The goal pose: ``--pose`` (12 or 16 numbers, the rows of T) or ``--pose-of Q``."""
    import numpy as np

    from dhsym.errors import DHError
    from dhsym.model.parsing import parse_number_list

    if (args.pose is None) == (args.pose_of is None):
        raise DHError("give the goal as --pose (12 or 16 numbers, T row by row) or --pose-of Q")
    if args.pose_of is not None:
        deg, unit = q_in_degrees(args, robot.table)
        # a note: on stderr with --json (stdout holds the JSON alone)
        print(f"pose of --pose-of: {unit}", file=sys.stderr if args.json else sys.stdout)
        return robot.fk(_parse_q(args.pose_of, len(robot.variables)), deg=deg)
    values = parse_number_list(args.pose, "--pose")
    if len(values) not in (12, 16):
        raise DHError(f"--pose needs 12 or 16 numbers (T row by row), got {len(values)}")
    T = np.eye(4)
    T[:3, :] = np.reshape(values[:12], (3, 4))
    return T


def _numeric_command(name: str) -> str:
    return f"dhsym ik {name} --pose T11,...,T34 --numeric (or --pose-of Q)"


def _in_radians(robot: Robot, q: list[float], deg: bool) -> list[float]:
    """Joint values ``q`` with the revolute ones turned from degrees when ``deg``."""
    import math

    rows = [r for r in robot.table.rows if r.variable is not None]
    return [math.radians(v) if deg and r.variable_field == "theta" else v for v, r in zip(q, rows)]


def _free_choices(args: argparse.Namespace, robot: Robot, deg: bool) -> list[dict[int, float]]:
    """``--free K=V`` (repeatable): each a joint (1-based) and its value in the unit of
    ``--q``; each is solved in turn. ``[{}]`` without ``--free``."""
    import math

    from dhsym.errors import DHError
    from dhsym.model.parsing import parse_number_list

    if not args.free:
        return [{}]
    n = len(robot.variables)
    rows = [r for r in robot.table.rows if r.variable is not None]
    out = []
    for text in args.free:
        joint, sep, value = text.partition("=")
        if not sep or not joint.strip().isdigit() or not value.strip():
            raise DHError(f"--free: expected JOINT=VALUE (e.g. --free 7=0.3), got {text!r}")
        k = int(joint)
        if not 1 <= k <= n:
            raise DHError(f"--free {text}: joint {k} is not a joint of {robot.name} (1 … {n})")
        (v,) = parse_number_list(value, f"--free {k}=")[:1]
        if not math.isfinite(v):
            raise DHError(f"--free {text}: the value must be a finite number")
        if deg and rows[k - 1].variable_field == "theta":
            v = math.radians(v)
        out.append({k: v})
    return out


def _ik_result(robot: Robot, sols: object, names: list[str]) -> dict[str, object]:
    """One :class:`~dhsym.ik.solution.IKSolution` as JSON data: the method, each solution
    (branch in words, its signs, q, residual, the singularities it is near) and the reason
    when there is none."""
    import numpy as np

    from dhsym.ik.solution import IKSolution

    assert isinstance(sols, IKSolution)
    q = np.round(np.asarray(sols.q, dtype=float), 12).tolist()
    residual = np.asarray(sols.residual, dtype=float).tolist()
    signs = np.asarray(sols.signs, dtype=int).tolist()
    out: dict[str, object] = {
        "method": sols.method,
        "variables": names,
        "q": q,
        "residual": residual,
        "branches": list(sols.branches),
        "solutions": [
            {"branch": b, "signs": sg, "q": row, "residual": res, "singular": list(near)}
            for b, sg, row, res, near in zip(sols.branches, signs, q, residual, sols.singular)
        ],
        "reason": sols.reason,
        "note": sols.note,
    }
    if sols.method == "numeric":
        out["converged"] = bool(sols.converged)
        out["iterations"] = sols.iterations
    return out


def _cmd_ik(args: argparse.Namespace) -> int:
    """``dhsym ik NAME --pose …``: every closed-form solution with its branch (a joint given
    with ``--free``, within ``--limits``, ``--near`` first), or one numeric one.

    Exit status 0 with solutions, 1 with none (the reason on stderr and in the JSON), 2 on
    bad input."""
    import numpy as np

    from dhsym.errors import DHError
    from dhsym.ik.levenberg_marquardt import DESCRIPTION, numeric_ik

    robot = load_robot(args.robot, args.values, need_numbers=True, tip=args.tip, base=args.base)
    T = _pose(args, robot)
    names = [str(v) for v in robot.variables]
    deg, _ = q_in_degrees(args, robot.table)
    if args.numeric:
        if args.free or args.limits or args.near is not None:
            raise DHError(
                "--numeric finds one solution from --q0: --free, --limits and --near "
                "apply to the closed form"
            )
        q0 = None if args.q0 is None else _parse_q(args.q0, len(names))
        sol = numeric_ik(robot, T, q0)
        error = float(sol.residual[0])
        result = {
            "method": DESCRIPTION,
            "converged": bool(sol.converged),
            "iterations": sol.iterations,
            "error": error,
            "branch": sol.branches[0],
            "residual": error,
            "reason": sol.reason,
        }
        solution = dict(zip(names, np.round(sol.q[0], 12).tolist()))
        result["q"] = solution
        if args.json:
            print(json.dumps(result))
        else:
            state = "converged" if sol.converged else "did NOT converge"
            print(f"{DESCRIPTION}: {state} in {sol.iterations} steps, error {error:.3g}")
            print("joint values (radians for revolute joints):")
            for n, v in solution.items():
                print(f"  {n} = {v:.9g}")
        return 0 if sol.converged else 1
    near = None
    if args.near is not None:
        near = _in_radians(robot, _parse_q(args.near, len(names), "--near"), deg)
    results = []
    for free in _free_choices(args, robot, deg):
        try:
            sols = robot.ik(T, tol=args.tol, free=free or None, limits=args.limits, near=near)
        except DHError as err:
            raise type(err)(
                f"{err.message}. A numeric solution: {_numeric_command(args.robot)}"
            ) from None
        if args.one and len(sols) > 1:
            sols = sols.take(np.array([0]))
        results.append((free, sols))
    found = any(len(s) for _, s in results)
    if args.json:
        data = [
            {
                **({"free": {str(k): v for k, v in f.items()}} if f else {}),
                **_ik_result(robot, s, names),
            }
            for f, s in results
        ]
        print(json.dumps(data[0] if len(data) == 1 else {"results": data}))
    else:
        for free, sols in results:
            _print_solutions(robot, sols, names, free)
    if not found:
        for _, sols in results:
            if sols.reason is not None:
                print(f"dhsym: no solution: {sols.reason}", file=sys.stderr)
    return 0 if found else 1


def _print_solutions(robot: Robot, sols: object, names: list[str], free: dict[int, float]) -> None:
    """The solutions one per line: the joint values (radians for revolute joints), the
    branch in words and the residual."""
    from dhsym.ik.solution import IKSolution

    assert isinstance(sols, IKSolution)
    given = "".join(f" with {names[k - 1]} = {v:.9g} given" for k, v in free.items())
    kind = {"closed form": "closed-form", "general 6R": "general 6R"}.get(sols.method, sols.method)
    print(
        f"{len(sols)} {kind} solution(s){given}, one per line (radians): {', '.join(names)}"
        "  | branch | residual"
    )
    if sols.method == "numeric":
        state = "converged" if sols.converged else "did NOT converge"
        print(
            f"  (numeric: Levenberg–Marquardt from several starts, {state}, "
            f"{sols.iterations} steps in all; other solutions may exist)"
        )
    for row, branch, res in zip(sols.q, sols.branches, sols.residual):
        print("  " + ", ".join(f"{v:.9g}" for v in row) + f"  | {branch} | {float(res):.2g}")
    if sols.note is not None:
        print(f"  note: {sols.note}")


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``list``, ``show``, ``derive``, ``fk`` and ``ik``."""
    add_command(sub, "list", "list the built-in robots").set_defaults(func=_cmd_list)

    s = add_command(sub, "show", "print a DH table")
    add_robot_argument(s)
    s.add_argument(
        "--format", choices=["markdown", "yaml"], default="markdown", help="output format"
    )
    add_urdf_options(s)
    s.set_defaults(func=_cmd_show)

    d = add_command(
        sub,
        "derive",
        "link matrices and the arm matrix in closed form",
        description="Derive ^iT_j step by step, the way the lecture does: the DH table, each\n"
        "link matrix, the products and the arm matrix in lecture notation (C12, S23).",
    )
    add_robot_argument(d)
    d.add_argument(
        "--format",
        choices=["text", "markdown", "latex", "json"],
        default="text",
        help="text for the terminal, markdown ($...$ math), a LaTeX fragment, or JSON",
    )
    d.add_argument("--from", dest="frm", type=int, default=None, help="frame i of ^iT_j (0)")
    d.add_argument("--to", type=int, default=None, help="frame j of ^iT_j (n, the last frame)")
    add_notation_options(d)
    d.add_argument(
        "-o", "--output", metavar="FILE", help="write to FILE (- or none: standard output)"
    )
    d.add_argument(
        "--what",
        choices=[
            "fk",
            "jacobian",
            "singularities",
            "screws",
            "ik",
            "dynamics",
            "trajectory",
            "control",
        ],  # fmt: skip
        default="fk",
        help="fk: forward kinematics (default); jacobian: column by column; singularities: "
        "det J factored and named; screws: the screw axes, M and the product of "
        "exponentials; ik: closed-form inverse kinematics, every branch; "
        "dynamics: energies, M, Christoffel symbols, g, tau and the Newton-Euler passes; "
        "trajectory: the cubic, quintic and LSPB of a joint from their boundary conditions; "
        "control: the computed-torque error equation and its gains",
    )
    add_urdf_options(d)
    d.set_defaults(func=_cmd_derive)

    f = add_command(sub, "fk", "numeric forward kinematics: the tool pose at joint values")
    add_robot_argument(f)
    f.add_argument(
        "--q", required=True, help="joint values, comma separated (angles in the table's unit)"
    )
    add_angle_options(f)
    f.add_argument(
        "--manipulability",
        action="store_true",
        help="also the manipulability sqrt(det(J Jᵀ)) (Yoshikawa): 0 at a singularity",
    )
    add_values_option(f)
    f.add_argument("--json", action="store_true", help="JSON output")
    add_urdf_options(f)
    f.set_defaults(func=_cmd_fk)

    k = add_command(
        sub,
        "ik",
        "inverse kinematics at a pose: every closed-form solution, or --numeric",
        description="Solve the inverse kinematics at a goal pose. Without --numeric: every\n"
        "closed-form solution (dhsym derive NAME --what ik shows the steps). With --numeric:\n"
        "one local solution by Levenberg-Marquardt from --q0 (default all zero), for arms\n"
        "without a closed form.",
    )
    add_robot_argument(k)
    k.add_argument("--pose", help="the goal T, 12 or 16 numbers row by row")
    k.add_argument("--pose-of", metavar="Q", help="the goal: the pose at these joint values")
    k.add_argument("--numeric", action="store_true", help="one numeric solution")
    k.add_argument("--q0", help="start of the numeric solver (default: all zero)")
    add_angle_options(k)
    add_values_option(k)
    k.add_argument(
        "--tol",
        type=float,
        default=None,
        help="largest entry error of fk against the pose for a solution to be kept "
        "(default: from the pose's own accuracy, 1e-9 for an exact pose; see the guide, "
        "inverse kinematics, 'Poses as they come')",
    )
    k.add_argument(
        "--free",
        metavar="JOINT=VALUE",
        action="append",
        help="give one joint (1-based) its value (unit of --q) and solve the others, e.g. "
        "--free 7=0.3 on a seven-joint arm; repeat it to solve at several choices in turn",
    )
    k.add_argument(
        "--limits", action="store_true", help="keep only solutions within the table's joint limits"
    )
    k.add_argument(
        "--near",
        metavar="Q",
        help="order the solutions by distance from these joint values (unit of --q)",
    )
    k.add_argument(
        "--one",
        action="store_true",
        help="print only the first solution (with --near: the nearest)",
    )
    k.add_argument(
        "--json", action="store_true", help="JSON output on stdout alone (notes on stderr)"
    )
    add_urdf_options(k)
    k.set_defaults(func=_cmd_ik)
