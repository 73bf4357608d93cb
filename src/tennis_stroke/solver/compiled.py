"""Compile the solver once, in a process of its own, and run only cached code.

Measured (2026-11-22): a process that compiles the solver itself can give results that
differ in the last bits (6e-14 km/h on one stroke of the tiny elbow-force map) from a
process that loads the same functions from numba's on-disk cache.  So that every job of
the workflow, every CLI call and every test gives the same bits whatever ran before, the
first call of an entry point of the compiled solver in a process (:func:`ensure_compiled`)
makes sure the cache holds it: if not, it runs ``python -m tennis_stroke.solver.warmup
GROUP`` (which compiles that group of entry points and writes the cache) and then loads
from the cache.  The groups (:data:`GROUPS`) compile apart, so a first stroke does not
wait for the contact-phase entry or the scipy reference path's right-hand sides.  A file lock makes
jobs that start together on a fresh machine wait for one compilation instead of each
compiling.

A group's cache is known to be complete by a marker file in ``NUMBA_CACHE_DIR`` named after the
checkout's path and the compiled sources' modification times, the two things besides the
sources' contents (already in the cache directory's name) that numba's cache index checks.
``TENNIS_STROKE_WARMUP=0`` turns the mechanism off (the process compiles in place).

This module imports nothing of the solver: the module that owns a group's entry points
passes the function that calls them (:func:`ensure_compiled`), and the compiling process
runs :mod:`tennis_stroke.solver.warmup`, which imports those modules from above (nothing
of the solver imports it).
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import shutil
import subprocess
import sys
import time
import traceback
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from .._cache import compiled_sources

#: Set in the compiling process, and by a user who wants to compile in place.
ENV = "TENNIS_STROKE_WARMUP"
#: Groups of entry points compiled together: the stroke batch and the contact phase
#: alone, each per method (a run of DOP853 compiles no DP54), the strokes' curves
#: (:mod:`tennis_stroke.solver.curves`, DOP853 only), the scipy reference path's
#: right-hand sides, and fixed-step RK4's compiled steps and the model functions it
#: (:mod:`tennis_stroke.solver.rk4`, the solver studies' baseline) calls from Python.
GROUPS = (
    "batch:DOP853",
    "batch:DP54",
    "contact:DOP853",
    "contact:DP54",
    "curves",
    "reference",
    "rk4",
)
_done: set[str] = set()


class CompileCacheError(OSError):
    """The compiled code's cache folder cannot be used (message is one line)."""


def _marker(group: str) -> Path | None:
    """The marker of a complete cache of ``group`` for this checkout, or None without a
    cache dir."""
    cache = os.environ.get("NUMBA_CACHE_DIR")
    if not cache:
        return None
    digest = hashlib.sha256(str(Path(__file__).resolve().parents[1]).encode())
    for path in compiled_sources():
        digest.update(f"{path.name}:{path.stat().st_mtime_ns}".encode())
    return Path(cache) / f"compiled-{group.replace(':', '-')}-{digest.hexdigest()[:16]}"


#: numba's module that reads and writes the on-disk cache: an error raised from it is a
#: damaged cache file, in this process (a traceback frame) or in the compiling one (its
#: stderr).
CACHING_MODULE = "numba/core/caching.py"


def _cache_trouble(exc: BaseException) -> bool:
    """Whether ``exc`` was raised while numba read its on-disk cache (a damaged file)."""
    return any(
        Path(frame.filename).as_posix().endswith(CACHING_MODULE)
        for frame in traceback.extract_tb(exc.__traceback__)
    )


def _say(text: str) -> None:
    sys.stderr.write(f"tennis-stroke: {text}\n")


def _clear(marker: Path) -> None:
    """Remove this checkout's cached functions and markers from the cache folder of
    ``marker`` (other checkouts of the same sources keep theirs): numba keeps a source
    folder's functions in a subfolder named after that folder's path."""
    folder, suffix = marker.parent, marker.name.rsplit("-", 1)[1]
    for path in folder.glob(f"compiled-*-{suffix}"):
        path.unlink(missing_ok=True)
    for source in compiled_sources():
        shutil.rmtree(folder / cache_subfolder(source), ignore_errors=True)


def cache_subfolder(source: Path) -> str:
    """The subfolder of ``NUMBA_CACHE_DIR`` in which numba caches the functions of
    ``source``: numba's ``_CacheLocator.get_suitable_cache_subpath`` (the source folder's
    name and the SHA-1 of its absolute path), written out here so that this module does
    not import numba (tests/solver/test_warmup.py compares the two)."""
    parent = os.path.dirname(os.path.abspath(source))
    return f"{os.path.basename(parent)}_{hashlib.sha1(parent.encode()).hexdigest()}"


