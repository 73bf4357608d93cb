"""Study 2: :func:`stability`."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from .axes import axis_label

#: One colour per outcome, in the order of the file's ``flag_meanings``.
COLOURS = ["#2ca02c", "#bcbd22", "#1f77b4", "#ff7f0e", "#d62728", "#7f7f7f"]


def _log_edges(k: np.ndarray) -> np.ndarray:
    """Cell edges around log-spaced values: half-way between neighbours in log k."""
    lk = np.log10(k)
    half = np.diff(lk) / 2 if lk.size > 1 else np.array([1.0])
    mids = lk[:-1] + half[: lk.size - 1]
    return 10 ** np.concatenate([[lk[0] - half[0]], mids, [lk[-1] + half[-1]]])


def _panel(ax, d: xr.Dataset, cases: np.ndarray, names: list[str], ylabel: str):
    part = d.isel(case=cases)
    mesh = ax.pcolormesh(
        _log_edges(part["k_contact"].values),
        np.arange(part.sizes["case"] + 1) - 0.5,
        part["outcome"].values,
        cmap=ListedColormap(COLOURS[: len(names)]),
        vmin=-0.5,
        vmax=len(names) - 0.5,
        shading="flat",
    )
    ax.set_xscale("log")
    labels = [str(c).replace(" @ ", ", ") for c in part["case"].values]
    if ylabel.startswith("RK4"):
        labels = [f"{float(v):g}" for v in part["setting"].values]
    ax.set_yticks(np.arange(part.sizes["case"]), labels, fontsize=7)
    ax.set_xlabel(axis_label(d["k_contact"]))
    ax.set_ylabel(ylabel)
    if "paper_k_contact" in d.attrs:
        low, high = np.asarray(d.attrs["paper_k_contact"], dtype=float)
        ax.axvspan(low, high, facecolor="none", edgecolor="k", hatch="//", lw=0.8, alpha=0.5)
    return mesh


def stability(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 2: the outcome of the isolated contact against the spring constant, the
    tolerance-controlled methods (method, rtol = atol) in the upper panel and fixed-step
    RK4 (its step) in the lower; the paper's range of k hatched and named in the legend,
    each outcome defined in it."""
    d = ds[0]
    names = d["outcome"].attrs["flag_meanings"].split()
    fixed = np.array([str(c).startswith("fixed.") for c in d["case"].values])
    groups = [
        (np.flatnonzero(~fixed), "method, tolerance\nrtol = atol (1)"),
        (np.flatnonzero(fixed), "RK4 step (s)"),
    ]
    groups = [(cases, label) for cases, label in groups if cases.size]
    heights = [max(cases.size, 3) for cases, _ in groups]
    fig, axes = plt.subplots(
        len(groups),
        1,
        figsize=(12.0, 0.32 * sum(heights) + 2.8),
        sharex=True,
        squeeze=False,
        gridspec_kw={"height_ratios": heights},
    )
    for ax, (cases, label) in zip(axes[:, 0], groups, strict=True):
        _panel(ax, d, cases, names, label)
    meanings = (
        dict(
            part.split(": ", 1)
            for part in d["outcome"].attrs.get("outcome_meanings", "").split("; ")
        )
        if d["outcome"].attrs.get("outcome_meanings")
        else {}
    )
    handles = [
        Patch(facecolor=COLOURS[i], label=f"{n}: {meanings.get(n, n)}") for i, n in enumerate(names)
    ]
    if "paper_k_contact" in d.attrs:
        low, high = np.asarray(d.attrs["paper_k_contact"], dtype=float)
        handles.append(
            Patch(
                facecolor="none",
                edgecolor="k",
                hatch="//",
                label=f"paper's k: {low:g}-{high:g} N/m",
            )
        )
    axes[0, 0].legend(
        handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0
    )
    axes[0, 0].set_title(title)
    return fig
