"""Cost against accuracy of the optimum search of Figs. 5-6: the nested grid (coarse
grid, fine grid, parabola) for several step pairs, and the search of the workflow
(coarse bracket, compass search) for several (bracket step, tolerance) pairs, against a
finer reference grid search."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from ..experiments.maps import mass_length_map
from ..experiments.optima import mass_length_optimum
from ..io.netcdf import provenance
from ..io.units import cf_attrs
from ..model.params import resolve_params
from ..solver.settings import SolverSettings
from .methods import OPTIMUM_DELTA0_RANGE, OPTIMUM_THETA0_RANGE
from .sampling import REFERENCE
from .timing import TIMING, median_time


def optimum_cost(
    m2: Sequence[float],
    l1: Sequence[float],
    steps: Sequence[tuple[float, float]],
    reference_step: float = 0.05,
    theta0_range=OPTIMUM_THETA0_RANGE,
    delta0_range=OPTIMUM_DELTA0_RANGE,
    searches: Sequence[tuple[float, float]] = (),
) -> xr.Dataset:
    """Accuracy of the optimum of Figs. 5-6 against its cost.

    For each ``(coarse, fine)`` step pair of ``steps`` the optimum at every ``(M2, L1)``
    point is found by the nested grid of
    :func:`tennis_stroke.experiments.maps.mass_length_map`, for each ``(bracket step,
    tolerance)`` of ``searches`` by the search of
    :func:`~tennis_stroke.experiments.optima.mass_length_optimum`; the reference is the
    nested grid with a ``reference_step`` fine grid around a 1-degree coarse one.  Errors
    are the largest over the points (the search's values are strokes' own; the grid's
    are parabola estimates, which can lie above every stroke at an edge of the range).
    """
    settings = SolverSettings()
    m2, l1 = np.asarray(m2, float), np.asarray(l1, float)
    ref = mass_length_map(m2, l1, 1.0, reference_step, theta0_range, delta0_range, {}, settings)
    rows = {k: [] for k in ("v_err", "theta0_err", "delta0_err", "seconds")}
    runs = [(mass_length_map, c, f) for c, f in steps]
    runs += [(mass_length_optimum, c, t) for c, t in searches]
    for fn, coarse, fine in runs:
        seconds, ds = median_time(
            lambda fn=fn, c=coarse, f=fine: fn(
                m2, l1, c, f, theta0_range, delta0_range, {}, settings
            ),
            1,
        )
        rows["seconds"].append(seconds)
        rows["v_err"].append(float(np.nanmax(np.abs(ds["v_out_best"] - ref["v_out_best"]))))
        rows["theta0_err"].append(float(np.nanmax(np.abs(ds["theta0_best"] - ref["theta0_best"]))))
        rows["delta0_err"].append(float(np.nanmax(np.abs(ds["delta0_best"] - ref["delta0_best"]))))
    labels = [f"grid: coarse {c:g} deg, fine {f:g} deg" for c, f in steps]
    labels += [f"search: bracket {c:g} deg, tolerance {t:g} deg" for c, t in searches]
    ds = xr.Dataset(
        {
            k: (
                "search",
                np.array(v),
                cf_attrs(k, **(TIMING if k == "seconds" else {})),
            )
            for k, v in rows.items()
        },
        coords={"search": ("search", labels, cf_attrs("search"))},
        attrs={"points": m2.size * l1.size, "reference_fine_step_deg": reference_step},
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    return ds


def optimum_cost_study(
    M2: Sequence[float],
    L1: Sequence[float],
    steps: Sequence[Sequence[float]],
    reference_step: float,
    searches: Sequence[Sequence[float]] = (),
) -> xr.Dataset:
    """The optimum-search cost from the config (``solver_study.optimum``)."""
    return optimum_cost(
        M2, L1, [tuple(s) for s in steps], reference_step, searches=[tuple(s) for s in searches]
    )
