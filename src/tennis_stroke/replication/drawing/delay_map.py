"""Figs. 7-8: :func:`delay_map`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ...inference.measures import measure_delay_threshold, valid_v_out
from .axes import colour_map


def delay_map(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Figs. 7-8: v_out over (C2 or delta0, tau) with the best tau per row."""
    d = ds[0]
    axis = "C2" if "C2" in d.dims else "delta0"
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    colour_map(ax, valid_v_out(d), axis, "tau")
    ax.plot(d[axis], d["best_tau"], "r-", lw=1.5, label="best tau")
    if axis == "C2":
        thr = measure_delay_threshold(d)
        ax.axvline(thr, color="w", ls="--", lw=1, label=f"best tau leaves 0: C2 = {thr:.2f} N m")
    else:
        v = valid_v_out(d)
        i = np.unravel_index(int(np.nanargmax(v.values)), v.shape)
        ax.plot(float(d[axis][i[0]]), float(d["tau"][i[1]]), "r*", ms=14, label="optimum")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title)
    return fig
