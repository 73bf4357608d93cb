"""Work-precision: every integrator over a sweep of tolerances (or steps) on one seeded
set of strokes.

Error = largest |v_out - reference| (km/h) against the compiled DOP853 at rtol = atol =
1e-13 (:data:`~tennis_stroke.studies.sampling.REFERENCE`); cost = microseconds per
stroke (compiled: median of repeats of a batch on one thread; scipy and fixed-step RK4:
median over the strokes) and right-hand-side evaluations per stroke.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..io.netcdf import provenance
from ..io.units import cf_attrs
from ..model.params import resolve_params
from ..solver.reference import solve_stroke
from ..solver.results import OK
from ..solver.rk4 import fixed_step_stroke
from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch
from .methods import parse_method
from .sampling import REFERENCE, sample_strokes, stroke_params
from .timing import TIMING, compiled_cost


def work_precision(
    strokes: Mapping[str, np.ndarray],
    compiled_tols: Sequence[float],
    scipy_tols: Sequence[float],
    rk4_steps: Sequence[float],
    scipy_methods: Sequence[str] = ("RK45", "DOP853", "LSODA", "Radau"),
    repeats: int = 3,
) -> xr.Dataset:
    """The work-precision table: dims ``method`` x ``setting``.

    ``setting`` is the tolerance (rtol = atol) of adaptive methods and the step (s) of
    fixed-step RK4; absent combinations are NaN.
    """
    params = stroke_params(strokes)
    th, de = strokes["theta0"], strokes["delta0"]
    n = th.size
    ref = strike_batch(th, de, params, REFERENCE)["v_out_kmh"]
    methods = [
        "tennis_stroke.DP54",
        "tennis_stroke.DOP853",
        *(f"scipy.{m}" for m in scipy_methods),
        "fixed.RK4",
    ]
    settings_axis = sorted({*compiled_tols, *scipy_tols, *rk4_steps}, reverse=True)
    shape = (len(methods), len(settings_axis))
    err, cost, evals, failed = (np.full(shape, np.nan) for _ in range(4))
    for mi, method in enumerate(methods):
        family, name = parse_method(method)
        values = {"tennis_stroke": compiled_tols, "scipy": scipy_tols, "fixed": rk4_steps}[family]
        for value in values:
            si = settings_axis.index(value)
            if family == "tennis_stroke":
                st = SolverSettings(method=name, rtol=value, atol=value)
                cost[mi, si], res = compiled_cost(th, de, params, st, repeats)
                v, nfev, ok = res["v_out_kmh"], res["rhs_evals"], res["status"] == OK
            else:
                per, v, nfev, ok = [], np.full(n, np.nan), np.zeros(n), np.zeros(n, bool)
                for i in range(n):
                    p = {k: float(params[k][i]) for k in params}
                    start = time.perf_counter()
                    if family == "scipy":
                        r = solve_stroke(
                            th[i], de[i], p, method=name, rtol=value, atol=value
                        ).result
                        ok[i] = r["status"] == OK
                    else:
                        r = fixed_step_stroke(th[i], de[i], p, value)
                        ok[i] = r["status"] == OK
                    per.append(time.perf_counter() - start)
                    v[i], nfev[i] = r["v_out_kmh"], r["rhs_evals"]
                cost[mi, si] = float(np.median(per)) * 1e6
            failed[mi, si] = float(np.sum(~ok))
            err[mi, si] = float(np.nanmax(np.abs(v - ref))) if ok.any() else np.nan
            evals[mi, si] = float(np.mean(nfev))
    coords = {
        "method": ("method", methods, cf_attrs("method")),
        "setting": (
            "setting",
            np.array(settings_axis),
            cf_attrs("setting"),
        ),
    }
    dims = ("method", "setting")
    ds = xr.Dataset(
        {
            "error_kmh": (dims, err, cf_attrs("error_kmh")),
            "us_per_stroke": (
                dims,
                cost,
                cf_attrs("us_per_stroke", **TIMING),
            ),
            "rhs_evals_per_stroke": (dims, evals, cf_attrs("rhs_evals_per_stroke")),
            "failed": (dims, failed, cf_attrs("failed")),
        },
        coords=coords,
        attrs={"strokes": n, "reference": "compiled DOP853, rtol = atol = 1e-13"},
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    ds.attrs["solver_settings_of"] = "the reference; each method's settings are the setting axis"
    return ds


def work_precision_study(
    strokes: int,
    seed: int,
    compiled_tolerances: Sequence[float],
    scipy_tolerances: Sequence[float],
    rk4_steps: Sequence[float],
    repeats: int,
) -> xr.Dataset:
    """The work-precision table from the config (``solver_study``): ``strokes`` seeded
    random strokes (:func:`tennis_stroke.studies.sampling.sample_strokes`)."""
    return work_precision(
        sample_strokes(strokes, seed),
        compiled_tolerances,
        scipy_tolerances,
        rk4_steps,
        repeats=repeats,
    )
