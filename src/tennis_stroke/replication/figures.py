"""The paper's figures, drawn from the result files (never re-simulating).

:func:`draw` draws a figure of the registry (:mod:`tennis_stroke.replication.registry`)
with its drawing function; axis labels and colour-bar labels
come from the files' ``long_name`` and ``units`` attributes.
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from ..inference.measures import measure_delay_threshold, valid_v_out  # noqa: E402
from ..io.netcdf import load_result  # noqa: E402
from .registry import FIGURES, Figure  # noqa: E402


def _label(da: xr.DataArray) -> str:
    return f"{da.attrs.get('long_name', da.name)} ({da.attrs.get('units', '')})"


def _map(ax, da: xr.DataArray, x: str, y: str, cmap="viridis"):
    """Colour map of ``da`` with ``x`` horizontal and ``y`` vertical, and its colour bar."""
    mesh = ax.pcolormesh(da[x], da[y], da.transpose(y, x), shading="auto", cmap=cmap)
    ax.set_xlabel(_label(da[x]))
    ax.set_ylabel(_label(da[y]))
    plt.colorbar(mesh, ax=ax, label=_label(da))
    return mesh


def angle_map(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Figs. 2-3: v_out over (theta0, delta0) with the best delta0 (red line)."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    v = valid_v_out(d)
    _map(ax, v, "theta0", "delta0")
    lines = ax.contour(
        d["theta0"],
        d["delta0"],
        v.transpose("delta0", "theta0"),
        colors="w",
        linewidths=0.5,
        levels=10,
    )
    ax.clabel(lines, fontsize=7, fmt="%.0f")  # km/h
    ax.plot(d["theta0"], d["best_delta0"], "r-", lw=2, label="best delta0")
    ax.legend(loc="upper right")
    ax.set_title(title)
    return fig


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
    ax.set_xlabel(_label(d["t"]))
    ax.set_ylabel("angular velocity (rad/s)")
    ax.legend(fontsize=8)
    ax.set_title(title)
    return fig


def mass_length(ds: Sequence[xr.Dataset], title: str, var: str) -> plt.Figure:
    """Figs. 5-6: the fastest rebound (or its theta_c) over (M2, L1)."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    _map(ax, d[var], "M2", "L1", cmap="viridis" if var == "v_out_best" else "magma")
    lines = ax.contour(d["M2"], d["L1"], d[var].transpose("L1", "M2"), colors="w", linewidths=0.5)
    ax.clabel(lines, fontsize=7, fmt="%.0f")  # in the colour bar's unit
    ax.set_title(title)
    return fig


