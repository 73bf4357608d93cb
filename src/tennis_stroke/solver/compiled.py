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
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import subprocess
import sys
from pathlib import Path

from .._cache import compiled_sources

#: Set in the compiling process, and by a user who wants to compile in place.
ENV = "TENNIS_STROKE_WARMUP"
#: Groups of entry points compiled together: the stroke batch and the contact phase
#: alone, each per method (a run of DOP853 compiles no DP54), and the scipy reference
#: path's right-hand sides.
GROUPS = ("batch:DOP853", "batch:DP54", "contact:DOP853", "contact:DP54", "reference")
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


def ensure_compiled(group: str) -> None:
    """Make sure numba's cache holds the entry points of ``group`` (compiling them in a
    subprocess if not)."""
    if group not in GROUPS:
        raise ValueError(f"unknown group of compiled entry points {group!r}")
    if group in _done or os.environ.get(ENV) == "0":
        return
    marker = _marker(group)
    if marker is not None and not marker.exists():
        try:
            marker.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise CompileCacheError(
                f"cannot use the compiled code's cache folder {str(marker.parent)!r}: "
                f"{exc.strerror} (set NUMBA_CACHE_DIR or XDG_CACHE_HOME to a folder)"
            ) from None
        with open(marker.parent / ".compile.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if not marker.exists():
                done = subprocess.run(
                    [sys.executable, "-m", "tennis_stroke.solver.warmup", group],
                    env={**os.environ, ENV: "0"},
                    capture_output=True,
                    text=True,
                )
                if done.returncode != 0:
                    last = (done.stderr.strip().splitlines() or ["(no output)"])[-1]
                    raise RuntimeError(f"compiling the solver failed: {last}")
                marker.touch()
    _done.add(group)
