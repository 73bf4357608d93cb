"""Support for the workflow's thin scripts: settings from params, logging, provenance."""

from __future__ import annotations

import contextlib
import hashlib
import json
import time
from collections.abc import Iterator, Mapping
from pathlib import Path

import numpy as np
import xarray as xr

from .experiments import grid
from .io import write_netcdf
from .stroke import SolverSettings


def settings(common: Mapping[str, object]) -> SolverSettings:
    """Solver settings from the ``common`` params of a rule."""
    return SolverSettings(**common["solver"])


def axis(spec) -> np.ndarray:
    """A ``[start, stop, step]`` params list (or a config range dict) as a grid."""
    if isinstance(spec, Mapping):
        spec = [spec["start"], spec["stop"], spec["step"]]
    return grid(*map(float, spec))


@contextlib.contextmanager
def logged(log_path: str | Path) -> Iterator[None]:
    """Send stdout and stderr of a script to its Snakemake log file."""
    Path(log_path).parent.mkdir(parents=True, exist_ok=True)
    with (
        open(log_path, "w") as log,
        contextlib.redirect_stdout(log),
        contextlib.redirect_stderr(log),
    ):
        yield


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


def save(ds: xr.Dataset, path: str | Path, params, wall_time: float) -> None:
    """Add the job's provenance (config hash and text, wall time) and write atomically."""
    items = dict(params.items()) if hasattr(params, "items") else dict(params)
    ds.attrs["config_sha256_16"] = params_hash(items)
    ds.attrs["config"] = json.dumps(items, sort_keys=True, default=str)
    ds.attrs["wall_time_s"] = float(wall_time)
    write_netcdf(ds, path)
    print(f"wrote {path} in {wall_time:.2f} s")
