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
from ..experiments.optima import mass_length_optimum
from ..experiments.search import StrokeObjective, coarse_axis, first_crossing, maximize
from ..experiments.specs import EXPERIMENTS
from ..experiments.strokes import table1_cases
from ..solver.results import FILE_NAMES
from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch
from .multiverse import paper_results
from .search_plan import NUMBERS_ONLY, SEARCHED


def _dataset(variables: Mapping, coords: Mapping, **attrs) -> xr.Dataset:
    """A targeted file: the variables its claims read (no labels: it is never written)."""
    ds = xr.Dataset(
        {k: (dims, np.asarray(v)) for k, (dims, v) in variables.items()},
        coords={k: (k, np.asarray(v, float)) for k, v in coords.items()},
    )
    ds.attrs.update(attrs, targeted="search (tennis_stroke.inference.targeted)")
    return ds


def angle_rows(args: Mapping, search: Mapping, model, settings, threads=None) -> xr.Dataset:
    """Figs. 2-3: the best ``delta0`` of every ``theta0`` row (a search along delta0)."""
    theta0 = axis(args["theta0"])
    d0 = args["delta0"]
    objective = StrokeObjective(
        ("delta0",),
        theta0.size,
        {"theta0": theta0},
        {**model, "L1": args["L1"]},
        settings,
        threads,
    )
    best = maximize(
        objective,
        theta0.size,
        [d0["start"]],
        [d0["stop"]],
        [search["angle_step"]],
        [search["angle_tolerance"]],
    )
    return _dataset(
        {"best_delta0": ("theta0", best.x[:, 0]), "best_v_out": ("theta0", best.value)},
        {"theta0": theta0},
    )


def mass_length_ends(
    args: Mapping, model, settings, l1_max: float | None = None, threads=None
) -> xr.Dataset:
    """Figs. 5-6: the optimum of every ``M2`` at the smallest and the largest ``L1`` of
    the grid (the largest at most ``l1_max``)."""
    l1 = axis(args["L1"])
    if l1_max is not None:
        l1 = l1[l1 <= l1_max + 1e-9]
    ends = np.unique(l1[[0, -1]])
    return mass_length_optimum(
        axis(args["M2"]),
        ends,
        args["coarse_step"],
        args["tolerance"],
        tuple(args["theta0_range"]),
        tuple(args["delta0_range"]),
        model,
        settings,
        threads,
    )


def _ends(spec: Mapping) -> tuple[float, float]:
    """The ends of a searched range (its step is the map's, not the search's)."""
    return float(spec["start"]), float(spec["stop"])


def _best_tau(c2: np.ndarray, tau, base, search, settings, threads):
    objective = StrokeObjective(("tau",), c2.size, {"C2": c2}, base, settings, threads)
    return maximize(
        objective, c2.size, [tau[0]], [tau[-1]], [search["tau_step"]], [search["time_tolerance"]]
    )


def delay_threshold(args: Mapping, search: Mapping, model, settings, threads=None) -> xr.Dataset:
    """Fig. 7: ``best_tau`` on ``C2`` rows ``C2_step`` apart and on the two rows at most
    ``C2_tolerance`` apart where it leaves 0 for good (more than half a step of the
    configured ``tau`` grid, as :func:`~tennis_stroke.inference.measures.measure_delay_threshold`
    reads it)."""
    tau = axis(args["tau"])
    half_step = 0.5 * float(tau[1] - tau[0])
    c2 = coarse_axis(args["C2"]["start"], args["C2"]["stop"], search["C2_step"])
    base = {**model, "L1": args["L1"], "theta0": args["theta0"], "delta0": args["delta0"]}
    best = _best_tau(c2, tau, base, search, settings, threads)
    rows, taus, speeds = [c2], [best.x[:, 0]], [best.value]
    positive = (best.x[:, 0] > half_step) & (c2 > 0)
    first = next((i for i in range(c2.size) if c2[i] > 0 and positive[i:].all()), None)
    if first is not None and first > 0:

        def leaves_zero(values: np.ndarray) -> np.ndarray:
            found = _best_tau(values.ravel(), tau, base, search, settings, threads)
            rows.append(values.ravel())
            taus.append(found.x[:, 0])
            speeds.append(found.value)
            return (found.x[:, 0] > half_step).reshape(values.shape)

        first_crossing(leaves_zero, c2[[first - 1]], c2[[first]], search["C2_tolerance"])
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


def delay_optimum(args: Mapping, search: Mapping, model, settings, threads=None) -> xr.Dataset:
    """Fig. 8: the point of the largest ``v_out`` over ``(delta0, tau)``."""
    d0, tau = args["delta0"], _ends(args["tau"])
    objective = StrokeObjective(
        ("delta0", "tau"), 1, {}, _sec5_base(args, model), settings, threads
    )
    best = maximize(
        objective,
        1,
        [d0["start"], tau[0]],
        [d0["stop"], tau[1]],
        [search["angle_step"], search["tau_step"]],
        [search["angle_tolerance"], search["time_tolerance"]],
    )
    v = np.reshape(best.value, (1, 1))
    return _dataset(
        {
            "v_out": (("delta0", "tau"), v),
            "status": (("delta0", "tau"), np.where(np.isfinite(v), 0, 1)),
        },
        {"delta0": best.x[:, 0], "tau": best.x[:, 1]},
    )


