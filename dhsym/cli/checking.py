"""``dhsym check`` and ``dhsym grade``: one answer, or a whole class.

Only ``argparse`` is imported here; the handlers import the checker when run.

Examples
--------
>>> import argparse
>>> p = argparse.ArgumentParser(prog="dhsym")
>>> register(p.add_subparsers(dest="command"))
>>> p.parse_args(["check", "--key", "planar2r", "--question", "T0_2", "--answer", "-"]).json
False
"""

from __future__ import annotations

import argparse
import json
import sys

__all__ = ["register"]

EXIT_CORRECT, EXIT_INCORRECT, EXIT_UNREADABLE = 0, 1, 2


def _read_answer(source: str, limit: int) -> bytes | str:
    from dhsym.checking._limits import UnreadableAnswer
    from dhsym.checking.answers import read_answer_file

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
    from dhsym.checking._limits import DEFAULT_ANSWER_LIMITS, AnswerLimits, UnreadableAnswer
    from dhsym.checking.checker import Key, check_answer
    from dhsym.checking.feedback import render_check
    from dhsym.checking.verdict import CheckResult, Verdict

    key = Key.load(args.key, args.question, tool_free=args.tool_free, rounding=args.rounding)
    limits = AnswerLimits(seconds=args.timeout) if args.timeout else DEFAULT_ANSWER_LIMITS
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
    from dhsym.checking.grading import grade

    report = grade(
        args.assignment,
        args.submissions,
        args.output,
        workers=args.workers,
        timeout=args.timeout,
        dask=args.dask,
        progress=not args.quiet,
    )
    print(
        f"graded {report.graded} submission(s), {report.skipped} already graded, "
        f"{report.failed} failed (timeout or error); mean score {report.mean:.2f}"
    )
    print(f"gradebook: {report.gradebook}")
    print(f"summary:   {report.summary}")
    return 0


def register(subparsers: argparse._SubParsersAction) -> None:
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
    c.add_argument(
        "--rounding",
        default=None,
        metavar="RULE",
        help="accepted rounding of decimals: digits=N (a decimal of at least N significant "
        "digits may be rounded or truncated; default digits=3), abs=T, rel=T, or off",
    )
    c.set_defaults(func=_cmd_check)

    g = subparsers.add_parser("grade", help="grade a class: gradebook, feedback, summary")
    g.add_argument("assignment", help="assignment YAML file")
    g.add_argument("submissions", help="folder of submissions, or a CSV file")
    g.add_argument("-o", "--output", required=True, help="report folder (created)")
    g.add_argument("--workers", type=int, default=2, help="worker processes (0: none)")
    g.add_argument(
        "--timeout",
        type=float,
        default=None,
        help="time limit of one answer in seconds (default: the assignment's, 5)",
    )
    g.add_argument(
        "--dask", default=None, metavar="ADDRESS", help="run on a Dask cluster (scheduler address)"
    )
    g.add_argument("--quiet", action="store_true", help="no progress bar")
    g.set_defaults(func=_cmd_grade)
