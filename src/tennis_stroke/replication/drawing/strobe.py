"""Figs. 11-12: :func:`strobe`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr


def strobe(ds: Sequence[xr.Dataset], title: str, label: str) -> plt.Figure:
    """Figs. 11-12: stick figures of rod 1 (blue) and rod 2 (black) from the file's
    positions, the one at the contact start in red."""
    d = ds[0]
    i = int(np.flatnonzero(d["label"].values == label)[0])
    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    times = d["t"].values
    picks = np.linspace(0, np.flatnonzero(np.isfinite(d["theta"][i]))[-1], 17).astype(int)
    t_c = float(d["t_contact_start"][i])
    contact = int(np.argmin(np.abs(times - t_c)))
    for k in [*picks, contact]:
        at = {v: float(d[v][i, k]) for v in d.data_vars if v.startswith(("x_", "y_"))}
        first = k == picks[0]
        ax.plot(
            [at["x_elbow"], at["x_wrist"]],
            [at["y_elbow"], at["y_wrist"]],
            color="r" if k == contact else "tab:blue",
            lw=2,
            label="rod 1 (arm), every 1/16 of the stroke" if first else None,
        )
        ax.plot(
            [at["x_wrist"], at["x_racket"]],
            [at["y_wrist"], at["y_racket"]],
            color="r" if k == contact else "k",
            lw=1.5,
            label="rod 2 (racket)" if first else None,
        )
    ax.plot([], [], color="r", lw=2, label=f"at the contact start, t = {t_c:.4f} s")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"{title} ({label} = {float(d['tau'][i]):g} s)")
    return fig
