"""Where grading jobs run: in this process, in a pool of sandboxes, on a Dask cluster.

Each job but the serial ones runs in a :class:`~dhsym.checking.grading.sandbox.Sandbox`
(a killable child process):

- :func:`run_pool` drives ``workers`` sandboxes from as many threads, sending each
  child a *batch* of jobs at a time
  (:meth:`~dhsym.checking.grading.sandbox.Sandbox.call_many`: one message out,
  one result back per job as it finishes, each job under its own deadline; after a
  kill the rest of the batch goes on in a fresh child); the children are forked from
  one warm :class:`~dhsym.checking.grading.sandbox.Template` that imported the modules
  and built the jobs' shared state once (``warm``), so a child, and the fresh child
  after a kill, starts in milliseconds instead of importing sympy;
- :func:`run_dask` sends each job to a Dask worker, where it runs in a sandbox of
  the worker thread (any ``--nthreads`` is safe: a hung job blocks nothing but its
  own child process, which is killed on time);
- :func:`run_serial` runs in this process (no isolation: only the per-answer
  deadline of :func:`dhsym.checking.reading.limits.time_limit` applies, checked between the
  checker's steps).

All yield ``(index, outcome)`` as jobs finish, where the outcome is the job's
return value or a :class:`~dhsym.checking.grading.sandbox.JobFailure` (``timeout`` or
``error``); :class:`Progress` draws the progress bar.
"""

from __future__ import annotations

import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from typing import IO

from dhsym.errors import DHError

from .sandbox import PRELOAD, STARTUP_SECONDS, JobFailure, Sandbox, Template, run_in_sandbox

__all__ = ["Progress", "dask_address", "run_dask", "run_pool", "run_serial"]


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


def run_serial(
    fn: Callable[..., object], jobs: Sequence[object], state: Callable[[], object] | None = None
) -> Iterator[tuple[int, object]]:
    """Run the jobs one after another in this process (time limits from inside the job)."""
    shared = state() if state is not None else None
    for k, job in enumerate(jobs):
        try:
            yield k, (fn(job) if state is None else fn(job, shared))
        except Exception as err:  # noqa: BLE001 - one bad job never stops the batch
            yield k, JobFailure("error", f"{type(err).__name__}: {err}")


