"""Every claim across the readings consistent with the paper, and a cause for every
deviation (``config/readings.yaml``: ``multiverse``, ``evidence``).

:func:`evaluate_readings` evaluates every claim of ``config/claims.yaml`` on the paper's
experiments run under each kept reading of the multiverse
(:mod:`tennis_stroke.experiments.multiverse`), under every combination of the
claim-level readings (the instant Fig. 11's theta and Table I's omega2 are quoted at,
the figures' curves).  :func:`classify` gives each claim its robustness class and
:func:`evidence` each deviation of the default reading its evidence class, both by the
rules declared in ``config/readings.yaml`` before any result existed.
"""

from __future__ import annotations

import copy
import itertools
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
import xarray as xr

from ..chunking import select_rows
from ..experiments.identification import quoted_variable
from ..experiments.multiverse import (
    CLAIM_LEVEL,
    CURVE_FILES,
    experiment_config,
    paper_results,
    reading_of,
)
from ..experiments.reading_space import ReadingSpace
from ..io import labelled
from ..solver.settings import SolverSettings
from .claims import measure, within

#: Robustness classes with their meaning, in the order of config/readings.yaml.
ROBUSTNESS_MEANING = {
    "used_for_fit": "in a fit set: it chose the readings, so it cannot confirm them",
    "robust": "passes under every consistent reading",
    "reading_dependent": "passes under some consistent readings; the deciding unknown is "
    "the one whose choices (or lower and upper half) differ most in pass rate",
    "not_reproduced": "fails under every consistent reading",
}
ROBUSTNESS = tuple(ROBUSTNESS_MEANING)
#: Evidence classes of a deviation (a claim that does not pass under the default
#: reading) with their meaning, in the order of config/readings.yaml.
EVIDENCE_MEANING = {
    "ill_conditioned": "an optimum's location whose objective at the paper's value lies "
    "within the speed tolerance of the optimum: the paper's argument is as good as ours",
    "reading_dependent": "passes under some consistent readings (the deciding unknown is named)",
    "paper_inconsistency": "passes under some consistent readings, but none of them also "
    "passes every claim the default passes",
    "irreducible": "fails under every consistent reading (the best value reached is shown)",
}
EVIDENCE = tuple(EVIDENCE_MEANING)
#: Columns :func:`annotate` adds to the claims table.
COLUMNS = (
    "robustness",
    "pass_share",
    "deciding",
    "best_value",
    "best_residual",
    "evidence",
    "objective_gap",
)


def variants(space: ReadingSpace) -> list[dict[str, str]]:
    """Every combination of the claim-level readings (:data:`CLAIM_LEVEL`)."""
    names = list(CLAIM_LEVEL)
    return [
        dict(zip(names, combo, strict=True))
        for combo in itertools.product(*(space.discrete[n] for n in names))
    ]


def quoted_claims(
    claims: Sequence[Mapping], space: ReadingSpace, instants: Mapping[str, str]
) -> list[dict]:
    """The claims with each quoted variable read at the instant of its quoting group
    (``instants``: group -> ``phi0`` or ``contact``; groups not named keep the file's
    variable of ``config/claims.yaml``)."""
    group_of = space.quoting_of_claim()
    out = []
    for c in claims:
        group = group_of.get(c["id"])
        if group in instants and "var" in c["measure"]:
            c = copy.deepcopy(dict(c))
            c["measure"]["var"] = quoted_variable(c["measure"]["var"], instants[group], space)
        out.append(c)
    return out


def files_of_reading(
    results: Mapping[str, xr.Dataset], curves: str, l1_max: float | None
) -> dict[str, xr.Dataset]:
    """The result files one claim evaluation reads: the curve files of ``curves``, and
    the Figs. 5-6 map cut at ``L1 <= l1_max`` (the unknown end of the figures' axis)."""
    files = {k: v for k, v in results.items() if "/" not in k}
    for key in CURVE_FILES:
        files[key] = results[f"{key}/{curves}"]
    if l1_max is not None and "ml" in files:
        ml = files["ml"]
        files["ml"] = ml.isel(L1=np.flatnonzero(ml["L1"].values <= l1_max + 1e-9))
    return files


