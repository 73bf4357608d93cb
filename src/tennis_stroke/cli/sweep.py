"""simulate a (theta0, delta0) grid into netCDF

Simulate every stroke of a (theta0, delta0) grid into a netCDF file.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from .parsing import add_model_options, angle_help, parse_set, solver_settings
from .ranges import RANGE_FORMS, range_spec

#: Strokes per thread in one call of the compiled solver during a sweep: the memory of a
#: batch's work arrays is that of one block, not of the grid.  (Ctrl-C stops a call at
#: the next stroke of each thread, :func:`tennis_stroke.solver.stroke.solve_coefficients`,
#: whatever a block's size.)  Blocks never change a number: every stroke is computed on
#: its own.
SWEEP_BLOCK_PER_THREAD = 4096


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description += f" A RANGE is {RANGE_FORMS}."  # the forms the errors name too
    for name in ("theta0", "delta0"):
        parser.add_argument(
            f"--{name}", required=True, metavar="RANGE", help=angle_help(name, ": a RANGE")
        )
    parser.add_argument(
        "--out",
        required=True,
        metavar="FILE.nc",
        help="the netCDF file to write (under a temporary name, then renamed)",
    )
    parser.add_argument("--threads", type=int, default=None, help="threads (default: all)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.add_argument(
        "--max-memory",
        default=None,
        metavar="SIZE",
        help="refuse a grid needing more memory (e.g. 8G; default: "
        "$TENNIS_STROKE_MAX_MEMORY, else half the machine's memory)",
    )
    add_model_options(parser)


def _sweep_blocks(theta0, delta0, overrides, settings, threads, block, progress):
    """``strike_batch`` over the grid ``theta0 x delta0`` in blocks of ``block`` strokes;
    the result fields on the grid."""
    from ..solver.stroke import strike_batch

    nd, n = delta0.size, theta0.size * delta0.size
    results: dict[str, np.ndarray] = {}
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=n, unit="stroke", leave=False)
    try:
        for a in range(0, n, block):
            index = np.arange(a, min(a + block, n))
            res = strike_batch(
                theta0[index // nd], delta0[index % nd], overrides, settings, threads
            )
            for name, values in res.items():
                results.setdefault(name, np.empty(n, values.dtype))[a : a + index.size] = values
            if bar is not None:
                bar.update(index.size)
    finally:
        if bar is not None:
            bar.close()
    return {name: values.reshape(theta0.size, nd) for name, values in results.items()}


def run(args: argparse.Namespace) -> int:
    from ..experiments.memory import batch_bytes, check_memory, memory_limit, result_bytes
    from ..io.netcdf import check_writable, result_dataset, write_netcdf
    from ..model.params import initial_angles, resolve_params
    from ..solver.results import OK
    from ..solver.stroke import default_threads

    theta_range = range_spec(args.theta0, "theta0")
    delta_range = range_spec(args.delta0, "delta0")
    ends = [np.array([r.start, r.stop]) for r in (theta_range, delta_range)]
    initial_angles(ends[0][:, None], ends[1][None, :])  # the grid's corners, nothing made
    overrides = parse_set(args.set)
    params = resolve_params(overrides)
    settings = solver_settings(args)
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"--threads must be >= 1, got {args.threads}")
    threads = min(args.threads or default_threads(), default_threads())
    n = theta_range.num * delta_range.num
    block = min(n, SWEEP_BLOCK_PER_THREAD * threads)
    check_memory(
        result_bytes(n) + batch_bytes(block, threads, settings.history),
        f"a sweep of {theta_range.num} x {delta_range.num} strokes",
        memory_limit(args.max_memory, "--max-memory"),
    )
    out = check_writable(args.out)
    theta0, delta0 = theta_range.values(), delta_range.values()
    start = time.perf_counter()
    results = _sweep_blocks(
        theta0,
        delta0,
        overrides,
        settings,
        args.threads,
        block,
        progress=not args.no_progress and sys.stderr.isatty(),
    )
    wall = time.perf_counter() - start
    ds = result_dataset(
        results,
        {"theta0": theta0, "delta0": delta0},
        params,
        settings,
        {"wall_time_s": wall, "command": " ".join(sys.argv)},
    )
    write_netcdf(ds, out)
    n_ok = int((results["status"] == OK).sum())
    print(f"{out}: {results['status'].size} strokes ({n_ok} ok) in {wall:.2f} s")
    return 0
