"""Identification: :func:`score_profiles`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import xarray as xr

from .axes import axis_label


def score_profiles(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Identification: the RMS normalised residual of each fit set along each of its
    unknowns (the others refitted), the declared range shaded; dots where every fit
    claim is within tolerance."""
    panels = [(d, name) for d in ds for name in d.coords]
    fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels), 3.4), squeeze=False)
    for ax, (d, name) in zip(axes[0], panels, strict=True):
        x = d[name].values
        score = d[f"score_{name}"].values
        ax.plot(x, score, "k-", lw=1)
        inside = d[f"in_range_{name}"].values.astype(bool)
        if inside.any():
            ax.axvspan(x[inside].min(), x[inside].max(), color="tab:green", alpha=0.15)
        passed = d[f"passed_{name}"].values
        full = passed == passed.max()
        ax.plot(x[full], score[full], "o", ms=3, color="tab:green")
        if x.min() > 0 and x.max() / x.min() > 20:
            ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(axis_label(d[name]))
        ax.set_ylabel("RMS normalised residual (1)")
        ax.set_title(f"fit set {d.attrs.get('fit_set', '')}: {name}", fontsize=9)
    fig.suptitle(title, fontsize=10)
    return fig
