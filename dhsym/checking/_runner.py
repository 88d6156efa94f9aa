"""Running grading jobs: a process pool with a watchdog, a Dask cluster, a progress bar.

Both runners yield ``(index, outcome)`` as jobs finish, where the outcome is the
job's return value or a :class:`JobFailure` (``timeout`` or ``error``); one bad job
never stops the others.  The pool keeps at most two jobs per worker in flight (one
running, one queued), so a job is at most one deadline away from its start; a job
not back within twice its deadline gets the pool's processes killed (the hung one
marked ``timeout``, the others run again) and a fresh pool.
"""

from __future__ import annotations

import sys
import time
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import IO

__all__ = ["JobFailure", "Progress", "run_dask", "run_pool", "run_serial"]

_RETRIES = 2


@dataclass(frozen=True)
class JobFailure:
    """A job that did not return: ``kind`` is ``timeout`` or ``error``."""

    kind: str
    message: str


class Progress:
    """A one-line progress bar on stderr (a line per 10 % when not a terminal)."""

    def __init__(self, total: int, stream: IO[str] | None = None, enabled: bool = True) -> None:
        self.total, self.done, self.enabled = total, 0, enabled
        self.stream = stream or sys.stderr
        self.start = time.monotonic()
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.last_decile = -1

    def step(self, n: int = 1) -> None:
        """Count ``n`` finished jobs and redraw."""
        self.done += n
        if not self.enabled:
            return
        frac = self.done / self.total if self.total else 1.0
        elapsed = time.monotonic() - self.start
        bar = "#" * int(30 * frac) + "." * (30 - int(30 * frac))
        line = f"grading [{bar}] {self.done}/{self.total} {elapsed:6.1f} s"
        if self.tty:
            self.stream.write("\r" + line + ("\n" if self.done >= self.total else ""))
            self.stream.flush()
        elif int(frac * 10) > self.last_decile:
            self.last_decile = int(frac * 10)
            self.stream.write(line + "\n")
            self.stream.flush()


def run_serial(fn: Callable, jobs: Sequence) -> Iterator[tuple[int, object]]:
    """Run the jobs one after another in this process (time limits from inside the job)."""
    for k, job in enumerate(jobs):
        try:
            yield k, fn(job)
        except Exception as err:  # noqa: BLE001 - one bad job never stops the batch
            yield k, JobFailure("error", f"{type(err).__name__}: {err}")


def _new_pool(workers: int):  # noqa: ANN202
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    method = "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
    ctx = multiprocessing.get_context(method)
    if method == "forkserver":
        ctx.set_forkserver_preload(["dhsym.checking.grading"])
    return ProcessPoolExecutor(max_workers=workers, mp_context=ctx)


def _kill(pool) -> None:  # noqa: ANN001
    for proc in list(getattr(pool, "_processes", {}).values()):
        try:
            proc.kill()
        except (OSError, AttributeError):
            pass
    pool.shutdown(wait=False, cancel_futures=True)


def run_pool(
    fn: Callable, jobs: Sequence, workers: int, deadline: float
) -> Iterator[tuple[int, object]]:
    """Run the jobs in a ``ProcessPoolExecutor``; each gets ``deadline`` seconds of work."""
    from concurrent.futures import FIRST_COMPLETED, wait
    from concurrent.futures.process import BrokenProcessPool

    pending = deque((k, 0) for k in range(len(jobs)))
    running: dict = {}
    pool = _new_pool(workers)
    try:
        while pending or running:
            while pending and len(running) < 2 * workers:  # one running, one queued each
                k, tries = pending.popleft()
                running[pool.submit(fn, jobs[k])] = (k, time.monotonic(), tries)
            done, _ = wait(list(running), timeout=0.25, return_when=FIRST_COMPLETED)
            broken = False
            for fut in done:
                k, _, tries = running.pop(fut)
                try:
                    yield k, fut.result()
                except BrokenProcessPool:
                    broken = True
                    if tries < _RETRIES:
                        pending.appendleft((k, tries + 1))
                    else:
                        yield k, JobFailure("error", "the worker process died")
                except Exception as err:  # noqa: BLE001
                    yield k, JobFailure("error", f"{type(err).__name__}: {err}")
            now = time.monotonic()
            late = [f for f, (_, start, _) in running.items() if now - start > 2 * deadline]
            if late or broken:
                for fut in late:
                    k, _, _ = running.pop(fut)
                    yield k, JobFailure("timeout", f"no result within {deadline:g} s")
                for k, _, tries in running.values():  # killed with the pool: run again
                    pending.appendleft((k, tries))
                running.clear()
                _kill(pool)
                pool = _new_pool(workers)
    finally:
        _kill(pool) if running else pool.shutdown(wait=True)


def run_dask(
    fn: Callable, jobs: Sequence, address: object, deadline: float
) -> Iterator[tuple[int, object]]:
    """Run the jobs on a Dask cluster (``address`` or a ``Client``); late jobs are cancelled.

    Dask runs tasks in worker threads, where no time limit can interrupt them: a
    job past its deadline is reported ``timeout`` and cancelled, and the answers'
    own cost limits keep the work bounded.
    """
    from dask.distributed import Client

    client = address if isinstance(address, Client) else Client(address)
    own = client is not address
    try:
        slots = max(1, sum(client.nthreads().values())) * 2
        pending = deque(range(len(jobs)))
        running: dict = {}
        while pending or running:
            while pending and len(running) < slots:
                k = pending.popleft()
                running[client.submit(fn, jobs[k], pure=False)] = (k, time.monotonic())
            done = [f for f in running if f.done()]
            if not done:
                time.sleep(0.01)
            for fut in done:
                k, _ = running.pop(fut)
                try:
                    yield k, fut.result()
                except Exception as err:  # noqa: BLE001
                    yield k, JobFailure("error", f"{type(err).__name__}: {err}")
            now = time.monotonic()
            for fut in [f for f, (_, t0) in running.items() if now - t0 > deadline]:
                k, _ = running.pop(fut)
                fut.cancel()
                yield k, JobFailure("timeout", f"no result within {deadline:g} s")
    finally:
        if own:
            client.close()
