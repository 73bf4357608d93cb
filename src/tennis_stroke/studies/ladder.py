"""The model ladder on random strokes: the paper's spring contact against the
instantaneous elastic impact at ``phi = 0`` (the rung ``contact_model="impact"``,
:mod:`tennis_stroke.model.impact`), on the same strokes, with costs.  The ladder claim
by claim is :mod:`tennis_stroke.inference.ladder`."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..io.netcdf import provenance
from ..io.units import cf_attrs
from ..model.params import resolve_params
from ..solver.results import OK
from .sampling import REFERENCE, sample_strokes, stroke_params
from .timing import compiled_cost


def ladder(strokes: Mapping[str, np.ndarray], repeats: int = 3) -> xr.Dataset:
    """v_out of the spring contact (the paper) and of the instantaneous impact at
    ``phi = 0`` on the same strokes, with their costs (µs per stroke, both the compiled
    solver on one thread)."""
    params = stroke_params(strokes)
    th, de = strokes["theta0"], strokes["delta0"]
    us_spring, spring = compiled_cost(th, de, params, None, repeats)
    impact_params = {**params, "contact_model": "impact"}
    us_impact, impact_res = compiled_cost(th, de, impact_params, None, repeats)
    impact = np.where(impact_res["status"] == OK, impact_res["v_out_kmh"], np.nan)
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
            "us_per_stroke_impact": us_impact,
            "max_error_impact_kmh": float(np.nanmax(np.abs(impact - spring["v_out_kmh"]))),
        },
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    return ds


def ladder_study(strokes: int, seed: int) -> xr.Dataset:
    """The model ladder from the config (``solver_study``): ``strokes`` seeded random
    strokes (:func:`tennis_stroke.studies.sampling.sample_strokes`)."""
    return ladder(sample_strokes(strokes, seed))
