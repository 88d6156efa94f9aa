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


def test_children_forked_from_a_template_start_with_its_state_and_die_alone():
    from dhsym.checking.grading.sandbox import Template, can_fork

    from .._jobs import Counter, count_calls, warm_counter

    if not can_fork():  # pragma: no cover - a platform without fork: cold children only
        return
    with Template(preload=(), state=Counter, warm=warm_counter) as t:
        with Sandbox(preload=(), template=t) as box, Sandbox(preload=(), template=t) as other:
            pid, calls = box.call(count_calls, None, deadline=30, state=Counter)
            assert calls == 101  # the state the template built, not a fresh one
            assert pid != t.pid and other.call(count_calls, None, 30, Counter)[1] == 101
            failure = box.call(die, None, deadline=30)
            assert failure == JobFailure("error", "the worker process died (exit code 3)")
            out = dict(box.call_many(stuck_or_square, [2, -1, 3], deadline=5.0))
            assert out == {0: 4, 1: JobFailure("timeout", "no result within 5 s"), 2: 9}
            # the killed children cost nothing else: the other child goes on with its state
            assert other.call(count_calls, None, 30, Counter)[1] == 102
            assert box.proc is not None and box.proc.pid != pid
        assert t.proc is not None and t.proc.poll() is None  # the template ran no job


def test_a_sandbox_whose_template_cannot_start_starts_cold():
    from dhsym.checking.grading.sandbox import Template

    t = Template(preload=("no_such_module_for_dhsym",))
    with Sandbox(preload=(), template=t) as box:
        assert box.call(abs, -4, deadline=60) == 4
    assert t.failed and t.proc is None


def test_a_template_forked_from_this_process_starts_from_its_state():
    import threading

    from dhsym.checking.grading.sandbox import Template, can_fork

    from .._jobs import Counter, count_calls

    if not can_fork() or threading.active_count() > 1:  # pragma: no cover - cold template
        return
    mine = Counter()
    mine.calls = 500
    with Template(preload=(), state=Counter, local=mine) as t:
        t.start()
        assert t.own is not None and t.proc is None  # forked here, no interpreter started
        with Sandbox(preload=(), template=t) as box:
            assert box.call(count_calls, None, deadline=30, state=Counter)[1] == 501
            assert box.call(die, None, deadline=30).message.endswith("(exit code 3)")
            assert box.call(count_calls, None, deadline=30, state=Counter)[1] == 501
    assert mine.calls == 500  # the children had copies: this process's state is untouched
    assert t.own is None  # closed and reaped
