"""The sandbox: a job that overruns or kills its child costs only its own result."""

from __future__ import annotations

from dhsym.checking.grading.sandbox import JobFailure, Sandbox

from .._jobs import die, die_or_square, stuck_or_square


def test_a_job_that_kills_its_process_is_an_error_and_the_sandbox_recovers():
    with Sandbox(preload=()) as box:
        failure = box.call(die, None, deadline=30)
        assert failure == JobFailure("error", "the worker process died (exit code 3)")
        assert box.call(abs, -5, deadline=30) == 5


def test_a_batch_goes_on_after_a_timeout_in_its_middle_each_job_on_its_own_clock():
    jobs = [2, 3, -1, 4, 5]
    with Sandbox(preload=()) as box:
        out = dict(box.call_many(stuck_or_square, jobs, deadline=5.0))
    assert out[2] == JobFailure("timeout", "no result within 5 s")
    assert [out[k] for k in (0, 1, 3, 4)] == [4, 9, 16, 25]


def test_a_batch_goes_on_after_a_job_kills_its_process():
    with Sandbox(preload=()) as box:
        out = list(box.call_many(die_or_square, [2, -3, 4], deadline=30))
    assert out == [
        (0, 4),
        (1, JobFailure("error", "the worker process died (exit code 3)")),
        (2, 16),
    ]
