"""The targeted evaluation checked against the full maps, claim by claim, on kept
readings of the robustness analysis (``config/readings.yaml``, ``multiverse.validation``).

For each chosen reading, every claim that reads a file the targeted evaluation finds by a
search (:data:`tennis_stroke.inference.search_plan.SEARCHED`) is measured twice with the
same measurement: on the targeted files and on the full maps (the workflow's steps on
the multiverse's rows; Figs. 5-6 by the grid search that the workflow used before).  The
claims that read only files of single strokes are the same computation either way and
are left out.  The default reading is checked in ``results/claims.csv`` (its
``map_value``), against the workflow's own maps.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..experiments.grids import axis
from ..experiments.maps import mass_length_map
from ..experiments.specs import PAPER_RESULTS, VALIDATION_GROUPS
from ..io.netcdf import labelled, provenance
from ..solver.settings import SolverSettings
from .claims import (
    AGREEMENT,
    agrees,
    cause,
    claim_files,
    difference,
    grid_half_step,
    measure,
)
from .labels import variable
from .multiverse import experiment_configs, paper_results
from .reading_space import ReadingSpace
from .search_plan import SEARCHED
from .targeted import searched_files_of

#: The validation's jobs, by group: the searched files each checks.
GROUPS = VALIDATION_GROUPS


def searched_claims(claims: Sequence[Mapping], keys: Sequence[str] = SEARCHED) -> list[Mapping]:
    """The claims that read a file found by a search (of ``keys``) and no other file."""
    return [c for c in claims if set(claim_files(c)) <= set(keys)]


def chosen_readings(count: int, kept: int) -> np.ndarray:
    """``count`` of the ``kept`` readings, evenly spread over them (all if fewer)."""
    return np.unique(np.round(np.linspace(0, kept - 1, min(count, kept))).astype(int))


def maps_of_reading(
    config: Mapping,
    model: Mapping,
    settings: SolverSettings,
    l1_max,
    ml_steps,
    threads=1,
    keys: Sequence[str] = SEARCHED,
) -> dict[str, xr.Dataset]:
    """The full maps of the searched files ``keys`` under one reading's ``config`` and
    ``model``: the table's functions, Figs. 5-6 by the grid search of ``ml_steps``
    (coarse, fine) at the two ends of L1 the claims read."""
    skip = [k for k in PAPER_RESULTS if k not in keys or k == "ml"]
    out = paper_results(config, model, settings, threads=threads, skip=skip)
    if "ml" not in keys:
        return out
    ml = config["mass_length"]
    l1 = axis(ml["L1"])
    if l1_max is not None:
        l1 = l1[l1 <= l1_max + 1e-9]
    out["ml"] = mass_length_map(
        axis(ml["M2"]),
        np.unique(l1[[0, -1]]),
        float(ml_steps[0]),
        float(ml_steps[1]),
        tuple(ml["theta0_range"]),
        tuple(ml["delta0_range"]),
        model,
        settings,
        threads,
    )
    return out


def validate(
    claims: Sequence[Mapping],
    space: ReadingSpace,
    readings: xr.Dataset,
    config: Mapping,
    settings: SolverSettings,
    threads: int | None = 1,
    group: str | None = None,
) -> xr.Dataset:
    """Targeted against map values of every searched claim (of the files of ``group`` of
    :data:`GROUPS`; None: all) on the readings chosen by ``multiverse.validation``
    (:func:`chosen_readings`), over ``(reading, claim)``."""
    keys = GROUPS[group] if group is not None else SEARCHED
    spec = space.raw["multiverse"]["validation"]
    index = chosen_readings(int(spec["readings"]), readings.sizes["reading"])
    checked = searched_claims(claims, keys)
    values = {k: np.full((index.size, len(checked)), np.nan) for k in ("targeted", "map")}
    half = np.zeros((index.size, len(checked)))
    chosen, configs, models = experiment_configs(config, space, readings, index)
    l1_maxes = [r.get("fig6_L1_max") for r in chosen]
    targeted = searched_files_of(configs, models, settings, l1_maxes, threads, keys)
    for n, (cfg, model, l1_max) in enumerate(zip(configs, models, l1_maxes, strict=True)):
        found = {
            "targeted": targeted[n],
            "map": maps_of_reading(cfg, model, settings, l1_max, spec["ml_steps"], threads, keys),
        }
        for kind, results in found.items():
            files = {k: results[k] for k in keys}
            for j, c in enumerate(checked):
                values[kind][n, j] = measure(c["measure"], files)
                if kind == "map":
                    half[n, j] = grid_half_step(c, files)
    tol = np.array([c["tolerance"] for c in checked], float)
    pair = ("reading", "claim")
    ds = xr.Dataset(
        {
            "targeted_value": variable(pair, values["targeted"], "targeted_value"),
            "map_value": variable(pair, values["map"], "map_value"),
            "difference": variable(
                pair, difference(values["targeted"], values["map"], tol), "difference"
            ),
            "agrees": variable(
                pair,
                agrees(values["targeted"], values["map"], tol).astype(np.int8),
                "agrees",
                agreement=AGREEMENT,
            ),
            "grid_half_step": variable(pair, half, "grid_half_step"),
            "cause": variable(
                pair, cause(values["targeted"], values["map"], tol, half).astype(object), "cause"
            ),
            "tolerance": variable("claim", tol, "tolerance"),
            "claim_unit": variable("claim", [c["unit"] for c in checked], "claim_unit"),
        },
        coords={
            "reading": variable("reading", readings["reading"].values[index], "validation.reading"),
            "claim": variable("claim", [c["id"] for c in checked], "claim"),
        },
    )
    ds.attrs.update(provenance({}, settings))
    ds.attrs["agreement"] = AGREEMENT
    ds.attrs["files"] = " ".join(keys)
    return labelled(ds)
