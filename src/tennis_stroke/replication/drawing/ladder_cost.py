"""Speed against accuracy per scene: :func:`ladder_cost`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr


def ladder_cost(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Speed against accuracy per scene: for each group of result files that claims read
    together (a panel; the file's ``file_group``), each
    rung's right-hand-side evaluations on the group against the reference rung's (x) and
    the largest distance of the group's claims from the reference rung's values, in
    tolerances (y; a claim the rung cannot answer counts as infinitely far: drawn at the
    top)."""
    d = ds[0]
    group = d["file_group"].values
    groups = [list(d["file"].values[group == g]) for g in range(group.max() + 1)]
    ref = list(d["rung"].values).index(d.attrs["reference_rung"])
    cols = 4
    rows = -(-len(groups) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.1 * cols, 2.6 * rows), squeeze=False)
    # a claim the rung cannot answer, or without a value, is infinitely far
    distance = d["from_reference"].values
    distance = np.where((d["comparable"].values == 1) & np.isfinite(distance), distance, np.inf)
    ceiling = 30.0
    markers = "os^vDPX*"
    for g, (ax, files) in enumerate(zip(axes.flat, groups, strict=False)):
        reads = d["claim_group"].values == g
        evals = d["rhs_evals"].sel(file=files).sum("file").values
        cost = evals / evals[ref]
        worst = np.minimum(distance[:, reads].max(axis=1), ceiling)
        for i, rung in enumerate(d["rung"].values):
            y = max(worst[i], 1e-6)  # the reference itself, and exact agreement
            ax.scatter(  # hollow, smaller for later rungs: rungs on one point all show
                cost[i],
                y,
                s=max(110 - 12 * i, 20),
                marker=markers[i % len(markers)],
                facecolors="none",
                edgecolors=f"C{i}",
                linewidths=1.3,
                label=rung,
            )
        ax.axhline(d.attrs["adoption_agreement"], color="grey", lw=0.8, ls="--")
        ax.set_yscale("log")
        ax.set_ylim(1e-6, ceiling * 2)
        ax.set_title(f"{' + '.join(files)} ({int(reads.sum())} claims)", fontsize=8)
        ax.set_xlabel("evaluations / reference", fontsize=7)
        ax.set_ylabel("distance (tolerances)", fontsize=7)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(groups) :]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower right", fontsize=7)
    fig.suptitle(
        f"{title}\nx: right-hand-side evaluations / the reference rung's; y: largest distance "
        f"of the file's claims from the reference, in tolerances (top: no answer, >= "
        f"{ceiling:g}); dashed: the adoption rule",
        fontsize=9,
    )
    fig.tight_layout()
    return fig
