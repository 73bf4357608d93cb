"""The model ladder: the paper's spring contact against an instantaneous elastic impact
at ``phi = 0`` (:mod:`tennis_stroke.model.impact`), on the same strokes, with costs."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..io.netcdf import provenance
from ..io.units import cf_attrs
from ..model.dynamics import coefficients
from ..model.impact import impact_rebound_kmh
from ..model.params import resolve_params
from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch
from .sampling import REFERENCE, sample_strokes, stroke_params
from .timing import compiled_cost, median_time


def impact_model(
    theta0: np.ndarray,
    delta0: np.ndarray,
    params: Mapping[str, object],
    settings: SolverSettings | None = None,
) -> np.ndarray:
    """v_out (km/h) of the instantaneous elastic impact at ``phi = 0`` for each stroke:
    the swing by the compiled solver, then :func:`~tennis_stroke.model.impact.
    impact_rebound_kmh`; NaN where the swing fails."""
    res = strike_batch(theta0, delta0, params, settings)
    shape = res["status"].shape
    theta = np.radians(res["theta_deg_at_phi0"]).ravel()
    w1, w2, t0 = (res[k].ravel() for k in ("omega1_phi0", "omega2_phi0", "t_phi0"))
    cf_rows = coefficients(resolve_params(params), theta0, delta0)
    v = np.full(theta.shape, np.nan)
    for i, cf in enumerate(cf_rows):
        if res["status"].ravel()[i] == 0:
            v[i] = impact_rebound_kmh(theta[i], w1[i], w2[i], t0[i], cf)
    return v.reshape(shape)


def ladder(strokes: Mapping[str, np.ndarray], repeats: int = 3) -> xr.Dataset:
    """v_out of the spring contact (the paper) and of the instantaneous impact at
    ``phi = 0`` on the same strokes, with their costs (µs per stroke)."""
    params = stroke_params(strokes)
    th, de = strokes["theta0"], strokes["delta0"]
    us_spring, spring = compiled_cost(th, de, params, None, repeats)
    t_impact, impact = median_time(lambda: impact_model(th, de, params), 1)
    ds = xr.Dataset(
        {
            "v_out_spring": (
                "stroke",
                spring["v_out_kmh"],
                cf_attrs("v_out_spring"),
            ),
            "v_out_impact": (
                "stroke",
                impact,
                cf_attrs("v_out_impact"),
            ),
        },
        coords={"stroke": ("stroke", np.arange(th.size), cf_attrs("stroke"))},
        attrs={
            "us_per_stroke_spring": us_spring,
            "us_per_stroke_impact_python": t_impact / th.size * 1e6,
            "max_error_impact_kmh": float(np.nanmax(np.abs(impact - spring["v_out_kmh"]))),
        },
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    return ds


def ladder_study(strokes: int, seed: int) -> xr.Dataset:
    """The model ladder from the config (``solver_study``): ``strokes`` seeded random
    strokes (:func:`tennis_stroke.studies.sampling.sample_strokes`)."""
    return ladder(sample_strokes(strokes, seed))
