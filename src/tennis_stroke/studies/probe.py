"""The state along a stroke at fixed times, by every family of integrators: the "state"
error of the work-precision study, an L2 over fixed times (DiffEqDevTools' ``:L2``).

Every method follows the stroke in the same two pieces: the swing from rest to the
reference's contact start ``t_c``, then (the spring contact only) the contact from the
method's own state there, the ball put at the hitting point, to the last time.  The
event times are measured on their own (:mod:`tennis_stroke.studies.work_precision`), so
this error is the integration's alone, not a shifted event's.  scipy's methods are read
on their dense output.  The compiled integrators give none to Python: each time is the
end of a run of its own from its phase's start (stopping one run at every time would
cap its steps at the times' spacing and flatter a loose tolerance).  Fixed-step RK4
stops at each time (its steps do not grow; only the one before a time is shortened).
The state is the rods' angular velocities ``omega1, omega2`` (rad/s): the angles are
their integrals, and ``v_out`` is made from them.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import partial

import numpy as np

from ..model.dynamics import (
    A_OMEGA1,
    A_OMEGA2,
    CF_PHI0,
    CF_THETA0,
    COS_PH,
    COS_TH,
    OMEGA1,
    OMEGA2,
    PHI,
    SIN_PH,
    SIN_TH,
    THETA,
    coefficients,
    contact_duration,
    incoming_ball,
    to_trig,
)
from ..model.params import resolve_params
from ..solver._kernels import coefficient_tuple
from ..solver.compiled import ensure_compiled
from ..solver.integrate import HISTORY_COLS, N_STATS, PHASE_FAIL, specialised
from ..solver.reference import dense_phase
from ..solver.rk4 import fixed_phase
from ..solver.settings import METHOD_IDS, SolverSettings
from ..solver.stroke import exercise_contact, run_phases
from .methods import parse_method


def probe_times(t_end: float, n: int) -> np.ndarray:
    """``n`` times (s) evenly spread over ``(0, t_end]``."""
    return t_end * np.arange(1, n + 1) / n


def omegas_at(
    method: str,
    setting: float,
    stroke: tuple[float, float, Mapping[str, object]],
    t_contact: float,
    times: np.ndarray,
    spring: bool = True,
) -> np.ndarray:
    """``omega1, omega2`` (rad/s) of ``stroke = (theta0, delta0, params)`` at ``times``
    (s, increasing), shape ``(len(times), 2)``, by ``method`` (``family.NAME``) at its
    tolerance or step ``setting``: the swing to ``t_contact`` (s), then, with ``spring``,
    the contact from there.  NaN where the method failed."""
    family, name = parse_method(method)
    theta0, delta0, params = stroke
    cf = coefficients(resolve_params(params), theta0, delta0)[0]
    times = np.asarray(times, dtype=float)
    split = int(np.searchsorted(times, t_contact, side="right")) if spring else times.size
    run = {"tennis_stroke": _compiled, "scipy": _scipy, "fixed": _rk4}[family]
    return run(name, setting, cf, t_contact, times[:split], times[split:])


def _ball_on(cf, t_c: float, y: np.ndarray) -> tuple[np.ndarray, float]:
    """The angle-layout state ``y`` at the contact start with the ball at the hitting
    point, and the contact's step cap (half the two-body contact time, as the strokes)."""
    trig = to_trig(y)
    s, w = incoming_ball(t_c, trig[SIN_TH], trig[SIN_PH], cf)
    cap = contact_duration(trig[SIN_TH], trig[COS_TH], trig[SIN_PH], trig[COS_PH], cf)
    return np.array([*y[:4], s, w]), cap / SolverSettings.contact_min_steps


def _scipy(name, rtol, cf, t_c, swing_t, contact_t) -> np.ndarray:
    out = np.full((swing_t.size + contact_t.size, 2), np.nan)
    y0 = np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    end = t_c if contact_t.size else swing_t[-1]
    dense, y, ok = dense_phase(cf, 0.0, y0, end, False, name, rtol, rtol)
    if not ok:
        return out
    sampled = dense.sample(swing_t)
    out[: swing_t.size] = np.column_stack([sampled["omega1"], sampled["omega2"]])
    if contact_t.size:
        y, cap = _ball_on(cf, t_c, y)
        dense, _, ok = dense_phase(cf, t_c, y, contact_t[-1], True, name, rtol, rtol, cap)
        if ok:
            sampled = dense.sample(contact_t)
            out[swing_t.size :] = np.column_stack([sampled["omega1"], sampled["omega2"]])
    return out


def _rk4(_, h, cf, t_c, swing_t, contact_t) -> np.ndarray:
    out = []
    t, y = 0.0, np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    for time in swing_t:
        t, y, _, _ = fixed_phase(cf, t, y, time, h, False)
        out.append(y[[A_OMEGA1, A_OMEGA2]])
    if contact_t.size:
        if t < t_c:
            t, y, _, _ = fixed_phase(cf, t, y, t_c, h, False)
        y, _ = _ball_on(cf, t_c, y)
        for time in contact_t:
            t, y, _, _ = fixed_phase(cf, t, y, time, h, True)
            out.append(y[[A_OMEGA1, A_OMEGA2]])
    out = np.array(out, dtype=float).reshape(-1, 2)
    out[~np.isfinite(out).all(axis=1)] = np.nan
    return out


def _compiled(name, tol, cf, t_c, swing_t, contact_t) -> np.ndarray:
    """Each time is the end of a run of its own from its phase's start (the swing from
    rest, the contact from the swing's state at ``t_c``), so no stop shortens the steps
    before it: the state at each time is that of a free run ending there."""
    settings = SolverSettings(method=name, rtol=tol, atol=tol)
    ensure_compiled(f"contact:{name}", partial(exercise_contact, name))
    cft, st = coefficient_tuple(cf), settings.as_array()
    entry = []

    def run(contact: bool, t: float, y: tuple, t_stop: float, h: float, h_max: float):
        args = (contact, t, y, t_stop, h, h_max, cft, False, st)
        args += (np.zeros(N_STATS), np.zeros((1, HISTORY_COLS)))
        if not entry:
            entry.append(specialised(run_phases, METHOD_IDS[name], *args))
        status, _, y, h = entry[0](*args)
        return (None if status == PHASE_FAIL else y), h

    def omegas(y) -> tuple[float, float]:
        return (np.nan, np.nan) if y is None else (y[OMEGA1], y[OMEGA2])

    start = to_trig(np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0]))
    out = [omegas(run(False, 0.0, start, time, settings.first_step, np.inf)[0]) for time in swing_t]
    if contact_t.size:
        y, h = run(False, 0.0, start, t_c, settings.first_step, np.inf)
        if y is None:
            out += [(np.nan, np.nan)] * contact_t.size
        else:
            angles, cap = _ball_on(cf, t_c, np.array(y)[[THETA, PHI, OMEGA1, OMEGA2]])
            ball = to_trig(angles)
            out += [omegas(run(True, t_c, ball, time, min(h, cap), cap)[0]) for time in contact_t]
    return np.array(out, dtype=float).reshape(-1, 2)
