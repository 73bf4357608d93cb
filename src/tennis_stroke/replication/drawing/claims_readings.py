"""Robustness: :func:`claims_readings`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr


def claims_readings(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Robustness: the share of claim-level variants in which each claim (row) is within
    tolerance, under each consistent reading (column); fit claims marked with '*'.  Beside
    it, each held-out claim's pass share over all readings with its 95 % interval
    (:func:`~tennis_stroke.replication.robustness.share_interval`)."""
    from ..robustness import CONFIDENCE, share_interval

    d = ds[0]
    share = d["within"].mean("variant").transpose("claim", "reading")
    fig, (ax, bars, cax) = plt.subplots(
        1,
        3,
        figsize=(10.0, 0.17 * d.sizes["claim"] + 1.6),
        gridspec_kw={"width_ratios": [4, 1.3, 0.12]},
    )
    bars.sharey(ax)
    bars.tick_params(labelleft=False)
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
    within = d["within"].transpose("reading", "variant", "claim").values.astype(bool)
    for j, f in enumerate(fit):
        if f:
            continue
        ok = within[:, :, j]
        low, high, _, _ = share_interval(ok)
        mid = float(ok.mean())
        bars.errorbar(
            mid, j + 0.5, xerr=[[mid - low], [high - mid]], fmt="o", ms=3, color="k", capsize=2
        )
    bars.set_ylabel("held-out claim (as left)", fontsize=7)
    bars.set_xlim(-0.05, 1.05)
    bars.set_xlabel(f"pass share ({100 * CONFIDENCE:.0f} % interval)", fontsize=8)
    bars.tick_params(labelsize=7)
    bars.grid(axis="x", alpha=0.3)
    fig.colorbar(mesh, cax=cax, label="share of variants within tolerance")
    ax.set_title(title, fontsize=10)
    return fig
