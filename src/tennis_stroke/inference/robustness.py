"""The robustness analysis, step 3: every claim of ``config/claims.yaml`` evaluated on the
paper's experiments run under each kept reading of the multiverse
(:mod:`tennis_stroke.inference.multiverse`), under every combination of the claim-level
readings (the instant Fig. 11's theta and Table I's omega2 are quoted at, the figures'
curves).  The replication classifies the result (:mod:`tennis_stroke.replication.robustness`).
"""

from __future__ import annotations

import copy
import itertools
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..experiments.grids import select_rows
from ..io.netcdf import labelled
from ..solver.settings import SolverSettings
from .claims import measure, within
from .identification import quoted_variable
from .labels import claim_facts, variable
from .multiverse import experiment_configs
from .reading_space import CLAIM_LEVEL, CURVE_FILES, ReadingSpace
from .targeted import targeted_files_of


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

    A claim is measured once per distinct thing it reads: its measure (the quoted
    variable of its instant) and, if it reads a curve file, the curves; the variants that
    change neither reuse the value."""
    fixed = {g: str(reading[g]) for g in space.raw["quoting"] if g in reading}
    l1_max = reading.get("fig6_L1_max")
    out, seen = [], {}
    cases = variants(space)
    for case in cases:
        instants = {**fixed, **{g: case[g] for g in CLAIM_LEVEL if g in space.raw["quoting"]}}
        files = files_of_reading(results, case["figure_curves"], l1_max)
        row = []
        for c in quoted_claims(claims, space, instants):
            names = c["measure"]["file"]
            names = names if isinstance(names, list) else [names]
            curves = case["figure_curves"] if set(names) & set(CURVE_FILES) else None
            key = (c["id"], repr(sorted(c["measure"].items())), curves)
            if key not in seen:
                seen[key] = measure(c["measure"], files)
            row.append(seen[key])
        out.append(np.array(row, dtype=float))
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
            "value": variable(("reading", "variant", "claim"), values, "robustness.value"),
            "within": variable(
                ("reading", "variant", "claim"), ok.astype(np.int8), "robustness.within"
            ),
            **{
                k: variable("variant", [case[k] for case in cases], "reading", name=k)
                for k in CLAIM_LEVEL
            },
            **claim_facts(paper, tol, [c["unit"] for c in claims]),
            "fit_set": variable(
                "claim", [space.fit_of_claim().get(c["id"], "") for c in claims], "fit_set"
            ),
        },
        coords={
            "reading": readings["reading"],
            "variant": variable(
                "variant", np.arange(len(cases), dtype=np.int32), "index", name="variant"
            ),
            "claim": variable("claim", [c["id"] for c in claims], "claim"),
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
    :func:`tennis_stroke.experiments.grids.chunk_rows`): the files the claims read, by
    the targeted evaluation (:func:`tennis_stroke.inference.targeted.targeted_files_of`,
    every reading's searches in lockstep) on the rows of the multiverse's resolution over
    the workflow ``config``, the claims evaluated under every claim-level variant
    (:func:`readings_results`)."""
    index = select_rows(np.arange(readings.sizes["reading"]), rows)
    cases = variants(space)
    values = np.full((index.size, len(cases), len(claims)), np.nan)
    chosen, configs, models = experiment_configs(config, space, readings, index)
    found = targeted_files_of(
        configs,
        models,
        settings,
        space.discrete["figure_curves"],
        [r.get("fig6_L1_max") for r in chosen],
        threads,
    )
    for n, (reading, results) in enumerate(zip(chosen, found, strict=True)):
        values[n] = evaluate_reading(claims, space, results, reading)[0]
    return readings_results(claims, space, readings.isel(reading=index), values, cases)
