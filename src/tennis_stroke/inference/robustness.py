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
from .claims import claim_files, measure_stacks, within
from .identification import quoted_variable
from .labels import claim_facts, variable
from .measures import Stack
from .multiverse import experiment_configs
from .reading_space import CLAIM_LEVEL, CURVE_FILES, ReadingSpace
from .search_plan import SEARCHED
from .targeted import curve_files_of, number_files_of, targeted_files_of


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
    """The result files one claim evaluation reads: the curve files of ``curves`` (those
    ``results`` holds), and the Figs. 5-6 map cut at ``L1 <= l1_max`` (the unknown end of
    the figures' axis)."""
    files = {k: v for k, v in results.items() if "/" not in k}
    for key in CURVE_FILES:
        if f"{key}/{curves}" in results:
            files[key] = results[f"{key}/{curves}"]
    if l1_max is not None and "ml" in files:
        ml = files["ml"]
        keep = ml["L1"].values <= l1_max + 1e-9
        if not keep.all():  # the targeted file holds no L1 beyond the reading's end
            files["ml"] = ml.isel(L1=np.flatnonzero(keep))
    return files


def evaluate_reading(
    claims: Sequence[Mapping],
    space: ReadingSpace,
    results: Mapping[str, xr.Dataset],
    reading: Mapping[str, object],
) -> tuple[np.ndarray, list[dict[str, str]]]:
    """Values of every claim (``variant x claim``) under ``reading`` (its discrete
    readings and continuous unknowns) and every claim-level variant: the case of one
    reading of :func:`evaluate_across`."""
    values, cases = evaluate_across(claims, space, [results], [reading])
    return values[0], cases


def _measured(
    claims: Sequence[Mapping], space: ReadingSpace, readings: Sequence[Mapping[str, object]]
) -> tuple[dict[tuple, dict[int, list[int]]], dict[tuple, Mapping], list[dict[str, str]]]:
    """What :func:`evaluate_across` measures: each distinct thing a claim reads, keyed
    ``(claim index, its measure, the curves if it reads a curve file)``, with the
    readings that read it and, for each, the variants; the measure of each key; the
    variants."""
    cases = variants(space)
    quoting = space.raw["quoting"]
    reads_curves = [bool(set(claim_files(c)) & set(CURVE_FILES)) for c in claims]
    tasks: dict[tuple, dict[int, list[int]]] = {}
    specs: dict[tuple, Mapping] = {}
    quoted: dict[tuple, list[tuple[str, Mapping]]] = {}
    for v, case in enumerate(cases):
        level = {g: case[g] for g in CLAIM_LEVEL if g in quoting}
        for r, reading in enumerate(readings):
            instants = {**{g: str(reading[g]) for g in quoting if g in reading}, **level}
            at = tuple(sorted(instants.items()))
            if at not in quoted:
                quoted[at] = [
                    (repr(sorted(c["measure"].items())), c["measure"])
                    for c in quoted_claims(claims, space, instants)
                ]
            for j, (text, spec) in enumerate(quoted[at]):
                key = (j, text, case["figure_curves"] if reads_curves[j] else None)
                specs[key] = spec
                tasks.setdefault(key, {}).setdefault(r, []).append(v)
    return tasks, specs, cases


def evaluate_across(
    claims: Sequence[Mapping],
    space: ReadingSpace,
    results: Sequence[Mapping[str, xr.Dataset]],
    readings: Sequence[Mapping[str, object]],
    stacked: Mapping[str, Stack] | None = None,
) -> tuple[np.ndarray, list[dict[str, str]]]:
    """Values of every claim (``reading x variant x claim``) under each of ``readings``
    (``results[r]``: the files of reading ``r``) and every claim-level variant.
    ``stacked``: files of every reading at once, keyed as ``results`` keys them (a curve
    file ``"{key}/{curves}"``), in place of the readings' own
    (:func:`~tennis_stroke.inference.targeted.curve_files_of`).

    A claim is measured once per distinct thing it reads: its measure (the quoted
    variable of its instant) and, if it reads a curve file, the curves; the variants
    that change neither reuse the value.  Each is measured under all the readings that
    read it in one call (:func:`~tennis_stroke.inference.claims.measure_stacks`), the
    readings whose files have the same sizes stacked together."""
    stacked = stacked or {}
    tasks, specs, cases = _measured(claims, space, readings)
    values = np.full((len(readings), len(cases), len(claims)), np.nan)
    curves = {c["figure_curves"] for c in cases}
    files = {
        (r, c): files_of_reading(res, c, reading.get("fig6_L1_max"))
        for r, (res, reading) in enumerate(zip(results, readings, strict=True))
        for c in curves
    }

    def whole(n: str, c: str) -> str:
        """The key of file ``n`` under the curves ``c`` in ``stacked`` (if there)."""
        return f"{n}/{c}" if n in CURVE_FILES else n

    stacks: dict[tuple, Stack] = {}
    for key, users in tasks.items():
        names = claim_files({"measure": specs[key]})
        c = key[2] or cases[0]["figure_curves"]
        groups: dict[tuple, list[int]] = {}
        for r in users:
            sizes = tuple(
                () if whole(n, c) in stacked else tuple(files[r, c][n].sizes.items()) for n in names
            )
            groups.setdefault(sizes, []).append(r)
        for group in map(tuple, groups.values()):
            read = {}
            for n in names:  # a file stacked once for a group of readings, for every claim
                at = (n, key[2] if n in CURVE_FILES else None, group)
                if at not in stacks:
                    if whole(n, c) in stacked:
                        stacks[at] = stacked[whole(n, c)].take(group)
                    else:
                        stacks[at] = Stack([files[r, c][n] for r in group])
                read[n] = stacks[at]
            got = measure_stacks(specs[key], read)
            for r, value in zip(group, got, strict=True):
                values[r, users[r], key[0]] = value
    return values, cases


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
    every reading's searches in lockstep, no stroke run twice; the files of single
    strokes of every reading at once as arrays,
    :func:`~tennis_stroke.inference.targeted.curve_files_of` and
    :func:`~tennis_stroke.inference.targeted.number_files_of`) on the rows of the
    multiverse's resolution over the workflow ``config``, the claims evaluated under every
    claim-level variant (:func:`evaluate_across`, :func:`readings_results`)."""
    index = select_rows(np.arange(readings.sizes["reading"]), rows)
    cases = variants(space)
    chosen, configs, models = experiment_configs(config, space, readings, index)
    curves = space.discrete["figure_curves"]
    found = targeted_files_of(
        configs,
        models,
        settings,
        curves,
        [r.get("fig6_L1_max") for r in chosen],
        threads,
        SEARCHED,
        memo=True,
    )
    stacked = {
        **curve_files_of(configs, models, settings, curves),
        **number_files_of(configs, models, settings, threads),
    }
    values = evaluate_across(claims, space, found, chosen, stacked)[0]
    return readings_results(claims, space, readings.isel(reading=index), values, cases)
