"""Running grading jobs in killable worker processes: a local pool, a Dask cluster, a progress bar.

Every job runs in a :class:`Sandbox`: a child Python process that runs one job at
a time and is killed (and replaced by a fresh one) when a job overruns its
deadline, whatever the job is doing — a regular expression or a C loop that no
signal interrupts included.  A job that kills its process is reported once it
failed twice.  So a job costs only its own result, never another job's:

- :func:`run_pool` drives ``workers`` sandboxes from as many threads, sending each
  child a *batch* of jobs at a time (:meth:`Sandbox.call_many`: one message out,
  one result back per job as it finishes, each job under its own deadline; after a
  kill the rest of the batch goes on in a fresh child);
- :func:`run_dask` sends each job to a Dask worker, where it runs in a sandbox of
  the worker thread (any ``--nthreads`` is safe: a hung job blocks nothing but its
  own child process, which is killed on time);
- :func:`run_serial` runs in this process (no isolation: only the per-answer
  deadline of :func:`dhsym.checking.reading.limits.time_limit` applies, checked between the
  checker's steps).

All yield ``(index, outcome)`` as jobs finish, where the outcome is the job's
return value or a :class:`JobFailure` (``timeout`` or ``error``).

A job function may keep what its jobs share for the life of its worker: given
``state`` (a picklable factory, e.g. a class), each worker calls it once and runs
``fn(job, that_state)`` for every job it gets — the grader's prepared keys
(:class:`~dhsym.checking.judging.checker.PreparedKeys`), built once per child process.

Run as a script (``python …/_runner.py MODULE…``, without importing the package)
this module is the child of a sandbox: it imports the modules, then answers framed
pickled jobs on its standard input (the parent is the only writer: nothing a
student wrote is unpickled).
"""

from __future__ import annotations

import atexit
import os
import pickle
import select
import struct
import subprocess
import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import IO

__all__ = [
    "JobFailure",
    "Progress",
    "Sandbox",
    "dask_address",
    "run_dask",
    "run_in_sandbox",
    "run_pool",
    "run_serial",
]

_HEADER = struct.Struct("!Q")
_STARTUP_SECONDS = 120.0  # importing sympy on a loaded machine
_PRELOAD = ("dhsym.checking.grading.batch",)


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


# --- the sandbox: a child process that runs one job at a time ----------------------------


def _write_frame(fh: IO[bytes], payload: bytes) -> None:
    fh.write(_HEADER.pack(len(payload)) + payload)
    fh.flush()


class _Expired(Exception):
    """No complete answer from the child before the deadline."""


class _Gone(Exception):
    """The child closed its end: it died."""


def _read_exact(fd: int, n: int, end: float) -> bytes:
    chunks, got = [], 0
    while got < n:
        left = end - time.monotonic()
        if left <= 0:
            raise _Expired
        ready, _, _ = select.select([fd], [], [], min(left, 1.0))
        if not ready:
            continue
        chunk = os.read(fd, min(n - got, 1 << 20))
        if not chunk:
            raise _Gone
        chunks.append(chunk)
        got += len(chunk)
    return b"".join(chunks)


