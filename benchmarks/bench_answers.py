"""The answer corpus as a benchmark: the fraction of answers judged right (target: 100 %).

Run ``python benchmarks/bench_answers.py`` (``--wrong`` lists every answer judged wrong,
``--forms`` the count per form).  The corpus is ``tests/data/answers/*.yaml``: correct
answers in every accepted form, wrong ones with each catalogued mistake, refused ones;
each with its expected verdict (see ``tests/checking/answer_corpus.py``).  Also prints the median
time per answer, against parsing the same answer texts with the whitelist parser alone
(same run).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.checking.answer_corpus import load_corpus, run_case  # noqa: E402


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--wrong", action="store_true", help="list the answers judged wrong")
    p.add_argument("--forms", action="store_true", help="answers and misses per form")
    args = p.parse_args()
    cases = load_corpus()
    for case in cases[:3]:  # prepare a few keys and warm sympy's caches
        run_case(case)
    outcomes, times = [], []
    for case in cases:
        t0 = time.perf_counter()
        outcomes.append(run_case(case))
        times.append(time.perf_counter() - t0)
    right = sum(o.ok for o in outcomes)
    verdicts = Counter(c.verdict for c in cases)
    print(
        f"answer corpus: {len(cases)} answers in {len({c.file for c in cases})} files "
        f"({verdicts['correct']} correct, {verdicts['incorrect']} incorrect, "
        f"{verdicts['unreadable']} unreadable)"
    )
    print(
        f"judged right: {right}/{len(cases)} = {100 * right / len(cases):.1f} % "
        f"[{'ok' if right == len(cases) else 'FAIL'}: target 100 %]"
    )
    print(
        f"time per answer: median {1000 * statistics.median(times):.1f} ms, "
        f"max {1000 * max(times):.0f} ms"
    )
    if args.forms:
        total = Counter(c.form for c in cases)
        missed = Counter(o.case.form for o in outcomes if not o.ok)
        for form in sorted(total):
            miss = f"missed {missed[form]}" if missed[form] else ""
            print(f"  {form:48s} {total[form]:3d} {miss}")
    if args.wrong:
        for o in outcomes:
            if not o.ok:
                print(f"  {o.case.id}: {o.why}\n    {o.case.answer[:150]!r}")
    return 0 if right == len(cases) else 1


if __name__ == "__main__":
    raise SystemExit(main())
