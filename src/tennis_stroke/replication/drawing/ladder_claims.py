"""The model ladder: :func:`ladder_claims`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import xarray as xr


def ladder_claims(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """The model ladder: each claim (row) under each rung (column), green within the
    paper's tolerance, red outside, grey where the rung cannot answer it; fit claims marked
    '*', the value written in each cell."""
    d = ds[0]
    state = np.where(d["comparable"].values == 0, 0.5, d["within"].values.astype(float)).T
    fig, ax = plt.subplots(figsize=(1.15 * d.sizes["rung"] + 3.8, 0.2 * d.sizes["claim"] + 1.8))
    colours = matplotlib.colors.ListedColormap(["#e8a8a0", "#d9d9d9", "#a8d8a0"])
    ax.pcolormesh(
        np.arange(d.sizes["rung"] + 1),
        np.arange(d.sizes["claim"] + 1),
        state,
        cmap=colours,
        vmin=0,
        vmax=1,
        edgecolors="white",
        linewidth=0.5,
    )
    for j, column in enumerate(d["value"].values):
        for i, value in enumerate(column):
            if np.isfinite(value):
                ax.text(j + 0.5, i + 0.5, f"{value:.4g}", ha="center", va="center", fontsize=5)
    fit = d["fit_set"].values
    labels = [f"{c}{' *' if f else ''}" for c, f in zip(d["claim"].values, fit, strict=True)]
    ax.set_yticks(np.arange(d.sizes["claim"]) + 0.5, labels, fontsize=6)
    ax.set_xticks(np.arange(d.sizes["rung"]) + 0.5, d["rung"].values, fontsize=7, rotation=30)
    ax.invert_yaxis()
    ax.set_ylabel("claim (* used for fit)")
    ax.set_xlabel("rung (in order of model detail); green: within tolerance, grey: no answer")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    return fig
