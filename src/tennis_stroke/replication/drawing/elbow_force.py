"""Fig. 13: :func:`elbow_force`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ...inference.measures import valid_v_out
from .axes import colour_map


def elbow_force(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Fig. 13: v_out over the force direction psi_F and extra delay tau_F."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    v = valid_v_out(d)
    colour_map(ax, v, "psi_F", "tau_F")
    i = np.unravel_index(int(np.nanargmax(v.values)), v.shape)
    ax.plot(float(d["psi_F"][i[0]]), float(d["tau_F"][i[1]]), "r*", ms=14, label="maximum")
    ax.legend(loc="best")
    ax.set_title(title)
    return fig