def _compile(group: str, marker: Path) -> None:
    """Compile ``group`` into the cache in a process of its own (under the folder's lock),
    unless ``marker`` says it is there; a compile that trips over a damaged cache file
    clears the folder and compiles again."""
    try:
        marker.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CompileCacheError(
            f"cannot use the compiled code's cache folder {str(marker.parent)!r}: "
            f"{exc.strerror} (set NUMBA_CACHE_DIR or XDG_CACHE_HOME to a folder)"
        ) from None
    with open(marker.parent / ".compile.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        for attempt in (1, 2):
            if marker.exists():
                return
            done = subprocess.run(
                [sys.executable, "-m", "tennis_stroke.solver.warmup", group],
                env={**os.environ, ENV: "0"},
                capture_output=True,
                text=True,
            )
            if done.returncode == 0:
                marker.touch()
                return
            last = (done.stderr.strip().splitlines() or ["(no output)"])[-1]
            if attempt == 1 and CACHING_MODULE in done.stderr:
                _say(
                    f"the compiled code's cache in {str(marker.parent)!r} is damaged "
                    f"({last}): cleared, compiling again"
                )
                _clear(marker)
                continue
            raise RuntimeError(f"compiling the solver failed: {last}")


def _heal(group: str, marker: Path, why: str) -> None:
    """Clear the cache folder of ``marker`` and compile ``group`` into it again."""
    with open(marker.parent / ".compile.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        _clear(marker)
    _say(f"the compiled code's cache in {str(marker.parent)!r} {why}: cleared and compiled again")
    _compile(group, marker)


#: Seconds this process spent making sure of and loading its compiled code (a job's log
#: reports it apart from its compute, :func:`tennis_stroke.pipeline.jobs.logged`).
SECONDS = [0.0]


def ensure_compiled(group: str, exercise: Callable[[], object]) -> None:
    """Make sure numba's cache holds the entry points of ``group`` (compiling them in a
    subprocess if not), and load them in this process by calling ``exercise`` (the caller's
    function that calls them with the argument types the package passes; it may call back
    here: the group then counts as loading).

    The load is checked: a cache file that cannot be read (truncated, emptied, garbage)
    or an entry point missing from a cache said complete (numba then compiles in this
    process) clears the cache and compiles it again, in one line on stderr.
    """
    if group not in GROUPS:
        raise ValueError(f"unknown group of compiled entry points {group!r}")
    if group in _done or os.environ.get(ENV) == "0":
        return
    marker = _marker(group)
    if marker is None:  # no cache: numba compiles in this process
        _done.add(group)
        return
    start = time.perf_counter()
    _compile(group, marker)
    _done.add(group)  # the loading calls below come back here
    try:
        _load(group, marker, exercise)
    except BaseException:
        _done.discard(group)
        raise
    finally:
        SECONDS[0] += time.perf_counter() - start


class CompileInPlace(Exception):
    """numba was about to compile in this process: the cache lacks an entry point
    (raised by :func:`refusing_compiles`)."""


@contextmanager
def refusing_compiles() -> Iterator[None]:
    """Inside the block numba may load compiled code from its cache but not compile:
    a compile raises :class:`CompileInPlace` before it starts (numba's ``numba:compile``
    event), so the process keeps only cached code."""
    from numba.core import event

    class Refuse(event.Listener):
        def on_start(self, ev):
            raise CompileInPlace()

        def on_end(self, ev):
            pass

    with event.install_listener("numba:compile", Refuse()):
        yield


def _load(group: str, marker: Path, exercise: Callable[[], object]) -> None:
    """Load ``group`` from the cache in this process by calling ``exercise`` with numba's
    compiling refused; a cache file numba cannot read, or a compile in place (refused
    before it starts), clears this checkout's cache and compiles it again in a process of
    its own, then loads."""
    try:
        with refusing_compiles():
            exercise()
        return
    except CompileInPlace:
        why = "lacked an entry point it was said to hold"
    except Exception as exc:
        if not _cache_trouble(exc):
            raise
        first = str(exc).splitlines()[0] if str(exc) else ""
        why = f"is damaged ({type(exc).__name__}: {first})"
    _heal(group, marker, why)
    with refusing_compiles():
        exercise()
