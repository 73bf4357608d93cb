"""The curves of single strokes over time (Figs. 4, 10-12, 14) from the compiled solver.

For many strokes at once (one call), the state ``theta, phi, omega1, omega2`` at given
sample times, either of the free swing without the ball (the paper's Sec. II) or of the
stroke with the ball (the swing until the contact start, the spring contact until
separation, then the free swing again; for the cheap rungs of the model ladder, the
instantaneous collision at ``phi = 0``), plus the elbow's position and the rods' kinetic
energy there (the model's :func:`~tennis_stroke.model.dynamics.elbow_position` and
:func:`~tennis_stroke.model.dynamics.mechanical_energy`, called per sample in compiled
code).

The integrator *stops at every sample time*: each sample ends a step (the step that
would cross it is shortened to land on it), so a sample is a step's end state, with the
method's global error and no interpolation error (DOP853's own dense output is of order
7, a cubic Hermite interpolant of the ring's steps of order 3 to 4; both would add their
error to the integration's).  The phases are those of the compiled stroke
(:mod:`tennis_stroke.solver.stroke`: the same events, restart at the contact start from
the swing's step history, contact step limit); the curves use tighter tolerances than
the stroke numbers (:data:`CURVE_TOLERANCE`).  ``tests/solver/test_curves.py`` compares
them with :func:`scipy.integrate.solve_ivp` (:mod:`tennis_stroke.solver.reference`) on
many strokes and readings; docs/solver.md gives the bound.

Which samples a stroke has follows the reference path's
(:meth:`~tennis_stroke.solver.reference.ReferenceStroke.sample`): NaN after a stroke
that ends before its contact (``phi = 0`` before the lead, the racket not closing in on
the ball: NaN after the contact start), at a phase boundary the later phase's value.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from numba import literally, njit

from ..model.dynamics import (
    CF_CONTACT_MODEL,
    CF_LEAD,
    CF_PHI0,
    CF_THETA0,
    COS_PH,
    COS_TH,
    JIT,
    JIT_INNER,
    OMEGA1,
    OMEGA2,
    PHI,
    SIN_PH,
    SIN_TH,
    SPRING,
    THETA,
    coefficients,
    contact_duration,
    elbow_position,
    mechanical_energy,
)
from ..model.impact import instant_contact
from ..model.params import resolve_params
from ._kernels import coefficient_tuple
from .compiled import ensure_compiled
from .integrate import (
    HISTORY_COLS,
    N_STATS,
    PHASE_END,
    PHASE_EVENT,
    ST_NFEV,
    flag,
    history_find,
    history_reset,
    specialised,
)
from .results import N_OUT
from .settings import METHOD_IDS, S_CONTACT_STEPS, S_FIRST_STEP, S_TMAX, SolverSettings
from .stroke import contact_start, restart_at, run_phases

#: The method of the curves (the reference path's, which drew them before): of order 8.
CURVE_METHOD = "DOP853"
#: Relative and absolute tolerance of the curves (the reference path's, which drew them
#: before): far tighter than the stroke numbers', at a cost of a few thousand
#: right-hand-side evaluations per stroke.
CURVE_TOLERANCE = 1e-10
#: Columns of a sample: the angle layout's ``theta, phi`` (rad), ``omega1, omega2``
#: (rad/s), then the elbow's ``x, y`` (m) and the rods' kinetic energy (J).
C_THETA, C_PHI, C_OMEGA1, C_OMEGA2, C_X_ELBOW, C_Y_ELBOW, C_ENERGY = range(7)
N_COLUMNS = 7
#: The curves' names by column, as :func:`stroke_curves` returns them.
COLUMNS = ("theta", "phi", "omega1", "omega2", "x_elbow", "y_elbow", "kinetic_energy")


@njit(inline="always", **JIT_INNER)
def _write(rows, k, y):
    """The state ``y`` (trig layout) into the sample row ``k``."""
    rows[k, C_THETA] = y[THETA]
    rows[k, C_PHI] = y[PHI]
    rows[k, C_OMEGA1] = y[OMEGA1]
    rows[k, C_OMEGA2] = y[OMEGA2]


@njit(**JIT_INNER)
def sample_phase(
    method, contact, t, y, h, h_max, t_stop, cf, event_on, st, stats, history, times, k, rows
):
    """Integrate one phase kind from ``(t, y)`` until its event or ``t_stop``, stopping
    at each sample time ``times[k:]`` on the way and writing the state there into
    ``rows``; a sample at the start ``t`` gets the start state.  Returns ``(status, t, y,
    h, k)``: the phase integrator's status, the time and state reached, the next step,
    and the first sample not written."""
    method = literally(method)
    n = times.shape[0]
    while True:
        if k < n and times[k] <= t:
            _write(rows, k, y)
            k += 1
            continue
        target = times[k] if k < n and times[k] < t_stop else t_stop
        status, t, y, h = run_phases(
            method, contact, t, y, target, h, h_max, cf, event_on, st, stats, history
        )
        if status != PHASE_END:
            return status, t, y, h, k
        if target == t_stop:
            if k < n and times[k] <= t:
                _write(rows, k, y)
                k += 1
            return status, t, y, h, k


@njit(inline="always", **JIT_INNER)
def _free_samples(method, t, y, h, t_stop, cf, st, stats, no_history, times, k, rows):
    """The free swing from ``(t, y)`` to ``t_stop``, no event, sampled from ``times[k]``."""
    free = flag(False)
    return sample_phase(
        method, free, t, y, h, np.inf, t_stop, cf, free, st, stats, no_history, times, k, rows
    )


@njit(inline="always", **JIT_INNER)
def _first_at_or_after(times, t):
    """Index of the first sample at or after ``t``."""
    k = 0
    while k < times.shape[0] and times[k] < t:
        k += 1
    return k


@njit(inline="always", **JIT_INNER)
def _forget_after(rows, times, t):
    """NaN for the states of the samples after ``t``."""
    for k in range(times.shape[0]):
        if times[k] > t:
            rows[k, C_THETA : C_OMEGA2 + 1] = np.nan


@njit(**JIT_INNER)
def stroke_samples(method, cf_row, times, with_ball, st, rows, history, stats, scratch):
    """One stroke's curves into ``rows`` (shape ``(len(times), N_COLUMNS)``): the free
    swing until ``times[-1]``, or ``with_ball`` the stroke's phases."""
    method = literally(method)
    cf = coefficient_tuple(cf_row)
    rows[:] = np.nan
    stats[:] = 0.0
    th0, ph0 = cf[CF_THETA0], cf[CF_PHI0]
    y = (math.sin(th0), math.cos(th0), math.sin(ph0), math.cos(ph0), 0.0, 0.0, th0, ph0, 0.0, 0.0)
    history_reset(history)
    h = st[S_FIRST_STEP]
    no_history = history[:1]
    if not with_ball:
        _free_samples(method, 0.0, y, h, times[-1], cf, st, stats, no_history, times, 0, rows)
    else:
        _with_ball(method, cf, y, h, times, st, rows, history, stats, scratch)
    for k in range(times.shape[0]):
        x_e, y_e = elbow_position(times[k], cf)
        rows[k, C_X_ELBOW] = x_e
        rows[k, C_Y_ELBOW] = y_e
        if not math.isnan(rows[k, C_THETA]):
            rows[k, C_ENERGY] = mechanical_energy(times[k], rows[k], cf, False)
    return stats[ST_NFEV]


