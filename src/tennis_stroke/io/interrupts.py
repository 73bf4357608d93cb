"""Signals while a file is written: SIGINT and SIGTERM end a command within a second,
with no temporary file left and no earlier output lost.

An interrupt that lands inside the netCDF library leaves xarray's HDF5 lock held (the
``KeyboardInterrupt`` is raised between the library's acquire and release), and closing
the file then waits on that lock forever (seen: ``tennis-stroke sweep`` and a workflow job
asleep on a futex in ``xarray.backends.locks``).  So a write runs with the two signals
deferred (:func:`deferred_signals`): a signal that arrives is recorded, the write
finishes or fails on its own, its temporary file is removed instead of renamed, and
the signal is delivered again afterwards.  SIGTERM, which would end the interpreter
without cleanup, raises :class:`Terminated` where :func:`terminate_raises` is in force
(the command line and the workflow's jobs).
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from collections.abc import Iterator

#: The signals deferred during a write.
SIGNALS = (signal.SIGINT, signal.SIGTERM)
#: Exit statuses after them, as a shell reports them (128 + the signal's number).
EXIT_STATUS = {signal.SIGINT: 130, signal.SIGTERM: 143}


class Terminated(BaseException):
    """SIGTERM as an exception (like KeyboardInterrupt for SIGINT): cleanup code runs."""


def _raise_terminated(signum, frame) -> None:
    raise Terminated()


@contextlib.contextmanager
def terminate_raises() -> Iterator[None]:
    """Inside the block SIGTERM raises :class:`Terminated` (main thread only); the
    previous handler is back on leaving it, so a caller that runs the command line in its
    own process (a test run) still ends on SIGTERM afterwards."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


@contextlib.contextmanager
def deferred_signals() -> Iterator[list[int]]:
    """Record SIGINT and SIGTERM instead of acting on them; yields the list of those
    received.  On leaving, the previous handlers are back and the first signal received
    is raised again (:func:`signal.raise_signal`), after the caller's cleanup.  Outside
    the main thread signals cannot be handled there, and nothing is deferred."""
    received: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield received
        return
    previous = {s: signal.getsignal(s) for s in SIGNALS}

    def record(signum, frame) -> None:
        received.append(signum)

    for s in SIGNALS:
        signal.signal(s, record)
    try:
        yield received
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    if received:
        signal.raise_signal(received[0])


#: The Snakemake process that started a workflow job, as ``PID:START`` (its start time
#: in clock ticks after boot, so that a reused PID is not taken for it); set by the
#: Snakefile (:func:`process_identity`), inherited by the jobs' processes.
PARENT_ENV = "TENNIS_STROKE_SNAKEMAKE"
#: Seconds between two looks at it.
WATCH_INTERVAL = 0.5


def process_identity(pid: int) -> str:
    """``PID:START`` of process ``pid`` (START empty where ``/proc`` is not there)."""
    try:
        with open(f"/proc/{pid}/stat") as file:
            stat = file.read()
    except OSError:
        return f"{pid}:"
    return f"{pid}:{stat.rsplit(')', 1)[1].split()[19]}"


def _alive(identity: str) -> bool:
    pid = int(identity.split(":")[0])
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        pass
    return identity.endswith(":") or process_identity(pid) == identity


@contextlib.contextmanager
def stop_with_snakemake() -> Iterator[None]:
    """Inside the block, the end of the Snakemake process named in :data:`PARENT_ENV`
    (killed with SIGKILL, say) sends this process SIGTERM within :data:`WATCH_INTERVAL`
    seconds: a job whose workflow died stops instead of computing on and writing its
    output after it (a write in progress finishes first, :func:`deferred_signals`).
    Nothing happens outside a workflow job."""
    identity = os.environ.get(PARENT_ENV, "")
    if not identity or not identity.split(":")[0].isdigit():
        yield
        return
    done = threading.Event()

    def watch() -> None:
        while not done.wait(WATCH_INTERVAL):
            if not _alive(identity):
                sys.stderr.write(
                    f"tennis-stroke job: its Snakemake (pid {identity.split(':')[0]}) ended: "
                    "stopping\n"
                )
                os.kill(os.getpid(), signal.SIGTERM)
                return

    threading.Thread(target=watch, name="stop-with-snakemake", daemon=True).start()
    try:
        yield
    finally:
        done.set()


#: What a command that runs Snakemake for the user passes on of the signals it receives:
#: Ctrl-C as Ctrl-C, a termination or a closed terminal as SIGTERM.  Snakemake stops on
#: either, its jobs first, and removes its locks (``.snakemake/locks``).
FORWARDED = {
    signal.SIGINT: signal.SIGINT,
    signal.SIGTERM: signal.SIGTERM,
    signal.SIGHUP: signal.SIGTERM,
}


def run_forwarding(command: list[str]) -> int:
    """Run ``command`` (Snakemake) in a process group of its own and wait for it; a
    SIGINT, SIGTERM or SIGHUP this process receives meanwhile is passed on once
    (:data:`FORWARDED`) and the command is waited for, so it can stop its jobs and remove
    its locks; then the signal ends this process as it would have (KeyboardInterrupt,
    :class:`Terminated`).  Returns the command's exit status otherwise.  (A child left
    in the terminal's group would get Ctrl-C twice, and ``subprocess.run`` kills it
    0.25 s after Ctrl-C, before Snakemake removed its locks.)"""
    import subprocess

    received: list[int] = []
    proc = subprocess.Popen(command, process_group=0)

    def forward(signum, frame) -> None:
        if not received and proc.poll() is None:
            proc.send_signal(FORWARDED[signum])
        received.append(signum)

    main = threading.current_thread() is threading.main_thread()
    previous = {s: signal.getsignal(s) for s in FORWARDED} if main else {}
    previous = {s: h for s, h in previous.items() if h is not signal.SIG_IGN}  # nohup
    for s in previous:
        signal.signal(s, forward)
    try:
        code = proc.wait()
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    if received and received[0] == signal.SIGINT:
        raise KeyboardInterrupt
    if received:
        raise Terminated()
    return code
