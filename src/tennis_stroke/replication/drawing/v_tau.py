"""Fig. 9: :func:`v_tau`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import xarray as xr

from ...inference.measures import valid_v_out
from .axes import axis_label


def v_tau(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Fig. 9: v_out as a function of the delay tau."""
    d = ds[0].isel(delta0=0)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    v = valid_v_out(d)
    ax.plot(d["tau"], v, lw=2)
    ax.plot(
        float(d["best_tau"]),
        float(d["best_v_out"]),
        "r*",
        ms=12,
        label=f"tau_H = {float(d['best_tau']):.4f} s, v_H = {float(d['best_v_out']):.1f} km/h",
    )
    ax.plot(0.0, float(v[0]), "ko", label=f"tau_L = 0, v_L = {float(v[0]):.1f} km/h")
    ax.set_xlabel(axis_label(d["tau"]))
    ax.set_ylabel(axis_label(d["v_out"]))
    ax.legend()
    ax.set_title(title)
    return fig
