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

Snakemake 9.27 does not stop its local jobs when it ends (on SIGTERM it waits for them,
SIGINT to its process alone and ``kill -9`` leave them running and writing; measured
2026-12-07; snakemake/snakemake#448, #492 open), so a job watches it
(:func:`stop_with_snakemake`) and ``whatif`` signals Snakemake's whole process group
(:func:`run_forwarding`).
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


def job_stop_status(exc: BaseException, log_path: str | None = None) -> int:
    """Write the one line of a workflow job stopped by ``exc`` (KeyboardInterrupt or
    :class:`Terminated`) to stderr, naming its log where it has one; returns its exit
    status (130 or 143)."""
    interrupted = isinstance(exc, KeyboardInterrupt)
    where = f" (log in {log_path})" if log_path else ""
    sys.stderr.write(f"tennis-stroke job {'interrupted' if interrupted else 'terminated'}{where}\n")
    return EXIT_STATUS[signal.SIGINT if interrupted else signal.SIGTERM]


def quiet_job_stops() -> None:
    """From here to the end of this process (a workflow job's script calls it first,
    before its imports, which take most of a short job's time): SIGTERM raises
    :class:`Terminated`, and an interrupt nothing catches (Ctrl-C or SIGTERM during the
    imports, say) ends the process with one line and the signal's exit status (130 or
    143), never a traceback (``sys.excepthook``).  Inside the job's block,
    :func:`tennis_stroke.pipeline.jobs.logged` catches them itself, naming the log."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _raise_terminated)
    previous = sys.excepthook

    def hook(kind, value, traceback) -> None:
        if not issubclass(kind, KeyboardInterrupt | Terminated):
            previous(kind, value, traceback)
            return
        status = job_stop_status(value)
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(status)  # nothing is left to clean up: the exception reached the top

    sys.excepthook = hook


#: What a command that runs Snakemake for the user passes on of the signals it receives:
#: each as Ctrl-C, to Snakemake's whole process group, its jobs included, as a terminal's
#: Ctrl-C does: the jobs stop at once (Snakemake alone would wait for them), Snakemake
#: then stops and removes its locks (``.snakemake/locks``).  Never SIGTERM: Snakemake's
#: SIGTERM handler (``JobScheduler.exit_gracefully``, 9.15) takes the scheduler's
#: non-reentrant lock from the main thread, which may hold it already (it does while it
#: handles the job the same signal just stopped): Snakemake then hangs for ever (a
#: `tennis-stroke whatif` stopped by SIGHUP hung 300 s, 2026-12-07).  Ctrl-C raises
#: KeyboardInterrupt there instead, which leaves the lock as it unwinds.  This process
#: still ends with the status of the signal it received.
FORWARDED = {
    signal.SIGINT: signal.SIGINT,
    signal.SIGTERM: signal.SIGINT,
    signal.SIGHUP: signal.SIGINT,
}
#: ``prctl`` option: the signal a process gets when its parent ends (Linux).
PR_SET_PDEATHSIG = 1


def _die_with_parent(parent: int):
    """A ``preexec_fn`` for the child of process ``parent``: SIGKILL when the parent
    ends, also by SIGKILL (Linux ``prctl(PR_SET_PDEATHSIG)``; elsewhere None, nothing)."""
    import ctypes

    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl  # the C library's, on Linux
    except (OSError, AttributeError):
        return None

    def child() -> None:
        prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
        if os.getppid() != parent:  # the parent ended before prctl: end too
            os.kill(os.getpid(), signal.SIGKILL)

    return child


def run_forwarding(command: list[str]) -> int:
    """Run ``command`` (Snakemake) in a process group of its own and wait for it; each
    SIGINT, SIGTERM or SIGHUP this process receives meanwhile is passed on to that
    group (:data:`FORWARDED`) and the command is waited for, so its jobs stop and it
    removes its locks; then the first signal ends this process as it would have
    (KeyboardInterrupt, :class:`Terminated`).  Returns the command's exit status
    otherwise.  (A child left in the terminal's group would get Ctrl-C twice, and
    ``subprocess.run`` kills it 0.25 s after Ctrl-C, before Snakemake removed its locks.)

    Should this process end without a signal it can handle (``kill -9``), the command
    gets SIGKILL from the kernel (:func:`_die_with_parent`), and its jobs, which watch
    their Snakemake (:func:`stop_with_snakemake`), stop within a second: nothing runs on
    unseen, and the next run removes the locks left and reruns the jobs left incomplete
    (``tennis_stroke.pipeline.checkout.hold_folder``, ``--rerun-incomplete``)."""
    import subprocess

    received: list[int] = []
    proc = subprocess.Popen(command, process_group=0, preexec_fn=_die_with_parent(os.getpid()))

    def forward(signum, frame) -> None:
        received.append(signum)
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(proc.pid, FORWARDED[signum])

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
