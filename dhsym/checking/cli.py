"""``dhsym check`` and ``dhsym grade``: registered by :func:`register_cli`.

Only ``argparse`` is imported here; the handlers import the checker when run.

Examples
--------
>>> import argparse
>>> p = argparse.ArgumentParser(prog="dhsym")
>>> register_cli(p.add_subparsers(dest="command"))
>>> p.parse_args(["check", "--key", "planar2r", "--question", "T0_2", "--answer", "-"]).json
False
"""

from __future__ import annotations

import argparse
import json
import sys

__all__ = ["register_cli"]

EXIT_CORRECT, EXIT_INCORRECT, EXIT_UNREADABLE = 0, 1, 2


def _read_answer(source: str, limit: int) -> bytes | str:
    from ._limits import UnreadableAnswer
    from .answers import read_answer_file

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
    from dhsym.robot import Robot

    from ._limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, UnreadableAnswer, check_seconds
    from .checker import Key, check_answer
    from .feedback import render_check
    from .verdict import CheckResult, Verdict

    limits = (
        AnswerLimits(seconds=check_seconds(args.timeout, "--timeout"))
        if args.timeout is not None
        else DEFAULT_ANSWER_LIMITS
    )
    key = Key.load(args.key, args.question, tool_free=args.tool_free)
    if key.question.kind != "table":
        Robot(key.table).check_transform_size(key.question.frm, key.question.to)
    try:
        answer = _read_answer(args.answer, limits.max_bytes)
        result = check_answer(key, answer, limits=limits)
    except UnreadableAnswer as err:
        result = CheckResult(
            key.question.spec,
            Verdict.UNREADABLE,
            f"The answer could not be read: {err}",
            reason=str(err),
            key=key.name,
        )
    if args.json:
        print(json.dumps(result.to_json(), indent=2, ensure_ascii=False))
    else:
        print(render_check(result), end="")
    if result.verdict is Verdict.UNREADABLE and not args.json:
        print(f"dhsym: unreadable answer: {result.reason}", file=sys.stderr)
    return result.verdict.exit_code


def _cmd_grade(args: argparse.Namespace) -> int:
    from .grading import grade

    report = grade(
        args.assignment,
        args.submissions,
        args.output,
        workers=args.workers,
        timeout=args.timeout,
        dask=args.dask,
        progress=not args.quiet,
    )
    for warning in report.warnings:
        print(f"dhsym: warning: {warning}", file=sys.stderr)
    flagged = sum(bool(r.get("flags")) for r in report.records)
    print(
        f"graded {report.graded} submission(s), {report.skipped} already graded, "
        f"{report.failed} failed (timeout or error), {flagged} flagged; "
        f"mean score {report.mean:.2f}"
    )
    print(f"gradebook: {report.gradebook}")
    print(f"summary:   {report.summary}")
    return 0


def register_cli(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``check`` and ``grade`` sub-commands."""
    c = subparsers.add_parser(
        "check", help="check one answer (exit 0 correct, 1 incorrect, 2 unreadable)"
    )
    c.add_argument("--key", required=True, help="built-in robot name or table file")
    c.add_argument(
        "--question",
        required=True,
        help="table, T<i>_<j>, A<k>, arm, px, or T<i>_<j>[row,col] (0-based)",
    )
    c.add_argument("--answer", required=True, help="answer file, or - for standard input")
    c.add_argument("--json", action="store_true", help="print the result as JSON")
    c.add_argument(
        "--tool-free", action="store_true", help="accept another tool frame in a table answer"
    )
    c.add_argument("--timeout", type=float, default=None, help="time limit in seconds")
    c.set_defaults(func=_cmd_check)

    g = subparsers.add_parser("grade", help="grade a class: gradebook, feedback, summary")
    g.add_argument("assignment", help="assignment YAML file")
    g.add_argument("submissions", help="folder of submissions, or a CSV file")
    g.add_argument("-o", "--output", required=True, help="report folder (created)")
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
    g.set_defaults(func=_cmd_grade)
