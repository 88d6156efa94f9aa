"""``dhsym check``, ``dhsym grade`` and ``dhsym autograder``: one answer, a class, a platform.

Only ``argparse`` is imported here; the handlers import the checker when run.

Examples
--------
>>> import argparse
>>> p = argparse.ArgumentParser(prog="dhsym")
>>> register(p.add_subparsers(dest="command"))
>>> p.parse_args(["check", "--key", "planar2r", "--question", "T0_2", "--answer", "-"]).format
'text'
>>> p.parse_args(["check", "--key", "k", "--question", "q", "--answer", "-", "--json"]).format
'json'
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

from .common import add_command

__all__ = ["register"]

EXIT_CORRECT, EXIT_INCORRECT, EXIT_UNREADABLE = 0, 1, 2


def _read_answer(source: str, limit: int) -> bytes | str:
    from dhsym.checking.reading.answers import read_answer_file
    from dhsym.checking.reading.limits import UnreadableAnswer

    if source == "-":
        data = (
            sys.stdin.buffer.read(limit + 1)
            if hasattr(sys.stdin, "buffer")
            else sys.stdin.read(limit + 1)
        )
        if len(data) > limit:
            raise UnreadableAnswer(f"the answer is larger than {limit} bytes")
        return data
    return read_answer_file(source)


def _cmd_check(args: argparse.Namespace) -> int:
    from dhsym.checking.comparing.verdict import CheckResult, Verdict
    from dhsym.checking.grading.feedback import render_check
    from dhsym.checking.judging.checker import check_answer
    from dhsym.checking.judging.key import PreparedKeys, load_key
    from dhsym.checking.reading.limits import (
        DEFAULT_ANSWER_LIMITS,
        AnswerLimits,
        UnreadableAnswer,
        check_seconds,
    )

    limits = (
        AnswerLimits(seconds=check_seconds(args.timeout, "--timeout"))
        if args.timeout is not None
        else DEFAULT_ANSWER_LIMITS
    )
    keys = PreparedKeys()  # the key prepared once: to check it on loading, then to judge
    key = load_key(
        args.key, args.question, tool_free=args.tool_free, rounding=args.rounding, keys=keys
    )
    try:
        answer = _read_answer(args.answer, limits.max_bytes)
        result = check_answer(key, answer, limits=limits, keys=keys)
    except UnreadableAnswer as err:
        result = CheckResult(
            key.question.spec,
            Verdict.UNREADABLE,
            f"The answer could not be read: {err}",
            reason=str(err),
            key=key.name,
        )
    if args.format == "json":
        print(json.dumps(result.to_json(), indent=2, ensure_ascii=False))
    else:
        print(render_check(result, "md" if args.format == "markdown" else "txt"), end="")
    if result.verdict is Verdict.UNREADABLE and args.format != "json":
        print(f"dhsym: unreadable answer: {result.reason}", file=sys.stderr)
    return result.verdict.exit_code


def _cmd_grade(args: argparse.Namespace) -> int:
    from dhsym.checking.grading.assignment import Assignment
    from dhsym.checking.grading.batch import grade
    from dhsym.checking.judging.key import PreparedKeys
    from dhsym.errors import DHError

    keys = PreparedKeys()  # prepared once: to load the assignment, then for its tests
    assignment = Assignment.load(args.assignment, keys)
    roster = None
    if args.gradebook:
        from dhsym.checking.platforms.gradebooks import Roster

        if args.roster:
            roster = Roster.load(args.roster)
        elif args.gradebook != "generic":
            raise DHError(f"--gradebook {args.gradebook} needs --roster FILE (LMS ids per student)")
    elif args.roster:
        raise DHError("--roster is used with --gradebook canvas|moodle|generic")

    report = grade(
        assignment,
        args.submissions,
        args.output,
        workers=args.workers,
        timeout=args.timeout,
        dask=args.dask,
        progress=not args.quiet,
        variants=args.variants,
        keys=keys,
    )
    for warning in report.warnings:
        print(f"dhsym: warning: {warning}", file=sys.stderr)
    flagged = sum(bool(r.flags) for r in report.records)
    print(
        f"graded {report.graded} submission(s), {report.skipped} already graded, "
        f"{report.failed} failed (timeout or error), {flagged} flagged; "
        f"mean score {report.mean:.2f}"
    )
    # the paths as the user gave the report folder, not resolved
    print(f"gradebook: {os.path.join(args.output, Path(report.gradebook).name)}")
    print(f"summary:   {os.path.join(args.output, Path(report.summary).name)}")
    if args.gradebook:
        from dhsym.checking.platforms.gradebooks import write_lms_gradebook

        out = write_lms_gradebook(
            args.gradebook, report, assignment, roster, column=args.lms_column
        )
        print(f"{args.gradebook} import: {os.path.join(args.output, Path(out.path).name)}")
        for line in out.notes:
            print(f"note: {line}", file=sys.stderr)
    return 0


def _cmd_check_assignment(args: argparse.Namespace) -> int:
    from dhsym.checking.grading.assignment import Assignment
    from dhsym.checking.grading.assignment_tests import run_assignment_tests
    from dhsym.checking.judging.key import PreparedKeys
    from dhsym.model.parsing import check_count

    samples = check_count(args.samples, "--samples", 0, 1000)
    keys = PreparedKeys()
    report = run_assignment_tests(
        Assignment.load(args.assignment, keys), samples=samples, keys=keys
    )
    print(report.text(), end="")
    return 0 if report.passed else 1


def _cmd_variants(args: argparse.Namespace) -> int:
    from dhsym.checking.grading.assignment import Assignment
    from dhsym.checking.grading.variants import ClassList, list_variants, new_secret
    from dhsym.errors import DHError

    from .common import emit

    if args.new_secret:
        from dhsym.model.yamlsafe import load_yaml

        data = load_yaml(Path(args.assignment).read_text(encoding="utf-8"))
        ref = data.get("secret") if isinstance(data, dict) else None
        if not isinstance(ref, str) or not ref.strip():
            raise DHError(
                "name the secret's file first: add 'secret: hw.secret' to the assignment",
                file=args.assignment,
                field="secret",
            )
        path = new_secret(Path(args.assignment).parent / ref.strip())
        print(f"wrote {path} (keep it private: it decides every student's values)")
        return 0
    a = Assignment.load(args.assignment)
    if a.variants is None:
        raise DHError(
            "the assignment draws no values per student (no variants:)", file=args.assignment
        )
    if not args.roster:
        raise DHError(
            "give the class list: --roster CLASS.csv (a 'submission' or 'student' column)"
        )
    emit(list_variants(a.variants, ClassList.load(args.roster), args.format), args.output)
    return 0


def _cmd_new_assignment(args: argparse.Namespace) -> int:
    """Copy the packaged example homework (``dhsym.examples``) into a new folder."""
    from importlib.resources import files

    import dhsym
    from dhsym.errors import DHError

    out = Path(args.folder)
    if out.exists() and (not out.is_dir() or any(out.iterdir())):
        raise DHError(f"{args.folder}: exists and is not an empty folder")
    packaged = Path(str(files(dhsym))) / "examples"  # the wheel's package data
    source = Path(dhsym.__file__).resolve().parents[1] / "examples" / "homework"  # a checkout
    root = next((f for f in (packaged, source) if (f / "assignment.yaml").is_file()), None)
    if root is None:
        raise DHError(f"the example homework is missing (looked in {packaged} and {source})")

    def copy(src: Path, dst: Path) -> None:
        for item in sorted(src.iterdir()):
            if item.name.startswith(("_", ".")) or item.name.endswith((".py", ".pyc")):
                continue
            if item.is_dir():
                (dst / item.name).mkdir()
                copy(item, dst / item.name)
            else:
                (dst / item.name).write_bytes(item.read_bytes())

    out.mkdir(parents=True, exist_ok=True)
    copy(root, out)
    a = os.path.join(args.folder, "assignment.yaml")
    print(f"wrote {a} (commented), its table file and a class in {args.folder}/submissions")
    print(f"grade it: dhsym grade {a} {os.path.join(args.folder, 'submissions')} -o REPORT")
    return 0


def _cmd_autograder(args: argparse.Namespace) -> int:
    from dhsym.checking.platforms.autograder import build_autograder, run_autograder
    from dhsym.errors import DHError

    if args.run:
        data = run_autograder()
        print(f"score {data['score']:g}; {len(data['tests'])} tests written to results.json")
        return 0
    if not args.assignment or not args.output:
        raise DHError("dhsym autograder ASSIGNMENT -o autograder.zip (or --run in the grader)")
    out = build_autograder(
        args.assignment,
        args.output,
        wheel=args.wheel,
        visibility=args.visibility,
        show_key=args.show_key,
    )
    print(f"autograder: {out}")
    return 0


CHECK_EPILOG_TAIL = """\
Exit status:
  0  the answer is correct (or a valid alternative)
  1  the answer is incorrect
  2  the answer could not be read, or the key or question is wrong (reason printed)

