"""Figs. 4 and 10: :func:`omegas`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import xarray as xr

from .axes import axis_label


def omegas(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Figs. 4 and 10: omega1(t), omega2(t) of the strokes, contact times dashed."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for i, label in enumerate(d["label"].values):
        line = ax.plot(d["t"], d["omega2"][i], lw=2, label=f"omega2 {label}")[0]
        ax.plot(
            d["t"], d["omega1"][i], "--", color=line.get_color(), lw=1.2, label=f"omega1 {label}"
        )
        ax.axvline(
            float(d["t_contact_start"][i]),
            color=line.get_color(),
            ls=":",
            lw=1,
            label=f"contact starts {label}",
        )
    ax.set_xlabel(axis_label(d["t"]))
    ax.set_ylabel("angular velocity (rad/s)")
    ax.legend(fontsize=8)
    ax.set_title(title)
    return fig
