"""Fig. 14: :func:`elbow_paths`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import xarray as xr

from .axes import axis_label


def elbow_paths(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Fig. 14: elbow trajectories from t = 0 to the contact, with and without the force."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(5.5, 5.0))
    for i, label in enumerate(d["label"].values):
        keep = d["t"] <= float(d["t_contact_start"][i])
        ax.plot(d["x_elbow"][i][keep], d["y_elbow"][i][keep], lw=2, label=str(label))
    ax.set_aspect("equal")
    ax.set_xlabel(axis_label(d["x_elbow"]))
    ax.set_ylabel(axis_label(d["y_elbow"]))
    ax.legend(fontsize=8)
    ax.set_title(title)
    return fig