Answers may be plain math (c1*c2 - s1*s2, C12, a1 C1 + a2 C_{12}), LaTeX
(\\begin{bmatrix} ... \\end{bmatrix}) or, for tables, YAML, CSV or a pasted table.
Nothing a student typed is executed."""

QUESTION_KINDS = """\
Question kinds (ask: in the assignment, --question for check):
  table                the DH table
  T<i>_<j>, A<k>, arm  a matrix: ^iT_j, link matrix k, ^0T_n
  px, py, pz           one entry of the position
  T<i>_<j>[row,col]    one entry, 0-based (e.g. T0_6[0,3])
  J, J[row,col]        the geometric Jacobian [v; w], or one entry
  det J                its determinant
  ik, ik all           inverse kinematics in the pose n s a p: one branch, or every branch
  ik@q1,...,qn         the joint values of the pose at q
  M, M[row,col]        the inertia matrix M(q) (Spong's D(q)), or one entry, 0-based
  g, C                 the gravity vector g(q); the Coriolis matrix C(q, qdot)
  c_ijk                Spong's Christoffel symbol, 1-based (e.g. c_112)
  tau                  the joint torques M qddot + C qdot + g (rates qdot1, accelerations qddot1)
  tau_static           the torques J^T F balancing a tip wrench fx fy fz nx ny nz (base frame)
  S, S<i>, B, B<i>     the space or body screw axes (6xn, rows [w; v]), or one axis (S3)
  Mhome (M0)           the home configuration M of the product of exponentials
  Js, Jb               the space and body Jacobians (rows [w; v])
  T(theta)             the forward kinematics in product-of-exponentials form, its closed form
Of a profile (the key: cubic(q0=0, qf=1, tf=2), quintic(...), lspb(q0=, qf=, tf=, V= or a=),
minimum_time(q0=, qf=, vmax=, amax=) or gains(omega=, zeta=1); names keep it symbolic):
  traj a<k>            coefficient k of a cubic or quintic (e.g. traj a2 = 3(qf - q0)/tf^2)
  tb, vmax             the blend time; the peak velocity of a rest-to-rest motion
  q@<t>                the position at time t (e.g. q@1.5, q@tf/2)
  kp, kd               the gains for the natural frequency omega and damping zeta"""

CHECK_EPILOG = QUESTION_KINDS + "\n\n" + CHECK_EPILOG_TAIL

GRADE_EPILOG = (
    QUESTION_KINDS
    + """

The assignment file: title, key (robot, table file or profile), time_limit, rounding,
questions: [{id, ask, points, key, rounding, tool}]; every key is described in
docs/guide/assignments.md, and dhsym new-assignment DIR writes a commented example.

Exit status:
  0  the class was graded (each student's score is in the gradebook, even when
     single submissions failed or timed out)
  2  the assignment or the submissions could not be read

Writes REPORT/gradebook.csv, REPORT/feedback/<student>.md|.html and
REPORT/summary.html; a rerun skips what is already graded."""
)


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add the ``check``, ``grade`` and ``autograder`` sub-commands."""
    c = add_command(
        subparsers,
        "check",
        "check one answer (exit 0 correct, 1 incorrect, 2 unreadable)",
        description="Check one answer against a key: a built-in robot, a table file or a "
        "profile (cubic(q0=0, qf=1, tf=2)).",
        epilog=CHECK_EPILOG,
    )
    c.add_argument(
        "--key",
        required=True,
        help="built-in robot name, table file, or a profile such as 'cubic(q0=0, qf=1, tf=2)'",
    )
    c.add_argument(
        "--question",
        required=True,
        help="the question kind: table, T<i>_<j>, A<k>, arm, px, py, pz, T<i>_<j>[row,col] "
        "(0-based), J, J[row,col], det J, ik, ik all, ik@q1,...,qn, M, M[row,col], g, C, "
        "c_ijk, tau, tau_static, S, S<i>, B, B<i>, Mhome, Js, Jb, T(theta); of a profile "
        "traj a<k>, tb, vmax, q@<t>, kp, kd (see below)",
    )
    c.add_argument("--answer", required=True, help="answer file, or - for standard input")
    c.add_argument(
        "--format",
        choices=["text", "markdown", "json"],
        default="text",
        help="text for the terminal, Markdown (as in the feedback pages), or JSON",
    )
    c.add_argument(
        "--json",
        dest="format",
        action="store_const",
        const="json",
        help="print the result as JSON (same as --format json)",
    )
    c.add_argument(
        "--tool-free", action="store_true", help="accept another tool frame in a table answer"
    )
    c.add_argument("--timeout", type=float, default=None, help="time limit in seconds (default: 5)")
    c.add_argument(
        "--rounding",
        default=None,
        metavar="RULE",
        help="accepted rounding of decimals: digits=N (a decimal of at least N significant "
        "digits may be rounded or truncated; default digits=3), abs=T, rel=T, or off",
    )
    c.set_defaults(func=_cmd_check)

    g = add_command(
        subparsers,
        "grade",
        "grade a class: gradebook, feedback, summary",
        description="Grade every submission of a class against an assignment.",
        epilog=GRADE_EPILOG,
    )
    g.add_argument("assignment", help="assignment YAML file")
    g.add_argument("submissions", help="folder of submissions, or a CSV file")
    g.add_argument(
        "-o", "--output", required=True, metavar="REPORT", help="report folder (created)"
    )
    g.add_argument(
        "--workers",
        type=int,
        default=2,
        help="worker processes, each killed and replaced when a submission overruns "
        "(0: grade in this process, without isolation)",
    )
    g.add_argument(
        "--timeout",
        type=float,
        default=None,
        help="time limit of one answer in seconds, above 0 and at most 3600 "
        "(default: the assignment's, 5)",
    )
    g.add_argument(
        "--dask", default=None, metavar="ADDRESS", help="run on a Dask cluster (scheduler address)"
    )
    g.add_argument("--quiet", action="store_true", help="no progress bar")
    g.add_argument(
        "--gradebook",
        choices=("canvas", "moodle", "generic"),
        default=None,
        help="also write the import CSV of this LMS into the report folder",
    )
    g.add_argument(
        "--roster", default=None, metavar="FILE", help="CSV: submission name -> LMS ids/email"
    )
    g.add_argument(
        "--lms-column",
        default=None,
        metavar="NAME",
        help="the LMS assignment column (Canvas: 'Name (id)'); default the assignment title",
    )
    g.add_argument(
        "--variants",
        default=None,
        metavar="CLASS",
        help="the class list (CSV, a 'submission' or 'student' column) of an assignment "
        "with variants: each student is graded against their own values",
    )
    g.set_defaults(func=_cmd_grade)

    ca = add_command(
        subparsers,
        "check-assignment",
        "grade the key's own answers and the question tests (exit 1 if one fails)",
        description="Check an assignment before grading with it: for every question the key's\n"
        "own answer is graded (with variants, for a sample of variants), and every\n"
        "question test (tests: right/wrong) must be graded as the test says.",
    )
    ca.add_argument("assignment", help="assignment YAML file")
    ca.add_argument(
        "--samples", type=int, default=3, help="variants drawn besides the first (with variants:)"
    )
    ca.set_defaults(func=_cmd_check_assignment)

    v = add_command(
        subparsers,
        "variants",
        "list each student's values of an assignment with variants",
        description="List the values an assignment with variants: draws for each student of a\n"
        "class list (seeded by the assignment's secret and the student id).",
    )
    v.add_argument("assignment", help="assignment YAML file")
    v.add_argument("--roster", default=None, metavar="CLASS", help="class list CSV")
    v.add_argument(
        "--format",
        choices=("text", "csv", "json"),
        default="text",
        help="the list as text (default), a CSV table or JSON",
    )
    v.add_argument("-o", "--output", default=None, help="write to FILE (- : standard output)")
    v.add_argument(
        "--new-secret",
        action="store_true",
        help="write a new random secret to the file the assignment's secret: names",
    )
    v.set_defaults(func=_cmd_variants)

    n = add_command(
        subparsers,
        "new-assignment",
        "write a commented example assignment and a small class to grade",
        description="Write the example homework (a commented assignment.yaml, a table file\n"
        "it uses, and ten students' submissions) into a new folder, to edit and grade.",
        epilog=QUESTION_KINDS,
    )
    n.add_argument("folder", help="the folder to create (must not exist, or be empty)")
    n.set_defaults(func=_cmd_new_assignment)

    ag = add_command(
        subparsers,
        "autograder",
        "build a Gradescope-style autograder zip (or --run it in the grader)",
    )
    ag.add_argument("assignment", nargs="?", help="assignment YAML file")
    ag.add_argument("-o", "--output", default=None, help="the zip to write")
    ag.add_argument("--wheel", default=None, help="dhsym wheel to include (default: build it)")
    ag.add_argument(
        "--visibility",
        default="visible",
        choices=("hidden", "after_due_date", "after_published", "visible"),
        help="when students see each question's result",
    )
    ag.add_argument(
        "--show-key", action="store_true", help="show the key's entries in the feedback"
    )
    ag.add_argument(
        "--run", action="store_true", help="grade /autograder/submission (used by run_autograder)"
    )
    ag.set_defaults(func=_cmd_autograder)
