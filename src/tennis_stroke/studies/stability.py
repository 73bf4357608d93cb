"""Stability where methods fail: the isolated contact over the spring constant.

The pendulum at rest (no torques, elbow still) meets a ball at 5 m/s: the mechanical
energy is conserved exactly, whatever ``k``, so an energy change is numerical, and the
exit speed has a closed form (the two-body collision with the racket's effective mass).
Each (method, setting) case is run for every ``k``; the outcome is one of
:data:`OUTCOMES`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr
from scipy.integrate import solve_ivp

from ..io.netcdf import provenance
from ..io.units import cf_attrs
from ..model.dynamics import (
    A_BALL_W,
    CF_MB,
    angle_rhs,
    coefficients,
    compression_angles,
    contact_duration,
    effective_mass,
    hit_offset,
    mechanical_energy,
)
from ..model.params import resolve_params
from ..solver.rk4 import contact_missed, fixed_phase
from ..solver.settings import SolverSettings
from ..solver.stroke import solve_contact
from ..solver.warmup import ready
from .methods import check_case
from .sampling import REFERENCE

#: Outcomes of the isolated-contact test, as stored (``flag_values``/``flag_meanings``).
OUTCOMES = ("ok", "inaccurate", "missed_contact", "energy_created", "blow_up", "event_error")
#: Relative energy change above which a run "created energy".
ENERGY_TOLERANCE = 1e-3
#: Exit-speed error (m/s) above which a run is "inaccurate".
SPEED_TOLERANCE = 1e-3
#: What each outcome means (the file's ``outcome`` attribute ``outcome_meanings``, the
#: figure's legend; checked in this order, the first that applies).
OUTCOME_MEANINGS = {
    "blow_up": "the state overflowed, or the energy changed more than tenfold",
    "missed_contact": "a step jumped over the contact (or it lasted < 0.1 of its closed form)",
    "event_error": "no separation found",
    "energy_created": f"the energy grew by more than {ENERGY_TOLERANCE:g} (relative)",
    "inaccurate": "the exit speed is off the closed form (two-body collision)",
    "ok": "none of these",
}
#: The isolated contact: no torques, the elbow still, the rods at these angles (rad),
#: the ball arriving at this speed (m/s).
STILL = {"C1": 0.0, "C2": 0.0, "vx_t1": 0.0, "vx_t2": 0.0, "vy_t1": 0.0, "vy_t2": 0.0}
THETA, PHI, BALL_SPEED = -0.15, 0.05, 5.0
#: First trial step of the compiled integrator here (s).
FIRST_STEP = 0.01


def isolated_start(k: float) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients and the angle-layout start state of the isolated contact at stiffness
    ``k`` (N/m): the ball at the hitting point, closing in at :data:`BALL_SPEED`."""
    cf = coefficients(resolve_params({**STILL, "k_contact": k}), 0.0, 0.0)[0]
    s = hit_offset(math.sin(THETA), math.sin(PHI), cf)
    return cf, np.array([THETA, PHI, 0.0, 0.0, s, BALL_SPEED])


