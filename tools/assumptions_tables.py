"""The identification and robustness tables of docs/assumptions.md, from the result
files: its generated blocks ``identification`` and ``robustness``, which
``tools/readme_results.py`` writes and checks with the README's (never typed by hand).
"""

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from tennis_stroke.replication.robustness import CONFIDENCE, MARGIN, across_short


def _row(cells) -> str:
    return "| " + " | ".join(str(c) for c in cells) + " |"


def tables(folder: Path, rows: int = 6) -> str:
    out = []
    for fit in ("model", "elbow_force"):
        fits = xr.load_dataset(folder / f"{fit}_fits.nc")
        loo = xr.load_dataset(folder / f"{fit}_loo.nc")
        cols = [v for v in fits.data_vars if fits[v].dims == ("combination",)]
        out.append(
            f"**Fit set `{fit}`** ({fits.sizes['combination']} combinations; "
            f"claims: {fits.attrs['fit_claims']})\n"
        )
        out.append(_row(cols))
        out.append(_row(["--"] * len(cols)))
        for i in range(min(rows, fits.sizes["combination"])):
            out.append(
                _row(
                    f"{fits[c].values[i]:.4g}" if fits[c].dtype.kind == "f" else fits[c].values[i]
                    for c in cols
                )
            )
        default = {
            k.removeprefix("default_"): v for k, v in fits.attrs.items() if k.startswith("default_")
        }
        out.append(
            "\nDefault by the declared rule: "
            + ", ".join(f"`{k} = {v}`" for k, v in default.items())
            + ".\n"
        )
        out.append(
            _row(
                [
                    "claim",
                    "paper",
                    "best fit",
                    "residual",
                    "left-out prediction",
                    "left-out residual",
                ]
            )
        )
        out.append(_row(["--"] * 6))
        for i, claim in enumerate(fits["claim"].values):
            out.append(
                _row(
                    [
                        claim,
                        f"{float(fits.paper_value[i]):g}",
                        f"{float(fits.value[0, i]):.4g}",
                        f"{float(fits.residual[0, i]):+.2f}",
                        f"{float(loo.predicted[i]):.4g}",
                        f"{float(loo.residual[i]):+.2f}",
                    ]
                )
            )
        out.append("")
    return "\n".join(out)


def robustness_tables(results: Path) -> str:
    """The consistent set, the robustness classes of the held-out claims and the evidence
    of every deviation (results/robustness, results/claims.csv)."""
    screen = xr.load_dataset(results / "robustness" / "screen.nc")
    kept = xr.load_dataset(results / "robustness" / "claims.nc")
    claims = pd.read_csv(results / "claims.csv", keep_default_na=False)
    n, c = screen.sizes["candidate"], screen.sizes["combination"]
    per_combo = screen["consistent"].sum("candidate").values
    combos = [
        ", ".join(
            f"{k}={screen[k].values[i]}"
            for k in screen.data_vars
            if screen[k].dims == ("combination",)
        )
        + f": {int(per_combo[i])}"
        for i in range(c)
        if per_combo[i]
    ]
    out = [
        f"Screen: {n} Sobol candidates x {c} discrete combinations = {n * c}; "
        f"consistent: {int(per_combo.sum())}; kept: {kept.sizes['reading']}, each under "
        f"{kept.sizes['variant']} claim-level variants.  Consistent per combination: "
        + "; ".join(combos)
        + ".\n",
    ]
    ranges = []
    for name in ("k_contact", "ball_mass", "elbow_force_mass", "table1_tau_F", "fig6_L1_max"):
        values = kept[name].values
        ranges.append(
            f"`{name}` {values.min():.4g}-{values.max():.4g} {kept[name].attrs.get('units', '')}"
        )
    out.append("Ranges of the kept readings: " + ", ".join(ranges) + ".\n")
    held = claims[claims["fit_set"] == ""]
    counts = held["robustness"].value_counts()
    out.append(
        "Held-out claims by robustness class: "
        + ", ".join(f"{k} {v}" for k, v in counts.items())
        + f" (of {len(held)}; {len(claims) - len(held)} used for fit).\n"
    )
    robust = held[held["robustness"] == "robust"]
    if len(robust) and "class_bound" in robust:
        out.append(
            f"Each robust claim passes under all {int(robust['readings'].iloc[0])} readings: "
            f"its failure share is at most {100 * float(robust['class_bound'].max()):.2g} % "
            f"({100 * CONFIDENCE:.0f} %, exact).\n"
        )
    header = f"pass share (across readings, {100 * CONFIDENCE:.0f} % exact)"
    out.append(_row(["claim", "default status", "robustness", header, "deciding unknown"]))
    out.append(_row(["--"] * 5))
    for _, r in held[held["robustness"] != "robust"].iterrows():
        share = across_short(r.to_dict())
        out.append(_row([r["id"], r["status"], r["robustness"], share, r["deciding"] or "-"]))
    out.append(
        f"\n`*`: the readings are too few to decide the class at a share of "
        f'{100 * MARGIN:.0f} % ([inference.md](inference.md), "How sure each class is").\n'
    )
    out.append(
        _row(
            [
                "deviation",
                "paper",
                "default",
                "evidence",
                "best value",
                "best residual",
                "objective gap (km/h)",
            ]
        )
    )
    out.append(_row(["--"] * 7))
    for _, r in claims[claims["evidence"] != ""].iterrows():
        gap = r["objective_gap"]
        out.append(
            _row(
                [
                    r["id"],
                    f"{float(r['paper_value']):g}",
                    f"{float(r['reproduced_value']):.4g}",
                    r["evidence"],
                    f"{float(r['best_value']):.4g}",
                    f"{float(r['best_residual']):.2f}",
                    f"{float(gap):.3f}" if gap != "" else "-",
                ]
            )
        )
    return "\n".join(out) + "\n"


