"""``dhsym handout`` and ``dhsym notebooks build|run|export``: documents for a course."""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .common import STDOUT, add_command, add_notation_options, emit, parse_values, wrote

if TYPE_CHECKING:
    from dhsym.robot import Robot

__all__ = ["register"]


def _parse_check(text: str | None) -> object:
    if text is None:
        return None
    if text == "zero":
        return True
    from dhsym.model.parsing import parse_number_list

    return parse_number_list(text, "--check")


def _symbols(robot: Robot) -> set[str]:
    """The names a ``--values`` may set on ``robot``: lengths, offsets, inertials, gravity."""
    table = robot.table
    syms = set(table.constants)
    for row in table.rows:
        syms |= row.inertia.free_symbols if row.inertia is not None else set()
    syms |= set().union(*(g.free_symbols for g in table.gravity))
    return {s.name for s in syms}


def _with_values(robots: list[Robot], text: str | None, figure: bool, **style: Any) -> list[Robot]:
    """Each robot with the ``--values`` its table knows; with ``figure``, every length needs
    a number (from ``--values`` or the table's ``values:``), and the error names the missing.
    """
    from dhsym.errors import DHError
    from dhsym.robot import Robot

    given = parse_values(text) if text else {}
    unused = set(given) - set().union(*(_symbols(r) for r in robots))
    if unused:
        raise DHError(
            f"--values: no robot of this handout has a symbol {', '.join(sorted(unused))}"
        )
    out = []
    for robot in robots:
        own = {k: v for k, v in given.items() if k in _symbols(robot)}
        if own:
            robot = Robot(robot.table.with_values(own), **style)
        if figure:
            missing = sorted(
                str(s) for s in set(robot.table.constants) - set(robot.table.value_map)
            )
            if missing:
                example = ",".join(f"{m}=…" for m in missing)
                raise DHError(
                    f"--figure draws {robot.name or 'the robot'} with numbers, and it has none "
                    f"for {', '.join(missing)}: give them with --values {example} (or in the "
                    "table file's values:)"
                )
        out.append(robot)
    return out


def _cmd_sheets(args: argparse.Namespace) -> int:
    """``handout hw.yaml --variants class.csv -o FOLDER``: a problem sheet per student."""
    from dhsym.checking.grading.assignment import Assignment
    from dhsym.checking.grading.sheets import write_merged, write_sheets
    from dhsym.checking.grading.variants import ClassList
    from dhsym.errors import DHError

    if len(args.robots) != 1 or not args.robots[0].lower().endswith((".yaml", ".yml")):
        raise DHError(
            "--variants makes each student's sheet of one assignment: dhsym handout "
            "hw.yaml --variants class.csv -o FOLDER"
        )
    if args.output == STDOUT or args.output.endswith(".tex"):
        raise DHError("--variants writes one sheet per student: -o names a folder")
    for flag in ("figure", "values", "numeric"):
        if getattr(args, flag):
            raise DHError(f"--{flag} does not apply to --variants (each student has their values)")
    if args.merged is not None and not args.merged.lower().endswith((".tex", ".pdf")):
        raise DHError("--merged names one .tex or .pdf file for all the sheets")
    assignment, roster = Assignment.load(args.robots[0]), ClassList.load(args.variants)
    options = dict(
        sections=[s.strip() for s in args.sections.split(",") if s.strip()],
        course=args.course or "",
        date=args.date or "",
        template_dir=args.template_dir,
        notation=args.notation,
        compact=not args.full,
    )
    written = write_sheets(assignment, roster, args.output, pdf=args.pdf, **options)
    if args.merged is not None:
        written.append(write_merged(assignment, roster, args.merged, **options))
    for path in written:
        wrote(path)
    return 0


def _cmd_handout(args: argparse.Namespace) -> int:
    from dhsym.errors import DHError
    from dhsym.explain.documents import render_handout, write_handout
    from dhsym.explain.latex import run_latex
    from dhsym.robot import load

    if args.variants:
        return _cmd_sheets(args)

    style = dict(compact=not args.full, style=args.notation)
    robots = [load(name, **style) for name in args.robots]
    robots = _with_values(robots, args.values, args.figure, **style)
    options = dict(
        title=args.title,
        course=args.course or "",
        author=args.author or "",
        date=args.date or "",
        mode=args.mode,
        convention_note=args.convention_note,
        template_dir=args.template_dir,
        numeric=args.numeric,
        notation=args.notation,
        check=_parse_check(args.check),
        sections=args.sections,
    )
    if args.output == STDOUT:
        for flag in ("pdf", "figure", "keep_aux"):
            if getattr(args, flag):
                raise DHError(f"--{flag.replace('_', '-')} needs a file: -o NAME.tex, not -o -")
        emit(render_handout(robots, **options), STDOUT)
        return 0
    tex = write_handout(robots, args.output, figure=args.figure, **options)
    wrote(args.output)
    if args.figure:  # the pictures the handout includes, written beside it
        out = Path(args.output)
        stem = re.sub(r"[^A-Za-z0-9-]+", "-", out.stem).strip("-") or "handout"
        for picture in sorted(out.parent.glob(f"{stem}-*-home.pdf")):
            wrote(out.parent / picture.name if str(out.parent) != "." else picture.name)
    if args.pdf:
        run = run_latex(tex, keep_aux=args.keep_aux)
        wrote(Path(args.output).with_suffix(".pdf"))
        for issue in run.issues:
            print(f"dhsym: warning: {args.output}: {issue}", file=sys.stderr)
    return 0


