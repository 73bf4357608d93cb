"""The state along a stroke at fixed times, by every family of integrators: the "state"
error of the work-precision study, an L2 over fixed times (DiffEqDevTools' ``:L2``).

The state at a time is that of the method's own stroke, the one whose ``v_out`` and
event times the study measures: the swing until the method's own contact start ``t_c``,
then (the spring contact) the contact from there, the ball put at the hitting point.
scipy's methods and fixed-step RK4 are read on the solve that gave the stroke's result,
so the state costs no second solve.  scipy's methods are read on their dense output
(:func:`segment_omegas`; a time after the method's own separation, the reference's last
where the method separated first, on its last step's interpolant carried on).  The
other families give none: each time is the end of a run of its own from its phase's
start (the swing from rest, the contact from the method's state at its own ``t_c``),
so no stop shortens the steps before another time (stopping one run at every time would
cap its steps at the times' spacing and flatter a loose tolerance).  Fixed-step RK4
starts that run from the stroke's last step before the time, where a run from the
phase's start would be (:func:`path_omegas`: one step, not a solve); the compiled
integrators run each from the phase's start (:func:`compiled_omegas`).  The state is
the rods' angular velocities ``omega1, omega2`` (rad/s): the angles are their
integrals, and ``v_out`` is made from them.

The contact starts at the method's own ``t_c``, so the error of its contact start
enters the state error too.  Until 2026-12-07 every stroke was solved a second time for
its state, its contact from the reference's ``t_c`` and each phase ended at the
reference's (a last step cut short there); reading the one solve moved the medians over
the strokes by a factor 0.91-1.35 (scipy), 0.99-1.07 (compiled) and 1.00-1.02 (RK4), the
worst strokes by at most 2 (``docs/changes.md``, 2026-12-07).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
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
from ..solver.rk4 import fixed_phase
from ..solver.settings import METHOD_IDS, SolverSettings
from ..solver.stroke import exercise_contact, run_phases


def probe_times(t_end: float, n: int) -> np.ndarray:
    """``n`` times (s) evenly spread over ``(0, t_end]``."""
    return t_end * np.arange(1, n + 1) / n


def segment_omegas(segments: Sequence, times: np.ndarray) -> np.ndarray:
    """``omega1, omega2`` (rad/s) at ``times`` (s, increasing), shape ``(len(times), 2)``,
    of scipy's stroke (``segments``: those of a
    :class:`~tennis_stroke.solver.reference.ReferenceStroke`): each time on the dense
    output of the last segment that starts by then (at a phase boundary the later
    phase's, as :meth:`~tennis_stroke.solver.reference.ReferenceStroke.states`)."""
    times = np.asarray(times, dtype=float)
    which = np.searchsorted([seg.t0 for seg in segments], times, side="right") - 1
    out = np.full((times.size, 2), np.nan)
    for k in np.unique(which[which >= 0]):
        at = which == k
        out[at] = segments[k].sol(times[at])[[A_OMEGA1, A_OMEGA2]].T
    return out


def path_omegas(path: Sequence, cf: np.ndarray, h: float, times: np.ndarray) -> np.ndarray:
    """``omega1, omega2`` (rad/s) at ``times`` (s, increasing), shape ``(len(times), 2)``,
    of fixed-step RK4's stroke (step ``h``, s; coefficients ``cf``): each the end of a run
    of its own from the last step of ``path`` that starts before it (the step starts
    :func:`~tennis_stroke.solver.rk4.fixed_step_stroke` records, phase by phase), which
    is the end of a run from the phase's start, bit for bit.  Its few steps (one, before
    the method's separation) are the probe's evaluations, not the stroke's.  NaN where
    the state is not finite."""
    times = np.asarray(times, dtype=float)
    starts = np.concatenate([phase[0] for phase in path])
    which = np.searchsorted(starts, times, side="left") - 1
    first = np.cumsum([0] + [phase[0].size for phase in path])  # each phase's first step
    out = np.full((times.size, 2), np.nan)
    for i in np.flatnonzero(which >= 0):
        k = int(np.searchsorted(first, which[i], side="right")) - 1
        step_times, states, contact = path[k]
        row = which[i] - first[k]
        at = fixed_phase(cf, step_times[row], states[row], times[i], h, contact)[1]
        out[i] = at[[A_OMEGA1, A_OMEGA2]]
    out[~np.isfinite(out).all(axis=1)] = np.nan
    return out


def compiled_omegas(
    name: str,
    tol: float,
    stroke: tuple[float, float, Mapping[str, object]],
    t_contact: float,
    times: np.ndarray,
    spring: bool = True,
) -> np.ndarray:
    """``omega1, omega2`` (rad/s) of ``stroke = (theta0, delta0, params)`` at ``times``
    (s, increasing), shape ``(len(times), 2)``, by the compiled method ``name`` at
    rtol = atol = ``tol``: the swing until ``t_contact`` (s, the method's own contact
    start), then, with ``spring``, the contact from there.  NaN where the method failed."""
    theta0, delta0, params = stroke
    cf = coefficients(resolve_params(params), theta0, delta0)[0]
    times = np.asarray(times, dtype=float)
    split = int(np.searchsorted(times, t_contact, side="right")) if spring else times.size
    return _compiled(name, tol, cf, t_contact, times[:split], times[split:])


def _ball_on(cf, t_c: float, y: np.ndarray) -> tuple[np.ndarray, float]:
    """The angle-layout state ``y`` at the contact start with the ball at the hitting
    point, and the contact's step cap (half the two-body contact time, as the strokes)."""
    trig = to_trig(y)
    s, w = incoming_ball(t_c, trig[SIN_TH], trig[SIN_PH], cf)
    cap = contact_duration(trig[SIN_TH], trig[COS_TH], trig[SIN_PH], trig[COS_PH], cf)
    return np.array([*y[:4], s, w]), cap / SolverSettings.contact_min_steps


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
