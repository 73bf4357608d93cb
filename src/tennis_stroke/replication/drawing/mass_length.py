"""Figs. 5-6: :func:`mass_length`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import xarray as xr

from .axes import colour_map


def mass_length(ds: Sequence[xr.Dataset], title: str, var: str) -> plt.Figure:
    """Figs. 5-6: the fastest rebound (or its theta_c) over (M2, L1)."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    colour_map(ax, d[var], "M2", "L1", cmap="viridis" if var == "v_out_best" else "magma")
    lines = ax.contour(d["M2"], d["L1"], d[var].transpose("L1", "M2"), colors="w", linewidths=0.5)
    ax.clabel(lines, fontsize=7, fmt="%.0f")  # in the colour bar's unit
    ax.set_title(title)
    return fig