def _register_handout(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    h = add_command(
        subparsers,
        "handout",
        "a LaTeX handout (and PDF) for one or more robots",
        description="Write a standalone LaTeX handout with the derivation of each robot (or,\n"
        "with --mode problems, the questions), and compile it to PDF with --pdf.\n"
        "LaTeX runs with shell escape off; its auxiliary files go to a temporary folder.",
    )
    h.add_argument("robots", nargs="+", metavar="NAME|FILE", help="built-in names or table files")
    h.add_argument(
        "-o", "--output", required=True, metavar="FILE.tex", help="the .tex to write (-: stdout)"
    )
    h.add_argument("--pdf", action="store_true", help="compile it with latexmk/pdflatex")
    h.add_argument(
        "--keep-aux",
        action="store_true",
        help="keep LaTeX's .aux/.log/.fls files beside the .tex (default: a temporary folder)",
    )
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
    add_notation_options(h)
    h.add_argument("--numeric", action="store_true", help="substitute the numeric lengths")
    h.add_argument(
        "--sections",
        default="fk",
        metavar="LIST",
        help="comma separated, any of fk, jacobian, singularities, screws, ik, dynamics "
        "(default fk)",
    )
    h.add_argument(
        "--figure",
        action="store_true",
        help="include a picture of each robot at its home configuration (its lengths need "
        "numbers: the table's values: or --values)",
    )
    h.add_argument(
        "--values",
        metavar="NAME=NUMBER,...",
        help="numbers for symbolic lengths, e.g. a1=1,a2=0.8 (for --figure and --numeric)",
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
    h.add_argument(
        "--variants",
        default=None,
        metavar="CLASS",
        help="with an assignment (hw.yaml) instead of robots: one problem sheet per student "
        "of the class list (CSV), with their values; -o names the folder",
    )
    h.add_argument(
        "--merged",
        default=None,
        metavar="FILE.pdf",
        help="with --variants: also every student's sheet in one document (a .pdf is "
        "compiled, a .tex written), each sheet on new pages",
    )
    h.set_defaults(func=_cmd_handout)


def _cmd_build(args: argparse.Namespace) -> int:
    from dhsym.errors import DHError
    from dhsym.explain.notebooks import build_notebook

    sources = args.sources or sorted(Path("notebooks").glob("*.py"))
    if not sources:
        raise DHError("no notebook sources given and none in notebooks/")
    for source in sources:
        path = build_notebook(source, execute=not args.no_execute, timeout=args.timeout)
        wrote(path)
    return 0


def _cmd_run(args: argparse.Namespace) -> int:
    from dhsym.errors import DHError
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
            wrote(f)
    return 0


def _add_commands(sub: Any) -> None:
    b = add_command(sub, "build", "write notebooks from their .py sources and execute them")
    b.add_argument("sources", nargs="*", help="jupytext .py sources (default: notebooks/*.py)")
    b.add_argument("--timeout", type=int, default=120, help="seconds per cell")
    b.add_argument(
        "--no-execute", action="store_true", help="only update the cells, do not run them"
    )
    b.set_defaults(func=_cmd_build)
    r = add_command(sub, "run", "execute notebooks; fail on errors and warnings")
    r.add_argument("notebooks", nargs="*", help="notebook files (default: notebooks/*.ipynb)")
    r.add_argument("--timeout", type=int, default=120, help="seconds per cell")
    r.add_argument("--write", action="store_true", help="save the outputs into the notebooks")
    r.set_defaults(func=_cmd_run)
    e = add_command(sub, "export", "export notebooks to HTML and Markdown")
    e.add_argument("notebooks", nargs="+", help="notebook files")
    e.add_argument("-o", "--output", default="build/notebooks", help="folder")
    e.add_argument("--to", default="html,markdown", help="html, markdown or both")
    e.add_argument("--mathjax-url", help="MathJax address (default: local libjs-mathjax if any)")
    e.set_defaults(func=_cmd_export)


def _register_notebooks(subparsers: Any) -> None:
    p = add_command(subparsers, "notebooks", "build, run or export the course notebooks")
    _add_commands(p.add_subparsers(dest="notebooks_command", required=True, metavar="ACTION"))


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``handout`` and ``notebooks build|run|export``."""
    _register_handout(subparsers)
    _register_notebooks(subparsers)
