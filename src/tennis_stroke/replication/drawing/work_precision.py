"""Study 1: :func:`work_precision`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .axes import axis_label


def work_precision(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 1: log error against log cost, one line per method (SciML style)."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.8, 4.8))
    floor = 1e-12  # errors below the reference's own accuracy are drawn at this floor
    for i, method in enumerate(d["method"].values):
        row = d.isel(method=i)
        err, cost = row["error_kmh"].values, row["us_per_stroke"].values
        keep = np.isfinite(err) & np.isfinite(cost)
        if keep.any():
            ax.loglog(cost[keep], np.maximum(err[keep], floor), "o-", label=str(method))
    ax.axhline(1e-4, color="grey", ls="--", lw=1, label="1e-4 km/h")
    ax.set_xlabel(axis_label(d["us_per_stroke"]))
    ax.set_ylabel(axis_label(d["error_kmh"]))
    ax.legend(fontsize=8)
    ax.set_title(title)
    return fig
