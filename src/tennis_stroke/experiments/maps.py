"""The paper's experiments as functions of plain parameters, each returning a dataset.

Every function takes model overrides (``params``: scalars and readings), solver settings
and a thread count, runs strokes through :func:`tennis_stroke.solver.stroke.strike_batch` (or the
reference path for the few trajectories that figures draw) and returns an
:class:`xarray.Dataset` with CF metadata (:func:`tennis_stroke.io.result_dataset`).  The
workflow scripts only call these and write the files.

Optima found on a grid are refined by a parabola through the best grid point and its two
neighbours along each axis (:func:`refine_peak`), so their accuracy is much finer than the
grid; the grid spacing is recorded with every optimum.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..io import result_dataset
from ..model.dynamics import coefficients, elbow_position
from ..model.params import resolve_params
from ..solver.reference import free_swing, solve_stroke
from ..solver.stroke import SolverSettings, strike, strike_batch

KMH = ("km/h", "rebound speed of the ball towards -x")


def grid(start: float, stop: float, step: float) -> np.ndarray:
    """Inclusive grid ``start, start + step, ..., stop`` (rounded to the step's decimals)."""
    n = int(round((stop - start) / step)) + 1
    return np.round(start + step * np.arange(n), 10)


def refine_peak(x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
    """Location and value of the maximum of samples ``v(x)`` (NaN = failed stroke).

    A parabola through the best sample and its neighbours refines both; at the edge of
    the grid the best sample itself is returned.
    """
    if not np.any(np.isfinite(v)):
        return np.nan, np.nan
    i = int(np.nanargmax(v))
    if 0 < i < len(x) - 1 and np.all(np.isfinite(v[i - 1 : i + 2])):
        y0, y1, y2 = v[i - 1 : i + 2]
        denom = y0 - 2.0 * y1 + y2
        if denom < 0.0:
            shift = 0.5 * (y0 - y2) / denom
            h = x[i + 1] - x[i]
            return float(x[i] + shift * h), float(y1 - 0.25 * (y0 - y2) * shift)
    return float(x[i]), float(v[i])


def _ok(res: Mapping[str, np.ndarray]) -> np.ndarray:
    """v_out with failed strokes as NaN."""
    return np.where(res["status"] == 0, res["v_out_kmh"], np.nan)


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
    v = _ok(res)
    best = np.array([refine_peak(delta0, row) for row in v])
    ds["best_delta0"] = (
        "theta0",
        best[:, 0],
        {"units": "degree", "long_name": "delta0 of the fastest rebound"},
    )
    ds["best_v_out"] = (
        "theta0",
        best[:, 1],
        {"units": KMH[0], "long_name": "fastest rebound speed"},
    )
    return ds


#: How the curves of omega(t) are drawn: the free swing without the ball (the paper
#: computes the swing and the collision separately, Sec. II) or the stroke with the ball.
CURVES = ("free_swing", "with_ball")


def trajectories(
    strokes: Sequence[tuple[float, float, Mapping[str, object]]],
    labels: Sequence[str],
    times: np.ndarray,
    params: Mapping[str, object],
    settings: SolverSettings,
    curves: str = "free_swing",
) -> xr.Dataset:
    """Figs. 4, 10-12, 14: omega1, omega2, theta, phi and the elbow path over time.

    Each stroke is ``(theta0, delta0, extra params)``.  Curves come from the reference path
    (dense output up to ``times[-1]``): the free swing, or with ``curves="with_ball"``
    the stroke with the contact and the follow-through.  The stroke numbers come from the
    compiled path.  Curves are NaN outside the simulated span.
    """
    if curves not in CURVES:
        raise ValueError(f"curves must be one of {', '.join(CURVES)}, got {curves!r}")
    samples = {k: [] for k in ("omega1", "omega2", "theta", "phi", "x_elbow", "y_elbow")}
    numbers: dict[str, list] = {}
    for theta0, delta0, extra in strokes:
        p = {**params, **extra}
        res = strike(theta0, delta0, p, settings)
        for key, value in res.items():
            if key != "status_name":
                numbers.setdefault(key, []).append(value)
        if curves == "free_swing":
            ref = free_swing(theta0, delta0, float(times[-1]), p)
        else:
            ref = solve_stroke(
                theta0,
                delta0,
                p,
                rtol=1e-10,
                atol=1e-10,
                follow_through=max(times[-1] - res["t_separation"], 0.0)
                if res["status"] == 0
                else 0.0,
            )
        sampled = ref.sample(times)
        for key in ("omega1", "omega2"):
            samples[key].append(sampled[key])
        samples["theta"].append(np.degrees(sampled["theta"]))
        samples["phi"].append(np.degrees(sampled["phi"]))
        cf = coefficients(resolve_params(p), theta0, delta0)[0]
        path = np.array([elbow_position(t, cf) for t in times])
        samples["x_elbow"].append(path[:, 0])
        samples["y_elbow"].append(path[:, 1])
    meta = {
        "omega1": ("rad/s", "rod-1 angular velocity (clockwise)"),
        "omega2": ("rad/s", "rod-2 angular velocity (clockwise)"),
        "theta": ("degree", "rod-1 angle from -y"),
        "phi": ("degree", "rod-2 angle from -y"),
        "x_elbow": ("m", "elbow x position"),
        "y_elbow": ("m", "elbow y position"),
    }
    results = {k: np.asarray(v) for k, v in numbers.items()}
    ds = result_dataset(
        results,
        {"stroke": (np.arange(len(strokes)), "1", "stroke index")},
        resolve_params(params),
        settings,
    )
    ds = ds.assign_coords(
        label=("stroke", list(labels)),
        theta0=(
            "stroke",
            [s[0] for s in strokes],
            {"units": "degree", "long_name": "initial rod-1 angle"},
        ),
        delta0=(
            "stroke",
            [s[1] for s in strokes],
            {"units": "degree", "long_name": "initial angle between the rods"},
        ),
    )
    ds["label"].attrs = {"units": "1", "long_name": "stroke label"}
    ds = ds.assign_coords(time=("time", times, {"units": "s", "long_name": "time"}))
    ds.attrs["curves"] = curves
    for key, values in samples.items():
        ds[key] = (
            ("stroke", "time"),
            np.asarray(values),
            {"units": meta[key][0], "long_name": meta[key][1]},
        )
    return ds


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
    coarse = _ok(coarse_res)
    flat = coarse.reshape(*mm.shape, -1)
    best = np.nanargmax(np.where(np.isnan(flat), -np.inf, flat), axis=-1)
    ti, di = np.unravel_index(best, (th_c.size, de_c.size))
    offsets = grid(-coarse_step, coarse_step, fine_step)
    th_f = np.clip(th_c[ti][..., None, None] + offsets[:, None], *theta0_range)
    de_f = np.clip(de_c[di][..., None, None] + offsets[None, :], *delta0_range)
    fine_res = strike_batch(th_f, de_f, p, settings, threads)
    fine = _ok(fine_res)
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
    coords = {
        "M2": (m2, "kg", "mass of rod 2 (hand+racket)"),
        "L1": (l1, "m", "length of rod 1 (elbow to hand, projected)"),
    }
    ds = result_dataset(
        {},
        coords,
        resolve_params(params),
        settings,
        {
            "coarse_step_deg": coarse_step,
            "fine_step_deg": fine_step,
            "strokes_per_point": th_c.size * de_c.size + offsets.size**2,
        },
    )
    meta = {
        "v": ("v_out_best", KMH[0], "fastest rebound speed over the initial angles"),
        "theta0": ("theta0_best", "degree", "theta0 of the fastest rebound"),
        "delta0": ("delta0_best", "degree", "delta0 of the fastest rebound"),
        "theta_c": ("theta_c", "degree", "|theta| at phi = 0 of the fastest rebound"),
    }
    for key, (name, units, long_name) in meta.items():
        ds[name] = (("M2", "L1"), out[key], {"units": units, "long_name": long_name})
    ds["failed_strokes"] = (
        ("M2", "L1"),
        failed.astype(np.int64),
        {"units": "1", "long_name": "failed strokes of the optimum search at this point"},
    )
    return ds


def delay_map(
    axis_name: str,
    axis: np.ndarray,
    axis_meta: tuple[str, str],
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
    ds = result_dataset(
        res,
        {axis_name: (axis, *axis_meta), "tau": (tau, "s", "delay of the wrist torque C2")},
        resolve_params(params),
        settings,
    )
    v = _ok(res)
    best = np.array([refine_peak(tau, row) for row in v])
    ds["best_tau"] = (
        axis_name,
        best[:, 0],
        {"units": "s", "long_name": "delay of the fastest rebound"},
    )
    ds["best_v_out"] = (
        axis_name,
        best[:, 1],
        {"units": KMH[0], "long_name": "fastest rebound speed"},
    )
    ds["v_out_tau0"] = (
        axis_name,
        v[:, 0],
        {"units": KMH[0], "long_name": "rebound speed at tau = 0"},
    )
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
        {
            "psi_F": (psi, "degree", "direction of the elbow force from +x"),
            "tau_F": (tau_f, "s", "delay of the force pulse after tau_H"),
        },
        resolve_params(params),
        settings,
        {"t_ref_s": t_ref},
    )
