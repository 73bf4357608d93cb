"""The robustness analysis (the multiverse): readings consistent with the paper, and the
paper's experiments under each of them (``config/readings.yaml``, ``multiverse``).

Three steps, each a workflow job:

1. :func:`screen` draws ``candidates`` points of a scrambled Sobol design (seeded) over
   every continuous unknown (its declared ``range``, log where its scale is log) and
   simulates, for every combination of the model fit's discrete readings, the strokes of
   both fit sets (Fig. 4's two strokes, Table I's strokes) at each point.  A candidate is
   *consistent* when every fit claim lies within ``consistent.max_abs_residual``
   tolerances (or, for a fit set that no fitted reading brings all within, its RMS
   normalised residual is at most the best fit's + ``fallback_margin``).
2. :func:`select` keeps up to ``readings`` consistent readings, in Sobol order,
   round-robin over the consistent discrete combinations (so each is represented).
3. :func:`paper_results` runs every paper experiment of one reading (the grids of
   ``multiverse.resolution`` merged over the workflow config), a loop over the table of
   experiments; :mod:`tennis_stroke.inference.robustness` evaluates every claim on them
   and :mod:`tennis_stroke.replication.robustness` classifies the result.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..experiments.specs import EXPERIMENTS, compute
from ..io.netcdf import labelled, provenance
from ..model.params import PARAMETERS
from ..solver.settings import SolverSettings
from .identification import elbow_simulator, model_simulator, residuals, targets
from .labels import variable
from .reading_space import CURVE_FILES, ELBOW_FIT, FIT_SETS, MODEL_FIT, ReadingSpace


class MultiverseError(ValueError):
    """The robustness analysis cannot run as declared (one line)."""


def unknowns(space: ReadingSpace) -> list[str]:
    """The continuous unknowns in their declared order (the design's dimensions)."""
    return list(space.continuous)


def design(space: ReadingSpace) -> dict[str, np.ndarray]:
    """The declared Sobol design: ``candidates`` points over every continuous unknown,
    as values in each unknown's unit (the same points for every discrete combination)."""
    spec = space.raw["multiverse"]
    names = unknowns(space)
    n = int(spec["candidates"])
    from scipy.stats import qmc  # about 1 s to import: only the samplers load it

    sobol = qmc.Sobol(len(names), scramble=True, seed=int(spec["seed"]))
    u = sobol.random(2 ** math.ceil(math.log2(n)))[:n]
    return {name: space.continuous[name].from_unit(u[:, i]) for i, name in enumerate(names)}


def model_combinations(space: ReadingSpace) -> list[dict[str, str]]:
    """Every combination of the model fit's discrete readings, in declared order."""
    names = list(space.fits[MODEL_FIT].discrete)
    return [
        dict(zip(names, combo, strict=True))
        for combo in itertools.product(*(space.discrete[n] for n in names))
    ]


def _bound(fit_summary: Mapping[str, float] | None, space: ReadingSpace, n_claims: int):
    """(max |residual|, max RMS) of the consistency rule for one fit set: all claims
    within ``max_abs_residual``, or the fallback when the best fit does not reach that."""
    rule = space.raw["consistent"]
    if fit_summary is None or fit_summary["passed"] >= n_claims:
        return float(rule["max_abs_residual"]), math.inf
    return math.inf, float(fit_summary["score"]) + float(rule["fallback_margin"])


def _within(res: np.ndarray, rms: np.ndarray, bound: tuple[float, float]) -> np.ndarray:
    """Candidates whose residuals (last axis) and RMS meet a consistency ``bound``
    (NaN: not computed, inconsistent)."""
    with np.errstate(invalid="ignore"):
        return (np.max(np.abs(res), axis=-1) <= bound[0] + 1e-12) & (rms <= bound[1])


def screen(
    space: ReadingSpace,
    claims: Sequence[Mapping],
    fig4: Sequence[Sequence[float]],
    force: Mapping[str, object],
    stroke: Mapping[str, object],
    base: Mapping[str, object] | None = None,
    best_fits: Mapping[str, Mapping[str, float]] | None = None,
    settings: SolverSettings | None = None,
    threads: int = 1,
) -> xr.Dataset:
    """Fit-set RMS residuals and consistency of every candidate under every model
    combination, and every fit claim's residual at each consistent one.

    ``best_fits``: per fit set, ``passed`` and ``score`` of the identification's best fit
    (the fallback of the consistency rule).  Returns a dataset over ``(combination,
    candidate)`` with the RMS normalised residual per fit set and ``consistent``, and over
    ``point`` (the consistent pairs, combination-major, candidates in Sobol order) each
    fit claim's residual.  Table I's strokes are simulated only for candidates the Fig. 4
    fit set leaves consistent (the others have a NaN Table I RMS: ruled out already).
    ``threads``: the strokes of one batch share them (the values do not depend on it).
    """
    points = design(space)
    if "table1_tau_F" not in points:
        raise MultiverseError("the screen expects table1_tau_F among the unknowns")
    fits = [space.fits[name] for name in FIT_SETS]
    goals = {f.name: targets(space, f, claims) for f in fits}
    sims = {
        MODEL_FIT: model_simulator(fig4, settings, threads),
        ELBOW_FIT: elbow_simulator(force, stroke, settings, threads),
    }
    bounds = [_bound((best_fits or {}).get(f.name), space, len(goals[f.name])) for f in fits]
    combos = model_combinations(space)
    rms, consistent, kept = _residuals(space, combos, points, goals, sims, bounds, dict(base or {}))
    claim_ids = [t.claim for f in fits for t in goals[f.name]]
    ds = _screen_dataset(space, combos, points, rms, consistent, kept, claim_ids, bounds)
    ds.attrs.update(provenance({}, settings or SolverSettings()))
    ds.attrs["design_seed"] = int(space.raw["multiverse"]["seed"])
    return labelled(ds)


def _residuals(space, combos, points, goals, sims, bounds, base):
    """RMS per fit set ``(combination, candidate, fit_set)`` and consistency
    ``(combination, candidate)`` of every candidate, and the residuals of the consistent
    ones (``(combination, candidate, residuals)`` rows); Table I's strokes only where the
    model fit set leaves the candidate consistent (NaN RMS elsewhere).  The model's
    strokes are simulated once per combination of the physical readings."""
    n = len(next(iter(points.values())))
    physical = [k for k in space.fits[MODEL_FIT].discrete if k in space.raw["model"]]
    quoting = [k for k in space.fits[MODEL_FIT].discrete if k in space.raw["quoting"]]
    params = {k: v[:, None] for k, v in points.items() if k in PARAMETERS}
    rms = np.full((len(combos), n, len(FIT_SETS)), np.nan)
    consistent = np.zeros((len(combos), n), dtype=bool)
    kept: list[tuple[int, np.ndarray, np.ndarray]] = []
    cache: dict[tuple, dict] = {}
    for c, combo in enumerate(combos):
        key = tuple(combo[k] for k in physical)
        overrides = {**base, **{k: combo[k] for k in physical}}
        if key not in cache:
            cache = {key: sims[MODEL_FIT]({**overrides, **params})}  # one held at a time
        instants = {k: combo[k] for k in quoting}
        model_res = residuals(cache[key], goals[MODEL_FIT], instants, space)[1]
        rms[c, :, 0] = np.sqrt(np.mean(model_res**2, axis=1))
        todo = np.flatnonzero(_within(model_res, rms[c, :, 0], bounds[0]))
        if todo.size == 0:
            continue
        sub = {k: v[todo] for k, v in params.items()}
        sub["table1_tau_F"] = points["table1_tau_F"][todo, None]
        elbow = sims[ELBOW_FIT]({**overrides, **sub})
        elbow_res = residuals(elbow, goals[ELBOW_FIT], instants, space)[1]
        rms[c, todo, 1] = np.sqrt(np.mean(elbow_res**2, axis=1))
        good = _within(elbow_res, rms[c, todo, 1], bounds[1])
        consistent[c, todo[good]] = True
        kept.append((c, todo[good], np.concatenate([model_res[todo[good]], elbow_res[good]], 1)))
    return rms, consistent, kept


def _screen_dataset(space, combos, points, rms, consistent, kept, claim_ids, bounds):
    """The screen's file: each combination's readings, each candidate's unknowns, the RMS
    per fit set (single precision, compressed: about 4 bytes per candidate and
    combination for the two fit sets), consistency, the fit claims' residuals at the
    consistent pairs and the bounds of the rule."""
    n = len(next(iter(points.values())))
    fits = [space.fits[name] for name in FIT_SETS]
    names = unknowns(space)
    index = lambda name, values: variable(  # noqa: E731
        name, np.asarray(values, dtype=np.int32), "index", name=name
    )
    point_combo = np.concatenate([np.full(i.size, c, np.int32) for c, i, _ in kept] or [[]])
    point_cand = np.concatenate([i for _, i, _ in kept] or [[]]).astype(np.int32)
    point_res = np.concatenate([r for _, _, r in kept]) if kept else np.zeros((0, len(claim_ids)))
    packed = {"zlib": True, "complevel": 4}
    ds = xr.Dataset(
        {
            **{
                k: variable("combination", [combo[k] for combo in combos], "reading", name=k)
                for k in combos[0]
            },
            **{
                k: variable("candidate", points[k], "unknown", space.continuous[k].unit, name=k)
                for k in names
            },
            "rms": variable(("combination", "candidate", "fit_set"), rms.astype(np.float32), "rms"),
            "consistent": variable(
                ("combination", "candidate"), consistent.astype(np.int8), "consistent"
            ),
            "point_combination": variable("point", point_combo, "multiverse.point_combination"),
            "point_candidate": variable("point", point_cand, "multiverse.point_candidate"),
            "residual": variable(("point", "claim"), point_res, "residual"),
            "max_abs_residual": variable("fit_set", [b[0] for b in bounds], "max_abs_residual"),
            "max_rms": variable("fit_set", [b[1] for b in bounds], "max_rms"),
        },
        coords={
            "combination": index("combination", np.arange(len(combos))),
            "candidate": index("candidate", np.arange(n)),
            "point": index("point", np.arange(point_combo.size)),
            "claim": variable("claim", claim_ids, "claim"),
            "fit_set": variable("fit_set", [f.name for f in fits], "multiverse.fit_set"),
        },
    )
    for name in ("rms", "consistent"):
        ds[name].encoding.update(packed)
    return ds


def select(screened: xr.Dataset, count: int) -> list[tuple[int, int]]:
    """Up to ``count`` consistent ``(combination, candidate)`` pairs, in Sobol order,
    round-robin over the combinations that have consistent candidates."""
    ok = screened["consistent"].values.astype(bool)
    queues = [list(np.flatnonzero(row)) for row in ok]
    chosen: list[tuple[int, int]] = []
    for rank in itertools.count():
        progressed = False
        for c, queue in enumerate(queues):
            if rank < len(queue) and len(chosen) < count:
                chosen.append((c, int(queue[rank])))
                progressed = True
        if not progressed or len(chosen) >= count:
            return chosen
    return chosen  # pragma: no cover (itertools.count never ends)


def readings_dataset(space: ReadingSpace, screened: xr.Dataset) -> xr.Dataset:
    """The selected readings (``multiverse.readings`` of the consistent candidates) as a
    dataset over ``reading``: each discrete reading and continuous unknown."""
    chosen = select(screened, int(space.raw["multiverse"]["readings"]))
    if not chosen:
        raise MultiverseError(
            "no candidate of the declared design is consistent with the paper "
            "(config/readings.yaml, consistent)"
        )
    combos = [c for c, _ in chosen]
    cands = [i for _, i in chosen]
    names = [k for k in screened.data_vars if screened[k].dims == ("combination",)]
    out = xr.Dataset(
        {
            **{k: ("reading", screened[k].values[combos], screened[k].attrs) for k in names},
            **{
                k: ("reading", screened[k].values[cands], screened[k].attrs)
                for k in unknowns(space)
            },
            "combination": ("reading", np.array(combos, dtype=np.int32), {"units": "1"}),
            "candidate": ("reading", np.array(cands, dtype=np.int32), {"units": "1"}),
        },
        coords={"reading": ("reading", np.arange(len(chosen), dtype=np.int32), {"units": "1"})},
    )
    out.attrs.update(screened.attrs)
    return labelled(out)


def reading_of(readings: xr.Dataset, index: int) -> dict[str, object]:
    """One reading of :func:`readings_dataset` as a plain dict (strings and floats)."""
    row = readings.isel(reading=index)
    out = {}
    for k, v in row.data_vars.items():
        if k in ("combination", "candidate"):
            continue
        value = v.values.item()
        out[k] = value if isinstance(value, str) else float(value)
    return out


def experiment_config(
    config: Mapping, space: ReadingSpace, reading: Mapping[str, object]
) -> tuple[dict, dict]:
    """The workflow config at the multiverse's resolution (``angle_maps`` and
    ``mass_length`` merged over their sections, ``fig7_tau`` as Fig. 7's ``tau``) with
    ``reading``'s experiment unknowns, and the model overrides of ``reading`` (readings
    and parameters) on top of the config's ``model``."""
    cfg = space.at_resolution(config)
    # a config pruned to what one job reads may lack this section
    if "table1_tau_F" in reading and "elbow_force" in cfg:
        cfg["elbow_force"]["table1_tau_F"] = float(reading["table1_tau_F"])
    model = dict(cfg.get("model") or {})
    model.update({k: v for k, v in reading.items() if k in space.raw["model"]})
    model.update({k: float(v) for k, v in reading.items() if k in PARAMETERS})
    return cfg, model


def experiment_configs(
    config: Mapping, space: ReadingSpace, readings: xr.Dataset, index: Sequence[int]
) -> tuple[list[dict], list[dict], list[dict]]:
    """The kept readings ``index`` of ``readings`` (:func:`reading_of`) with their workflow
    configs and model overrides (:func:`experiment_config`): three lists, one entry per
    reading, as the searches in lockstep take them."""
    chosen = [reading_of(readings, int(i)) for i in index]
    pairs = [experiment_config(config, space, r) for r in chosen]
    return chosen, [c for c, _ in pairs], [m for _, m in pairs]


def paper_results(
    config: Mapping,
    model: Mapping[str, object],
    settings: SolverSettings,
    curves: Sequence[str] = ("free_swing",),
    threads: int | None = 1,
    skip: Sequence[str] = (),
) -> dict[str, xr.Dataset]:
    """Every paper experiment of the table (:data:`tennis_stroke.experiments.specs.EXPERIMENTS`,
    family ``paper``) from the workflow ``config`` with ``model`` overrides, by result key
    (``fig2`` ... ``elbow``).  The curve files (:data:`CURVE_FILES`) are computed once per
    entry of ``curves``, keyed ``"{key}/{curves}"``; another row that reads the curves
    setting gets the first; the others are computed once.  ``skip``: keys not computed."""
    config = {**config, "figure_curves": curves[0]}
    out: dict[str, xr.Dataset] = {}
    for key, experiment in EXPERIMENTS.items():
        if experiment.family != "paper" or key in skip:
            continue
        args = experiment.arguments(config)
        if "curves" in args and key in CURVE_FILES:
            for c in curves:
                run = {**args, "curves": c}
                out[f"{key}/{c}"] = compute(experiment, run, model, settings, None, threads)
            continue
        if "curves" in args:
            args["curves"] = curves[0]
        out[key] = compute(experiment, args, model, settings, None, threads)
    return out


def best_fits(fits: Mapping[str, xr.Dataset]) -> dict[str, dict[str, float]]:
    """``passed`` and ``score`` of the best fit of each fit set (the identification's
    ``{fit}_fits`` files, best first): the fallback of the consistency rule."""
    return {
        name: {"passed": int(ds["passed"].values[0]), "score": float(ds["score"].values[0])}
        for name, ds in fits.items()
    }