@njit(inline="always", **JIT_INNER)
def _with_ball(method, cf, y, h, times, st, rows, history, stats, scratch):
    """The stroke with the ball (the phases of :func:`~tennis_stroke.solver.stroke.stroke_row`)
    sampled at ``times`` into ``rows``."""
    t_max, t_end = st[S_TMAX], times[-1]
    no_history = history[:1]
    status, t, y, h, _ = sample_phase(
        method,
        flag(False),
        0.0,
        y,
        h,
        np.inf,
        t_max,
        cf,
        flag(True),
        st,
        stats,
        history,
        times,
        0,
        rows,
    )
    if status != PHASE_EVENT:  # no phi = 0 before t_max, or a failed step
        return
    spring = cf[CF_CONTACT_MODEL] == SPRING
    t_c = t - cf[CF_LEAD] if spring else t
    row = history_find(history, t_c)
    if t_c < 0.0 or (spring and row < 0):
        return
    if spring:
        y = restart_at(method, t_c, history[row], cf, st, stats)
    approaches, s_ball, w = contact_start(t_c, y, cf, scratch)
    _forget_after(rows, times, t_c)  # the swing's samples after the contact start
    if not approaches:
        return
    k = _first_at_or_after(times, t_c)
    if spring:
        y = (
            y[SIN_TH],
            y[COS_TH],
            y[SIN_PH],
            y[COS_PH],
            y[OMEGA1],
            y[OMEGA2],
            y[THETA],
            y[PHI],
            s_ball,
            w,
        )
        h_max = (
            contact_duration(y[SIN_TH], y[COS_TH], y[SIN_PH], y[COS_PH], cf) / st[S_CONTACT_STEPS]
        )
        status, t, y, h, k = sample_phase(
            method,
            flag(True),
            t_c,
            y,
            min(h, h_max),
            h_max,
            t_max,
            cf,
            flag(True),
            st,
            stats,
            no_history,
            times,
            k,
            rows,
        )
        if status != PHASE_EVENT:  # no separation before t_max, or a failed step
            return
    else:
        _, w1, w2 = instant_contact(t, y, cf)
        y = (y[SIN_TH], y[COS_TH], y[SIN_PH], y[COS_PH], w1, w2, y[THETA], y[PHI], 0.0, 0.0)
    if t < t_end:
        _free_samples(method, t, y, h, t_end, cf, st, stats, no_history, times, k, rows)


