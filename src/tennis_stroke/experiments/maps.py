"""The paper's maps as functions of plain parameters, each returning a dataset.

Every function takes model overrides (``params``: scalars and readings), solver settings
and a thread count, runs strokes through :func:`tennis_stroke.solver.stroke.strike_batch`
and returns an :class:`xarray.Dataset` with CF metadata
(:func:`tennis_stroke.io.netcdf.result_dataset`).  The first axis of every map can be computed
in chunks of rows (:mod:`tennis_stroke.pipeline.chunks`); the workflow's scripts only call
these and write the files.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..io.netcdf import result_dataset
from ..io.units import cf_attrs
from ..model.params import resolve_params
from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch
from .grids import axis, grid, ok_speeds, refine_peak, select_rows


def angle_map(
    theta0: np.ndarray,
    delta0: np.ndarray,
    params: Mapping[str, object],
    settings: SolverSettings,
    threads: int | None = None,
) -> xr.Dataset:
    """Figs. 2-3: every result over ``(theta0, delta0)`` and the best ``delta0`` per ``theta0``.

    ``best_delta0`` is the red line of the figures (parabola-refined).
    """
    res = strike_batch(theta0[:, None], delta0[None, :], params, settings, threads)
    ds = result_dataset(res, {"theta0": theta0, "delta0": delta0}, resolve_params(params), settings)
    v = ok_speeds(res)
    best = np.array([refine_peak(delta0, row) for row in v])
    ds["best_delta0"] = ("theta0", best[:, 0], cf_attrs("best_delta0"))
    ds["best_v_out"] = ("theta0", best[:, 1], cf_attrs("best_v_out"))
    return ds


def optimum_dataset(m2, l1, variables, params, settings, attrs) -> xr.Dataset:
    """A Figs. 5-6 file: ``variables`` (name -> values over ``(M2, L1)``) with their
    labels, the model's provenance and the search's ``attrs``."""
    ds = result_dataset({}, {"M2": m2, "L1": l1}, resolve_params(params), settings, attrs)
    return ds.assign({k: (("M2", "L1"), v, cf_attrs(k)) for k, v in variables.items()})


def mass_length_map(
    m2: np.ndarray,
    l1: np.ndarray,
    coarse_step: float,
    fine_step: float,
    theta0_range: tuple[float, float],
    delta0_range: tuple[float, float],
    params: Mapping[str, object],
    settings: SolverSettings,
    threads: int | None = None,
) -> xr.Dataset:
    """Figs. 5-6: the fastest rebound over the initial angles at every ``(M2, L1)``.

    What is optimised: ``v_out`` over ``(theta0, delta0)`` in the given ranges, the other
    parameters fixed.  How: a coarse grid (``coarse_step`` degrees) over the whole range,
    then a fine grid (``fine_step``) of +-1 coarse step around the coarse optimum, refined
    by parabolas; the fine grid is clipped to the ranges, so an optimum on the edge of
    the range stays there.  ``theta_c`` is ``|theta|`` at ``phi = 0`` of the optimal
    stroke.  ``failed_strokes`` counts the strokes of each point's search that failed
    (attribute ``strokes_per_point``: how many it ran).
    """
    th_c = grid(*theta0_range, coarse_step)
    de_c = grid(*delta0_range, coarse_step)
    mm, ll = np.meshgrid(m2, l1, indexing="ij")
    p = {**params, "M2": mm[..., None, None], "L1": ll[..., None, None]}
    coarse_res = strike_batch(
        th_c[None, None, :, None], de_c[None, None, None, :], p, settings, threads
    )
    coarse = ok_speeds(coarse_res)
    flat = coarse.reshape(*mm.shape, -1)
    best = np.nanargmax(np.where(np.isnan(flat), -np.inf, flat), axis=-1)
    ti, di = np.unravel_index(best, (th_c.size, de_c.size))
    offsets = grid(-coarse_step, coarse_step, fine_step)
    th_f = np.clip(th_c[ti][..., None, None] + offsets[:, None], *theta0_range)
    de_f = np.clip(de_c[di][..., None, None] + offsets[None, :], *delta0_range)
    fine_res = strike_batch(th_f, de_f, p, settings, threads)
    fine = ok_speeds(fine_res)
    failed = np.count_nonzero(coarse_res["status"].reshape(*mm.shape, -1), axis=-1)
    failed += np.count_nonzero(fine_res["status"].reshape(*mm.shape, -1), axis=-1)
    out = {k: np.full(mm.shape, np.nan) for k in ("v", "theta0", "delta0", "theta_c")}
    for idx in np.ndindex(mm.shape):
        f = fine[idx]
        if not np.any(np.isfinite(f)):
            continue
        i, j = np.unravel_index(np.nanargmax(f), f.shape)
        t_opt, v_t = refine_peak(th_f[idx][:, 0], f[:, j])
        d_opt, v_d = refine_peak(de_f[idx][0, :], f[i, :])
        out["v"][idx] = max(v_t, v_d)
        out["theta0"][idx], out["delta0"][idx] = t_opt, d_opt
        out["theta_c"][idx] = abs(fine_res["theta_deg_at_phi0"][idx][i, j])
    names = {"v": "v_out_best", "theta0": "theta0_best", "delta0": "delta0_best"}
    variables = {names.get(k, k): v for k, v in out.items()}
    variables["failed_strokes"] = failed.astype(np.int64)
    attrs = {
        "coarse_step_deg": coarse_step,
        "fine_step_deg": fine_step,
        "strokes_per_point": th_c.size * de_c.size + offsets.size**2,
    }
    return optimum_dataset(m2, l1, variables, params, settings, attrs)


def delay_map(
    axis_name: str,
    axis: np.ndarray,
    tau: np.ndarray,
    theta0: float,
    delta0,
    params: Mapping[str, object],
    settings: SolverSettings,
    threads: int | None = None,
) -> xr.Dataset:
    """Figs. 7-8: ``v_out`` over (``axis``, wrist-torque delay ``tau``) and the best ``tau``.

    ``axis_name`` is a parameter (``C2``) or ``delta0``; ``best_tau`` and ``best_v_out``
    along ``tau`` for each value of the axis (parabola-refined).
    """
    if axis_name == "delta0":
        res = strike_batch(
            theta0, axis[:, None], {**params, "tau": tau[None, :]}, settings, threads
        )
    else:
        res = strike_batch(
            theta0,
            delta0,
            {**params, axis_name: axis[:, None], "tau": tau[None, :]},
            settings,
            threads,
        )
    fixed = {"theta0_deg": float(theta0)}
    if delta0 is not None:
        fixed["delta0_deg"] = float(delta0)
    ds = result_dataset(res, {axis_name: axis, "tau": tau}, resolve_params(params), settings, fixed)
    v = ok_speeds(res)
    best = np.array([refine_peak(tau, row) for row in v])
    ds["best_tau"] = (axis_name, best[:, 0], cf_attrs("best_tau"))
    ds["best_v_out"] = (axis_name, best[:, 1], cf_attrs("best_v_out"))
    ds["v_out_tau0"] = (axis_name, v[:, 0], cf_attrs("v_out_tau0"))
    return ds


def elbow_force_map(
    psi: np.ndarray,
    tau_f: np.ndarray,
    t_ref: float,
    theta0: float,
    delta0: float,
    params: Mapping[str, object],
    settings: SolverSettings,
    threads: int | None = None,
) -> xr.Dataset:
    """Fig. 13: ``v_out`` over the direction ``psi_F`` and extra delay ``tau_F`` of Eq. 14.

    The pulse is centred at ``t_ref + tau_F`` (the paper: ``tau_H + tau_F``).
    """
    res = strike_batch(
        theta0,
        delta0,
        {**params, "psi_F_deg": psi[:, None], "t_F": t_ref + tau_f[None, :]},
        settings,
        threads,
    )
    return result_dataset(
        res,
        {"psi_F": psi, "tau_F": tau_f},
        resolve_params(params),
        settings,
        {"t_ref_s": t_ref},
    )


def torque_delay_section(
    L1: float,
    theta0: float,
    C2,
    delta0,
    tau,
    params: Mapping[str, object],
    settings: SolverSettings,
    rows: tuple[int, int] | None = None,
    threads: int | None = None,
) -> xr.Dataset:
    """Figs. 7-9 from their config: ``L1`` (m), ``theta0`` (degrees), ``tau`` (a range, s)
    and ``C2`` (N m), ``delta0`` (degrees), one of them a range (the map's first axis:
    ``C2`` for Fig. 7, ``delta0`` for Figs. 8-9) and the other a number (a number
    ``delta0`` with a number ``C2`` gives a one-row map, Fig. 9).

    ``rows``: ``(index, count)``, only that chunk of the first axis
    (:func:`tennis_stroke.experiments.grids.chunk_rows`).
    """
    model = {**params, "L1": L1}
    tau = axis(tau)
    if isinstance(C2, Mapping):  # Fig. 7: (C2, tau) at fixed delta0
        return delay_map(
            "C2", select_rows(axis(C2), rows), tau, theta0, delta0, model, settings, threads
        )
    # Figs. 8-9: (delta0, tau) at fixed C2
    delta0 = axis(delta0) if isinstance(delta0, Mapping) else np.array([float(delta0)])
    return delay_map(
        "delta0",
        select_rows(delta0, rows),
        tau,
        theta0,
        None,
        {**model, "C2": C2},
        settings,
        threads,
    )


def elbow_force_section_map(
    force: Mapping[str, float],
    psi_f,
    tau_f,
    stroke: Mapping[str, float],
    params: Mapping[str, object],
    settings: SolverSettings,
    rows: tuple[int, int] | None = None,
    threads: int | None = None,
) -> xr.Dataset:
    """Fig. 13 from the config: the force ``{F0, t_d}`` of Eq. 14 in the directions
    ``psi_f`` (degrees) centred at ``tau_H + tau_f`` (s; both ranges ``[start, stop,
    step]``), on the Sec. V stroke ``{L1, C2, tau_H, theta0, delta0}``.

    ``rows``: ``(index, count)``, only that chunk of the ``psi_F`` axis.
    """
    psi = axis(psi_f)
    model = {
        **params,
        "L1": stroke["L1"],
        "C2": stroke["C2"],
        "tau": stroke["tau_H"],
        "F0": force["F0"],
        "t_d": force["t_d"],
    }
    return elbow_force_map(
        select_rows(psi, rows),
        axis(tau_f),
        stroke["tau_H"],
        stroke["theta0"],
        stroke["delta0"],
        model,
        settings,
        threads,
    )


def k_sensitivity_strokes(
    strokes, k_range: tuple[float, float], points: int, params, settings, threads=None
) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """The strokes ``(theta0, delta0)`` (``(n, 2)``, degrees), the geometric grid of
    ``points`` spring constants spanning ``k_range`` (N/m) and the results of every
    stroke at each, ``(n, points)``; model overrides ``params`` of arrays shaped
    ``(sets, 1, 1)`` give ``(sets, n, points)``, set by set what each gives alone."""
    strokes = np.asarray(strokes, dtype=float).reshape(-1, 2)
    k = np.geomspace(float(k_range[0]), float(k_range[1]), int(points))
    res = strike_batch(
        strokes[:, 0, None],
        strokes[:, 1, None],
        {**params, "k_contact": k[None, :]},
        settings,
        threads,
    )
    return strokes, k, res


def k_sensitivity_map(
    strokes,
    k_range: tuple[float, float],
    points: int,
    params: Mapping[str, object],
    settings: SolverSettings,
    threads: int | None = None,
) -> xr.Dataset:
    """Sec. II: every result of the strokes ``(theta0, delta0)`` (degrees) over a
    geometric grid of ``points`` spring constants spanning ``k_range`` (N/m)
    (:func:`k_sensitivity_strokes`).

    The paper: 'the coupling constant k determines the collision duration, but the speed
    of the rebound ball is not altered very much'.
    """
    strokes, k, res = k_sensitivity_strokes(strokes, k_range, points, params, settings, threads)
    ds = result_dataset(
        res, {"stroke": np.arange(len(strokes)), "k_contact": k}, resolve_params(params), settings
    )
    ds = ds.assign_coords(
        theta0=("stroke", strokes[:, 0], cf_attrs("theta0")),
        delta0=("stroke", strokes[:, 1], cf_attrs("delta0")),
    )
    return ds


def angle_map_section(
    theta0,
    delta0,
    L1: float,
    params: Mapping[str, object],
    settings: SolverSettings,
    rows: tuple[int, int] | None = None,
    threads: int | None = None,
) -> xr.Dataset:
    """Figs. 2-3 from their config: the ranges ``theta0`` and ``delta0`` (degrees) at the
    figure's rod-1 length ``L1`` (m); ``rows``: only that chunk of the ``theta0`` rows."""
    theta = select_rows(axis(theta0), rows)
    return angle_map(theta, axis(delta0), {**params, "L1": float(L1)}, settings, threads)
