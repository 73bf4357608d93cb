"""Speed and accuracy of the compiled solver against straightforward ``solve_ivp``.

Measures, in one run on one machine:

* the compiled solver (default settings) on the 241 x 181 (theta0, delta0) grid of Fig. 2
  (theta0 60..120 deg, delta0 0..90 deg): microseconds per stroke, with 1 thread and with
  all threads (median of ``--repeats``), the mean right-hand-side evaluations and
  accepted steps per stroke, and the largest |v_out - reference| where the
  reference is the compiled DOP853 at rtol = atol = 1e-12;
* the whole ``tennis-stroke sweep`` process on that grid (start-up, cache load, netCDF);
* ``scipy.integrate.solve_ivp`` (DOP853, events, the same phase splitting:
  :func:`tennis_stroke.solver.reference.solve_stroke`) on a seeded random subset of the grid, at
  the loosest tolerance whose largest error on that subset is within ``--target`` km/h
  ("matched accuracy"); its per-stroke cost is a median over the subset.

Usage::

    python benchmarks/bench_sweep.py [--subset 200] [--repeats 3] [--target 1e-4]
                                     [--compiled-only]

Prints a Markdown table; ``--json FILE`` also writes the numbers.  ``--compiled-only``
measures the compiled solver alone (no sweep process, no ``solve_ivp``): a few seconds,
for side-by-side runs of two commits.  Not a test: timings
vary with the machine's load, so read the ratios, measured side by side.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from tennis_stroke import SolverSettings, strike_batch
from tennis_stroke.solver.reference import solve_stroke
from tennis_stroke.solver.stroke import default_threads

THETA0 = np.linspace(60.0, 120.0, 241)
DELTA0 = np.linspace(0.0, 90.0, 181)
SCIPY_RTOLS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10)


def timed(fn, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--subset", type=int, default=200, help="strokes for solve_ivp")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--target", type=float, default=1e-4, help="accuracy target (km/h)")
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument(
        "--compiled-only", action="store_true", help="the compiled solver alone (no baseline)"
    )
    args = ap.parse_args()

    th, de = THETA0[:, None], DELTA0[None, :]
    n = THETA0.size * DELTA0.size
    settings = SolverSettings()
    reference = strike_batch(th, de, settings=SolverSettings(rtol=1e-12, atol=1e-12, history=4096))
    ok = reference["status"] == 0
    n_threads = default_threads()
    rows = {}
    for threads in sorted({1, n_threads}):
        strike_batch(th[:2], de, settings=settings, threads=threads)  # warm up
        wall, res = timed(
            lambda t=threads: strike_batch(th, de, settings=settings, threads=t), args.repeats
        )
        rows[threads] = wall
    err = np.abs(res["v_out_kmh"] - reference["v_out_kmh"])[ok]
    compiled_err = float(err.max())
    us_core = rows[1] / n * 1e6
    if args.compiled_only:
        table = {
            "grid_strokes": n,
            "compiled_us_per_stroke_1_thread": us_core,
            "compiled_us_per_stroke_wall_all_threads": rows[max(rows)] / n * 1e6,
            "threads": n_threads,
            "compiled_rhs_evals_per_stroke_mean": float(res["rhs_evals"][ok].mean()),
            "compiled_max_err_kmh": compiled_err,
        }
        return report(table, args.json)

    with tempfile.TemporaryDirectory() as tmp:
        cmd = [
            str(Path(sys.executable).with_name("tennis-stroke")),
            "sweep",
            "--theta0",
            "60:120:241",
            "--delta0",
            "0:90:181",
            "--no-progress",
            "--out",
            os.path.join(tmp, "sweep.nc"),
        ]
        process_wall, _ = timed(
            lambda: subprocess.run(cmd, check=True, capture_output=True), args.repeats
        )

    rng = np.random.default_rng(20261121)
    idx = rng.choice(np.flatnonzero(ok.ravel()), size=args.subset, replace=False)
    ti, di = np.unravel_index(idx, ok.shape)
    ref_sub = reference["v_out_kmh"][ti, di]
    scipy_row = None
    for rtol in SCIPY_RTOLS:
        costs, errs = [], []
        for a, b, r in zip(THETA0[ti], DELTA0[di], ref_sub, strict=True):
            start = time.perf_counter()
            out = solve_stroke(a, b, rtol=rtol, atol=rtol).result
            costs.append(time.perf_counter() - start)
            errs.append(abs(out["v_out_kmh"] - r))
        scipy_row = (rtol, statistics.median(costs) * 1e6, max(errs))
        if max(errs) <= args.target:
            break
    sub_err = float(np.abs(res["v_out_kmh"][ti, di] - ref_sub).max())

    table = {
        "grid_strokes": n,
        "compiled_settings": settings.as_dict(),
        "compiled_us_per_stroke_1_thread": us_core,
        "compiled_us_per_stroke_wall_all_threads": rows[max(rows)] / n * 1e6,
        "threads": n_threads,
        "compiled_rhs_evals_per_stroke_mean": float(res["rhs_evals"][ok].mean()),
        "compiled_steps_per_stroke_mean": float(res["steps"][ok].mean()),
        "compiled_max_err_kmh": compiled_err,
        "compiled_max_err_kmh_subset": sub_err,
        "sweep_process_s": process_wall,
        "sweep_process_us_per_stroke": process_wall / n * 1e6,
        "scipy_method": "DOP853",
        "scipy_rtol_matched": scipy_row[0],
        "scipy_us_per_stroke": scipy_row[1],
        "scipy_max_err_kmh_subset": scipy_row[2],
        "subset": args.subset,
        "ratio_per_core": scipy_row[1] / us_core,
        "ratio_whole_process_per_stroke": scipy_row[1] / (process_wall / n * 1e6),
    }
    return report(table, args.json)


def report(table: dict, json_path: Path | None) -> int:
    """Print ``table`` as Markdown (and write it to ``json_path``)."""
    print("| quantity | value |\n|---|---|")
    for key, value in table.items():
        print(f"| {key} | {value:.4g} |" if isinstance(value, float) else f"| {key} | {value} |")
    if json_path:
        json_path.write_text(json.dumps(table, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
