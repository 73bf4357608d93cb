"""Where the robustness analysis' time goes: cProfile of ``evaluate_readings`` (the
robustness chunk's work) on a few kept readings of a finished run.

Usage (from the project's folder, after ``snakemake -j2 report``)::

    python benchmarks/profile_readings.py [--readings 2] [--top 25] [--sort cumulative]

It reads the shipped configuration as the workflow does (the schema's defaults, one
spelling per value), the kept readings ``results/robustness/readings.nc``, evaluates the
first ``--readings`` once untimed (the compiled code's first load), then again under
cProfile, and prints the elapsed time and the functions by their own time (or, with
``--sort cumulative``, by the time spent in them and what they call).  Used in
issue 35 to find the ``repr`` of every parameter value that a search's stroke batches
paid for an error they never raised.  It also counts, in the profiled evaluation, the
rows the compiled solver was given and the swings it integrated for them (rows that
differ only in the ball, the spring or the contact's timing share one swing:
``solver.stroke.swings_integrated``).
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import time

import yaml
from snakemake.utils import validate

import tennis_stroke.solver.stroke as stroke
from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.inference.robustness import evaluate_readings
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.pipeline import params as job_params
from tennis_stroke.pipeline.config_check import canonical, load_schema
from tennis_stroke.solver.settings import SolverSettings

SCHEMA = "workflow/schemas/config.schema.yaml"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--readings", type=int, default=2, help="kept readings to profile")
    parser.add_argument("--top", type=int, default=25, help="functions to print")
    parser.add_argument(
        "--sort", default="tottime", help="pstats order: tottime (own time) or cumulative"
    )
    args = parser.parse_args()
    config = yaml.safe_load(open("config/config.yaml"))
    validate(config, SCHEMA, set_default=True)
    config = canonical(config, load_schema(SCHEMA))
    common = job_params.common_params(config)
    experiments = {**job_params.paper_experiments(config), "model": common["model"]}
    claims, space = claims_and_readings("config/claims.yaml", "config/readings.yaml")
    kept = load_result("results/robustness/readings.nc")
    settings = SolverSettings(**common["solver"])
    # rows (i, n): chunk i of n; the first of kept / readings chunks holds `readings`
    rows = (0, max(1, kept.sizes["reading"] // args.readings))
    evaluate_readings(claims, space, kept, experiments, settings, rows, 1)
    counted = stroke.swings_integrated()
    profile = cProfile.Profile()
    start = time.perf_counter()
    profile.enable()
    evaluate_readings(claims, space, kept, experiments, settings, rows, 1)
    profile.disable()
    print(f"elapsed under cProfile: {time.perf_counter() - start:.2f} s")
    rows, swings = (b - a for a, b in zip(counted, stroke.swings_integrated(), strict=True))
    print(f"rows solved: {rows}; swings integrated: {swings}")
    pstats.Stats(profile).sort_stats(args.sort).print_stats(args.top)


if __name__ == "__main__":
    main()
