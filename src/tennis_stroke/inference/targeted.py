"""The targeted evaluation of the claims: each result file reduced to what the claims
read, its optima and its threshold found by a search instead of a dense map.

A claim keeps one definition, its measurement (:mod:`tennis_stroke.inference.measures`).
The targeted files hold the variables the measurements read, on the points they read,
so the same measurement answers the same question on either file:

* Figs. 2-3 (``fig2``, ``fig3``): ``best_delta0`` and ``best_v_out`` of every ``theta0``
  row, by a search along ``delta0`` (the red line of the figures);
* Figs. 5-6 (``ml``): the optimum of every ``M2`` at the smallest and the largest ``L1``
  (the claims compare these two ends; the largest no further than the reading's
  ``l1_max``), by the search of :func:`tennis_stroke.experiments.optima.mass_length_optimum`;
* Fig. 7 (``fig7``): ``best_tau`` on ``C2`` rows ``C2_step`` apart, plus the two rows at
  most ``C2_tolerance`` apart between which the best delay leaves 0 (located by
  :func:`~tennis_stroke.experiments.search.first_crossing`); the ``tau`` coordinate is
  the configured grid, whose step says what "leaves 0" means (half a step);
* Fig. 8 (``fig8``): the one point of the largest ``v_out`` over ``(delta0, tau)``;
* Fig. 9 (``fig9``): ``v_out`` at ``tau = 0`` and at the best delay, ``best_tau`` and
  ``best_v_out``;
* Fig. 13 (``elbow_map``): ``v_out`` on the 2 x 2 grid of the directions and delays of
  the largest and the smallest ``v_out`` (four real strokes); a direction range of a
  full turn is searched as the circle it is (the grid's 0 and 360 deg are one direction);
* the files of single strokes (Figs. 4, 10-12, Table I, the k sensitivity) are computed
  whole, as the workflow does: they are a few strokes each.

The steps and tolerances of the searches are the ``search`` section of the workflow
config; :func:`tennis_stroke.inference.validation` compares every claim's targeted value
with its value from the full maps.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..experiments.grids import axis
from ..experiments.maps import k_sensitivity_strokes
from ..experiments.optima import mass_length_optima
from ..experiments.search import (
    coarse_axis,
    first_crossing,
    lockstep_objective,
    maximize,
    stacked,
)
from ..experiments.specs import EXPERIMENTS
from ..experiments.strokes import delay_cases, fig4_cases, table1_cases, trajectory_arrays
from ..solver.results import FILE_NAMES
from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch
from .measures import Stack
from .multiverse import paper_results
from .reading_space import CURVE_FILES
from .search_plan import NUMBERS_ONLY, SEARCHED


def _dataset(variables: Mapping, coords: Mapping, **attrs) -> xr.Dataset:
    """A targeted file: the variables its claims read (no labels: it is never written)."""
    ds = xr.Dataset(
        {k: (dims, np.asarray(v)) for k, (dims, v) in variables.items()},
        coords={k: (k, np.asarray(v, float)) for k, v in coords.items()},
    )
    ds.attrs.update(attrs, targeted="search (tennis_stroke.inference.targeted)")
    return ds


def _split(values: np.ndarray, sets: int) -> np.ndarray:
    """Per-problem values of ``sets`` parameter sets with as many problems each, by set."""
    return np.asarray(values).reshape(sets, -1, *np.shape(values)[1:])


def angle_rows(
    args: Mapping, search: Mapping, models: Sequence[Mapping], settings, threads=None, memo=False
) -> list[xr.Dataset]:
    """Figs. 2-3: the best ``delta0`` of every ``theta0`` row (a search along delta0),
    for each parameter set of ``models`` (model overrides), all in one search."""
    theta0 = axis(args["theta0"])
    d0, sets = args["delta0"], len(models)
    n = theta0.size * sets
    objective = lockstep_objective(
        ("delta0",),
        n,
        {"theta0": np.tile(theta0, sets)},
        [{**m, "L1": args["L1"]} for m in models],
        [theta0.size] * sets,
        settings,
        threads,
        memo=memo,
    )
    best = maximize(
        objective,
        n,
        [d0["start"]],
        [d0["stop"]],
        [search["angle_step"]],
        [search["angle_tolerance"]],
    )
    x, v = _split(best.x[:, 0], sets), _split(best.value, sets)
    return [
        _dataset(
            {"best_delta0": ("theta0", x[r]), "best_v_out": ("theta0", v[r])},
            {"theta0": theta0},
        )
        for r in range(sets)
    ]


def mass_length_ends(
    args: Mapping,
    models: Sequence[Mapping],
    settings,
    l1_max: Sequence[float | None] | None = None,
    threads=None,
    memo=False,
) -> list[xr.Dataset]:
    """Figs. 5-6: the optimum of every ``M2`` at the smallest and the largest ``L1`` of
    the grid (the largest at most ``l1_max``, one per parameter set of ``models``)."""
    l1_max = [None] * len(models) if l1_max is None else list(l1_max)
    ends = []
    for top in l1_max:
        l1 = axis(args["L1"])
        if top is not None:
            l1 = l1[l1 <= top + 1e-9]
        ends.append(np.unique(l1[[0, -1]]))
    return mass_length_optima(
        axis(args["M2"]),
        ends,
        args["coarse_step"],
        args["tolerance"],
        tuple(args["theta0_range"]),
        tuple(args["delta0_range"]),
        models,
        settings,
        threads,
        memo=memo,
    )


def _ends(spec: Mapping) -> tuple[float, float]:
    """The ends of a searched range (its step is the map's, not the search's)."""
    return float(spec["start"]), float(spec["stop"])


def _best_tau(c2: np.ndarray, owner: np.ndarray, tau, bases, search, settings, threads, memo):
    """The best delay of each ``C2`` value ``c2[i]`` under the parameter set
    ``bases[owner[i]]`` (``owner`` ascending: each set's rows together)."""
    counts = np.bincount(owner, minlength=len(bases))
    used = np.flatnonzero(counts)
    objective = lockstep_objective(
        ("tau",),
        c2.size,
        {"C2": c2},
        [bases[r] for r in used],
        counts[used],
        settings,
        threads,
        memo=memo,
    )
    return maximize(
        objective, c2.size, [tau[0]], [tau[-1]], [search["tau_step"]], [search["time_tolerance"]]
    )


def delay_threshold(
    args: Mapping, search: Mapping, models: Sequence[Mapping], settings, threads=None, memo=False
) -> list[xr.Dataset]:
    """Fig. 7: ``best_tau`` on ``C2`` rows ``C2_step`` apart and on the two rows at most
    ``C2_tolerance`` apart where it leaves 0 for good (more than half a step of the
    configured ``tau`` grid, as :func:`~tennis_stroke.inference.measures.measure_delay_threshold`
    reads it), for each parameter set of ``models``."""
    tau = axis(args["tau"])
    half_step = 0.5 * float(tau[1] - tau[0])
    c2 = coarse_axis(args["C2"]["start"], args["C2"]["stop"], search["C2_step"])
    sets = len(models)
    bases = [
        {**m, "L1": args["L1"], "theta0": args["theta0"], "delta0": args["delta0"]} for m in models
    ]
    best = _best_tau(
        np.tile(c2, sets),
        np.repeat(np.arange(sets), c2.size),
        tau,
        bases,
        search,
        settings,
        threads,
        memo,
    )
    found = [
        ([c2], [x], [v])
        for x, v in zip(_split(best.x[:, 0], sets), _split(best.value, sets), strict=True)
    ]
    crossing, below, above = [], [], []
    for r, (_, (x,), _) in enumerate(found):
        positive = (x > half_step) & (c2 > 0)
        first = next((i for i in range(c2.size) if c2[i] > 0 and positive[i:].all()), None)
        if first is not None and first > 0:
            crossing.append(r)
            below.append(c2[first - 1])
            above.append(c2[first])
    if crossing:
        crossing = np.array(crossing)

        def leaves_zero(values: np.ndarray, index: np.ndarray) -> np.ndarray:
            owner = np.repeat(crossing[index], values.shape[1])
            got = _best_tau(values.ravel(), owner, tau, bases, search, settings, threads, memo)
            x, v = got.x[:, 0].reshape(values.shape), got.value.reshape(values.shape)
            for row, r in enumerate(crossing[index]):
                found[r][0].append(values[row])
                found[r][1].append(x[row])
                found[r][2].append(v[row])
            return x > half_step

        first_crossing(leaves_zero, np.array(below), np.array(above), search["C2_tolerance"])
    return [_threshold_file(rows, taus, speeds, tau) for rows, taus, speeds in found]


def _threshold_file(rows, taus, speeds, tau) -> xr.Dataset:
    """Fig. 7's file of one parameter set from the rows its searches evaluated."""
    c2_all, bt, bv = (np.concatenate(a) for a in (rows, taus, speeds))
    # keep the rows up to the narrowest bracket: every row below it false, above it true
    order = np.argsort(c2_all, kind="stable")
    c2_all, bt, bv = c2_all[order], bt[order], bv[order]
    keep = np.concatenate([[True], np.diff(c2_all) > 0])
    return _dataset(
        {"best_tau": ("C2", bt[keep]), "best_v_out": ("C2", bv[keep])},
        {"C2": c2_all[keep], "tau": tau},
    )


def _sec5_base(args: Mapping, model) -> dict:
    return {**model, "L1": args["L1"], "theta0": args["theta0"], "C2": args["C2"]}


def delay_optimum(
    args: Mapping, search: Mapping, models: Sequence[Mapping], settings, threads=None, memo=False
) -> list[xr.Dataset]:
    """Fig. 8: the point of the largest ``v_out`` over ``(delta0, tau)``, for each
    parameter set of ``models``."""
    d0, tau = args["delta0"], _ends(args["tau"])
    sets = len(models)
    bases = [_sec5_base(args, m) for m in models]
    objective = lockstep_objective(
        ("delta0", "tau"), sets, {}, bases, [1] * sets, settings, threads, memo=memo
    )
    best = maximize(
        objective,
        sets,
        [d0["start"], tau[0]],
        [d0["stop"], tau[1]],
        [search["angle_step"], search["tau_step"]],
        [search["angle_tolerance"], search["time_tolerance"]],
    )
    out = []
    for r in range(sets):
        v = np.reshape(best.value[r], (1, 1))
        out.append(
            _dataset(
                {
                    "v_out": (("delta0", "tau"), v),
                    "status": (("delta0", "tau"), np.where(np.isfinite(v), 0, 1)),
                },
                {"delta0": best.x[r : r + 1, 0], "tau": best.x[r : r + 1, 1]},
            )
        )
    return out


def delay_line(
    args: Mapping, search: Mapping, models: Sequence[Mapping], settings, threads=None, memo=False
) -> list[xr.Dataset]:
    """Fig. 9: ``v_out`` at ``tau = 0`` (the grid's first delay) and at the best delay,
    for each parameter set of ``models``."""
    tau = _ends(args["tau"])
    sets = len(models)
    bases = [{**_sec5_base(args, m), "delta0": args["delta0"]} for m in models]
    c2 = np.full(sets, float(args["C2"]))
    best = _best_tau(c2, np.arange(sets), tau, bases, search, settings, threads, memo)
    objective = lockstep_objective(("tau",), sets, {}, bases, [1] * sets, settings, threads)
    v0 = objective(np.full((sets, 1, 1), tau[0]), np.arange(sets))[:, 0]
    out = []
    for r in range(sets):
        v = np.array([[v0[r], best.value[r]]])
        out.append(
            _dataset(
                {
                    "v_out": (("delta0", "tau"), v),
                    "status": (("delta0", "tau"), np.where(np.isfinite(v), 0, 1)),
                    "best_tau": ("delta0", best.x[r : r + 1, 0]),
                    "best_v_out": ("delta0", best.value[r : r + 1]),
                },
                {"delta0": [float(args["delta0"])], "tau": [tau[0], best.x[r, 0]]},
            )
        )
    return out


def elbow_extremes(
    args: Mapping, search: Mapping, models: Sequence[Mapping], settings, threads=None, memo=False
) -> list[xr.Dataset]:
    """Fig. 13: ``v_out`` on the 2 x 2 grid of the directions and pulse delays of the
    largest and the smallest ``v_out`` (each a search over ``(psi_F, tau_F)``), for each
    parameter set of ``models``."""
    force, stroke = args["force"], args["stroke"]
    psi, tau_f = _ends(args["psi_f"]), _ends(args["tau_f"])
    t_ref = float(stroke["tau_H"])
    sets = len(models)
    bases = [
        {
            **m,
            "L1": stroke["L1"],
            "C2": stroke["C2"],
            "tau": t_ref,
            "F0": force["F0"],
            "t_d": force["t_d"],
            "theta0": stroke["theta0"],
            "delta0": stroke["delta0"],
        }
        for m in models
    ]
    objective = lockstep_objective(
        ("psi_F_deg", "t_F"), sets, {}, bases, [1] * sets, settings, threads, memo=memo
    )
    turn = 360.0 if np.isclose(psi[-1] - psi[0], 360.0) else None  # a full turn wraps
    found = [
        maximize(
            objective,
            sets,
            [psi[0], t_ref + tau_f[0]],
            [psi[-1], t_ref + tau_f[-1]],
            [search["psi_F_step"], search["tau_F_step"]],
            [search["angle_tolerance"], search["time_tolerance"]],
            sign=sign,
            periods=[turn, None],
        ).x
        for sign in (1.0, -1.0)
    ]
    p = np.stack([x[:, 0] for x in found], axis=1)  # (sets, 2): largest, smallest
    t = np.stack([x[:, 1] for x in found], axis=1) - t_ref
    points = np.stack(
        [np.stack(np.meshgrid(p[r], t[r] + t_ref, indexing="ij"), axis=-1) for r in range(sets)]
    ).reshape(sets, 4, 2)
    res = objective.strike(points, np.arange(sets))
    return [
        _dataset(
            {
                "v_out": (("psi_F", "tau_F"), res["v_out_kmh"][r].reshape(2, 2)),
                "status": (("psi_F", "tau_F"), res["status"][r].reshape(2, 2)),
            },
            {"psi_F": p[r], "tau_F": t[r]},
            t_ref_s=t_ref,
        )
        for r in range(sets)
    ]


def _table1_strokes(args: Sequence[Mapping], params: Mapping, settings) -> dict[str, np.ndarray]:
    """The results of Table I's strokes (:func:`table1_numbers`) under each of ``args``
    (one per parameter set; ``params``: the sets' model overrides, arrays shaped
    ``(sets, 1)`` or shared), shaped ``(sets, strokes)``."""
    cases = [table1_cases(a["force"], a["stroke"]) for a in args]
    values = {k: np.array([[c[k] for c in one] for one in cases], float) for k in cases[0][0]}
    stroke = args[0]["stroke"]
    return strike_batch(stroke["theta0"], stroke["delta0"], {**params, **values}, settings, 1)


def table1_numbers(args: Mapping, model, settings) -> xr.Dataset:
    """Table I: the numbers of its strokes (the curves of Fig. 14 left out), the same
    strokes as :func:`tennis_stroke.experiments.strokes.elbow_force_strokes`."""
    res = {k: v[0] for k, v in _table1_strokes([args], model, settings).items()}
    psi = [*args["force"]["table1_psi"], np.nan]
    return _dataset(
        {FILE_NAMES.get(k, k): ("stroke", v) for k, v in res.items()} | {"psi_F": ("stroke", psi)},
        {"stroke": np.arange(len(psi))},
    )


def _searched(key: str, args: Mapping, search: Mapping, models, l1_max, settings, threads, memo):
    """The files of the searched key ``key`` for the parameter sets ``models``."""
    if key in ("fig2", "fig3"):
        return angle_rows(args, search, models, settings, threads, memo)
    if key == "ml":
        return mass_length_ends(args, models, settings, l1_max, threads, memo)
    run = {
        "fig7": delay_threshold,
        "fig8": delay_optimum,
        "fig9": delay_line,
        "elbow_map": elbow_extremes,
    }
    return run[key](args, search, models, settings, threads, memo)


def _same(a: object, b: object) -> bool:
    """Whether two config values (mappings, sequences, arrays, scalars) are equal."""
    if isinstance(a, Mapping) or isinstance(b, Mapping):
        return (
            isinstance(a, Mapping)
            and isinstance(b, Mapping)
            and a.keys() == b.keys()
            and all(_same(a[k], b[k]) for k in a)
        )
    if isinstance(a, (list, tuple, np.ndarray)) or isinstance(b, (list, tuple, np.ndarray)):
        return np.shape(a) == np.shape(b) and bool(np.all(np.asarray(a) == np.asarray(b)))
    return type(a) is type(b) and a == b


def searched_files(
    config: Mapping,
    model: Mapping[str, object],
    settings: SolverSettings,
    l1_max: float | None = None,
    threads: int | None = 1,
    keys: Sequence[str] = SEARCHED,
) -> dict[str, xr.Dataset]:
    """The files ``keys`` of :data:`SEARCHED` by their searches, from the workflow
    ``config`` (its ``search`` section: the steps and tolerances; only the sections the
    files read are needed) with ``model`` overrides.  ``l1_max``: the largest ``L1`` of
    Figs. 5-6 (a reading; None: the grid's)."""
    return searched_files_of([config], [model], settings, [l1_max], threads, keys)[0]


def searched_files_of(
    configs: Sequence[Mapping],
    models: Sequence[Mapping[str, object]],
    settings: SolverSettings,
    l1_max: Sequence[float | None] | None = None,
    threads: int | None = 1,
    keys: Sequence[str] = SEARCHED,
    memo: bool = False,
) -> list[dict[str, xr.Dataset]]:
    """:func:`searched_files` of several readings (reading ``r``: the workflow config
    ``configs[r]``, the model overrides ``models[r]``, the largest ``L1`` ``l1_max[r]``)
    in lockstep: the readings whose file reads the same arguments and search steps are
    searched together, every iteration of the search one batch of strokes for all of
    them.  Each reading gets the files :func:`searched_files` gives it alone: a search's
    problems do not depend on each other.  ``memo``: the searches run no stroke twice
    (:class:`~tennis_stroke.experiments.search.StrokeObjective`; the same files, fewer
    strokes run)."""
    l1_max = [None] * len(models) if l1_max is None else list(l1_max)
    out: list[dict[str, xr.Dataset]] = [{} for _ in models]
    for key in keys:
        groups: list[tuple[Mapping, Mapping, list[int]]] = []
        for r, config in enumerate(configs):
            args, search = EXPERIMENTS[key].arguments(config), config["search"]
            for a, s, members in groups:
                if _same(a, args) and _same(s, search):
                    members.append(r)
                    break
            else:
                groups.append((args, search, [r]))
        for args, search, members in groups:
            files = _searched(
                key,
                args,
                search,
                [models[r] for r in members],
                [l1_max[r] for r in members],
                settings,
                threads,
                memo,
            )
            for r, ds in zip(members, files, strict=True):
                out[r][key] = ds
    return out


def targeted_files(
    config: Mapping,
    model: Mapping[str, object],
    settings: SolverSettings,
    curves: Sequence[str] = ("free_swing",),
    l1_max: float | None = None,
    threads: int | None = 1,
    keys: Sequence[str] | None = None,
) -> dict[str, xr.Dataset]:
    """The files the claims read, by key as
    :func:`~tennis_stroke.inference.multiverse.paper_results` gives them: those of
    :data:`SEARCHED` by :func:`searched_files`, Table I's numbers
    (:func:`table1_numbers`), the others (a few strokes each) computed whole.  ``keys``:
    only these result files (default: every paper file)."""
    return targeted_files_of([config], [model], settings, curves, [l1_max], threads, keys)[0]


def targeted_files_of(
    configs: Sequence[Mapping],
    models: Sequence[Mapping[str, object]],
    settings: SolverSettings,
    curves: Sequence[str] = ("free_swing",),
    l1_max: Sequence[float | None] | None = None,
    threads: int | None = 1,
    keys: Sequence[str] | None = None,
    memo: bool = False,
) -> list[dict[str, xr.Dataset]]:
    """:func:`targeted_files` of several readings (as :func:`searched_files_of` takes
    them, ``memo`` too), the searches in lockstep."""
    keys = [k for k in EXPERIMENTS if EXPERIMENTS[k].family == "paper"] if keys is None else keys
    skip = tuple(k for k in EXPERIMENTS if k not in keys) + SEARCHED + NUMBERS_ONLY
    searched = [k for k in SEARCHED if k in keys]
    found = searched_files_of(configs, models, settings, l1_max, threads, searched, memo)
    out = []
    for config, model, files in zip(configs, models, found, strict=True):
        one = paper_results(config, dict(model), settings, curves, threads, skip=skip)
        if "elbow" in keys:
            elbow = EXPERIMENTS["elbow"].arguments({**config, "figure_curves": curves[0]})
            one["elbow"] = table1_numbers(elbow, dict(model), settings)
        out.append({**one, **files})
    return out


#: The strokes, labels and sample times of each curve file (:data:`CURVE_FILES`) from
#: its experiment's arguments, as its function computes them.
CURVE_CASES = {
    "fig4": lambda a: fig4_cases(a["strokes"], a["t_end"], a["samples"]),
    "delay": lambda a: delay_cases(a["stroke"]),
}


def curve_files_of(
    configs: Sequence[Mapping],
    models: Sequence[Mapping[str, object]],
    settings: SolverSettings,
    curves: Sequence[str] = ("free_swing",),
) -> dict[str, Stack]:
    """The curve files (:data:`CURVE_FILES`) of several readings (as
    :func:`searched_files_of` takes them) as :class:`Stack` s over the readings, keyed
    ``"{key}/{curves}"`` as :func:`~tennis_stroke.inference.multiverse.paper_results`
    keys them: the stroke numbers, the curves and the coordinates ``stroke``, ``t``,
    ``theta0`` and ``delta0``, every stroke of every reading in one call of the compiled
    solver per file (:func:`~tennis_stroke.experiments.strokes.trajectory_arrays`).  The
    same numbers as the readings' datasets, without building them.  The readings must
    sample their curves at the same times."""
    out = {}
    for key in CURVE_FILES:
        cases = [
            CURVE_CASES[key](EXPERIMENTS[key].arguments({**c, "figure_curves": curves[0]}))
            for c in configs
        ]
        times = cases[0][2]
        if any(not np.array_equal(t, times) for _, _, t in cases):
            raise ValueError(f"{key}: the readings sample the curves at different times")
        strokes = [s for s, _, _ in cases]
        numbers, drawn = trajectory_arrays(strokes, models, times, settings, curves)
        coords = {
            "stroke": (
                ("stroke",),
                np.tile(np.arange(len(strokes[0]), dtype=float), (len(strokes), 1)),
            ),
            "t": (("t",), np.tile(times, (len(strokes), 1))),
            "theta0": (("stroke",), np.array([[s[0] for s in one] for one in strokes])),
            "delta0": (("stroke",), np.array([[s[1] for s in one] for one in strokes])),
        }
        fields = {FILE_NAMES.get(k, k): (("stroke",), v) for k, v in numbers.items()}
        for c in curves:
            samples = {k: (("stroke", "t"), v) for k, v in drawn[c].items()}
            out[f"{key}/{c}"] = Stack.of_arrays({**fields, **samples, **coords}, list(coords))
    return out


def _alike(args: Sequence[Mapping], key: str) -> Mapping:
    """The arguments of file ``key`` that every reading shares (raises ValueError if
    they differ): those of the first."""
    if any(not _same(a, args[0]) for a in args):
        raise ValueError(f"{key}: the readings' files read different arguments")
    return args[0]


def number_files_of(
    configs: Sequence[Mapping],
    models: Sequence[Mapping[str, object]],
    settings: SolverSettings,
    threads: int | None = 1,
) -> dict[str, Stack]:
    """The files of single strokes that the claims read only the numbers of, the k
    sensitivity (``k_sensitivity``) and Table I's numbers (``elbow``,
    :func:`table1_numbers`), of several readings (as :func:`searched_files_of` takes
    them) as :class:`Stack` s over the readings: every stroke of every reading in one
    batch per file, the readings' model overrides one value per reading.  The same
    numbers as the readings' datasets, without building them."""
    sets = len(models)
    shared, per_set = stacked(models, [1] * sets)

    def lead(v: np.ndarray, axes: int) -> np.ndarray:  # (sets,) -> (sets, 1, ...)
        return v.reshape(sets, *[1] * axes)

    def of_sets(res: Mapping[str, np.ndarray], shape: tuple[int, ...]) -> dict:
        return {k: np.broadcast_to(v, (sets, *shape)) for k, v in res.items()}

    k_args = _alike([EXPERIMENTS["k_sensitivity"].arguments(c) for c in configs], "k_sensitivity")
    params = {**shared, **{k: lead(v, 2) for k, v in per_set.items()}}
    strokes, k, res = k_sensitivity_strokes(
        k_args["strokes"], k_args["k_range"], k_args["points"], params, settings, threads
    )
    n = np.arange(len(strokes), dtype=float)
    dims = ("stroke", "k_contact")
    k_file = {FILE_NAMES.get(f, f): (dims, v) for f, v in of_sets(res, (n.size, k.size)).items()}
    k_file.update(
        {
            "stroke": (("stroke",), np.broadcast_to(n, (sets, n.size))),
            "k_contact": (("k_contact",), np.broadcast_to(k, (sets, k.size))),
            "theta0": (("stroke",), np.broadcast_to(strokes[:, 0], (sets, n.size))),
            "delta0": (("stroke",), np.broadcast_to(strokes[:, 1], (sets, n.size))),
        }
    )
    elbow = [EXPERIMENTS["elbow"].arguments({**c, "figure_curves": "free_swing"}) for c in configs]
    _alike([{**a, "force": {**a["force"], "table1_tau_F": 0.0}} for a in elbow], "elbow")
    params = {**shared, **{k: lead(v, 1) for k, v in per_set.items()}}
    res = _table1_strokes(elbow, params, settings)
    psi = np.array([*elbow[0]["force"]["table1_psi"], np.nan])
    e_file = {FILE_NAMES.get(f, f): (("stroke",), v) for f, v in of_sets(res, psi.shape).items()}
    e_file["psi_F"] = (("stroke",), np.broadcast_to(psi, (sets, psi.size)))
    e_file["stroke"] = (
        ("stroke",),
        np.broadcast_to(np.arange(psi.size, dtype=float), (sets, psi.size)),
    )
    return {
        "k_sensitivity": Stack.of_arrays(k_file, ["stroke", "k_contact", "theta0", "delta0"]),
        "elbow": Stack.of_arrays(e_file, ["stroke"]),
    }
