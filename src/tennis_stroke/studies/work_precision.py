"""Work-precision per scene: every integrator over a sweep of tolerances (or steps), on
seeded strokes of each scene, against an independent reference.

A scene (config ``solver_study.scenes``) is a set of model parameters over the sampled
strokes (:func:`~tennis_stroke.studies.sampling.sample_scene`): the swing only, the
paper's spring contact, the Sec. VI elbow force, a stiff contact.  The reference is
scipy's :data:`REFERENCE_METHOD` at rtol = atol = :data:`REFERENCE_TOL` on the
independent path (:mod:`tennis_stroke.solver.reference`: the model, not the compiled
code under test).  Per stroke, three errors: ``v_out`` (km/h); the event times (s), the
largest error of :data:`EVENTS`; the state along the stroke (rad/s), the RMS over
``state_times`` fixed times of the error of ``(omega1, omega2)``, each stroke's read on
the solve that gave its result, the reference's too (:mod:`tennis_stroke.studies.probe`:
one solve per stroke and setting for scipy and RK4).  The cost of record is the right-hand-side
evaluations per stroke, the same on every machine; beside it the wall time per stroke
on the machine that ran it (compiled: ``repeats`` timed batches, the median and the
fastest and slowest; scipy and RK4: each stroke timed once, the median and quartiles
over the strokes).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from functools import partial

import numpy as np
import xarray as xr

from ..experiments.grids import select_rows
from ..io.netcdf import provenance
from ..io.units import cf_attrs
from ..model.dynamics import coefficients
from ..model.params import resolve_params
from ..solver.reference import solve_stroke
from ..solver.results import OK
from ..solver.rk4 import fixed_step_stroke
from ..solver.settings import SolverSettings
from .methods import parse_method
from .probe import compiled_omegas, path_omegas, probe_times, segment_omegas
from .sampling import REFERENCE, sample_scene
from .tables import ERRORS, meets, rule_table
from .timing import TIMING, compiled_costs

#: The independent reference: scipy's ``solve_ivp`` method and its rtol = atol.
REFERENCE_METHOD, REFERENCE_TOL = "DOP853", 1e-13
#: The event times whose largest error is a stroke's event-time error.
EVENTS = ("t_phi0", "t_contact_start", "t_separation")
#: Strokes per timed batch of the compiled solver here (its fixed cost, about 1 ms,
#: then weighs under 2 % of a batch at the loosest tolerance).
TIMING_BATCH = 512
#: The families whose sweep stops at the first setting (from the loosest) that meets the
#: requirement: their right-hand sides run in Python, and a tighter setting of the same
#: method costs more evaluations (in every sweep measured), so it is not the rule
#: table's cheapest.  The compiled methods run every setting (the default's among them).
UNTIL_MET = ("scipy", "fixed")
#: The compiled method whose settings are the default (:class:`SolverSettings`).
DEFAULT_METHOD = f"tennis_stroke.{SolverSettings.method}"


def _methods(scipy_methods: Sequence[str]) -> list[str]:
    return [
        "tennis_stroke.DP54",
        "tennis_stroke.DOP853",
        *(f"scipy.{m}" for m in scipy_methods),
        "fixed.RK4",
    ]


def _one(method: str, setting: float, stroke) -> tuple[dict[str, float], Callable]:
    """One stroke ``(theta0, delta0, params)`` by a scipy method or fixed-step RK4: its
    result, and its ``omega1, omega2`` at given times read on the same solve
    (:mod:`tennis_stroke.studies.probe`)."""
    family, name = parse_method(method)
    if family == "scipy":
        solved = solve_stroke(*stroke, method=name, rtol=setting, atol=setting)
        return solved.result, partial(segment_omegas, solved.segments)
    path: list = []
    result = fixed_step_stroke(*stroke, setting, path=path)
    cf = coefficients(resolve_params(stroke[2]), stroke[0], stroke[1])[0]
    return result, partial(path_omegas, path, cf, setting)


def _strokes(strokes: Mapping[str, np.ndarray], params: Mapping[str, object]) -> list:
    """The strokes as ``(theta0, delta0, params)``, one value of each parameter (an
    array's element, or the scene's fixed value)."""

    def value(v, i):
        return v if isinstance(v, str) or np.ndim(v) == 0 else float(np.asarray(v)[i])

    return [
        (
            float(strokes["theta0"][i]),
            float(strokes["delta0"][i]),
            {k: value(v, i) for k, v in params.items()},
        )
        for i in range(strokes["theta0"].size)
    ]


def _run(method, setting, strokes, params, repeats, spring) -> dict[str, object]:
    """Every stroke by ``method`` at ``setting``: ``v_out``, the event times (n, 3),
    ``ok``, ``rhs_evals``, the wall time per stroke ``us`` (median, low, high), and per
    stroke ``omegas``, its ``omega1, omega2`` at given times (a function of the times:
    the stroke's own, with a ``spring`` contact or without; :mod:`.probe`)."""
    family, name = parse_method(method)
    each = _strokes(strokes, params)
    if family == "tennis_stroke":
        th, de = strokes["theta0"], strokes["delta0"]
        st = SolverSettings(method=name, rtol=setting, atol=setting)
        us, res = compiled_costs(th, de, params, st, repeats, TIMING_BATCH)
        t_c = res["t_contact_start"]
        return {
            "v_out": res["v_out_kmh"],
            "events": np.column_stack([res[e] for e in EVENTS]),
            "ok": res["status"] == OK,
            "rhs_evals": res["rhs_evals"].astype(float),
            "us": np.array([np.median(us), us.min(), us.max()]),
            "omegas": [
                partial(compiled_omegas, name, setting, stroke, t_c[i], spring=spring)
                for i, stroke in enumerate(each)
            ],
        }
    rows, per, omegas = [], [], []
    for stroke in each:
        start = time.perf_counter()
        row, at = _one(method, setting, stroke)
        per.append(time.perf_counter() - start)
        rows.append(row)
        omegas.append(at)
    per = np.array(per) * 1e6
    return {
        "v_out": np.array([r["v_out_kmh"] for r in rows], dtype=float),
        "events": np.array([[r[e] for e in EVENTS] for r in rows], dtype=float),
        "ok": np.array([r["status"] == OK for r in rows]),
        "rhs_evals": np.array([r["rhs_evals"] for r in rows], dtype=float),
        "us": np.array([np.median(per), *np.quantile(per, [0.25, 0.75])]),
        "omegas": omegas,
    }


def _reference(strokes, params, state_times: int) -> dict[str, object]:
    """The reference of every stroke: ``v_out``, event times, ``ok`` and the probe's
    times and ``omega1, omega2`` there (:mod:`tennis_stroke.studies.probe`), read on the
    reference's own solve."""
    spring = params.get("contact_model", "spring") == "spring"
    ref = _run(f"scipy.{REFERENCE_METHOD}", REFERENCE_TOL, strokes, params, 1, spring)
    ref["times"] = [
        probe_times(ref["events"][i, 2], state_times) if ok else None  # not ok: no probe
        for i, ok in enumerate(ref["ok"])
    ]
    ref["omegas"] = [
        at(times) if times is not None else None
        for at, times in zip(ref["omegas"], ref["times"], strict=True)
    ]
    ref["spring"] = spring
    return ref


def _errors(method, setting, strokes, params, ref) -> tuple[np.ndarray, ...]:
    """Per stroke: the three :data:`ERRORS`, the evaluations, and the timing."""
    run = _run(method, setting, strokes, params, ref["repeats"], ref["spring"])
    ok = run["ok"] & ref["ok"]
    v_err = np.where(ok, np.abs(run["v_out"] - ref["v_out"]), np.nan)
    ev = np.abs(run["events"] - ref["events"])
    ev_err = np.where(ok, np.max(np.where(ok[:, None], ev, 0.0), axis=1), np.nan)
    state = np.full(v_err.shape, np.nan)
    for i in np.flatnonzero(ok):
        om = run["omegas"][i](ref["times"][i])
        state[i] = np.sqrt(np.mean(np.sum((om - ref["omegas"][i]) ** 2, axis=1)))
    failed = float(np.sum(~run["ok"] & ref["ok"]))
    evals = np.where(run["ok"], run["rhs_evals"], np.nan)
    return v_err, ev_err, state, evals, run["us"], failed


def _worst(errors: np.ndarray) -> float:
    """The worst error over the compared strokes (NaN where none was compared)."""
    return float(np.nanmax(errors)) if np.any(~np.isnan(errors)) else np.nan


def _scene(strokes, params, methods, values, settings_axis, state_times, repeats, requirement):
    """The per-stroke arrays of one scene: (method, setting, stroke) each.  Each method
    runs its settings from the loosest; a family of :data:`UNTIL_MET` stops after the
    first that meets ``requirement`` (:func:`~tennis_stroke.studies.tables.meets`)."""
    n = strokes["theta0"].size
    ref = _reference(strokes, params, state_times) | {"repeats": repeats}
    shape = (len(methods), len(settings_axis))
    per = {k: np.full((*shape, n), np.nan) for k in (*ERRORS, "rhs_evals")}
    timing = np.full((*shape, 3), np.nan)
    failed = np.full(shape, np.nan)
    for mi, method in enumerate(methods):
        family = parse_method(method)[0]
        for value in sorted(values[family], reverse=True):
            si = settings_axis.index(value)
            *errs, evals, us, failed[mi, si] = _errors(method, value, strokes, params, ref)
            for key, arr in zip((*ERRORS, "rhs_evals"), (*errs, evals), strict=True):
                per[key][mi, si] = arr
            timing[mi, si] = us
            met = meets(_worst(errs[0]), _worst(errs[1]), failed[mi, si], requirement)
            if family in UNTIL_MET and met:
                break
    return per, timing, failed, int(np.sum(~ref["ok"]))


def work_precision(
    scenes: Mapping[str, Mapping[str, object]],
    strokes: int,
    seed: int,
    compiled_tols: Sequence[float],
    scipy_tols: Sequence[float],
    rk4_steps: Sequence[float],
    scipy_methods: Sequence[str] = ("RK45", "DOP853", "LSODA", "Radau"),
    state_times: int = 16,
    requirement: Mapping[str, float] | None = None,
    repeats: int = 3,
    rows: tuple[int, int] | None = None,
) -> xr.Dataset:
    """The work-precision table of every scene: dims ``scene`` x ``method`` x
    ``setting`` (x ``stroke`` for the errors and evaluations).

    ``setting`` is the tolerance (rtol = atol) of adaptive methods and the step (s) of
    fixed-step RK4; absent combinations are NaN (scipy's and RK4's settings tighter
    than their first that meets ``requirement`` are not run: :data:`UNTIL_MET`).
    ``requirement``: ``v_out`` (km/h) and ``event_time`` (s), the accuracy the rule
    table asks (:func:`rule_table`).
    ``rows = (index, count)``: only that chunk of the scenes, in their order (each
    scene is computed on its own: the chunks, gathered, equal the whole bit for bit).
    """
    requirement = dict(requirement or {"v_out": 1e-4, "event_time": 1e-6})
    methods = _methods(scipy_methods)
    settings_axis = sorted({*compiled_tols, *scipy_tols, *rk4_steps}, reverse=True)
    values = {"tennis_stroke": compiled_tols, "scipy": scipy_tols, "fixed": rk4_steps}
    names = [str(n) for n in select_rows(np.array(list(scenes), dtype=object), rows)]
    parts, drawn = [], {}
    for name in names:
        sample, params = sample_scene(strokes, seed, scenes[name])
        parts.append(
            _scene(
                sample, params, methods, values, settings_axis, state_times, repeats, requirement
            )
        )
        drawn[name] = sample
    return _dataset(names, methods, settings_axis, parts, drawn, requirement, scenes)


def _dataset(scenes, methods, settings_axis, parts, drawn, requirement, scene_params):
    dims = ("scene", "method", "setting")
    per = {k: np.stack([p[0][k] for p in parts]) for k in parts[0][0]}
    timing = np.stack([p[1] for p in parts])
    data = {
        **{k: ((*dims, "stroke"), v, cf_attrs(k)) for k, v in per.items()},
        "us_per_stroke": (dims, timing[..., 0], cf_attrs("us_per_stroke", **TIMING)),
        "us_per_stroke_low": (dims, timing[..., 1], cf_attrs("us_per_stroke_low", **TIMING)),
        "us_per_stroke_high": (dims, timing[..., 2], cf_attrs("us_per_stroke_high", **TIMING)),
        "failed": (dims, np.stack([p[2] for p in parts]), cf_attrs("failed")),
        "reference_failed": ("scene", [p[3] for p in parts], cf_attrs("reference_failed")),
        **{
            k: (("scene", "stroke"), np.stack([drawn[s][k] for s in scenes]), cf_attrs(k))
            for k in ("theta0", "delta0")
        },
        "scene_params": (
            "scene",
            [_shown(scene_params[s]) for s in scenes],
            cf_attrs("scene_params"),
        ),
    }
    coords = {
        "scene": ("scene", scenes, cf_attrs("scene")),
        "method": ("method", methods, cf_attrs("method")),
        "setting": ("setting", np.array(settings_axis), cf_attrs("setting")),
        "stroke": ("stroke", np.arange(per["v_out_error"].shape[-1]), cf_attrs("stroke")),
    }
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    ds.attrs.update(
        strokes=ds.sizes["stroke"],
        reference=f"scipy {REFERENCE_METHOD}, rtol = atol = {REFERENCE_TOL:g}",
        solver_settings_of="the sampling of the strokes; each method's is the setting axis",
        required_v_out_error_kmh=float(requirement["v_out"]),
        required_event_time_error_s=float(requirement["event_time"]),
        default_method=DEFAULT_METHOD,
        default_setting=float(SolverSettings.rtol),
    )
    # a scene's rule reads that scene alone: the same in a chunk as in the whole file
    rules = [f"{r.method} @ {r.setting:g}" for r in rule_table(ds).itertuples()]
    ds["rule"] = ("scene", rules, cf_attrs("rule"))
    return ds


def _shown(scene: Mapping[str, object]) -> str:
    return "; ".join(f"{k} = {v}" for k, v in scene.items()) or "the paper's defaults"


def work_precision_study(
    scenes: Mapping[str, Mapping[str, object]],
    scene_strokes: int,
    seed: int,
    compiled_tolerances: Sequence[float],
    scipy_tolerances: Sequence[float],
    rk4_steps: Sequence[float],
    scipy_methods: Sequence[str],
    state_times: int,
    requirement: Mapping[str, float],
    repeats: int,
    rows: tuple[int, int] | None = None,
) -> xr.Dataset:
    """The work-precision table from the config (``solver_study``): ``scene_strokes``
    seeded strokes per scene (:func:`tennis_stroke.studies.sampling.sample_scene`);
    the workflow runs one job per scene (``rows``, the chunk of the scenes)."""
    return work_precision(
        scenes,
        scene_strokes,
        seed,
        compiled_tolerances,
        scipy_tolerances,
        rk4_steps,
        scipy_methods,
        state_times,
        requirement,
        repeats,
        rows,
    )