def run_pool(
    fn: Callable[..., object],
    jobs: Sequence[object],
    workers: int,
    deadline: float,
    preload: Sequence[str] = PRELOAD,
    batch: int | None = None,
    state: Callable[[], object] | None = None,
    warm: Callable[[object], object] | None = None,
    local: object | None = None,
) -> Iterator[tuple[int, object]]:
    """Run the jobs in ``workers`` sandboxes; each job gets ``deadline`` seconds of work.

    Jobs go to the children in batches of ``batch`` (default: about an eighth of a
    worker's share, 1 … 16), each job still under its own deadline
    (:meth:`Sandbox.call_many`); results come as jobs finish.  The children are forked
    from one :class:`Template` (cold children where it cannot run), which builds the
    state once for all of them, ``warm(state())``, before the first fork; forked from this
    process when it runs one thread, the template starts from ``local``, this process's
    own state (e.g. the keys it prepared), instead of ``state()``.
    """
    import queue

    n = max(1, workers)
    size = batch or max(1, min(16, len(jobs) // (8 * n)))
    pending = deque(range(k, min(k + size, len(jobs))) for k in range(0, len(jobs), size))
    results: queue.SimpleQueue[tuple[int, object] | None] = queue.SimpleQueue()
    template = Template(preload, state, warm, local)
    template.start()  # before this function's threads: forked from this process if it can
    owned = [Sandbox(preload, template) for _ in range(n)]
    stop = threading.Event()
    lock = threading.Lock()

    def work(box: Sandbox) -> None:
        try:
            while not stop.is_set():
                with lock:
                    if not pending:
                        return
                    ks = pending.popleft()
                for j, outcome in box.call_many(fn, [jobs[k] for k in ks], deadline, state):
                    results.put((ks[j], outcome))
                    if stop.is_set():
                        return
        except Exception as err:  # noqa: BLE001 - a fault of the runner: every job left fails
            with lock:
                left = [k for ks in pending for k in ks]
                pending.clear()
            for k in left:
                results.put((k, JobFailure("error", f"{type(err).__name__}: {err}")))
        finally:
            results.put(None)

    threads = [
        threading.Thread(target=work, args=(box,), name=f"dhsym-grade-{i}", daemon=True)
        for i, box in enumerate(owned)
    ]
    for t in threads:
        t.start()
    try:
        running = len(threads)
        while running:
            item = results.get()
            if item is None:
                running -= 1
            else:
                yield item
    finally:
        stop.set()
        for box in owned:  # a stopped run: running children die, waiting threads return
            box.close()
        for t in threads:
            t.join()
        for box in owned:
            box.close()
        template.close()


def dask_address(address: object) -> object:
    """``address`` checked as a Dask scheduler address (or a ``Client``, kept as is).

    A malformed address is a :class:`~dhsym.errors.DHError` naming ``--dask``, before
    any submission is read.

    >>> dask_address("tcp://127.0.0.1:8786")
    'tcp://127.0.0.1:8786'
    >>> dask_address("garbage://x")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: --dask: 'garbage://x' is not a Dask scheduler address (unknown ...
    """
    try:
        from dask.distributed import Client
    except ImportError:
        raise DHError("--dask needs dask.distributed (pip install 'dhsym[dask]')") from None
    if isinstance(address, Client):
        return address
    if not isinstance(address, str) or not address.strip():
        raise DHError(
            f"--dask: expected a scheduler address such as tcp://host:8786, got {address!r}"
        )
    from distributed.comm import parse_address
    from distributed.comm.addressing import parse_host_port
    from distributed.comm.registry import get_backend

    try:
        scheme, location = parse_address(address)
        get_backend(scheme)
        if scheme in ("tcp", "tls", "ws", "wss"):
            parse_host_port(location)
    except (ValueError, TypeError) as err:
        reason = str(err).split(" (known", 1)[0]
        raise DHError(
            f"--dask: {address!r} is not a Dask scheduler address ({reason}); "
            "expected e.g. tcp://host:8786"
        ) from None
    return address


def run_dask(
    fn: Callable[..., object],
    jobs: Sequence[object],
    address: object,
    deadline: float,
    preload: Sequence[str] = PRELOAD,
    state: Callable[[], object] | None = None,
) -> Iterator[tuple[int, object]]:
    """Run the jobs on a Dask cluster (``address`` or a ``Client``), each in a sandbox.

    The deadline is enforced in the worker (the sandbox's child is killed), so a
    job waiting in a worker's queue is never charged for another one's time; a
    job that the cluster does not return at all within a generous backstop
    (twice the deadline plus the sandbox's start-up) is reported ``timeout``.
    """
    from dask.distributed import Client, Future

    address = dask_address(address)
    try:
        client = address if isinstance(address, Client) else Client(address, timeout=30)
    except (OSError, TimeoutError, ValueError) as err:
        raise DHError(f"--dask: cannot reach the scheduler at {address!r}: {err}") from None
    own = client is not address
    backstop = 2 * (deadline + STARTUP_SECONDS) + 30.0
    try:
        slots = max(1, sum(client.nthreads().values())) * 2
        pending = deque(range(len(jobs)))
        running: dict[Future[object], tuple[int, float]] = {}  # future -> (job, start)
        while pending or running:
            while pending and len(running) < slots:
                k = pending.popleft()
                fut = client.submit(
                    run_in_sandbox, fn, jobs[k], deadline, preload, state, pure=False
                )
                running[fut] = (k, time.monotonic())
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
            for fut in [f for f, (_, t0) in running.items() if now - t0 > backstop]:
                k, _ = running.pop(fut)
                fut.cancel()
                yield k, JobFailure("timeout", f"no result from the cluster within {backstop:g} s")
    finally:
        if own:
            client.close()
