"""What the work-precision study computes, counted, not timed: per scene of the shipped
config, the right-hand-side evaluations that run in Python (scipy's methods, the
reference, and the two at each event of fixed-step RK4, whose steps are compiled: every
call of ``tennis_stroke.model.dynamics.angle_rhs``'s function), those of RK4's strokes
(its ``rhs_evals``, compiled), and the calls of ``solve_ivp``
(one per phase between torque switches of a solve), with scipy and RK4 stopping at
their first setting that meets the requirement (the study's rule,
``studies.work_precision.UNTIL_MET``) and, with ``--every-setting``, running all of them
(the study before 2026-12-06); and the compiled evaluations of the compiled methods'
strokes and of their timing (``repeats`` batches of ``TIMING_BATCH`` strokes).

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/work_precision_evals.py
[--every-setting]`` (one thread, as the workflow's jobs: Radau's LU factorisations, and
so its evaluations, can differ with OpenBLAS's thread count).  About a minute and a half
of one core.
"""

from __future__ import annotations

import argparse
import math

import numpy as np
import yaml
from scipy.integrate import solve_ivp

import tennis_stroke.solver.reference as reference
import tennis_stroke.solver.rk4 as rk4
import tennis_stroke.studies.work_precision as wp
from tennis_stroke.model.dynamics import angle_rhs

CALLS = [0]
SOLVES = [0]


def counted(*args):
    """:func:`angle_rhs`, its function counting its calls in :data:`CALLS`."""
    fun = angle_rhs(*args)

    def f(t, y):
        CALLS[0] += 1
        return fun(t, y)

    return f


def solve_ivp_counted(*args, **kwargs):
    """``solve_ivp``, its calls counted in :data:`SOLVES`."""
    SOLVES[0] += 1
    return solve_ivp(*args, **kwargs)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--every-setting", action="store_true", help="scipy and RK4 run all")
    args = parser.parse_args()
    if args.every_setting:
        wp.UNTIL_MET = ()
    reference.angle_rhs = rk4.angle_rhs = counted
    reference.solve_ivp = solve_ivp_counted
    study = yaml.safe_load(open("config/config.yaml"))["solver_study"]
    scenes = dict(sorted(study["scenes"].items()))
    n = int(study["scene_strokes"])
    reps = max(1, wp.TIMING_BATCH // n) * int(study["repeats"])
    total = 0
    for i, scene in enumerate(scenes):
        CALLS[0] = SOLVES[0] = 0
        ds = wp.work_precision_study(
            scenes,
            n,
            study["seed"],
            study["compiled_tolerances"],
            study["scipy_tolerances"],
            study["rk4_steps"],
            study["scipy_methods"],
            study["state_times"],
            study["requirement"],
            study["repeats"],
            rows=(i, len(scenes)),
        )
        ours = [m for m in ds["method"].values if str(m).startswith("tennis_stroke.")]
        strokes = float(np.nansum(ds["rhs_evals"].sel({"method": ours}).values))
        fixed = float(np.nansum(ds["rhs_evals"].sel({"method": "fixed.RK4"}).values))
        ran = int(ds["failed"].notnull().sum())
        total += CALLS[0]
        print(
            f"{scene}: {CALLS[0]} Python evaluations, {SOLVES[0]} solve_ivp calls; "
            f"{ran} (method, setting) runs; RK4's strokes: {math.trunc(fixed)}; "
            f"compiled: {math.trunc(strokes)} in the strokes, "
            f"{math.trunc(strokes * reps)} in their timing"
        )
    print(f"all scenes: {total} Python evaluations")


if __name__ == "__main__":
    main()
