"""The report's sections on what we computed beyond the paper's figures, each built from
its result files: the fits of the readings (:func:`fit_tables`), the robustness across
the readings consistent with the paper (:func:`robustness_section`), the validation of
the targeted evaluation against the maps (:func:`validation_section`), the solver
studies' tables and the model ladder's largest error (:func:`studies_section`,
:func:`ladder_summary`) and the model ladder (:func:`model_ladder_section`)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd
import xarray as xr

from ..io.netcdf import load_result
from ..studies.tables import rule_table
from .claims import tally
from .formats import _table
from .ladder import claims_by_rung, experiments_by_rung, findings, verdict
from .robustness import ROBUSTNESS_MEANING, ROBUSTNESS_WORDS


def fit_tables(inference: Mapping[str, str], rows: int = 6) -> list[dict]:
    """The best fits and the leave-one-out table of each fit set (``inference``: the
    registry's keys ``{fit}_fits`` and ``{fit}_loo`` -> paths)."""
    out = []
    for key in sorted(k for k in inference if k.endswith("_fits")):
        fits = load_result(inference[key])
        loo = load_result(inference[key.removesuffix("_fits") + "_loo"])
        columns = [v for v in fits.data_vars if fits[v].dims == ("combination",)]
        table = fits[columns].to_dataframe().head(rows)
        default = {
            k.removeprefix("default_"): v for k, v in fits.attrs.items() if k.startswith("default_")
        }
        out.append(
            {
                "name": fits.attrs["fit_set"],
                "claims": fits.attrs["fit_claims"],
                "n": fits.sizes["combination"],
                "default": ", ".join(f"{k} = {v}" for k, v in default.items()),
                "table": _table(table.round(4), index=False),
                "loo": _table(loo.to_dataframe().round(4)),
            }
        )
    return out


def robustness_section(claims: pd.DataFrame, inference: Mapping[str, str]) -> dict:
    """The robustness section: the consistent set, the classes and the evidence."""
    if "robustness" not in inference or "robustness" not in claims:
        return {}
    numeric = ("paper_value", "best_value", "best_residual", "objective_gap")
    claims = claims.assign(
        **{c: pd.to_numeric(claims[c], errors="coerce") for c in numeric if c in claims}
    )
    screen = load_result(inference["robustness_screen"])
    kept = load_result(inference["robustness"])
    combos = sorted(
        {
            ", ".join(
                f"{k}={kept[k].values[i]}"
                for k in kept.data_vars
                if kept[k].dims == ("reading",) and kept[k].dtype.kind in "OUS"
            )
            for i in range(kept.sizes["reading"])
        }
    )
    classes = tally(claims)["robustness"]  # the held-out claims, each in one class
    deviations = claims[claims["evidence"] != ""]
    return {
        "candidates": screen.sizes["candidate"] * screen.sizes["combination"],
        "n_candidates": screen.sizes["candidate"],
        "n_combinations": screen.sizes["combination"],
        "consistent": int(screen["consistent"].sum()),
        "readings": kept.sizes["reading"],
        "variants": kept.sizes["variant"],
        "combos": combos,
        "classes": [
            {
                "word": ROBUSTNESS_WORDS.get(k, k or "no class"),
                "n": n,
                "meaning": ROBUSTNESS_MEANING.get(k, "no robustness class was computed"),
            }
            for k, n in classes.parts
        ],
        "evidence": _table(
            deviations[
                [
                    "id",
                    "paper_value",
                    "reproduced_value",
                    "evidence",
                    "best_value",
                    "best_residual",
                    "objective_gap",
                ]
            ],
            index=False,
            float_format=lambda x: f"{x:.4g}",
            na_rep="-",
        ),
    }


def validation_table(claims: pd.DataFrame, validation: xr.Dataset) -> pd.DataFrame:
    """Per searched claim: the largest |targeted - map| (in tolerances) under the default
    reading (``claims.csv``) and over the validation's readings, with how many of them
    agree within the agreement, differ by no more than the map's grid step, or differ
    unexplained."""
    by_id = claims.set_index("id")
    rows = []
    for j, cid in enumerate(validation["claim"].values):
        diff = validation["difference"].values[:, j]
        causes = list(validation["cause"].values[:, j])
        default = by_id.loc[cid] if cid in by_id.index else None
        if default is not None:
            causes.append(default["map_cause"])
        rows.append(
            {
                "claim": cid,
                "default: targeted": float(default["reproduced_value"])
                if default is not None
                else np.nan,
                "default: map": float(default["map_value"]) if default is not None else np.nan,
                "default: difference (tol)": float(default["map_difference"])
                if default is not None
                else np.nan,
                "readings: largest difference (tol)": float(np.nanmax(diff)),
                "agree": causes.count("agrees"),
                "grid step": causes.count("grid_step"),
                "unexplained": causes.count("unexplained"),
            }
        )
    return pd.DataFrame(rows)


def validation_section(claims: pd.DataFrame, inference: Mapping[str, str]) -> dict:
    """The validation of the targeted evaluation against the full maps."""
    paths = [v for k, v in inference.items() if k.startswith("validation_")]
    if not paths or "map_cause" not in claims:
        return {}
    ds = xr.concat([load_result(p) for p in paths], dim="claim", data_vars="all")
    table = validation_table(claims, ds)
    return {
        "readings": ds.sizes["reading"],
        "agreement": float(ds.attrs["agreement"]),
        "unexplained": int(table["unexplained"].sum()),
        "table": _table(table, index=False, float_format=lambda x: f"{x:.4g}", na_rep="-"),
    }


def ladder_summary(error: float | None, claims: pd.DataFrame) -> dict:
    """The model ladder's largest v_out error (km/h) against the smallest tolerance of the
    claims in km/h: ``error`` and ``tolerance`` as text, ``above`` whether it exceeds it."""
    speeds = claims.loc[claims["unit"] == "km/h", "tolerance"].astype(float)
    tolerance = float(speeds.min()) if len(speeds) else float("nan")
    if error is None:
        return {"error": "n/a", "tolerance": f"{tolerance:g}", "above": False}
    return {"error": f"{error:.2f}", "tolerance": f"{tolerance:g}", "above": error > tolerance}


def _optimum_table(ds: xr.Dataset) -> dict:
    """The optimum-search study's table: each method's errors and time."""
    return {
        "title": "The optimum of Figs. 5-6: nested grids (coarse grid, fine grid, parabola) "
        "and searches (bracket, compass search) against a finer reference grid",
        "html": _table(ds.to_dataframe().round(4)),
    }


def _stability_table(ds: xr.Dataset) -> dict:
    """The stability study's table: per case (method and setting), how many spring
    constants end in each outcome."""
    names = ds["outcome"].attrs["flag_meanings"].split()
    counts = pd.DataFrame(
        [[int((row == i).sum()) for i in range(len(names))] for row in ds["outcome"].values],
        index=[str(c) for c in ds["case"].values],
        columns=names,
    )
    return {
        "title": "Stability: outcomes of the isolated contact over k = "
        f"{float(ds.k_contact.min()):g} ... {float(ds.k_contact.max()):g} N/m",
        "html": _table(counts),
    }


def rule_caption(ds: xr.Dataset) -> str:
    """What the work-precision study's rule table is, from its file (the page's title of
    it and the article's caption)."""
    return (
        "A rule for a new scene: the cheapest method and tolerance (or RK4 step) "
        f"whose worst of {ds.sizes['stroke']} strokes per scene meets "
        f"{ds.attrs['required_v_out_error_kmh']:g} km/h in v_out and "
        f"{ds.attrs['required_event_time_error_s']:g} s in the event times, against "
        f"{ds.attrs['reference']}; cost in median right-hand-side evaluations per stroke; "
        f"the default is {ds.attrs['default_method']} at {ds.attrs['default_setting']:g}"
    )


def _rule_table(ds: xr.Dataset) -> dict:
    """The work-precision study's rule table: per scene, the cheapest method and setting
    that meets the requested accuracy (:func:`tennis_stroke.studies.tables.rule_table`),
    beside the default settings' cost."""
    table = rule_table(ds).set_index("scene")
    return {
        "title": rule_caption(ds),
        "html": _table(table, float_format=lambda x: f"{x:.3g}", na_rep="-"),
    }


#: The studies' tables on the page, in its order: the study (its key in the table of
#: experiments, :data:`~tennis_stroke.experiments.specs.STUDY_RESULTS`) and the function
#: that makes its title and table.
STUDY_TABLES = {
    "work_precision": _rule_table,
    "optimum_cost": _optimum_table,
    "stability": _stability_table,
}
#: The study whose file gives the model ladder's largest v_out error (km/h), its
#: attribute ``max_error_impact_kmh``.
LADDER_STUDY = "ladder"


def studies_section(studies: Mapping[str, str]) -> tuple[float | None, list[dict]]:
    """The model ladder's largest error (km/h; None without its file) and the tables of
    the studies (:data:`STUDY_TABLES`) whose files are given (``studies``: the studies'
    keys -> paths)."""
    ladder_error = None
    if LADDER_STUDY in studies:
        ladder_error = float(load_result(studies[LADDER_STUDY]).attrs["max_error_impact_kmh"])
    tables = [
        tabulate(load_result(studies[key]))
        for key, tabulate in STUDY_TABLES.items()
        if key in studies
    ]
    return ladder_error, tables


def model_ladder_section(inference: Mapping[str, str]) -> dict:
    """The model ladder section: the thesis tested, each rung's findings, the cheapest
    rung per experiment and the claims-by-rungs table (empty without the ladder's file)."""
    if "model_ladder" not in inference:
        return {}
    ds = load_result(inference["model_ladder"])
    seconds = float(ds["seconds"].sel(rung=ds.attrs["reference_rung"]).sum())
    return {
        "verdict": verdict(ds),
        "findings": findings(ds),
        "reference": ds.attrs["reference_rung"],
        "agreement": f"{float(ds.attrs['adoption_agreement']):g}",
        "reference_seconds": f"{seconds:.2f}",
        "rungs": ", ".join(str(r) for r in ds["rung"].values),
        "experiments": _table(experiments_by_rung(ds).round(3), na_rep="-"),
        "claims": _table(claims_by_rung(ds)),
    }
