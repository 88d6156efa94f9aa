"""The back ends (serial, pool, Dask): a hung job is killed on time and costs no other job."""

from __future__ import annotations

import io

import pytest

from dhsym.checking.grading.backends import Progress, run_pool, run_serial
from dhsym.checking.grading.sandbox import JobFailure

from .._jobs import Counter, count_calls, is_gone, sleep_naming_the_process, stuck_or_square


def test_hung_worker_is_killed_and_the_batch_goes_on(tmp_path):
    jobs = [(seconds, str(tmp_path)) for seconds in (0.01, 300, 0.01, 0.02)]
    out = dict(run_pool(sleep_naming_the_process, jobs, workers=2, deadline=2.0, preload=()))
    assert out[1] == JobFailure("timeout", "no result within 2 s")
    assert out[0] is None and out[2] is None and out[3] is None
    # killed, not waited for (no clock here): the process that slept is gone
    hung = [int(p.name) for p in tmp_path.iterdir() if p.read_text() == "300"]
    assert len(hung) == 1 and is_gone(hung[0])


def test_a_job_stuck_in_c_code_is_killed_and_no_other_job_pays():
    jobs = [-1, 2, 3, -1, 4, 5, 6]
    out = dict(run_pool(stuck_or_square, jobs, workers=1, deadline=2.0, preload=()))
    assert out[0] == out[3] == JobFailure("timeout", "no result within 2 s")
    assert [out[k] for k in (1, 2, 4, 5, 6)] == [4, 9, 16, 25, 36]


def test_errors_are_results():
    out = dict(run_serial(int, ["1", "x"]))
    assert out[0] == 1 and isinstance(out[1], JobFailure) and out[1].kind == "error"
    out = dict(run_pool(int, ["2", "y"], workers=1, deadline=30, preload=()))
    assert out[0] == 2 and out[1].kind == "error"


def test_progress_bar_lines():
    buf = io.StringIO()
    p = Progress(4, stream=buf)
    for _ in range(4):
        p.step()
    assert buf.getvalue().count("grading [") == 4 and "4/4" in buf.getvalue()


@pytest.mark.slow
def test_dask_thread_stuck_in_c_code_costs_no_other_job():
    """One Dask worker thread: every job queues behind the stuck ones, and none times out."""
    distributed = pytest.importorskip("dask.distributed")
    from dhsym.checking.grading.backends import run_dask

    jobs = [-1, 2, -1, 3, 4, 5]
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        out = dict(
            run_dask(stuck_or_square, jobs, cluster.scheduler_address, deadline=5.0, preload=())
        )
    assert out[0] == out[2] == JobFailure("timeout", "no result within 5 s")
    assert [out[k] for k in (1, 3, 4, 5)] == [4, 9, 16, 25]


def test_each_worker_builds_its_state_once_and_keeps_it_between_batches():
    out = dict(
        run_pool(
            count_calls, list(range(12)), workers=2, deadline=30, preload=(), batch=2, state=Counter
        )
    )
    pids = {pid for pid, _ in out.values()}
    assert len(pids) <= 2
    for pid in pids:  # one Counter per child: its calls count 1, 2, 3 … across batches
        seen = sorted(n for p, n in out.values() if p == pid)
        assert seen == list(range(1, len(seen) + 1))
    serial = dict(run_serial(count_calls, [0, 1, 2], state=Counter))
    assert [n for _, n in serial.values()] == [1, 2, 3]
