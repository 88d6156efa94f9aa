"""The job runners: a hung worker does not hang the batch; failures are reported."""

from __future__ import annotations

import io
import time

from dhsym.checking._runner import JobFailure, Progress, run_pool, run_serial


def test_hung_worker_is_killed_and_the_batch_goes_on():
    t0 = time.monotonic()
    out = dict(run_pool(time.sleep, [0.01, 300, 0.01, 0.02], workers=2, deadline=2.0))
    assert time.monotonic() - t0 < 60
    assert out[1] == JobFailure("timeout", "no result within 2 s")
    assert out[0] is None and out[2] is None and out[3] is None


def test_errors_are_results():
    out = dict(run_serial(int, ["1", "x"]))
    assert out[0] == 1 and isinstance(out[1], JobFailure) and out[1].kind == "error"
    out = dict(run_pool(int, ["2", "y"], workers=1, deadline=30))
    assert out[0] == 2 and out[1].kind == "error"


def test_progress_bar_lines():
    buf = io.StringIO()
    p = Progress(4, stream=buf)
    for _ in range(4):
        p.step()
    assert buf.getvalue().count("grading [") == 4 and "4/4" in buf.getvalue()
