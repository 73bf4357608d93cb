"""Speed against accuracy: a work-precision study of the integrators, and a model ladder.

* :func:`work_precision`: one seeded set of strokes drawn across the paper's parameter
  space, solved by every method over a sweep of tolerances (adaptive methods) or steps
  (fixed-step RK4); error = largest |v_out - reference| (km/h) against the compiled
  DOP853 at rtol = atol = 1e-13, cost = microseconds per stroke (median of repeats, one
  thread) and right-hand-side evaluations per stroke.
* :func:`fixed_step_stroke`: the classical fixed-step RK4 through the same phases, with
  events found by a sign change between steps (linear interpolation): it misses a contact
  shorter than its step, which the stability study shows.
* :func:`impact_model`: the cheapest rung of the model ladder, an instantaneous elastic
  impact with the racket's effective mass at the hitting point (no spring phase).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr
from scipy.integrate import solve_ivp

from ..experiments.maps import mass_length_map
from ..io import provenance
from ..model.dynamics import (
    A_BALL_S,
    A_BALL_W,
    A_OMEGA1,
    A_OMEGA2,
    A_PHI,
    A_THETA,
    CF_L1,
    CF_LEAD,
    CF_LH,
    CF_MB,
    CF_PHI0,
    CF_THETA0,
    CF_VBALL,
    approach_rate,
    coefficients,
    contact_duration,
    effective_mass,
    elbow_velocity,
    hit_offset,
    mechanical_energy,
    rhs_angles,
)
from ..model.params import resolve_params
from ..solver._kernels import coefficient_tuple
from ..solver.integrate import HISTORY_COLS, METHOD_IDS, N_STATS
from ..solver.reference import solve_stroke
from ..solver.stroke import (
    MS_TO_KMH,
    S_CONTACT_STEPS,
    SolverSettings,
    next_switch,
    run_phases,
    strike_batch,
    wrist_torque,
)

#: Parameter space of the sampled strokes (uniform ranges).
STROKE_SPACE = {
    "theta0": (60.0, 120.0),
    "delta0": (0.0, 90.0),
    "L1": (0.25, 0.45),
    "M2": (0.2, 0.45),
    "C2": (0.0, 8.0),
    "tau": (0.0, 0.2),
}
REFERENCE = SolverSettings(rtol=1e-13, atol=1e-13, history=8192)
#: Strokes per timed batch of the compiled solver.
TIMING_STROKES = 4000
#: Attribute of variables that hold wall-clock measurements (the only numbers of a result
#: file that differ between two runs of the same configuration).
TIMING = {"timing": "wall-clock measurement: differs between runs"}


def sample_strokes(n: int, seed: int = 20261121) -> dict[str, np.ndarray]:
    """``n`` strokes drawn uniformly from :data:`STROKE_SPACE` (seeded), all ``ok``."""
    rng = np.random.default_rng(seed)
    out = {k: [] for k in STROKE_SPACE}
    while len(out["theta0"]) < n:
        draw = {k: rng.uniform(*r) for k, r in STROKE_SPACE.items()}
        res = strike_batch(
            draw["theta0"],
            draw["delta0"],
            {k: draw[k] for k in ("L1", "M2", "C2", "tau")},
            REFERENCE,
        )
        if res["status"] == 0:
            for k in out:
                out[k].append(draw[k])
    return {k: np.array(v) for k, v in out.items()}


def _rk4(fun, t, y, h):
    k1 = fun(t, y)
    k2 = fun(t + h / 2, y + h / 2 * k1)
    k3 = fun(t + h / 2, y + h / 2 * k2)
    k4 = fun(t + h, y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def _fixed_phase(cf, t, y, t_stop, h, contact, event):
    """RK4 with step ``h`` through the torque switches until ``event`` changes sign.

    Returns ``(t, y, hit, evaluations)``; the event state is interpolated linearly.
    """
    evals = 0
    while t < t_stop:
        t_seg = next_switch(t, cf, t_stop)
        c2 = wrist_torque(t, t_seg, cf)

        def fun(tt, yy, c2=c2):
            d = np.empty_like(yy)
            rhs_angles(tt, yy, cf, c2, contact, d)
            return d

        while t < t_seg:
            step = min(h, t_seg - t)
            y_new = _rk4(fun, t, y, step)
            evals += 4
            g0, g1 = event(y), event(y_new)
            if g0 > 0.0 >= g1:
                x = g0 / (g0 - g1)
                return t + x * step, y + x * (y_new - y), True, evals
            t, y = t + step, y_new
    return t, y, False, evals


def fixed_step_stroke(
    theta0_deg: float, delta0_deg: float, params: Mapping[str, object], h: float, t_max: float = 1.0
) -> dict[str, float]:
    """One stroke with fixed-step RK4 (step ``h``, s): ``status`` (``ok``,
    ``missed_contact``, ``no_phi_zero``, ``no_approach``, ``non_finite``), ``v_out_kmh``
    and ``rhs_evals``.

    The contact state at ``t_c`` is the RK4 state of the step before, advanced by one
    step of the remaining size.
    """
    cf = coefficients(resolve_params(params), theta0_deg, delta0_deg)[0]
    out = {"status": "ok", "v_out_kmh": math.nan, "rhs_evals": 0}
    y0 = np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    t0, y, hit, evals = _fixed_phase(cf, 0.0, y0, t_max, h, False, lambda y: y[A_PHI])
    out["rhs_evals"] += evals
    if not hit:
        out["status"] = "no_phi_zero" if np.all(np.isfinite(y)) else "non_finite"
        return out
    t_c = t0 - cf[CF_LEAD]
    _, yc, _, evals = _fixed_phase(cf, 0.0, y0, t_c, h, False, lambda y: 1.0)
    out["rhs_evals"] += evals
    st, sp = math.sin(yc[A_THETA]), math.sin(yc[A_PHI])
    ct, cp = math.cos(yc[A_THETA]), math.cos(yc[A_PHI])
    w = cf[CF_VBALL] - elbow_velocity(t_c, cf)[0]
    if approach_rate(st, ct, sp, cp, yc[A_OMEGA1], yc[A_OMEGA2], w, cf) <= 0.0:
        out["status"] = "no_approach"
        return out
    y = np.array([*yc, hit_offset(st, sp, cf), w])

    def compression(yy):
        return yy[A_BALL_S] - hit_offset(math.sin(yy[A_THETA]), math.sin(yy[A_PHI]), cf)

    # A step longer than the contact jumps over it: the compression is negative again at
    # the first step's end, so the event fires at once with a wrong ball speed.
    first = _rk4(lambda tt, yy: _angles_rhs(cf, tt, yy), t_c, y, h)
    if compression(first) <= 0.0:
        out["status"] = "missed_contact"
        out["rhs_evals"] += 4
        return out
    t_s, y, hit, evals = _fixed_phase(cf, t_c, y, t_max, h, True, compression)
    out["rhs_evals"] += evals
    if not hit or not np.all(np.isfinite(y)):
        out["status"] = "non_finite" if not np.all(np.isfinite(y)) else "no_release"
        return out
    out["v_out_kmh"] = -MS_TO_KMH * (y[A_BALL_W] + elbow_velocity(t_s, cf)[0])
    return out


def _angles_rhs(cf, t, y):
    d = np.empty_like(y)
    rhs_angles(t, y, cf, wrist_torque(t, t, cf), True, d)
    return d


def impact_model(
    theta0: np.ndarray,
    delta0: np.ndarray,
    params: Mapping[str, object],
    settings: SolverSettings | None = None,
) -> np.ndarray:
    """v_out (km/h) of an instantaneous elastic impact at ``phi = 0`` (the paper's ``t0``).

    The racket is replaced by its effective mass ``m`` at the hitting point (from the
    inertia matrix) moving with the hitting point's velocity ``v_H`` along x; the ball
    leaves with ``((m_b - m) v_b + 2 m v_H) / (m_b + m)``.  Only the swing is needed.
    """
    res = strike_batch(theta0, delta0, params, settings)
    shape = res["status"].shape
    theta = np.radians(res["theta_deg_at_phi0"]).ravel()
    w1, w2, t0 = (res[k].ravel() for k in ("omega1_phi0", "omega2_phi0", "t_phi0"))
    cf_rows = coefficients(resolve_params(params), theta0, delta0)
    v = np.full(theta.shape, np.nan)
    for i, cf in enumerate(cf_rows):
        if res["status"].ravel()[i] != 0:
            continue
        st, ct = math.sin(theta[i]), math.cos(theta[i])
        m = effective_mass(st, ct, 0.0, 1.0, cf)
        v_hit = elbow_velocity(t0[i], cf)[0] - cf[CF_L1] * w1[i] * ct - cf[CF_LH] * w2[i]
        mb = cf[CF_MB]
        v[i] = -MS_TO_KMH * ((mb - m) * cf[CF_VBALL] + 2.0 * m * v_hit) / (mb + m)
    return v.reshape(shape)


def _time(fn, repeats: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return float(np.median(times)), out


def work_precision(
    strokes: Mapping[str, np.ndarray],
    compiled_tols: Sequence[float],
    scipy_tols: Sequence[float],
    rk4_steps: Sequence[float],
    scipy_methods: Sequence[str] = ("RK45", "DOP853", "LSODA", "Radau"),
    repeats: int = 3,
) -> xr.Dataset:
    """The work-precision table: dims ``method`` x ``setting``.

    ``setting`` is the tolerance (rtol = atol) of adaptive methods and the step (s) of
    fixed-step RK4; absent combinations are NaN.
    """
    params = {k: strokes[k] for k in ("L1", "M2", "C2", "tau")}
    th, de = strokes["theta0"], strokes["delta0"]
    n = th.size
    ref = strike_batch(th, de, params, REFERENCE)["v_out_kmh"]
    methods = [
        "tennis_stroke.DP54",
        "tennis_stroke.DOP853",
        *(f"scipy.{m}" for m in scipy_methods),
        "fixed.RK4",
    ]
    settings_axis = sorted({*compiled_tols, *scipy_tols, *rk4_steps}, reverse=True)
    shape = (len(methods), len(settings_axis))
    err, cost, evals, failed = (np.full(shape, np.nan) for _ in range(4))
    for mi, method in enumerate(methods):
        family, name = method.split(".")
        values = {"tennis_stroke": compiled_tols, "scipy": scipy_tols, "fixed": rk4_steps}[family]
        for value in values:
            si = settings_axis.index(value)
            if family == "tennis_stroke":
                st = SolverSettings(method=name, rtol=value, atol=value)
                res = strike_batch(th, de, params, st, threads=1)
                v, nfev, ok = res["v_out_kmh"], res["rhs_evals"], res["status"] == 0
                # timed on the strokes repeated to TIMING_STROKES, so that the batch's
                # fixed cost (thread start, ~1 ms) does not count per stroke
                reps = max(1, TIMING_STROKES // n)
                big = {k: np.tile(val, reps) for k, val in params.items()}
                th_big, de_big = np.tile(th, reps), np.tile(de, reps)
                wall, _ = _time(
                    lambda st=st, a=th_big, b=de_big, p=big: strike_batch(a, b, p, st, threads=1),
                    repeats,
                )
                cost[mi, si] = wall / th_big.size * 1e6
            else:
                per, v, nfev, ok = [], np.full(n, np.nan), np.zeros(n), np.zeros(n, bool)
                for i in range(n):
                    p = {k: float(params[k][i]) for k in params}
                    start = time.perf_counter()
                    if family == "scipy":
                        r = solve_stroke(
                            th[i], de[i], p, method=name, rtol=value, atol=value
                        ).result
                        ok[i] = r["status"] == 0
                    else:
                        r = fixed_step_stroke(th[i], de[i], p, value)
                        ok[i] = r["status"] == "ok"
                    per.append(time.perf_counter() - start)
                    v[i], nfev[i] = r["v_out_kmh"], r["rhs_evals"]
                cost[mi, si] = float(np.median(per)) * 1e6
            failed[mi, si] = float(np.sum(~ok))
            err[mi, si] = float(np.nanmax(np.abs(v - ref))) if ok.any() else np.nan
            evals[mi, si] = float(np.mean(nfev))
    coords = {
        "method": ("method", methods, {"units": "1", "long_name": "integrator"}),
        "setting": (
            "setting",
            np.array(settings_axis),
            {"units": "1", "long_name": "tolerance rtol = atol, or RK4 step (s)"},
        ),
    }
    dims = ("method", "setting")
    ds = xr.Dataset(
        {
            "error_kmh": (dims, err, {"units": "km/h", "long_name": "largest |v_out error|"}),
            "us_per_stroke": (
                dims,
                cost,
                {"units": "us", "long_name": "cost per stroke, one thread", **TIMING},
            ),
            "rhs_evals": (dims, evals, {"units": "1", "long_name": "evaluations per stroke"}),
            "failed": (dims, failed, {"units": "1", "long_name": "strokes without status ok"}),
        },
        coords=coords,
        attrs={"strokes": n, "reference": "compiled DOP853, rtol = atol = 1e-13"},
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    ds.attrs["solver_settings_of"] = "the reference; each method's settings are the setting axis"
    return ds


# --- Stability where methods fail -------------------------------------------------------

#: Outcomes of the isolated-contact test, as stored (``flag_values``/``flag_meanings``).
OUTCOMES = ("ok", "inaccurate", "missed_contact", "energy_created", "blow_up", "event_error")
#: Relative energy change above which a run "created energy".
ENERGY_TOLERANCE = 1e-3
#: Exit-speed error (m/s) above which a run is "inaccurate".
SPEED_TOLERANCE = 1e-3
_STILL = {"C1": 0.0, "C2": 0.0, "vx_t1": 0.0, "vx_t2": 0.0, "vy_t1": 0.0, "vy_t2": 0.0}
_THETA, _PHI, _BALL_SPEED = -0.15, 0.05, 5.0


def _isolated_start(k: float):
    """Coefficients and the angle-layout state of the isolated contact at stiffness ``k``.

    The pendulum is at rest (no torques, elbow still) with the ball arriving at 5 m/s: its
    energy is conserved exactly, whatever ``k``, so energy changes are numerical.
    """
    cf = coefficients(resolve_params({**_STILL, "k_contact": k}), 0.0, 0.0)[0]
    y = np.array(
        [_THETA, _PHI, 0.0, 0.0, hit_offset(math.sin(_THETA), math.sin(_PHI), cf), _BALL_SPEED]
    )
    return cf, y


def isolated_contact(method: str, setting: float, k: float, t_end: float = 0.5) -> dict[str, float]:
    """Run the isolated contact with ``method`` (``tennis_stroke.X``, ``tennis_stroke.X
    (no step limit)``, ``scipy.X`` or ``fixed.RK4``) at tolerance or step ``setting``.

    Returns ``outcome`` (index into :data:`OUTCOMES`), ``v_exit`` (m/s), ``duration``
    (s), ``energy_change`` (relative), ``expected_duration`` (s, two-body closed form).
    """
    cf, y0 = _isolated_start(k)
    trig = (math.sin(_THETA), math.cos(_THETA), math.sin(_PHI), math.cos(_PHI))
    m = effective_mass(*trig, cf)
    expected = contact_duration(*trig, cf)
    e0 = mechanical_energy(0.0, y0, cf, True)
    family, name = method.split(".", 1)
    duration, y, failed, missed = math.nan, None, False, False
    if family == "tennis_stroke":
        base = name.split(" ")[0]
        limit = "no step limit" not in name
        st = SolverSettings(method=base, rtol=setting, atol=setting).as_array()
        if not limit:
            st[S_CONTACT_STEPS] = 1e-9
        h_max = expected / st[S_CONTACT_STEPS]
        yt = (
            math.sin(_THETA),
            math.cos(_THETA),
            math.sin(_PHI),
            math.cos(_PHI),
            0.0,
            0.0,
            _THETA,
            _PHI,
            y0[4],
            y0[5],
        )
        status, t, yt, _ = run_phases(
            METHOD_IDS[base],
            True,
            0.0,
            yt,
            t_end,
            min(0.01, h_max),
            h_max,
            coefficient_tuple(cf),
            True,
            st,
            np.zeros(N_STATS),
            np.zeros((1, HISTORY_COLS)),
        )
        failed = status != 1
        duration = t
        y = np.array([yt[6], yt[7], yt[4], yt[5], yt[8], yt[9]])
    elif family == "scipy":

        def sep(t, yy):
            return yy[A_BALL_S] - hit_offset(math.sin(yy[A_THETA]), math.sin(yy[A_PHI]), cf)

        sep.terminal, sep.direction = True, -1

        def fun(t, yy):
            d = np.empty_like(yy)
            rhs_angles(t, yy, cf, 0.0, True, d)
            return d

        sol = solve_ivp(fun, (0.0, t_end), y0, method=name, rtol=setting, atol=setting, events=sep)
        failed = sol.status != 1
        if not failed:
            duration, y = float(sol.t_events[0][0]), sol.y_events[0][0]
        elif sol.status == 0:
            duration, y = float(sol.t[-1]), sol.y[:, -1]
    else:

        def compression(yy):
            return yy[A_BALL_S] - hit_offset(math.sin(yy[A_THETA]), math.sin(yy[A_PHI]), cf)

        first = _rk4(lambda t, yy: _angles_rhs(cf, t, yy), 0.0, y0, setting)
        if np.all(np.isfinite(first)) and compression(first) <= 0.0:
            duration, y, missed = setting, first, True  # one step jumped over the contact
        else:
            duration, y, hit, _ = _fixed_phase(cf, 0.0, y0, t_end, setting, True, compression)
            failed = not hit
    out = {
        "expected_duration": expected,
        "duration": duration,
        "v_exit": math.nan,
        "energy_change": math.nan,
    }
    v_ref = (cf[CF_MB] - m) / (cf[CF_MB] + m) * _BALL_SPEED
    if y is not None and np.all(np.isfinite(y)):
        out["v_exit"] = float(y[A_BALL_W])
        out["energy_change"] = float(mechanical_energy(duration, y, cf, True) / e0 - 1.0)
    if y is None or not np.all(np.isfinite(y)) or abs(out["energy_change"]) > 10.0:
        outcome = "blow_up" if y is not None else "event_error"
    elif missed or (np.isfinite(duration) and duration < 0.1 * expected):
        outcome = "missed_contact"
    elif failed:
        outcome = "event_error"
    elif out["energy_change"] > ENERGY_TOLERANCE:
        outcome = "energy_created"
    elif abs(out["v_exit"] - v_ref) > SPEED_TOLERANCE + 0.05 * abs(v_ref) * math.sqrt(
        expected / 0.005
    ):
        outcome = "inaccurate"
    else:
        outcome = "ok"
    out["outcome"] = OUTCOMES.index(outcome)
    return out


def stability_map(cases: Sequence[tuple[str, float]], k_values: np.ndarray) -> xr.Dataset:
    """Outcome of the isolated contact for each (method, setting) case and stiffness ``k``."""
    labels = [f"{m} @ {v:g}" for m, v in cases]
    shape = (len(cases), len(k_values))
    fields = {
        key: np.full(shape, np.nan)
        for key in ("outcome", "v_exit", "duration", "energy_change", "expected_duration")
    }
    for i, (method, setting) in enumerate(cases):
        for j, k in enumerate(k_values):
            for key, value in isolated_contact(method, setting, float(k)).items():
                fields[key][i, j] = value
    meta = {
        "outcome": ("1", "outcome code (see flag_meanings)"),
        "v_exit": ("m/s", "ball velocity after separation (lab frame, along x)"),
        "duration": ("s", "contact duration"),
        "energy_change": ("1", "relative change of the mechanical energy"),
        "expected_duration": ("s", "two-body contact duration pi sqrt(mu/k)"),
    }
    dims = ("case", "k_contact")
    ds = xr.Dataset(
        {
            key: (dims, fields[key], {"units": meta[key][0], "long_name": meta[key][1]})
            for key in fields
        },
        coords={
            "case": ("case", labels, {"units": "1", "long_name": "method @ setting"}),
            "k_contact": (
                "k_contact",
                np.asarray(k_values, dtype=float),
                {"units": "N/m", "long_name": "spring constant"},
            ),
        },
    )
    ds["outcome"].attrs["flag_values"] = np.arange(len(OUTCOMES))
    ds["outcome"].attrs["flag_meanings"] = " ".join(OUTCOMES)
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    return ds


def ladder(strokes: Mapping[str, np.ndarray], repeats: int = 3) -> xr.Dataset:
    """Model ladder: v_out of the spring contact (the paper) and of the instantaneous
    impact at ``phi = 0`` on the same strokes, with their costs (µs per stroke)."""
    params = {k: strokes[k] for k in ("L1", "M2", "C2", "tau")}
    th, de = strokes["theta0"], strokes["delta0"]
    reps = max(1, TIMING_STROKES // th.size)
    big = {k: np.tile(v, reps) for k, v in params.items()}
    tb, db = np.tile(th, reps), np.tile(de, reps)
    t_spring, spring = _time(lambda: strike_batch(tb, db, big, threads=1), repeats)
    t_impact, impact = _time(lambda: impact_model(th, de, params), 1)
    ds = xr.Dataset(
        {
            "v_out_spring": (
                "stroke",
                spring["v_out_kmh"][: th.size],
                {"units": "km/h", "long_name": "v_out, spring contact (paper)"},
            ),
            "v_out_impact": (
                "stroke",
                impact,
                {"units": "km/h", "long_name": "v_out, instantaneous impact at phi=0"},
            ),
        },
        coords={"stroke": ("stroke", np.arange(th.size), {"units": "1", "long_name": "stroke"})},
        attrs={
            "us_per_stroke_spring": t_spring / tb.size * 1e6,
            "us_per_stroke_impact_python": t_impact / th.size * 1e6,
            "max_error_impact_kmh": float(
                np.nanmax(np.abs(impact - spring["v_out_kmh"][: th.size]))
            ),
        },
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    return ds


def optimum_cost(
    m2: Sequence[float],
    l1: Sequence[float],
    steps: Sequence[tuple[float, float]],
    reference_step: float = 0.05,
    theta0_range=(60.0, 120.0),
    delta0_range=(0.0, 100.0),
) -> xr.Dataset:
    """Accuracy of the nested optimum of Figs. 5-6 against its cost.

    For each ``(coarse, fine)`` step pair the optimum at every ``(M2, L1)`` point is found
    as in :func:`tennis_stroke.experiments.maps.mass_length_map`; the reference is the same
    search with a ``reference_step`` fine grid around a 1-degree coarse one.  Errors are the
    largest over the points.
    """
    settings = SolverSettings()
    m2, l1 = np.asarray(m2, float), np.asarray(l1, float)
    ref = mass_length_map(m2, l1, 1.0, reference_step, theta0_range, delta0_range, {}, settings)
    rows = {k: [] for k in ("v_err", "theta0_err", "delta0_err", "seconds")}
    for coarse, fine in steps:
        start = time.perf_counter()
        ds = mass_length_map(m2, l1, coarse, fine, theta0_range, delta0_range, {}, settings)
        rows["seconds"].append(time.perf_counter() - start)
        rows["v_err"].append(float(np.nanmax(np.abs(ds["v_out_best"] - ref["v_out_best"]))))
        rows["theta0_err"].append(float(np.nanmax(np.abs(ds["theta0_best"] - ref["theta0_best"]))))
        rows["delta0_err"].append(float(np.nanmax(np.abs(ds["delta0_best"] - ref["delta0_best"]))))
    labels = [f"coarse {c:g} deg, fine {f:g} deg" for c, f in steps]
    meta = {
        "v_err": ("km/h", "largest error of the best v_out"),
        "theta0_err": ("degree", "largest error of the best theta0"),
        "delta0_err": ("degree", "largest error of the best delta0"),
        "seconds": ("s", "wall time of the search over all points (all threads)"),
    }
    ds = xr.Dataset(
        {
            k: (
                "search",
                np.array(v),
                {
                    "units": meta[k][0],
                    "long_name": meta[k][1],
                    **(TIMING if k == "seconds" else {}),
                },
            )
            for k, v in rows.items()
        },
        coords={"search": ("search", labels, {"units": "1", "long_name": "steps"})},
        attrs={"points": m2.size * l1.size, "reference_fine_step_deg": reference_step},
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    return ds
