"""Study 4: :func:`convergence`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .axes import axis_label


def convergence(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 4: the error at the end of the swing stretch against the fixed step, one
    colour per method, its fitted slope beside its theoretical order in the legend, and
    a dotted line of the theoretical slope through each method's last point."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(9.0, 5.5))
    for i, method in enumerate(d["method"].values):
        row = d.sel({"method": method})
        step, err = row["step"].values, row["omega_error"].values
        keep = np.isfinite(step) & np.isfinite(err)
        slope, order = float(row["slope"]), int(row["order"])
        ax.loglog(
            step[keep],
            err[keep],
            "o-",
            color=f"C{i}",
            label=f"{method}: slope {slope:.2f} (order {order})",
        )
        h0, e0 = step[keep][-1], err[keep][-1]
        ax.loglog(step[keep], e0 * (step[keep] / h0) ** order, ":", color=f"C{i}", lw=1)
    ax.set_xlabel(axis_label(d["step"]))
    ax.set_ylabel(axis_label(d["omega_error"]))
    ax.grid(True, which="major", lw=0.3, alpha=0.5)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    ax.set_title(
        f"{title}\nthe swing from rest at theta0 = {d.attrs['theta0_deg']:g} deg, "
        f"delta0 = {d.attrs['delta0_deg']:g} deg,\nto {d.attrs['t_end_s']:g} s; dotted: "
        "the theoretical slope",
        fontsize=9,
    )
    return fig
