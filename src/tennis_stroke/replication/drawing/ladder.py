"""Study 3: :func:`ladder`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import xarray as xr

from .axes import axis_label


def ladder(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 3: the instantaneous-impact model against the spring contact, stroke by stroke."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    diff = d["v_out_impact"] - d["v_out_spring"]
    ax.plot(d["v_out_spring"], diff, "o")
    ax.axhspan(-1.0, 1.0, color="g", alpha=0.1, label="1 km/h tolerance of the speed claims")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel(axis_label(d["v_out_spring"]))
    ax.set_ylabel("impact model - spring contact (km/h)")
    ax.legend()
    ax.set_title(title)
    return fig
