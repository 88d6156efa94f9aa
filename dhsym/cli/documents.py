"""``dhsym handout`` and ``dhsym notebooks build|run|export``: documents for a course."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from dhsym.errors import DHError
from dhsym.notation.printers import TrigStyle

__all__ = ["register"]


def _parse_check(text: str | None) -> object:
    if text is None:
        return None
    if text == "zero":
        return True
    from dhsym.model.parsing import parse_number_list

    return parse_number_list(text, "--check")


def _cmd_handout(args: argparse.Namespace) -> int:
    from dhsym.explain.documents import write_handout
    from dhsym.explain.latex import check_log
    from dhsym.kinematics.robot import load

    robots = [load(name, compact=not args.full, style=args.notation) for name in args.robots]
    check = _parse_check(args.check)
    result = write_handout(
        robots,
        args.output,
        pdf=args.pdf,
        figure=args.figure,
        title=args.title,
        course=args.course or "",
        author=args.author or "",
        date=args.date or "",
        mode=args.mode,
        convention_note=args.convention_note,
        template_dir=args.template_dir,
        numeric=args.numeric,
        notation=args.notation,
        check=check,
        sections=args.sections,
    )
    print(f"wrote {args.output}", file=sys.stderr)
    if args.pdf:
        print(f"wrote {result}", file=sys.stderr)
        for issue in check_log(result.with_suffix(".log")):
            print(f"dhsym: warning: {result.with_suffix('.tex').name}: {issue}", file=sys.stderr)
    return 0


def _register_handout(subparsers: argparse._SubParsersAction) -> None:
    h = subparsers.add_parser("handout", help="a LaTeX handout (and PDF) for one or more robots")
    h.add_argument("robots", nargs="+", metavar="NAME|FILE", help="built-in names or table files")
    h.add_argument("-o", "--output", required=True, metavar="FILE.tex", help="the .tex to write")
    h.add_argument("--pdf", action="store_true", help="compile it with latexmk/pdflatex")
    h.add_argument("--title", default=None, help="title (default: Forward kinematics: NAMES)")
    h.add_argument("--course", default="", help="course name, printed above the title")
    h.add_argument("--author", default="", help="author line")
    h.add_argument("--date", default="", help="date line (default: none)")
    h.add_argument(
        "--mode",
        choices=["answers", "problems"],
        default="answers",
        help="answers: full derivations; problems: tables and questions",
    )
    h.add_argument(
        "--convention-note",
        action="store_true",
        help="add a note comparing the standard and modified conventions",
    )
    h.add_argument(
        "--template-dir",
        default=None,
        metavar="DIR",
        help="folder of templates that override the built-in ones",
    )
    h.add_argument("--full", action="store_true", help="full cos/sin instead of C12/S12")
    h.add_argument(
        "--notation",
        choices=[s.value for s in TrigStyle],
        default=TrigStyle.UPPER.value,
        help="C1: C12, S23 (default); c1: c12, s23 (Craig, Spong); c_theta: c_{θ12} in LaTeX",
    )
    h.add_argument("--numeric", action="store_true", help="substitute the numeric lengths")
    h.add_argument(
        "--sections",
        default="fk",
        metavar="LIST",
        help="comma separated, any of fk, jacobian, singularities, ik (default fk)",
    )
    h.add_argument(
        "--figure",
        action="store_true",
        help="include a picture of each robot at its home configuration",
    )
    h.add_argument(
        "--check",
        nargs="?",
        const="zero",
        default=None,
        metavar="Q",
        help="numeric check of the arm matrix at Q (comma separated; default zero); the ik "
        "section lists every solution of the pose at Q (default: away from singularities)",
    )
    h.set_defaults(func=_cmd_handout)


def _cmd_build(args: argparse.Namespace) -> int:
    from dhsym.explain.notebooks import build_notebook

    sources = args.sources or sorted(Path("notebooks").glob("*.py"))
    if not sources:
        raise DHError("no notebook sources given and none in notebooks/")
    for source in sources:
        path = build_notebook(source, execute=not args.no_execute, timeout=args.timeout)
        print(f"wrote {path}" + ("" if args.no_execute else " (executed)"), file=sys.stderr)
    return 0


def _cmd_run(args: argparse.Namespace) -> int:
    from dhsym.explain.notebooks import execute_notebook

    paths = args.notebooks or sorted(Path("notebooks").glob("*.ipynb"))
    if not paths:
        raise DHError("no notebooks given and none in notebooks/")
    for p in paths:
        execute_notebook(p, args.timeout, write=args.write)
        print(f"ran {p}" + (" (outputs saved)" if args.write else ""), file=sys.stderr)
    return 0


def _cmd_export(args: argparse.Namespace) -> int:
    from dhsym.explain.notebooks import export_notebook

    formats = [f.strip() for f in args.to.split(",") if f.strip()]
    for p in args.notebooks:
        for f in export_notebook(p, args.output, formats, args.mathjax_url):
            print(f"wrote {f}", file=sys.stderr)
    return 0


def _add_commands(sub: Any) -> None:
    b = sub.add_parser("build", help="write notebooks from their .py sources and execute them")
    b.add_argument("sources", nargs="*", help="jupytext .py sources (default: notebooks/*.py)")
    b.add_argument("--timeout", type=int, default=120, help="seconds per cell (default 120)")
    b.add_argument(
        "--no-execute", action="store_true", help="only update the cells, do not run them"
    )
    b.set_defaults(func=_cmd_build)
    r = sub.add_parser("run", help="execute notebooks; fail on errors and warnings")
    r.add_argument("notebooks", nargs="*", help="default: notebooks/*.ipynb")
    r.add_argument("--timeout", type=int, default=120, help="seconds per cell (default 120)")
    r.add_argument("--write", action="store_true", help="save the outputs into the notebooks")
    r.set_defaults(func=_cmd_run)
    e = sub.add_parser("export", help="export notebooks to HTML and Markdown")
    e.add_argument("notebooks", nargs="+")
    e.add_argument("-o", "--output", default="build/notebooks", help="folder (build/notebooks)")
    e.add_argument("--to", default="html,markdown", help="html, markdown or both (default)")
    e.add_argument("--mathjax-url", help="MathJax address (default: local libjs-mathjax if any)")
    e.set_defaults(func=_cmd_export)


def _register_notebooks(subparsers: Any) -> None:
    p = subparsers.add_parser("notebooks", help="build, run or export the course notebooks")
    _add_commands(p.add_subparsers(dest="notebooks_command", required=True))


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``handout`` and ``notebooks build|run|export``."""
    _register_handout(subparsers)
    _register_notebooks(subparsers)