def delay_line(args: Mapping, search: Mapping, model, settings, threads=None) -> xr.Dataset:
    """Fig. 9: ``v_out`` at ``tau = 0`` (the grid's first delay) and at the best delay."""
    tau = _ends(args["tau"])
    base = {**_sec5_base(args, model), "delta0": args["delta0"]}
    best = _best_tau(np.array([float(args["C2"])]), tau, base, search, settings, threads)
    objective = StrokeObjective(("tau",), 1, {}, base, settings, threads)
    v0 = objective(np.array([[[tau[0]]]]), np.arange(1))[0, 0]
    v = np.array([[v0, best.value[0]]])
    return _dataset(
        {
            "v_out": (("delta0", "tau"), v),
            "status": (("delta0", "tau"), np.where(np.isfinite(v), 0, 1)),
            "best_tau": ("delta0", best.x[:, 0]),
            "best_v_out": ("delta0", best.value),
        },
        {"delta0": [float(args["delta0"])], "tau": [tau[0], best.x[0, 0]]},
    )


def elbow_extremes(args: Mapping, search: Mapping, model, settings, threads=None) -> xr.Dataset:
    """Fig. 13: ``v_out`` on the 2 x 2 grid of the directions and pulse delays of the
    largest and the smallest ``v_out`` (each a search over ``(psi_F, tau_F)``)."""
    force, stroke = args["force"], args["stroke"]
    psi, tau_f = _ends(args["psi_f"]), _ends(args["tau_f"])
    t_ref = float(stroke["tau_H"])
    base = {
        **model,
        "L1": stroke["L1"],
        "C2": stroke["C2"],
        "tau": t_ref,
        "F0": force["F0"],
        "t_d": force["t_d"],
        "theta0": stroke["theta0"],
        "delta0": stroke["delta0"],
    }
    objective = StrokeObjective(("psi_F_deg", "t_F"), 1, {}, base, settings, threads)
    turn = 360.0 if np.isclose(psi[-1] - psi[0], 360.0) else None  # a full turn wraps
    found = [
        maximize(
            objective,
            1,
            [psi[0], t_ref + tau_f[0]],
            [psi[-1], t_ref + tau_f[-1]],
            [search["psi_F_step"], search["tau_F_step"]],
            [search["angle_tolerance"], search["time_tolerance"]],
            sign=sign,
            periods=[turn, None],
        ).x[0]
        for sign in (1.0, -1.0)
    ]
    p = np.array([x[0] for x in found])
    t = np.array([x[1] for x in found]) - t_ref
    points = np.stack(np.meshgrid(p, t + t_ref, indexing="ij"), axis=-1).reshape(1, 4, 2)
    res = objective.strike(points, np.arange(1))
    return _dataset(
        {
            "v_out": (("psi_F", "tau_F"), res["v_out_kmh"].reshape(2, 2)),
            "status": (("psi_F", "tau_F"), res["status"].reshape(2, 2)),
        },
        {"psi_F": p, "tau_F": t},
        t_ref_s=t_ref,
    )


def table1_numbers(args: Mapping, model, settings) -> xr.Dataset:
    """Table I: the numbers of its strokes (the curves of Fig. 14 left out), the same
    strokes as :func:`tennis_stroke.experiments.strokes.elbow_force_strokes`."""
    stroke = args["stroke"]
    cases = table1_cases(args["force"], stroke)
    values = {k: np.array([c[k] for c in cases], float) for k in cases[0]}
    res = strike_batch(stroke["theta0"], stroke["delta0"], {**model, **values}, settings, 1)
    psi = [*args["force"]["table1_psi"], np.nan]
    return _dataset(
        {FILE_NAMES.get(k, k): ("stroke", v) for k, v in res.items()} | {"psi_F": ("stroke", psi)},
        {"stroke": np.arange(len(cases))},
    )


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
    search, model = config["search"], dict(model)
    run = {
        "fig2": lambda a: angle_rows(a, search, model, settings, threads),
        "fig3": lambda a: angle_rows(a, search, model, settings, threads),
        "ml": lambda a: mass_length_ends(a, model, settings, l1_max, threads),
        "fig7": lambda a: delay_threshold(a, search, model, settings, threads),
        "fig8": lambda a: delay_optimum(a, search, model, settings, threads),
        "fig9": lambda a: delay_line(a, search, model, settings, threads),
        "elbow_map": lambda a: elbow_extremes(a, search, model, settings, threads),
    }
    return {key: run[key](EXPERIMENTS[key].arguments(config)) for key in keys}


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
    keys = [k for k in EXPERIMENTS if EXPERIMENTS[k].family == "paper"] if keys is None else keys
    skip = tuple(k for k in EXPERIMENTS if k not in keys) + SEARCHED + NUMBERS_ONLY
    out = paper_results(config, dict(model), settings, curves, threads, skip=skip)
    if "elbow" in keys:
        elbow = EXPERIMENTS["elbow"].arguments({**config, "figure_curves": curves[0]})
        out["elbow"] = table1_numbers(elbow, dict(model), settings)
    searched = [k for k in SEARCHED if k in keys]
    return {**out, **searched_files(config, model, settings, l1_max, threads, searched)}
