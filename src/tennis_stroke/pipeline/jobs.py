"""Support for the workflow's thin scripts: settings, chunks, logging, provenance.

A script reads ``snakemake.params`` and ``snakemake.wildcards``, makes one package call
and saves its result with :func:`save`; :func:`logged` turns any exception into one
line on stderr and the traceback in the job's log.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import sys
import time
import traceback
from collections.abc import Iterator, Mapping
from pathlib import Path

import xarray as xr

from ..io.interrupts import Terminated, job_stop_status, stop_with_snakemake, terminate_raises
from ..io.netcdf import write_netcdf
from ..solver.settings import SolverSettings
from .chunks import mark_chunk


def settings(common: Mapping[str, object]) -> SolverSettings:
    """Solver settings from the ``common`` params of a rule."""
    return SolverSettings(**common["solver"])


@contextlib.contextmanager
def logged(log_path: str | Path) -> Iterator[None]:
    """Send stdout and stderr of a script to its Snakemake log file.

    An exception ends the job with its traceback in the log, one line on stderr naming
    the problem and the log, and exit status 1 (Snakemake then reports the failed rule);
    SIGINT and SIGTERM end it with one line and status 130 or 143, no traceback.
    """
    Path(log_path).parent.mkdir(parents=True, exist_ok=True)
    entered = time.perf_counter()
    with terminate_raises(), stop_with_snakemake(), open(log_path, "w") as log:
        try:
            with contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
                yield
                print(time_split(entered))
        except (KeyboardInterrupt, Terminated) as exc:
            raise SystemExit(job_stop_status(exc, log_path)) from None
        except Exception as exc:
            traceback.print_exc(file=log)
            message = str(exc).splitlines()[0] if str(exc) else ""
            problem = f"{type(exc).__name__}: {message}" if message else type(exc).__name__
        else:
            return
    sys.stderr.write(f"tennis-stroke job failed: {problem} (traceback in {log_path})\n")
    raise SystemExit(1)


#: Seconds this job spent writing its result files (:func:`save`).
WRITE_SECONDS = [0.0]
#: The line a job's log ends with: where its time went (``benchmarks/job_split.py``).
SPLIT_PREFIX = "job time (s):"
SPLIT_PARTS = ("start-up", "imports", "compiled code", "compute", "writing")


def _process_age() -> float:
    """Seconds since this process started (Linux ``/proc``; NaN elsewhere)."""
    try:
        start = int(Path("/proc/self/stat").read_text().rsplit(")", 1)[1].split()[19])
        uptime = float(Path("/proc/uptime").read_text().split()[0])
    except (OSError, IndexError, ValueError):
        return float("nan")
    return uptime - start / os.sysconf("SC_CLK_TCK")


def time_split(entered: float) -> str:
    """Where this job's time went, as its log's last line: start-up (the interpreter and
    Snakemake's preamble, until the package's first import), imports (until the job's
    block, ``entered``), compiled code (loading it, :mod:`tennis_stroke.solver.compiled`),
    compute, and writing its files (:func:`save`).  The start-up is read from ``/proc``
    at a resolution of 10 ms."""
    import tennis_stroke

    now = time.perf_counter()
    imports = entered - tennis_stroke.IMPORT_STARTED
    startup = _process_age() - (now - tennis_stroke.IMPORT_STARTED)
    compiled = sys.modules.get("tennis_stroke.solver.compiled")
    loading = compiled.SECONDS[0] if compiled is not None else 0.0
    compute = now - entered - loading - WRITE_SECONDS[0]
    parts = (startup, imports, loading, compute, WRITE_SECONDS[0])
    return f"{SPLIT_PREFIX} " + ", ".join(
        f"{name} {value:.3f}" for name, value in zip(SPLIT_PARTS, parts, strict=True)
    )


def chunk_position(wildcards) -> tuple[int, int]:
    """Index and count of this job's chunk (wildcards ``chunk`` of ``chunks``)."""
    return int(wildcards.chunk), int(wildcards.chunks)


class Timer:
    """Wall time since creation (s)."""

    def __init__(self) -> None:
        self.start = time.perf_counter()

    def __call__(self) -> float:
        return time.perf_counter() - self.start


def params_hash(params) -> str:
    """SHA-256 (16 hex digits) of a rule's params: the configuration this job used.

    (A hash of the whole config as a rule param would rerun every job on any change.)
    """
    items = dict(params.items()) if hasattr(params, "items") else dict(params)
    return hashlib.sha256(json.dumps(items, sort_keys=True, default=str).encode()).hexdigest()[:16]


def save(
    ds: xr.Dataset,
    path: str | Path,
    params,
    wall_time: float,
    chunk_of=None,
) -> None:
    """Add the job's provenance (config hash and text, wall time) and write atomically.

    ``chunk_of``: the job's wildcards, to mark the file as chunk ``chunk`` of ``chunks``
    of a map (:func:`tennis_stroke.pipeline.chunks.mark_chunk`).
    """
    if chunk_of is not None:
        mark_chunk(ds, *chunk_position(chunk_of))
    items = dict(params.items()) if hasattr(params, "items") else dict(params)
    ds.attrs["config_sha256_16"] = params_hash(items)
    ds.attrs["config"] = json.dumps(items, sort_keys=True, default=str)
    ds.attrs["wall_time_s"] = float(wall_time)
    start = time.perf_counter()
    write_netcdf(ds, path)
    WRITE_SECONDS[0] += time.perf_counter() - start
    print(f"wrote {path} in {wall_time:.2f} s")