def _child_env() -> dict[str, str]:
    """The parent's environment with its ``sys.path``: the child imports the same dhsym."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    env.setdefault("MPLBACKEND", "Agg")
    return env


class Sandbox:
    """A child process that runs jobs one at a time; killed and replaced on a deadline.

    >>> with Sandbox(preload=()) as box:
    ...     box.call(abs, -3, deadline=60), box.call(int, "x", deadline=60).kind
    (3, 'error')
    """

    def __init__(self, preload: Sequence[str] = _PRELOAD) -> None:
        self.preload = tuple(preload)
        self.proc: subprocess.Popen[bytes] | None = None

    def __enter__(self) -> Sandbox:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _start(self) -> None:
        self.close()
        # the child runs this file as a script: only the standard library until the preload
        # ... and without the current folder on sys.path (as python -P): a file there never
        # shadows a module
        start = (
            "import sys; sys.path[:] = [p for p in sys.path if p]; import runpy; "
            "sys.argv[:] = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name='__main__')"
        )
        self.proc = subprocess.Popen(
            [sys.executable, "-c", start, os.path.abspath(__file__), *self.preload],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=_child_env(),
            close_fds=True,
        )
        assert self.proc.stdout is not None
        fd = self.proc.stdout.fileno()
        end = time.monotonic() + _STARTUP_SECONDS
        try:
            (n,) = _HEADER.unpack(_read_exact(fd, _HEADER.size, end))
            _read_exact(fd, n, end)
        except (_Expired, _Gone):
            code = self.proc.poll()
            self.close()
            raise RuntimeError(f"the worker process did not start (exit code {code})") from None

    def close(self) -> None:
        """Kill the child (if any) and reap it."""
        proc, self.proc = self.proc, None
        if proc is None:
            return
        try:
            proc.kill()
        except OSError:
            pass
        for stream in (proc.stdin, proc.stdout):
            try:
                if stream is not None:
                    stream.close()
            except OSError:
                pass
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass

    def call(
        self,
        fn: Callable[..., object],
        job: object,
        deadline: float,
        state: Callable[[], object] | None = None,
    ) -> object:
        """``fn(job)`` in the child (``fn(job, s)`` with the child's ``s = state()``), or a
        :class:`JobFailure` (timeout: the child is killed)."""
        payload = pickle.dumps((fn, [job], state), protocol=pickle.HIGHEST_PROTOCOL)
        died = ""
        for _attempt in range(2):  # a job whose process dies gets one more, fresh process
            try:
                if self.proc is None or self.proc.poll() is not None:
                    self._start()
                assert self.proc is not None and self.proc.stdin and self.proc.stdout
                _write_frame(self.proc.stdin, payload)
                fd = self.proc.stdout.fileno()
                end = time.monotonic() + deadline
                (n,) = _HEADER.unpack(_read_exact(fd, _HEADER.size, end))
                status, value = pickle.loads(_read_exact(fd, n, end))
            except _Expired:
                self.close()
                return JobFailure("timeout", f"no result within {deadline:g} s")
            except (_Gone, OSError, EOFError, pickle.UnpicklingError):
                code = None
                if self.proc is not None:
                    try:
                        code = self.proc.wait(timeout=5)
                    except subprocess.TimeoutExpired:
                        pass
                self.close()
                died = f"the worker process died (exit code {code})"
                continue
            except RuntimeError as err:
                return JobFailure("error", str(err))
            return value if status == "ok" else JobFailure("error", value)
        return JobFailure("error", died)

    def call_many(
        self,
        fn: Callable[..., object],
        jobs: Sequence[object],
        deadline: float,
        state: Callable[[], object] | None = None,
    ) -> Iterator[tuple[int, object]]:
        """``(k, fn(jobs[k]))`` for every job, in order, as each finishes (or a
        :class:`JobFailure`): one message carries the whole batch to the child, and
        objects the jobs share (the assignment) are pickled once for all of them.

        Each job has ``deadline`` seconds from the moment the child is free for it (the
        result of the job before it came back).  A job that overruns is a ``timeout``
        and its child is killed; the jobs after it go on in a fresh child.  A job whose
        child dies is run once more alone (:meth:`call`); the jobs after it go on.
        """
        start = 0
        while start < len(jobs):
            rest = list(jobs[start:])
            try:
                payload = pickle.dumps((fn, rest, state), protocol=pickle.HIGHEST_PROTOCOL)
            except Exception:  # noqa: BLE001 - a job that cannot be sent: one by one
                for k in range(start, len(jobs)):
                    yield k, self.call(fn, jobs[k], deadline, state)
                return
            try:
                if self.proc is None or self.proc.poll() is not None:
                    self._start()
                assert self.proc is not None and self.proc.stdin and self.proc.stdout
                _write_frame(self.proc.stdin, payload)
            except RuntimeError as err:
                for k in range(start, len(jobs)):
                    yield k, JobFailure("error", str(err))
                return
            except OSError:
                self.close()  # the child died before it read the batch: a fresh one
                yield start, self.call(fn, jobs[start], deadline, state)
                start += 1
                continue
            fd = self.proc.stdout.fileno()
            while start < len(jobs):
                try:
                    end = time.monotonic() + deadline
                    (n,) = _HEADER.unpack(_read_exact(fd, _HEADER.size, end))
                    status, value = pickle.loads(_read_exact(fd, n, end))
                except _Expired:
                    self.close()
                    yield start, JobFailure("timeout", f"no result within {deadline:g} s")
                    start += 1
                    break
                except (_Gone, OSError, EOFError, pickle.UnpicklingError):
                    self.close()  # it died in this job: the job gets one fresh process alone
                    yield start, self.call(fn, jobs[start], deadline, state)
                    start += 1
                    break
                yield start, (value if status == "ok" else JobFailure("error", value))
                start += 1


_LOCAL = threading.local()
_ALL: list[Sandbox] = []
_ALL_LOCK = threading.Lock()


def _close_all() -> None:
    with _ALL_LOCK:
        for box in _ALL:
            box.close()


atexit.register(_close_all)


def run_in_sandbox(
    fn: Callable[..., object],
    job: object,
    deadline: float,
    preload: Sequence[str] = _PRELOAD,
    state: Callable[[], object] | None = None,
) -> object:
    """``fn(job)`` in this thread's own :class:`Sandbox` (a Dask task runs this)."""
    boxes = getattr(_LOCAL, "boxes", None)
    if boxes is None:
        boxes = _LOCAL.boxes = {}
    box = boxes.get(tuple(preload))
    if box is None:
        box = boxes[tuple(preload)] = Sandbox(preload)
        with _ALL_LOCK:
            _ALL.append(box)
    return box.call(fn, job, deadline, state)


def run_pool(
    fn: Callable[..., object],
    jobs: Sequence[object],
    workers: int,
    deadline: float,
    preload: Sequence[str] = _PRELOAD,
    batch: int | None = None,
    state: Callable[[], object] | None = None,
) -> Iterator[tuple[int, object]]:
    """Run the jobs in ``workers`` sandboxes; each job gets ``deadline`` seconds of work.

    Jobs go to the children in batches of ``batch`` (default: about an eighth of a
    worker's share, 1 … 16), each job still under its own deadline
    (:meth:`Sandbox.call_many`); results come as jobs finish.
    """
    import queue

    n = max(1, workers)
    size = batch or max(1, min(16, len(jobs) // (8 * n)))
    pending = deque(range(k, min(k + size, len(jobs))) for k in range(0, len(jobs), size))
    results: queue.SimpleQueue[tuple[int, object] | None] = queue.SimpleQueue()
    owned = [Sandbox(preload) for _ in range(n)]
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
    from dhsym.errors import DHError  # here: the sandbox's child runs this file without dhsym

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
    preload: Sequence[str] = _PRELOAD,
    state: Callable[[], object] | None = None,
) -> Iterator[tuple[int, object]]:
    """Run the jobs on a Dask cluster (``address`` or a ``Client``), each in a sandbox.

    The deadline is enforced in the worker (the sandbox's child is killed), so a
    job waiting in a worker's queue is never charged for another one's time; a
    job that the cluster does not return at all within a generous backstop
    (twice the deadline plus the sandbox's start-up) is reported ``timeout``.
    """
    from dask.distributed import Client, Future

    from dhsym.errors import DHError

    address = dask_address(address)
    try:
        client = address if isinstance(address, Client) else Client(address, timeout=30)
    except (OSError, TimeoutError, ValueError) as err:
        raise DHError(f"--dask: cannot reach the scheduler at {address!r}: {err}") from None
    own = client is not address
    backstop = 2 * (deadline + _STARTUP_SECONDS) + 30.0
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


def _serve(preload: Sequence[str]) -> None:
    """The child's loop: read a job, run it, write ``("ok", result)`` or ``("error", text)``."""
    import importlib

    out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # anything the job prints goes to stderr, never into the protocol
    inp = sys.stdin.buffer
    for name in preload:
        importlib.import_module(name)
    _write_frame(out, pickle.dumps(("ready", None)))
    states: dict[
        Callable[[], object], object
    ] = {}  # this worker's state per job function's factory
    while True:
        head = inp.read(_HEADER.size)
        if len(head) < _HEADER.size:
            return
        (n,) = _HEADER.unpack(head)
        message = pickle.loads(inp.read(n))  # noqa: S301 - written by the parent only
        fn, batch, factory = message  # a batch: one reply per job, in order
        for job in batch:
            _write_frame(out, _run_one(fn, job, factory, states))


def _run_one(
    fn: Callable[..., object],
    job: object,
    factory: Callable[[], object] | None,
    states: dict[Callable[[], object], object],
) -> bytes:
    """The reply to one job: ``("ok", result)`` or ``("error", text)``, pickled."""
    try:
        if factory is None:
            reply = ("ok", fn(job))
        else:
            if factory not in states:
                states[factory] = factory()
            reply = ("ok", fn(job, states[factory]))
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as err:  # noqa: BLE001 - the job's failure is its result
        reply = ("error", f"{type(err).__name__}: {err}")
    try:
        return pickle.dumps(reply, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception as err:  # noqa: BLE001
        return pickle.dumps(("error", f"the result cannot be sent back: {err}"))


if __name__ == "__main__":
    _serve(sys.argv[1:])
