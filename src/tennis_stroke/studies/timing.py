"""One timing harness for the studies: wall-clock medians, and the compiled solver's
cost per stroke on one thread."""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from functools import partial

import numpy as np

from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch

#: Strokes per timed batch of the compiled solver: the batch's fixed cost (thread
#: start, about 1 ms) then does not count per stroke.
TIMING_STROKES = 4000
#: Attribute of variables that hold wall-clock measurements (the only numbers of a
#: result file that differ between two runs of the same configuration).
TIMING = {"timing": "wall-clock measurement: differs between runs"}


def timed(fn: Callable[[], object], repeats: int) -> tuple[np.ndarray, object]:
    """Wall times (s) of ``repeats`` calls of ``fn`` and the last call's result."""
    times, out = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return np.array(times), out


def median_time(fn: Callable[[], object], repeats: int) -> tuple[float, object]:
    """Median wall time (s) of ``repeats`` calls of ``fn`` and the last call's result."""
    times, out = timed(fn, repeats)
    return float(np.median(times)), out


def compiled_costs(
    theta0: np.ndarray,
    delta0: np.ndarray,
    params: Mapping[str, object],
    settings: SolverSettings | None,
    repeats: int,
    strokes: int = TIMING_STROKES,
) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Microseconds per stroke of the compiled solver on one thread, one per repeat, and
    the results.

    The strokes (one parameter value per stroke) are repeated up to ``strokes`` and timed
    as one batch ``repeats`` times; the results returned are those of the given strokes.
    Every copy integrates its own swing (``share_swings=False``): the copies of a stroke
    would otherwise share one, and the time would not be a stroke's.
    """
    n = theta0.size
    reps = max(1, strokes // n)
    big = {k: np.tile(v, reps) if np.ndim(v) else v for k, v in params.items()}  # options
    th, de = np.tile(theta0, reps), np.tile(delta0, reps)
    batch = partial(strike_batch, th, de, big, settings, threads=1, share_swings=False)
    walls, res = timed(batch, repeats)
    return walls / th.size * 1e6, {k: v[:n] for k, v in res.items()}


def compiled_cost(
    theta0: np.ndarray,
    delta0: np.ndarray,
    params: Mapping[str, object],
    settings: SolverSettings | None,
    repeats: int,
) -> tuple[float, dict[str, np.ndarray]]:
    """Microseconds per stroke of the compiled solver on one thread (the median of
    ``repeats`` batches of :data:`TIMING_STROKES` strokes, :func:`compiled_costs`), and
    the results of the given strokes."""
    us, res = compiled_costs(theta0, delta0, params, settings, repeats)
    return float(np.median(us)), res
