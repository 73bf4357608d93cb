"""The identification and robustness tables of docs/assumptions.md, from the result
files: its generated blocks ``identification`` and ``robustness``, which
``tools/readme_results.py`` writes and checks with the README's (never typed by hand).
"""

from pathlib import Path

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