def evaluate_reading(
    claims: Sequence[Mapping],
    space: ReadingSpace,
    results: Mapping[str, xr.Dataset],
    reading: Mapping[str, object],
) -> tuple[np.ndarray, list[dict[str, str]]]:
    """Values of every claim (``variant x claim``) under ``reading`` (its discrete
    readings and continuous unknowns) and every claim-level variant.

    Claims that no claim-level reading touches are evaluated once."""
    level = space.quoting_of_claim()
    touched = {c for c, g in level.items() if g in CLAIM_LEVEL}
    touched |= set(space.raw["figure_curves"].get("claims", []))
    fixed = {g: str(reading[g]) for g in space.raw["quoting"] if g in reading}
    l1_max = reading.get("fig6_L1_max")
    out = []
    cases = variants(space)
    first: np.ndarray | None = None
    for case in cases:
        instants = {**fixed, **{g: case[g] for g in CLAIM_LEVEL if g in space.raw["quoting"]}}
        files = files_of_reading(results, case["figure_curves"], l1_max)
        row = []
        for j, c in enumerate(quoted_claims(claims, space, instants)):
            if first is not None and c["id"] not in touched:
                row.append(first[j])
                continue
            row.append(measure(c["measure"], files))
        values = np.array(row, dtype=float)
        first = values if first is None else first
        out.append(values)
    return np.array(out), cases


def readings_results(
    claims: Sequence[Mapping],
    space: ReadingSpace,
    readings: xr.Dataset,
    values: np.ndarray,
    cases: Sequence[Mapping[str, str]],
) -> xr.Dataset:
    """The claims x readings file: ``value`` and ``within`` (1 if within the claim's
    tolerance) over ``(reading, variant, claim)``, with each reading's discrete readings
    and unknowns and each variant's claim-level readings."""
    paper = np.array([c["paper_value"] for c in claims], dtype=float)
    tol = np.array([c["tolerance"] for c in claims], dtype=float)
    ok = within(values, paper, tol)
    ds = xr.Dataset(
        {
            "value": (
                ("reading", "variant", "claim"),
                values,
                {"long_name": "reproduced value of the claim (its unit: claim_unit)"},
            ),
            "within": (
                ("reading", "variant", "claim"),
                ok.astype(np.int8),
                {"long_name": "1 if within the claim's declared tolerance", "units": "1"},
            ),
            **{
                k: ("variant", [case[k] for case in cases], {"long_name": f"reading {k}"})
                for k in CLAIM_LEVEL
            },
            "paper_value": ("claim", paper, {"long_name": "paper's value"}),
            "tolerance": ("claim", tol, {"long_name": "declared tolerance"}),
            "claim_unit": ("claim", [c["unit"] for c in claims], {"long_name": "unit"}),
            "fit_set": (
                "claim",
                [space.fit_of_claim().get(c["id"], "") for c in claims],
                {"long_name": "fit set that uses the claim (empty: held out)"},
            ),
        },
        coords={
            "reading": readings["reading"],
            "variant": ("variant", np.arange(len(cases), dtype=np.int32), {"units": "1"}),
            "claim": ("claim", [c["id"] for c in claims], {"long_name": "claim id"}),
        },
    )
    for k, v in readings.data_vars.items():
        ds[k] = v
    ds.attrs.update(readings.attrs)  # provenance of the screen that chose the readings
    return labelled(ds)


def evaluate_readings(
    claims: Sequence[Mapping],
    space: ReadingSpace,
    readings: xr.Dataset,
    config: Mapping,
    settings: SolverSettings,
    rows: tuple[int, int] | None = None,
    threads: int | None = 1,
) -> xr.Dataset:
    """Every claim under every kept reading (or chunk ``rows = (index, count)`` of them,
    :func:`tennis_stroke.chunking.chunk_rows`): the paper's experiments run at the
    multiverse's resolution over the workflow ``config``, the claims evaluated under
    every claim-level variant (:func:`readings_results`)."""
    index = select_rows(np.arange(readings.sizes["reading"]), rows)
    cases = variants(space)
    values = np.full((index.size, len(cases), len(claims)), np.nan)
    for n, i in enumerate(index):
        reading = reading_of(readings, int(i))
        cfg, model = experiment_config(config, space, reading)
        results = paper_results(cfg, model, settings, space.discrete["figure_curves"], threads)
        values[n] = evaluate_reading(claims, space, results, reading)[0]
    return readings_results(claims, space, readings.isel(reading=index), values, cases)


def _deciding(ok: np.ndarray, ds: xr.Dataset, space: ReadingSpace) -> str:
    """The unknown whose choices (discrete) or lower/upper half of the range (continuous)
    differ most in pass rate, with the passing and all (reading, variant) cells of each:
    ``name (a 8/8, b 0/472)``."""
    best, text = -1.0, ""
    groups: dict[str, dict[str, np.ndarray]] = {}
    for name in ds.data_vars:
        dims = ds[name].dims
        if dims == ("reading",) and name in space.discrete:
            labels = np.broadcast_to(ds[name].values[:, None], ok.shape)
        elif dims == ("variant",) and name in CLAIM_LEVEL:
            labels = np.broadcast_to(ds[name].values[None, :], ok.shape)
        elif dims == ("reading",) and name in space.continuous:
            u = space.continuous[name].to_unit(ds[name].values)
            half = np.where(u < 0.5, "lower half", "upper half")
            labels = np.broadcast_to(half[:, None], ok.shape)
        else:
            continue
        groups[name] = {str(v): ok[labels == v] for v in np.unique(labels)}
    for name, by_choice in groups.items():
        rates = {k: float(np.mean(v)) for k, v in by_choice.items() if v.size}
        if len(rates) < 2:
            continue
        spread = max(rates.values()) - min(rates.values())
        if spread > best + 1e-12:
            best = spread
            shown = ", ".join(f"{k} {int(by_choice[k].sum())}/{by_choice[k].size}" for k in rates)
            text = f"{name} ({shown})"
    return text


