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
import signal
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


def terminate_raises() -> None:
    """From now on SIGTERM raises :class:`Terminated` (main thread only)."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _raise_terminated)


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
