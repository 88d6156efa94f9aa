"""The sandbox of a grading job: a killable child process, the framing of its messages.

Every job runs in a :class:`Sandbox`: a child Python process that runs one job at
a time and is killed (and replaced by a fresh one) when a job overruns its
deadline, whatever the job is doing — a regular expression or a C loop that no
signal interrupts included.  A job that kills its process is reported once it
failed twice.  So a job costs only its own result, never another job's.  The back
ends that drive sandboxes (a local pool, a Dask cluster) are
:mod:`~dhsym.checking.grading.backends`'.

Parent and child speak in frames: an 8-byte length, then a pickle.  The parent sends
``(fn, jobs, state)``; the child answers one frame per job, ``("ok", result)`` or
``("error", text)``.  A job function may keep what its jobs share for the life of its
child: given ``state`` (a picklable factory, e.g. a class), the child calls it once
and runs ``fn(job, that_state)`` for every job it gets — the grader's prepared keys
(:class:`~dhsym.checking.judging.key.PreparedKeys`), built once per child process.

Run as a script (``python …/sandbox.py MODULE…``, without importing the package)
this module is the child of a sandbox: it imports the modules, then answers framed
pickled jobs on its standard input (the parent is the only writer: nothing a
student wrote is unpickled).  So it imports only the standard library.
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
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import IO

__all__ = ["PRELOAD", "STARTUP_SECONDS", "JobFailure", "Sandbox", "run_in_sandbox"]

_HEADER = struct.Struct("!Q")
#: how long a child may take to start (importing sympy on a loaded machine)
STARTUP_SECONDS = 120.0
#: what a grading child imports before its first job
PRELOAD = ("dhsym.checking.grading.batch",)


@dataclass(frozen=True)
class JobFailure:
    """A job that did not return: ``kind`` is ``timeout`` or ``error``."""

    kind: str
    message: str


# --- framing ---------------------------------------------------------------------------


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

    def __init__(self, preload: Sequence[str] = PRELOAD) -> None:
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
        end = time.monotonic() + STARTUP_SECONDS
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
    preload: Sequence[str] = PRELOAD,
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


# --- the child -------------------------------------------------------------------------


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