def classify(ds: xr.Dataset, space: ReadingSpace, claims: Sequence[Mapping]) -> pd.DataFrame:
    """Robustness class of every claim over the consistent readings (all kept readings x
    all claim-level variants): share passing, the deciding unknown of a
    reading-dependent claim, and the value closest to the paper (with its normalised
    residual)."""
    fit_of = space.fit_of_claim()
    rows = []
    for j, c in enumerate(claims):
        values = ds["value"].values[:, :, j]
        ok = ds["within"].values[:, :, j].astype(bool)
        share = float(ok.mean()) if ok.size else float("nan")
        residual = np.abs(values - c["paper_value"]) / max(c["tolerance"], 1e-300)
        finite = np.isfinite(residual)
        k = int(np.nanargmin(np.where(finite, residual, np.nan))) if finite.any() else None
        best_value = float(values.ravel()[k]) if k is not None else float("nan")
        best_residual = float(residual.ravel()[k]) if k is not None else float("nan")
        if c["tolerance"] == 0:  # qualitative: 0 (holds) or inf (does not)
            best_residual = 0.0 if ok.any() else 1.0
        if c["id"] in fit_of:
            cls = "used_for_fit"
        elif ok.all():
            cls = "robust"
        elif ok.any():
            cls = "reading_dependent"
        else:
            cls = "not_reproduced"
        deciding = _deciding(ok, ds, space) if cls == "reading_dependent" else ""
        rows.append(
            {
                "id": c["id"],
                "robustness": cls,
                "pass_share": share,
                "deciding": deciding,
                "best_value": best_value,
                "best_residual": best_residual,
            }
        )
    return pd.DataFrame(rows)


def objective_gap(spec: Mapping[str, str], argument: float, files: Mapping[str, xr.Dataset]):
    """How far (km/h) the objective ``v_out`` of the file lies below its optimum at the
    paper's ``argument`` of coordinate ``coord`` (nearest grid point; the other
    coordinates at their best)."""
    v = files[spec["file"]]["v_out"].where(files[spec["file"]]["status"] == 0)
    at = v.sel({spec["coord"]: argument}, method="nearest")
    return float(v.max()) - float(at.max())


def evidence(
    table: pd.DataFrame,
    ds: xr.Dataset,
    space: ReadingSpace,
    files: Mapping[str, xr.Dataset],
) -> pd.DataFrame:
    """Evidence class of every deviation of the default reading (status ``fail`` or
    ``known_deviation`` in ``table``) and, for the argmax claims of
    ``evidence.objective``, the objective's gap at the paper's argument."""
    rule = space.raw["evidence"]
    passing = [i for i, s in enumerate(table["status"]) if s == "pass"]
    ids = list(ds["claim"].values)
    held = ds["within"].values[:, :, [ids.index(table["id"].iloc[i]) for i in passing]]
    all_default = held.all(axis=-1) if held.size else np.ones(ds["within"].shape[:2], bool)
    rows = []
    for _, row in table.iterrows():
        cls, gap = "", float("nan")
        if row["status"] in ("fail", "known_deviation"):
            j = ids.index(row["id"])
            ok = ds["within"].values[:, :, j].astype(bool)
            spec = rule["objective"].get(row["id"])
            if spec is not None:
                gap = objective_gap(spec, float(row["paper_value"]), files)
            if spec is not None and gap <= float(rule["flat_gap"]):
                cls = "ill_conditioned"
            elif ok.any():
                cls = "reading_dependent" if (ok & all_default).any() else "paper_inconsistency"
            else:
                cls = "irreducible"
        rows.append({"id": row["id"], "evidence": cls, "objective_gap": gap})
    return pd.DataFrame(rows)


def annotate(
    table: pd.DataFrame,
    ds: xr.Dataset,
    space: ReadingSpace,
    claims: Sequence[Mapping],
    files: Mapping[str, xr.Dataset],
) -> pd.DataFrame:
    """The claims table with the robustness and evidence columns (:data:`COLUMNS`)."""
    out = table.merge(classify(ds, space, claims), on="id", how="left")
    return out.merge(evidence(table, ds, space, files), on="id", how="left")
