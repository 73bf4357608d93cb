"""What a job asks of the scheduler, Snakemake's ``resources: mem_mb, runtime``, from its
size, and the declared bound on that size.

A job's size is its **points**: the strokes it holds in one batch (a map's chunk, a
claim's search for every reading searched in lockstep, a study's optimum search) or the
(stroke, time) samples of its curves.  The config key ``max_points_per_job`` bounds
them, checked before any job (:func:`tennis_stroke.pipeline.config_check.points_errors`):
a mistyped step (1e-6 degrees) is refused at planning in one line naming its key, and a
map too large for one job is split with ``chunks``.  What a job asks follows from its
points, never from the machine: a cluster (``profiles/slurm``) enforces it, and on one
machine ``snakemake --resources mem_mb=8000`` runs only the jobs that fit together.
"""

from __future__ import annotations

import math

#: Memory (MB) every job asks besides its points: the interpreter with numpy, xarray,
#: matplotlib, numba and the compiled solver.  The report's largest job peaked at 869 MB
#: (max_rss of logs/benchmarks/robustness_screen.tsv after ``make report``,
#: 2026-12-07); the rest asks for room.
BASE_MB = 1500
#: Memory (bytes) asked per point: a stroke of a batch holds 456 bytes of the solver's
#: arrays (its angles, coefficients, order, output and result fields: 57 float64 values),
#: a curve's sample at most 240; asked about twice over, for the file being written.
BYTES_PER_POINT = 1024
#: Minutes every job asks besides its points (start-up, a cold compile of the solver:
#: under a minute here).
BASE_MINUTES = 15
#: Seconds asked per point: a compiled stroke costs 15-25 µs on one core, a search runs a
#: few batches; asked 20 times over.
SECONDS_PER_POINT = 5e-4
#: The default bound on a job's points (config key ``max_points_per_job``): the paper's
#: largest job holds 647,808 (a robustness chunk's search of the Figs. 2-3 maps' claims,
#: 5061 strokes for each of 128 readings); at the bound a job asks about 11 GB and 1.6 h.
DEFAULT_MAX_POINTS = 10_000_000


def mem_mb(points: int) -> int:
    """Memory (MB, Snakemake's ``mem_mb``) a job of ``points`` asks for."""
    return BASE_MB + math.ceil(max(0, int(points)) * BYTES_PER_POINT / 1e6)


def runtime(points: int) -> int:
    """Minutes (Snakemake's ``runtime``) a job of ``points`` asks for."""
    return BASE_MINUTES + math.ceil(max(0, int(points)) * SECONDS_PER_POINT / 60.0)


def asked(points: int) -> dict[str, int]:
    """Both resources of a job of ``points``."""
    return {"mem_mb": mem_mb(points), "runtime": runtime(points)}