def isolated_contact(
    method: str, setting: float, k: float, t_end: float = 0.5, step_limit: bool = True
) -> dict[str, float]:
    """Run the isolated contact with ``method`` (``tennis_stroke.X``, ``scipy.X`` or
    ``fixed.RK4``, :func:`~tennis_stroke.studies.methods.parse_method`) at tolerance or
    step ``setting``; ``step_limit=False`` lifts the compiled solver's cap on contact
    steps (to show what it guards against).

    Returns ``outcome`` (index into :data:`OUTCOMES`), ``v_exit`` (m/s), ``duration``
    (s), ``energy_change`` (relative), ``expected_duration`` (s, two-body closed form).
    """
    family, name = check_case(method, setting)
    ready("rk4")  # the model functions called from Python below, from the cache
    cf, y0 = isolated_start(k)
    trig = (math.sin(THETA), math.cos(THETA), math.sin(PHI), math.cos(PHI))
    m = effective_mass(*trig, cf)
    expected = contact_duration(*trig, cf)
    e0 = mechanical_energy(0.0, y0, cf, True)
    duration, y, failed, missed = math.nan, None, False, False
    if family == "tennis_stroke":
        settings = SolverSettings(  # loose tolerances on purpose: no accuracy bound
            method=name,
            rtol=setting,
            atol=setting,
            first_step=FIRST_STEP,
            contact_min_steps=SolverSettings.contact_min_steps if step_limit else 1e-9,
            accuracy_bound=False,
        )
        separated, duration, y = solve_contact(cf, y0, t_end, settings)
        failed = not separated
    elif family == "scipy":

        def separation(t, yy):
            return compression_angles(yy, cf)

        separation.terminal, separation.direction = True, -1
        sol = solve_ivp(
            angle_rhs(cf, 0.0, True),
            (0.0, t_end),
            y0,
            method=name,
            rtol=setting,
            atol=setting,
            events=separation,
        )
        failed = sol.status != 1
        if not failed:
            duration, y = float(sol.t_events[0][0]), sol.y_events[0][0]
        elif sol.status == 0:  # scipy's code: t_end reached without the event
            duration, y = float(sol.t[-1]), sol.y[:, -1]
    else:
        missed, first, _ = contact_missed(cf, 0.0, y0, setting, t_end)
        if missed:  # one step jumped over the contact
            duration, y = setting, first
        else:
            duration, y, hit, _ = fixed_phase(cf, 0.0, y0, t_end, setting, True, compression_angles)
            failed = not hit
    out = {
        "expected_duration": expected,
        "duration": duration,
        "v_exit": math.nan,
        "energy_change": math.nan,
    }
    v_ref = (cf[CF_MB] - m) / (cf[CF_MB] + m) * BALL_SPEED
    if y is not None and np.all(np.isfinite(y)):
        out["v_exit"] = float(y[A_BALL_W])
        out["energy_change"] = float(mechanical_energy(duration, y, cf, True) / e0 - 1.0)
    out["outcome"] = OUTCOMES.index(_outcome(y, out, missed, failed, duration, expected, v_ref))
    return out


def _outcome(y, out, missed, failed, duration, expected, v_ref) -> str:
    """Which failure mode (or ``ok``) a run of :func:`isolated_contact` shows."""
    if y is None or not np.all(np.isfinite(y)) or abs(out["energy_change"]) > 10.0:
        return "blow_up" if y is not None else "event_error"
    if missed or (np.isfinite(duration) and duration < 0.1 * expected):
        return "missed_contact"
    if failed:
        return "event_error"
    if out["energy_change"] > ENERGY_TOLERANCE:
        return "energy_created"
    allowed = SPEED_TOLERANCE + 0.05 * abs(v_ref) * math.sqrt(expected / 0.005)
    if abs(out["v_exit"] - v_ref) > allowed:
        return "inaccurate"
    return "ok"


def stability_map(
    cases: Sequence[tuple[str, float]],
    k_values: np.ndarray,
    paper_k: Sequence[float] | None = None,
) -> xr.Dataset:
    """Outcome of the isolated contact for each (method, setting) case and stiffness ``k``;
    ``paper_k``, the paper's range of ``k`` (N/m, low and high), is kept as the attribute
    ``paper_k_contact`` for the figure's band."""
    for method, setting in cases:
        check_case(method, setting)
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
    dims = ("case", "k_contact")
    ds = xr.Dataset(
        {key: (dims, fields[key], cf_attrs(key)) for key in fields},
        coords={
            "case": ("case", labels, cf_attrs("case")),
            "k_contact": (
                "k_contact",
                np.asarray(k_values, dtype=float),
                cf_attrs("k_contact"),
            ),
        },
    )
    ds["outcome"].attrs["flag_values"] = np.arange(len(OUTCOMES))
    ds["outcome"].attrs["flag_meanings"] = " ".join(OUTCOMES)
    ds["outcome"].attrs["outcome_meanings"] = "; ".join(
        f"{k}: {OUTCOME_MEANINGS[k]}" for k in OUTCOMES
    )
    ds["setting"] = ("case", [float(v) for _, v in cases], cf_attrs("setting"))
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    if paper_k is not None:
        ds.attrs["paper_k_contact"] = [float(k) for k in paper_k]
    return ds


def stability_study(
    k_contact: Mapping[str, float],
    cases: Sequence[Sequence],
    paper_k: Sequence[float] | None = None,
) -> xr.Dataset:
    """The stability map from the config (``solver_study.stability``): ``k_contact`` as
    ``{start, stop, num}`` of log10 k (N/m), ``cases`` as ``[method, setting]`` pairs,
    ``paper_k`` the paper's range of k (``k_sensitivity.k_contact``)."""
    k = np.logspace(k_contact["start"], k_contact["stop"], k_contact["num"])
    return stability_map([(str(m), float(v)) for m, v in cases], k, paper_k)