@njit(nogil=True, **JIT)
def curve_rows(method, cf_rows, times, with_ball, st, out, nfev, history_capacity):
    """The curves of every stroke of ``cf_rows`` into ``out`` (shape ``(n, len(times),
    N_COLUMNS)``) and each stroke's right-hand-side evaluations into ``nfev``."""
    method = literally(method)  # compiled per method (solver/integrate.py)
    history = np.zeros((history_capacity + 1, HISTORY_COLS))
    stats = np.zeros(N_STATS)
    scratch = np.zeros(N_OUT)
    for i in range(cf_rows.shape[0]):
        nfev[i] = stroke_samples(
            method, cf_rows[i], times, with_ball, st, out[i], history, stats, scratch
        )


def curve_settings(settings: SolverSettings | None = None) -> SolverSettings:
    """The settings the curves are computed with: ``settings``' limits (``t_max``, the
    contact's step limit, the history) with :data:`CURVE_METHOD` at
    :data:`CURVE_TOLERANCE`, whatever method and tolerances the stroke numbers take."""
    settings = settings or SolverSettings()
    return dataclasses.replace(
        settings, method=CURVE_METHOD, rtol=CURVE_TOLERANCE, atol=CURVE_TOLERANCE
    )


def stroke_curves(
    cf_rows: np.ndarray,
    times: np.ndarray,
    with_ball: bool,
    settings: SolverSettings | None = None,
) -> dict[str, np.ndarray]:
    """The curves of many strokes at the sample ``times``, in one call.

    Parameters
    ----------
    cf_rows : ndarray, shape (n, N_CF)
        The strokes' coefficients (:func:`tennis_stroke.model.dynamics.coefficients`).
    times : ndarray, shape (m,)
        Sample times (s), ascending, from 0 or later.
    with_ball : bool
        The stroke with the ball (contact and follow-through until ``times[-1]``), else
        the free swing without it.
    settings : SolverSettings, optional
        The limits; the method and tolerances are :data:`CURVE_METHOD` and
        :data:`CURVE_TOLERANCE` (:func:`curve_settings`).

    Returns
    -------
    dict of ndarray
        Each of :data:`COLUMNS` with shape ``(n, m)``: ``theta, phi`` (rad), ``omega1,
        omega2`` (rad/s), ``x_elbow, y_elbow`` (m), ``kinetic_energy`` (J, the two rods
        in the lab frame); and ``rhs_evals``, shape ``(n,)``, the right-hand-side
        evaluations of each stroke.
    """
    settings = curve_settings(settings)
    times = np.ascontiguousarray(times, dtype=float)
    if times.ndim != 1 or times.size == 0 or not np.all(np.isfinite(times)):
        raise ValueError("sample times must be a non-empty 1-d array of finite numbers")
    if times[0] < 0.0 or np.any(np.diff(times) < 0.0):
        raise ValueError("sample times must be ascending from 0 or later")
    ensure_compiled("curves", exercise_curves)
    cf_rows = np.ascontiguousarray(np.atleast_2d(cf_rows), dtype=float)
    out = np.empty((cf_rows.shape[0], times.size, N_COLUMNS))
    nfev = np.zeros(cf_rows.shape[0])
    args = (cf_rows, times, bool(with_ball), settings.as_array(), out, nfev, settings.history)
    specialised(curve_rows, METHOD_IDS[settings.method], *args)(*args)
    curves = {name: out[:, :, c] for c, name in enumerate(COLUMNS)}
    return {**curves, "rhs_evals": nfev.astype(np.int64)}


def exercise_curves() -> None:
    """The calls that compile (or load) the curves' entry point
    (:func:`tennis_stroke.solver.compiled.ensure_compiled`)."""
    cf_rows = coefficients(resolve_params({}), np.array([120.0, 90.0]), 45.0)
    times = np.linspace(0.0, 0.2, 5)
    for with_ball in (False, True):
        stroke_curves(cf_rows, times, with_ball)
