"""Figs. 2-3: :func:`angle_map`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import xarray as xr

from ...inference.measures import valid_v_out
from .axes import colour_map


def angle_map(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Figs. 2-3: v_out over (theta0, delta0) with the best delta0 (red line)."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    v = valid_v_out(d)
    colour_map(ax, v, "theta0", "delta0")
    lines = ax.contour(
        d["theta0"],
        d["delta0"],
        v.transpose("delta0", "theta0"),
        colors="w",
        linewidths=0.5,
        levels=10,
    )
    ax.clabel(lines, fontsize=7, fmt="%.0f")  # km/h
    ax.plot(d["theta0"], d["best_delta0"], "r-", lw=2, label="best delta0")
    ax.legend(loc="upper right")
    ax.set_title(title)
    return fig