def delay_map(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Figs. 7-8: v_out over (C2 or delta0, tau) with the best tau per row."""
    d = ds[0]
    axis = "C2" if "C2" in d.dims else "delta0"
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    _map(ax, valid_v_out(d), axis, "tau")
    ax.plot(d[axis], d["best_tau"], "r-", lw=1.5, label="best tau")
    if axis == "C2":
        thr = measure_delay_threshold(d)
        ax.axvline(thr, color="w", ls="--", lw=1, label=f"best tau leaves 0: C2 = {thr:.2f} N m")
    else:
        v = valid_v_out(d)
        i = np.unravel_index(int(np.nanargmax(v.values)), v.shape)
        ax.plot(float(d[axis][i[0]]), float(d["tau"][i[1]]), "r*", ms=14, label="optimum")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title)
    return fig


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
    ax.set_xlabel(_label(d["tau"]))
    ax.set_ylabel(_label(d["v_out"]))
    ax.legend()
    ax.set_title(title)
    return fig


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


def elbow_force(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Fig. 13: v_out over the force direction psi_F and extra delay tau_F."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    v = valid_v_out(d)
    _map(ax, v, "psi_F", "tau_F")
    i = np.unravel_index(int(np.nanargmax(v.values)), v.shape)
    ax.plot(float(d["psi_F"][i[0]]), float(d["tau_F"][i[1]]), "r*", ms=14, label="maximum")
    ax.legend(loc="upper right")
    ax.set_title(title)
    return fig


def elbow_paths(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Fig. 14: elbow trajectories from t = 0 to the contact, with and without the force."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(5.5, 5.0))
    for i, label in enumerate(d["label"].values):
        keep = d["t"] <= float(d["t_contact_start"][i])
        ax.plot(d["x_elbow"][i][keep], d["y_elbow"][i][keep], lw=2, label=str(label))
    ax.set_aspect("equal")
    ax.set_xlabel(_label(d["x_elbow"]))
    ax.set_ylabel(_label(d["y_elbow"]))
    ax.legend(fontsize=8)
    ax.set_title(title)
    return fig


def work_precision(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 1: log error against log cost, one line per method (SciML style)."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.8, 4.8))
    floor = 1e-12  # errors below the reference's own accuracy are drawn at this floor
    for i, method in enumerate(d["method"].values):
        row = d.isel(method=i)
        err, cost = row["error_kmh"].values, row["us_per_stroke"].values
        keep = np.isfinite(err) & np.isfinite(cost)
        if keep.any():
            ax.loglog(cost[keep], np.maximum(err[keep], floor), "o-", label=str(method))
    ax.axhline(1e-4, color="grey", ls="--", lw=1, label="1e-4 km/h")
    ax.set_xlabel(_label(d["us_per_stroke"]))
    ax.set_ylabel(_label(d["error_kmh"]))
    ax.legend(fontsize=8)
    ax.set_title(title)
    return fig


def stability(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 2: outcome of the isolated contact per method/setting and spring constant."""
    from matplotlib.colors import ListedColormap

    d = ds[0]
    names = d["outcome"].attrs["flag_meanings"].split()
    colours = ["#2ca02c", "#bcbd22", "#1f77b4", "#ff7f0e", "#d62728", "#7f7f7f"]
    fig, ax = plt.subplots(figsize=(7.5, 0.35 * d.sizes["case"] + 1.8))
    mesh = ax.pcolormesh(
        np.log10(d["k_contact"].values),
        np.arange(d.sizes["case"]),
        d["outcome"].values,
        cmap=ListedColormap(colours[: len(names)]),
        vmin=-0.5,
        vmax=len(names) - 0.5,
        shading="nearest",
    )
    ax.set_yticks(np.arange(d.sizes["case"]), [str(c) for c in d["case"].values], fontsize=7)
    ax.set_xlabel("log10 k_contact (N/m)")
    ax.set_ylabel(_label(d["case"]))
    ax.axvspan(np.log10(188), np.log10(19000), color="k", alpha=0.08, label="paper's k range")
    bar = plt.colorbar(mesh, ax=ax, ticks=np.arange(len(names)))
    bar.ax.set_yticklabels(names, fontsize=8)
    ax.set_title(title)
    return fig


def ladder(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Study 3: the instantaneous-impact model against the spring contact, stroke by stroke."""
    d = ds[0]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    diff = d["v_out_impact"] - d["v_out_spring"]
    ax.plot(d["v_out_spring"], diff, "o")
    ax.axhspan(-1.0, 1.0, color="g", alpha=0.1, label="1 km/h tolerance of the speed claims")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel(_label(d["v_out_spring"]))
    ax.set_ylabel("impact model - spring contact (km/h)")
    ax.legend()
    ax.set_title(title)
    return fig


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
        ax.set_xlabel(_label(d[name]))
        ax.set_ylabel("RMS normalised residual (1)")
        ax.set_title(f"fit set {d.attrs.get('fit_set', '')}: {name}", fontsize=9)
    fig.suptitle(title, fontsize=10)
    return fig


def claims_readings(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """Robustness: the share of claim-level variants in which each claim (row) is within
    tolerance, under each consistent reading (column); fit claims marked with '*'."""
    d = ds[0]
    share = d["within"].mean("variant").transpose("claim", "reading")
    fig, ax = plt.subplots(figsize=(8.0, 0.17 * d.sizes["claim"] + 1.6))
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
    plt.colorbar(mesh, ax=ax, label="share of variants within tolerance")
    ax.set_title(title, fontsize=10)
    return fig


def ladder_claims(ds: Sequence[xr.Dataset], title: str) -> plt.Figure:
    """The model ladder: each claim (row) under each rung (column), green within the
    paper's tolerance, red outside, grey where the rung cannot answer it; fit claims marked
    '*', the value written in each cell."""
    d = ds[0]
    state = np.where(d["comparable"].values == 0, 0.5, d["within"].values.astype(float)).T
    fig, ax = plt.subplots(figsize=(1.15 * d.sizes["rung"] + 3.8, 0.2 * d.sizes["claim"] + 1.8))
    colours = matplotlib.colors.ListedColormap(["#e8a8a0", "#d9d9d9", "#a8d8a0"])
    ax.pcolormesh(
        np.arange(d.sizes["rung"] + 1),
        np.arange(d.sizes["claim"] + 1),
        state,
        cmap=colours,
        vmin=0,
        vmax=1,
        edgecolors="white",
        linewidth=0.5,
    )
    for j, column in enumerate(d["value"].values):
        for i, value in enumerate(column):
            if np.isfinite(value):
                ax.text(j + 0.5, i + 0.5, f"{value:.4g}", ha="center", va="center", fontsize=5)
    fit = d["fit_set"].values
    labels = [f"{c}{' *' if f else ''}" for c, f in zip(d["claim"].values, fit, strict=True)]
    ax.set_yticks(np.arange(d.sizes["claim"]) + 0.5, labels, fontsize=6)
    ax.set_xticks(np.arange(d.sizes["rung"]) + 0.5, d["rung"].values, fontsize=7, rotation=30)
    ax.invert_yaxis()
    ax.set_ylabel("claim (* used for fit)")
    ax.set_xlabel("rung (in order of model detail); green: within tolerance, grey: no answer")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    return fig


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


#: The drawing functions by name (:attr:`tennis_stroke.replication.registry.Figure.draw`).
DRAWERS: dict[str, Callable[..., plt.Figure]] = {
    fn.__name__: fn
    for fn in (
        angle_map,
        omegas,
        mass_length,
        delay_map,
        v_tau,
        strobe,
        elbow_force,
        elbow_paths,
        work_precision,
        stability,
        ladder,
        score_profiles,
        claims_readings,
        ladder_claims,
        ladder_cost,
    )
}


def paper_marks(ax, marks: Sequence[Mapping], axes: Sequence[str]) -> None:
    """The paper's value of each mark (:func:`~tennis_stroke.replication.marks.mark_values`)
    in red, labelled with its claim: a ring at a point, a dashed line across the axes."""
    for mark in marks:
        along_x = mark["axis"] == axes[0]
        text = f"paper: {mark['claim']} = {mark['paper']:g}"
        if mark["other_paper"] is None:
            line = ax.axvline if along_x else ax.axhline
            line(mark["paper"], color="r", ls="--", lw=1.2, label=text)
            continue
        x, y = (mark["paper"], mark["other_paper"])[:: 1 if along_x else -1]
        text = f"paper: {mark['claim']} at ({x:g}, {y:g})"
        ax.plot(x, y, "o", ms=10, mfc="none", mec="r", mew=2, label=text)
    if marks:
        ax.legend(fontsize=7, loc="best", framealpha=0.7)


def drawn(
    figure: Figure,
    inputs: Sequence[str | Path],
    note: str = "",
    marks: Sequence[Mapping] = (),
) -> plt.Figure:
    """``figure`` (a registry entry) drawn from its result files: the drawing function's
    figure, the paper's ``marks`` in red, ``note`` (a scenario's changes) as a second
    title line."""
    datasets = [load_result(p) for p in inputs]
    fig = DRAWERS[figure.draw](datasets, figure.filled_title(datasets[0].attrs), *figure.args)
    paper_marks(fig.axes[0], marks, figure.axes)
    if note:  # below the drawing's own title, wrapped to the figure's width
        ax = fig.axes[0]
        ax.set_title(ax.get_title() + "\n" + "\n".join(textwrap.wrap(note, 48)))
    fig.tight_layout()
    return fig


def draw(
    figure: str | Figure,
    inputs: Sequence[str | Path],
    output: str | Path,
    note: str = "",
    marks: Sequence[Mapping] = (),
) -> None:
    """Draw ``figure`` (a registry entry, or its name in :data:`FIGURES`) from its result
    files into ``output`` (PNG, at the entry's dpi): :func:`drawn`."""
    figure = FIGURES[figure] if isinstance(figure, str) else figure
    fig = drawn(figure, inputs, note, marks)
    fig.savefig(output, dpi=figure.dpi)
    plt.close(fig)
