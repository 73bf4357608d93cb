"""Study 1: :func:`work_precision`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.lines import Line2D

from ...studies.tables import summary
from .axes import axis_label

#: Errors below the reference's own accuracy are drawn at these floors (the errors'
#: units: km/h, s, rad/s).
FLOORS = {"v_out_error": 1e-12, "event_time_error": 1e-15, "state_error": 1e-12}
#: The columns: the error drawn, the cost along x, the file's attribute of the
#: requested accuracy (None: no line).
COLUMNS = (
    ("v_out_error", "rhs_evals", "required_v_out_error_kmh"),
    ("event_time_error", "rhs_evals", "required_event_time_error_s"),
    ("state_error", "rhs_evals", None),
    ("v_out_error", "us_per_stroke", "required_v_out_error_kmh"),
)


def _label(value: float, method: str) -> str:
    text = f"{value:.0e}".replace("e-0", "e-")
    return text + " s" if method.startswith("fixed.") else text


def _curves(ax, d, s, col, i, method) -> None:
    """One method's worst (filled, solid) and median (open, dotted) errors in one panel;
    the points of the first column labelled by their tolerance or step."""
    error, cost_name, _ = COLUMNS[col]
    cost = (s["rhs_evals"] if cost_name == "rhs_evals" else d[cost_name]).values
    for kind, style in ((f"{error}_worst", "o-"), (error, "o:")):
        err = np.maximum(s[kind].values, FLOORS[error])
        keep = np.isfinite(err) & np.isfinite(cost)
        if not keep.any():
            continue
        face = f"C{i}" if kind.endswith("_worst") else "none"
        ax.plot(cost[keep], err[keep], style, ms=4, lw=1, color=f"C{i}", mfc=face)
        if cost_name == "us_per_stroke" and kind.endswith("_worst"):
            low, high = d["us_per_stroke_low"].values[keep], d["us_per_stroke_high"].values[keep]
            xerr = np.abs(np.vstack([cost[keep] - low, high - cost[keep]]))
            ax.errorbar(cost[keep], err[keep], xerr=xerr, fmt="none", ecolor=f"C{i}", lw=0.8)
        if col == 0 and kind.endswith("_worst"):
            for x, y, v in zip(cost[keep], err[keep], d["setting"].values[keep], strict=True):
                ax.annotate(
                    _label(v, method),
                    (x, y),
                    xytext=(3, 2),
                    textcoords="offset points",
                    fontsize=5,
                    color=f"C{i}",
                )


def work_precision(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 1, per scene (a row each): the worst (filled) and median (open) error over
    the strokes against the cost, one colour per method, each point a tolerance (or a
    fixed step, in s) written beside it in the first column (Hairer, Nørsett and
    Wanner's precision diagram).  Columns: the v_out, event-time and state errors
    against right-hand-side evaluations per stroke (the cost of record, the same on
    every machine), then the v_out error against this machine's wall time per stroke
    with its spread.  The requested accuracy is a grey dashed line; the legend stands
    outside the panels, so no measured time can place it over a point."""
    d = ds[0]
    scenes = [str(v) for v in d["scene"].values]
    fig, grid = plt.subplots(
        len(scenes), len(COLUMNS), figsize=(17, 3.0 * len(scenes) + 1.2), squeeze=False
    )
    for r, scene in enumerate(scenes):
        ds_r = d.sel(scene=scene)
        s = summary(ds_r)
        for col, (error, cost_name, required) in enumerate(COLUMNS):
            ax = grid[r, col]
            ax.set_xscale("log")
            ax.set_yscale("log")
            for i, method in enumerate(d["method"].values):
                pick = {"method": method}
                _curves(ax, ds_r.sel(pick), s.sel(pick), col, i, str(method))
            if required:
                ax.axhline(d.attrs[required], color="grey", ls="--", lw=1)
            ax.set_ylabel(axis_label(d[error]), fontsize=7)
            ax.set_xlabel(axis_label(d[cost_name]), fontsize=7)
            ax.tick_params(labelsize=7)
            ax.grid(True, which="major", lw=0.3, alpha=0.5)
        grid[r, 0].set_title(f"{scene}: {d.attrs.get(f'scene_{scene}', '')}", fontsize=8)
    handles = [
        Line2D([], [], color=f"C{i}", marker="o", label=str(m))
        for i, m in enumerate(d["method"].values)
    ]
    handles += [
        Line2D([], [], color="k", marker="o", ls="-", label="worst over the strokes"),
        Line2D([], [], color="k", marker="o", mfc="none", ls=":", label="median"),
        Line2D([], [], color="grey", ls="--", label="requested accuracy"),
    ]
    grid[0, -1].legend(
        handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0
    )
    strokes, ref = d.attrs.get("strokes", d.sizes["stroke"]), d.attrs.get("reference", "")
    fig.suptitle(
        f"{title}\n{strokes} strokes per scene against {ref}; each point: its rtol = atol, "
        "or its fixed step; an error below the reference's floor is drawn at it",
        fontsize=10,
    )
    return fig
