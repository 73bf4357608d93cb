"""Study 2: :func:`stability`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .axes import axis_label


def stability(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 2: outcome of the isolated contact per method/setting and spring constant."""
    from matplotlib.colors import ListedColormap

    d = ds[0]
    names = d["outcome"].attrs["flag_meanings"].split()
    colours = ["#2ca02c", "#bcbd22", "#1f77b4", "#ff7f0e", "#d62728", "#7f7f7f"]
    fig, ax = plt.subplots(figsize=(7.5, 0.35 * d.sizes["case"] + 1.8))
    mesh = ax.pcolormesh(
        np.log10(d["k_contact"].values),
        np.arange(d.sizes["case"]),
        d["outcome"].values,
        cmap=ListedColormap(colours[: len(names)]),
        vmin=-0.5,
        vmax=len(names) - 0.5,
        shading="nearest",
    )
    ax.set_yticks(np.arange(d.sizes["case"]), [str(c) for c in d["case"].values], fontsize=7)
    ax.set_xlabel("log10 k_contact (N/m)")
    ax.set_ylabel(axis_label(d["case"]))
    ax.axvspan(np.log10(188), np.log10(19000), color="k", alpha=0.08, label="paper's k range")
    bar = plt.colorbar(mesh, ax=ax, ticks=np.arange(len(names)))
    bar.ax.set_yticklabels(names, fontsize=8)
    ax.set_title(title)
    return fig
