"""The tables read from the work-precision file: the median and worst errors over the
strokes, and the rule table (the cheapest setting per scene that meets the requested
accuracy).  Plain xarray and pandas, no solver: the figures and the page import it."""

from __future__ import annotations

import warnings
from collections.abc import Mapping

import numpy as np
import pandas as pd
import xarray as xr

#: The errors per stroke, each a variable (scene, method, setting, stroke).
ERRORS = ("v_out_error", "event_time_error", "state_error")


def summary(ds: xr.Dataset) -> xr.Dataset:
    """Over the strokes: the median and the worst of each of :data:`ERRORS` (``NAME``
    and ``NAME_worst``), and the median evaluations per stroke (``rhs_evals``)."""
    with warnings.catch_warnings():  # a (method, setting) not run is NaN throughout
        warnings.simplefilter("ignore", RuntimeWarning)
        out = {f"{k}_worst": ds[k].max("stroke") for k in ERRORS}
        out |= {k: ds[k].median("stroke") for k in (*ERRORS, "rhs_evals")}
    return xr.Dataset(out)


def meets(v_out_worst, event_time_worst, failed, requirement: Mapping[str, float]):
    """Whether a setting meets ``requirement`` (``v_out`` km/h, ``event_time`` s): its
    worst errors over the strokes within both, and no failed stroke (arrays or
    DataArrays, element by element; a NaN worst error never meets it)."""
    return (
        (v_out_worst <= requirement["v_out"])
        & (event_time_worst <= requirement["event_time"])
        & (failed == 0)
    )


def rule_table(ds: xr.Dataset) -> pd.DataFrame:
    """For each scene, the cheapest method and setting (fewest median right-hand-side
    evaluations per stroke) whose worst errors over the strokes meet the file's
    requirement in ``v_out`` and the event times, with no failed stroke; and the
    default settings' own cost and whether they meet it.  A scene no setting meets has
    ``method`` "none"."""
    s = summary(ds)
    required = {
        "v_out": ds.attrs["required_v_out_error_kmh"],
        "event_time": ds.attrs["required_event_time_error_s"],
    }
    met = meets(s["v_out_error_worst"], s["event_time_error_worst"], ds["failed"], required)
    default = {"method": ds.attrs["default_method"], "setting": ds.attrs["default_setting"]}
    rows = []
    for scene in ds["scene"].values:
        cost = s["rhs_evals"].sel(scene=scene).where(met.sel(scene=scene))
        row = {"scene": str(scene), "method": "none", "setting": np.nan}
        if bool(cost.notnull().any()):
            best = cost.argmin(dim=("method", "setting"))
            pick = {k: int(v) for k, v in best.items()}
            row["method"] = str(ds["method"].values[pick["method"]])
            row["setting"] = float(ds["setting"].values[pick["setting"]])
        at = {"scene": scene, "method": row["method"], "setting": row["setting"]}
        found = row["method"] != "none"
        for key in ("rhs_evals", "v_out_error_worst", "event_time_error_worst"):
            row[key] = float(s[key].sel(at)) if found else np.nan
        there = {"scene": scene, **default}
        tried = default["setting"] in ds["setting"].values
        row["default_rhs_evals"] = float(s["rhs_evals"].sel(there)) if tried else np.nan
        row["default_meets"] = bool(met.sel(there)) if tried else False
        rows.append(row)
    return pd.DataFrame(rows)
