"""Study 1: :func:`work_precision`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .axes import axis_label

#: Errors below the reference's own accuracy are drawn at this floor (km/h).
FLOOR = 1e-12


def work_precision(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 1: log error against log cost, one line per method, each point a tolerance
    (or a fixed step, in s) written beside it (Hairer, Nørsett and Wanner's precision
    diagram). Left, the cost of record: right-hand-side evaluations per stroke, the same on
    every machine; right, this machine's wall time per stroke. The legend stands outside
    the panels, so no measured time can place it over a point."""
    d = ds[0]
    fig, panels = plt.subplots(1, 2, figsize=(11, 4.8), sharey=True)
    by_evals, by_time = panels
    settings = d["setting"].values
    for i, method in enumerate(d["method"].values):
        row = d.isel(method=i)
        err = np.maximum(row["error_kmh"].values, FLOOR)
        unit = " s" if str(method).startswith("fixed.") else ""
        for ax, cost_name in ((by_evals, "rhs_evals_per_stroke"), (by_time, "us_per_stroke")):
            cost = row[cost_name].values
            keep = np.isfinite(err) & np.isfinite(cost)
            if not keep.any():
                continue
            ax.loglog(cost[keep], err[keep], "o-", ms=4, color=f"C{i}", label=str(method))
            if ax is by_evals:
                for x, y, s in zip(cost[keep], err[keep], settings[keep], strict=True):
                    ax.annotate(
                        f"{s:.0e}{unit}".replace("e-0", "e-"),
                        (x, y),
                        xytext=(3, 2),
                        textcoords="offset points",
                        fontsize=6,
                        color=f"C{i}",
                    )
    for ax in panels:
        ax.axhline(1e-4, color="grey", ls="--", lw=1, label="requested: 1e-4 km/h")
        ax.set_ylabel(axis_label(d["error_kmh"]))
        ax.grid(True, which="major", lw=0.3, alpha=0.5)
    by_evals.set_xlabel(axis_label(d["rhs_evals_per_stroke"]))
    by_time.set_xlabel(axis_label(d["us_per_stroke"]))
    by_evals.set_title("cost of record: the same on every machine", fontsize=9)
    by_time.set_title("wall time on the machine that ran it", fontsize=9)
    by_time.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    fig.suptitle(
        f"{title}\n(each point: its rtol = atol, or its fixed step; an error below "
        f"{FLOOR:.0e} km/h is drawn at it)"
    )
    return fig
