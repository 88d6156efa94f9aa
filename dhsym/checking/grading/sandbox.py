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

A child is started cold (a fresh interpreter that imports the modules) or, much
faster, forked from a :class:`Template`: a warm child process of the parent that has
imported the modules once and prepared what every job shares (the assignment's keys),
and then only forks.  A forked child is a separate process like a cold one: killed
on its deadline, its crash or hang costs only its own job; the template runs no job
and no student text.  Where ``fork`` or descriptor passing is missing, or the template
cannot start, children start cold.

Run as a script (``python …/sandbox.py MODULE…``, without importing the package)
this module is the child of a sandbox (``--template FD MODULE…``: the template): it
imports the modules, then answers framed pickled jobs on its standard input (the
parent is the only writer: nothing a student wrote is unpickled).  So it imports only
the standard library.
"""

from __future__ import annotations

import atexit
import os
import pickle
import select
import signal
import socket
import struct
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import IO

__all__ = ["PRELOAD", "STARTUP_SECONDS", "JobFailure", "Sandbox", "Template", "run_in_sandbox"]

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


# --- starting a child --------------------------------------------------------------------

#: how the child and the template start: this file run as a script, only the standard
#: library until the preload, and without the current folder on sys.path (as python -P):
#: a file there never shadows a module
_START = (
    "import sys; sys.path[:] = [p for p in sys.path if p]; import runpy; "
    "sys.argv[:] = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name='__main__')"
)


def _popen(args: Sequence[str], pass_fds: Sequence[int] = ()) -> subprocess.Popen[bytes]:
    """A fresh interpreter running this file with ``args`` (a cold child, or the template)."""
    return subprocess.Popen(
        [sys.executable, "-c", _START, os.path.abspath(__file__), *args],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        env=_child_env(),
        close_fds=True,
        pass_fds=tuple(pass_fds),
    )


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

    def __init__(self, preload: Sequence[str] = PRELOAD, template: Template | None = None) -> None:
        self.preload = tuple(preload)
        self.template = template
        self.proc: subprocess.Popen[bytes] | _Forked | None = None

    def __enter__(self) -> Sandbox:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _start(self) -> None:
        self.close()
        forked = self.template.fork() if self.template is not None else None
        self.proc = forked if forked is not None else _popen(self.preload)
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
        _close_streams(proc)
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


_PID = struct.Struct("!q")
_RUNNING = -(2**63)  # the template's answer for a child that has not ended


def can_fork() -> bool:
    """True where children can be forked from a template (``fork`` and descriptor passing)."""
    return hasattr(os, "fork") and hasattr(socket, "send_fds") and hasattr(socket, "socketpair")


class Template:
    """A warm child process that forks sandbox children (a fork server).

    It imports ``preload`` and, given ``state`` and ``warm``, builds the jobs' shared
    state once (``warm(state())``: e.g. every key of an assignment prepared).  Then it only
    forks: each child gets its own pipes (passed over a socket), starts with the modules
    imported and the state built, and runs jobs exactly as a cold child does.  The
    template never runs a job.

    :meth:`start` forks the template from this process when this process runs one thread
    only (a command line run: the modules are imported already, and ``local``, this
    process's own state, e.g. the keys it prepared to load the assignment, is the
    children's starting state); else (a notebook's or a server's threads) the template is
    a fresh interpreter started as a cold child is.  :meth:`fork` returns None when the
    template cannot start or has died: the sandbox then starts a cold child.

    >>> with Template(preload=()) as t, Sandbox(preload=(), template=t) as box:
    ...     box.call(abs, -3, deadline=60), box.proc is not None and box.proc.pid != t.pid
    (3, True)
    """

    def __init__(
        self,
        preload: Sequence[str] = PRELOAD,
        state: Callable[[], object] | None = None,
        warm: Callable[[object], object] | None = None,
        local: object | None = None,
    ) -> None:
        self.preload, self.state, self.warm, self.local = tuple(preload), state, warm, local
        self.proc: subprocess.Popen[bytes] | None = None
        self.own: int | None = None  # the template's pid when forked from this process
        self.sock: socket.socket | None = None
        self.failed = not can_fork()
        self.lock = threading.Lock()

    @property
    def pid(self) -> int | None:
        """The template's process id (None before it started)."""
        return self.proc.pid if self.proc is not None else self.own

    def __enter__(self) -> Template:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def start(self) -> None:
        """Start the template now (forked from this process when it runs one thread only);
        a template that cannot start leaves its sandboxes to start cold children."""
        with self.lock:
            if self.failed or self.sock is not None:
                return
            try:
                if threading.active_count() == 1:
                    self._fork_here()
                else:
                    self._start()
            except (OSError, EOFError, _Expired, _Gone, pickle.PickleError):
                self.failed = True
                self._stop()

    def _fork_here(self) -> None:
        """The template forked from this process: its modules, and ``local`` as the state."""
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
        pid = os.fork()
        if pid == 0:  # the template: no job, no stream of the parent's
            try:
                ours.close()
                null = os.open(os.devnull, os.O_RDWR)
                for fd in (0, 1, 2):
                    os.dup2(null, fd)
                sys.path[:] = [p for p in sys.path if p]  # as a cold child's
                states: dict[Callable[[], object], object] = {}
                if self.state is not None and (self.local is not None or self.warm is not None):
                    states[self.state] = self.local if self.local is not None else self.state()
                    if self.warm is not None:
                        self.warm(states[self.state])
                _forks(theirs, states)
            finally:
                os._exit(0)
        theirs.close()
        self.own, self.sock = pid, ours

    def _start(self) -> None:
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            self.proc = _popen(
                ["--template", str(theirs.fileno()), *self.preload], pass_fds=[theirs.fileno()]
            )
        finally:
            theirs.close()
        self.sock = ours
        assert self.proc.stdin is not None and self.proc.stdout is not None
        message = pickle.dumps((self.state, self.warm), protocol=pickle.HIGHEST_PROTOCOL)
        _write_frame(self.proc.stdin, message)
        fd = self.proc.stdout.fileno()
        end = time.monotonic() + STARTUP_SECONDS
        (n,) = _HEADER.unpack(_read_exact(fd, _HEADER.size, end))
        _read_exact(fd, n, end)

    def fork(self) -> _Forked | None:
        """A new child forked from the template, or None (start a cold one instead)."""
        with self.lock:
            if self.failed:
                return None
            try:
                if self.sock is None:
                    self._start()
                assert self.sock is not None
                child_in, parent_in = os.pipe()  # the child's stdin
                parent_out, child_out = os.pipe()  # the child's stdout
                try:
                    socket.send_fds(self.sock, [b"F"], [child_in, child_out])
                finally:
                    os.close(child_in)
                    os.close(child_out)
                (pid,) = _PID.unpack(_recv_exact(self.sock, _PID.size))
            except (OSError, EOFError, _Expired, _Gone, pickle.PickleError):
                self.failed = True  # from now on: cold children
                self._stop()
                return None
            return _Forked(self, pid, os.fdopen(parent_in, "wb"), os.fdopen(parent_out, "rb"))

    def reap(self, pid: int, kill: bool, block: bool) -> int | None:
        """``pid``'s exit code once it ended (killed first with ``kill``; waited for with
        ``block``), None while it runs or when the template cannot tell."""
        with self.lock:
            if self.sock is None:
                if kill:
                    _kill(pid)
                return None
            try:
                flags = (1 if kill else 0) | (2 if block else 0)
                self.sock.sendall(b"R" + _PID.pack(pid) + bytes([flags]))
                (code,) = _PID.unpack(_recv_exact(self.sock, _PID.size))
            except (OSError, EOFError, _Gone):
                if kill:
                    _kill(pid)
                return None
            return None if code == _RUNNING else code

    def _stop(self) -> None:
        sock, self.sock = self.sock, None
        if sock is not None:
            sock.close()
        own, self.own = self.own, None
        if own is not None:  # it ends when its socket closes
            try:
                os.waitpid(own, 0)
            except ChildProcessError:
                pass
        proc, self.proc = self.proc, None
        if proc is not None:
            _close_streams(proc)
            try:
                proc.wait(timeout=10)  # it ends when its socket closes
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(timeout=10)

    def close(self) -> None:
        """Stop the template (the children it forked are the sandboxes' to close)."""
        with self.lock:
            self._stop()


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except OSError:
        pass


def _recv_exact(sock: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise _Gone
        data += chunk
    return data


def _close_streams(proc: subprocess.Popen[bytes] | _Forked) -> None:
    """Close a child's stdin and stdout (ours: the parent's ends of its pipes)."""
    for stream in (proc.stdin, proc.stdout):
        try:
            if stream is not None:
                stream.close()
        except OSError:
            pass


class _Forked:
    """A child forked from a :class:`Template`, seen as :class:`subprocess.Popen` is (the
    template, its parent, reaps it and tells its exit code)."""

    def __init__(self, template: Template, pid: int, stdin: IO[bytes], stdout: IO[bytes]) -> None:
        self.template, self.pid, self.stdin, self.stdout = template, pid, stdin, stdout
        self.returncode: int | None = None

    def poll(self) -> int | None:
        if self.returncode is None:
            self.returncode = self.template.reap(self.pid, kill=False, block=False)
        return self.returncode

    def wait(self, timeout: float | None = None) -> int | None:
        if self.returncode is None:
            self.returncode = self.template.reap(self.pid, kill=False, block=True)
        return self.returncode

    def kill(self) -> None:
        if self.returncode is None:
            self.returncode = self.template.reap(self.pid, kill=True, block=True)


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
    """A cold child: import the modules, then answer jobs (:func:`_answer`)."""
    import importlib

    for name in preload:
        importlib.import_module(name)
    _answer({})


def _answer(states: dict[Callable[[], object], object]) -> None:
    """The child's loop: read a job, run it, write ``("ok", result)`` or ``("error", text)``.

    ``states``: this worker's state per job function's factory (a forked child's come
    built from its template)."""
    out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # anything the job prints goes to stderr, never into the protocol
    inp = os.fdopen(0, "rb", closefd=False)
    _write_frame(out, pickle.dumps(("ready", None)))
    while True:
        head = inp.read(_HEADER.size)
        if len(head) < _HEADER.size:
            return
        (n,) = _HEADER.unpack(head)
        message = pickle.loads(inp.read(n))  # noqa: S301 - written by the parent only
        fn, batch, factory = message  # a batch: one reply per job, in order
        for job in batch:
            _write_frame(out, _run_one(fn, job, factory, states))


def _template(fd: int, preload: Sequence[str]) -> None:
    """A template started as a fresh interpreter: import the modules, build the shared
    state, then fork children (:func:`_forks`)."""
    import importlib

    for name in preload:
        importlib.import_module(name)
    sock = socket.socket(fileno=fd)
    inp, out = sys.stdin.buffer, sys.stdout.buffer
    (n,) = _HEADER.unpack(inp.read(_HEADER.size))
    factory, warm = pickle.loads(inp.read(n))  # noqa: S301 - written by the parent only
    states: dict[Callable[[], object], object] = {}
    if factory is not None and warm is not None:
        try:
            states[factory] = factory()
            warm(states[factory])
        except Exception:  # noqa: BLE001 - a fault here is each child's to meet and report
            states.clear()
    _write_frame(out, pickle.dumps(("ready", None)))
    _forks(sock, states)


def _forks(sock: socket.socket, states: dict[Callable[[], object], object]) -> None:
    """The template's loop: fork a child on request (``F`` with the child's two pipe ends),
    reap one (``R``: pid, flags); returns when the parent closes its end."""
    while True:
        try:
            op, fds, _, _ = socket.recv_fds(sock, 1, 2)
        except OSError:
            return
        if not op:
            return  # the parent closed its end
        if op == b"F":
            pid = os.fork()
            if pid == 0:  # the child: its pipes as stdin and stdout, the template's state
                try:
                    sock.close()
                    os.dup2(fds[0], 0)
                    os.dup2(fds[1], 1)
                    for f in fds:
                        os.close(f)
                    _answer(states)
                finally:
                    os._exit(0)
            for f in fds:
                os.close(f)
            sock.sendall(_PID.pack(pid))
        elif op == b"R":
            (child,) = _PID.unpack(_recv_exact(sock, _PID.size))
            flags = _recv_exact(sock, 1)[0]
            sock.sendall(_PID.pack(_reap_child(child, flags)))


def _reap_child(pid: int, flags: int) -> int:
    """Kill (flag 1) and/or wait for (flag 2) one of the template's children: its exit code
    as :class:`subprocess.Popen` gives it, or ``_RUNNING``."""
    if flags & 1:
        _kill(pid)
    try:
        done, status = os.waitpid(pid, 0 if flags & 2 else os.WNOHANG)
    except ChildProcessError:
        return _RUNNING
    return os.waitstatus_to_exitcode(status) if done else _RUNNING


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
    if sys.argv[1:2] == ["--template"]:
        _template(int(sys.argv[2]), sys.argv[3:])
    else:
        _serve(sys.argv[1:])
