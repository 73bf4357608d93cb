"""Robustness: :func:`claims_readings`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr


def claims_readings(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Robustness: the share of claim-level variants in which each claim (row) is within
    tolerance, under each consistent reading (column); fit claims marked with '*'."""
    d = ds[0]
    share = d["within"].mean("variant").transpose("claim", "reading")
    fig, ax = plt.subplots(figsize=(8.0, 0.17 * d.sizes["claim"] + 1.6))
    mesh = ax.pcolormesh(
        np.arange(d.sizes["reading"] + 1),
        np.arange(d.sizes["claim"] + 1),
        share.values,
        cmap="RdYlGn",
        vmin=0,
        vmax=1,
    )
    fit = d["fit_set"].values if "fit_set" in d else [""] * d.sizes["claim"]
    labels = [f"{c}{' *' if f else ''}" for c, f in zip(d["claim"].values, fit, strict=True)]
    ax.set_yticks(np.arange(d.sizes["claim"]) + 0.5, labels, fontsize=6)
    ax.invert_yaxis()
    ax.set_xlabel("consistent reading (index)")
    ax.set_ylabel("claim (* used for fit)")
    plt.colorbar(mesh, ax=ax, label="share of variants within tolerance")
    ax.set_title(title, fontsize=10)
    return fig