#: The design's size before the amendment of 2026-12-06 (config/readings.yaml): its
#: candidates are the first of today's design (same seed), so the readings they gave are
#: the sample the robustness classes rested on until then.
PREVIOUS_CANDIDATES = 32768


def coverage(results: Path) -> str:
    """How the kept readings cover the consistent set: the readings of the first
    :data:`PREVIOUS_CANDIDATES` candidates (the sample before the amendment) against those
    of the candidates added, each continuous unknown's quartiles in its declared scale
    with the two-sample Kolmogorov-Smirnov test (:func:`scipy.stats.ks_2samp`: the two are
    disjoint blocks of one Sobol design, so a small p would say they cover the set
    differently), and each discrete combination's share."""
    from scipy.stats import ks_2samp

    from tennis_stroke.inference.reading_space import load_reading_space

    kept = xr.load_dataset(results / "robustness" / "readings.nc")
    space = load_reading_space(Path("config/readings.yaml"))
    old = kept["candidate"].values < PREVIOUS_CANDIDATES
    groups = {"before": old, "added": ~old}
    out = [
        f"Kept readings: {int(old.sum())} from the first {PREVIOUS_CANDIDATES} candidates "
        f"(the sample before 2026-12-06), {int((~old).sum())} from the "
        f"{int(space.raw['multiverse']['candidates']) - PREVIOUS_CANDIDATES} added; "
        "each unknown in its declared scale "
        "(log: the quartiles of log10, shown as values).\n",
        _row(
            [
                "unknown",
                "unit",
                "scale",
                "before: 5 / 25 / 50 / 75 / 95 %",
                "added: same",
                "KS D",
                "KS p",
            ]
        ),
        _row(["--"] * 7),
    ]
    for name, unknown in space.continuous.items():
        values = kept[name].values
        u = np.log10(values) if unknown.scale == "log" else values
        cells = []
        for mask in groups.values():
            q = np.percentile(u[mask], [5, 25, 50, 75, 95]) if mask.any() else np.array([])
            shown = 10**q if unknown.scale == "log" else q
            cells.append(" / ".join(f"{v:.4g}" for v in shown) or "-")
        test = ks_2samp(u[old], u[~old]) if old.any() and (~old).any() else None
        out.append(
            _row(
                [
                    f"`{name}`",
                    unknown.unit,
                    unknown.scale,
                    *cells,
                    f"{test.statistic:.2f}" if test else "-",
                    f"{test.pvalue:.2f}" if test else "-",
                ]
            )
        )
    names = [
        k for k in kept.data_vars if kept[k].dtype.kind in "OUS" and kept[k].dims == ("reading",)
    ]
    combos = pd.Series(
        [", ".join(f"{k}={kept[k].values[i]}" for k in names) for i in range(kept.sizes["reading"])]
    )
    out.append("")
    out.append(_row(["discrete combination", "before", "added"]))
    out.append(_row(["--"] * 3))
    for combo in combos.unique():
        same = (combos == combo).values
        out.append(
            _row(
                [
                    combo,
                    *(
                        f"{int((same & m).sum())} ({100 * (same & m).mean() / m.mean():.0f} %)"
                        for m in groups.values()
                    ),
                ]
            )
        )
    return "\n".join(out) + "\n"
