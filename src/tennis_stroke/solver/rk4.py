"""Classical fixed-step RK4 through the same phases as the compiled path.

A third, deliberately simple integrator for the speed-against-accuracy studies: the
steps never change size, and an event is found by a sign change between two steps, then
located on the step's cubic Hermite interpolant (the states and derivatives at both
ends: fourth order, as RK4 itself; a linear interpolation made every stroke's v_out
second order in the step, measured 2026-12-03).  A contact shorter than one step is
jumped over (:data:`MISSED_CONTACT`), and a step beyond the explicit stability limit blows
up: the stability study shows both.  Phases end at the torque switches, as on the other
paths.  The steps run compiled (:func:`_steps`, the same bits as :func:`rk4_step` on
:func:`~tennis_stroke.model.dynamics.angle_rhs`); an event's location runs in Python.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np
from numba import njit
from scipy.optimize import brentq

from ..model.dynamics import (
    A_BALL_W,
    A_OMEGA1,
    A_OMEGA2,
    A_PHI,
    A_THETA,
    CF_CONTACT_MODEL,
    CF_LEAD,
    CF_PHI0,
    CF_THETA0,
    JIT,
    angle_rhs,
    approach_rate,
    coefficients,
    compression_angles,
    incoming_ball,
    next_switch,
    rebound_speed_kmh,
    rhs_angles,
    swing_event_angles,
    to_trig,
    wrist_torque,
)
from ..model.impact import instant_contact
from ..model.params import initial_angles, resolve_params
from .compiled import ensure_compiled
from .results import NO_APPROACH, NO_PHI_ZERO, NO_RELEASE, OK, STATUS_NAMES, STEP_FAILURE

#: The one status fixed-step RK4 adds to the solver's codes (:data:`STATUS_NAMES`): its
#: first contact step jumped over the whole contact (a contact shorter than the step).
MISSED_CONTACT = len(STATUS_NAMES)
#: The statuses of :func:`fixed_step_stroke`: the solver's, and :data:`MISSED_CONTACT`.
FIXED_STATUS_NAMES = {**STATUS_NAMES, MISSED_CONTACT: "missed_contact"}


def rk4_step(fun: Callable, t: float, y: np.ndarray, h: float) -> np.ndarray:
    """One classical Runge-Kutta step of size ``h`` (s) of ``dy/dt = fun(t, y)``."""
    k1 = fun(t, y)
    k2 = fun(t + h / 2, y + h / 2 * k1)
    k3 = fun(t + h / 2, y + h / 2 * k2)
    k4 = fun(t + h, y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def hermite(y0, f0, y1, f1, h: float, x: float) -> np.ndarray:
    """The cubic Hermite interpolant of a step of size ``h`` (s) at its fraction ``x``
    from the states ``y0``, ``y1`` and derivatives ``f0``, ``f1`` at its ends."""
    x2, x3 = x * x, x * x * x
    return (
        (2 * x3 - 3 * x2 + 1) * y0
        + (x3 - 2 * x2 + x) * h * f0
        + (3 * x2 - 2 * x3) * y1
        + (x3 - x2) * h * f1
    )


def _event_fraction(event, cf, ends) -> float:
    """Where in a step (a fraction) ``event`` falls through 0 on its Hermite interpolant
    (``ends``: the arguments of :func:`hermite` but the fraction)."""
    return brentq(lambda x: event(hermite(*ends, x), cf), 0.0, 1.0, xtol=1e-15)


#: The events :func:`fixed_phase` stops at, by their code in :func:`_steps`.
_EVENT_CODES = {None: 0, swing_event_angles: 1, compression_angles: 2}
#: How :func:`_steps` ended: at ``t_stop``, after ``max_steps`` steps, or with the event
#: fallen through 0 in its last step.
_STOPPED, _LIMITED, _CROSSED = 0, 1, 2
#: Room for the step starts a path records beyond ``(t_stop - t) / h``: a short step at
#: each torque switch and at ``t_stop``, and one more where the times' rounding adds one.
_PATH_SPARE = 8


@njit(**JIT)
def _event_value(code, y, cf):
    """The event of ``code`` (:data:`_EVENT_CODES`) at the angle-layout state ``y``."""
    return swing_event_angles(y, cf) if code == 1 else compression_angles(y, cf)


@njit(**JIT)
def _stage(t, y, cf, c2, contact):
    dydt = np.empty_like(y)
    rhs_angles(t, y, cf, c2, contact, dydt)
    return dydt


@njit(**JIT)
def _rk4_step(t, y, h, cf, c2, contact):
    """:func:`rk4_step` of :func:`~tennis_stroke.model.dynamics.rhs_angles`, compiled
    (the same operations in the same order: the same bits)."""
    k1 = _stage(t, y, cf, c2, contact)
    k2 = _stage(t + h / 2, y + h / 2 * k1, cf, c2, contact)
    k3 = _stage(t + h / 2, y + h / 2 * k2, cf, c2, contact)
    k4 = _stage(t + h, y + h * k3, cf, c2, contact)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


@njit(**JIT)
def _steps(cf, t, y, t_stop, h, contact, code, max_steps, starts_t, starts_y):
    """:func:`fixed_phase`'s steps, compiled: until the event of ``code`` falls through 0
    in a step, ``t_stop`` or ``max_steps`` (negative: no limit) steps; each step's start
    into ``starts_t``, ``starts_y`` when they have room.  Returns ``(how, t, y, y_new,
    step, c2, evaluations, steps)``: ``how`` one of :data:`_STOPPED`, :data:`_LIMITED`,
    :data:`_CROSSED` (then ``y_new`` ends the step of size ``step`` from ``(t, y)``,
    with the wrist torque ``c2``)."""
    evals = steps = 0
    c2 = 0.0
    record = starts_t.size > 0
    while t < t_stop:
        t_seg = next_switch(t, cf, t_stop)
        c2 = wrist_torque(t, t_seg, cf)
        while t < t_seg:
            if max_steps >= 0 and steps >= max_steps:
                return _LIMITED, t, y, y, 0.0, c2, evals, steps
            step = min(h, t_seg - t)
            y_new = _rk4_step(t, y, step, cf, c2, contact)
            if record:
                starts_t[steps] = t
                starts_y[steps] = y
            evals += 4
            steps += 1
            if code != 0 and _event_value(code, y, cf) > 0.0 >= _event_value(code, y_new, cf):
                return _CROSSED, t, y, y_new, step, c2, evals, steps
            t, y = t + step, y_new
    return _STOPPED, t, y, y, 0.0, c2, evals, steps


def fixed_phase(cf, t, y, t_stop, h, contact, event=None, max_steps=None, path=None):
    """RK4 with step ``h`` (s) through the torque switches until ``event(y, cf)`` falls
    through 0, ``t_stop``, or ``max_steps`` steps (angle layout); ``event`` is
    :func:`~tennis_stroke.model.dynamics.swing_event_angles`,
    :func:`~tennis_stroke.model.dynamics.compression_angles` or None.

    Returns ``(t, y, hit, evaluations)``; an event is located on the step's
    :func:`hermite` interpolant (Brent's method, to rounding), whose end derivative costs
    one evaluation more.  The steps are compiled (:func:`_steps`), the event's location
    is not.  ``path``, a list, gets the starts of the steps taken, ``(times, states,
    contact)``: a run of this function from one of them to a time before the next ends
    where a run from ``(t, y)`` given here would, bit for bit (the same steps).
    """
    ensure_compiled("rk4", exercise_rk4)
    room = 0
    if path is not None:
        room = math.ceil((t_stop - t) / h) + _PATH_SPARE if t_stop > t else 0
        room = room if max_steps is None else min(room, max_steps)
    starts_t, starts_y = np.empty(room), np.empty((room, y.size))
    limit = -1 if max_steps is None else int(max_steps)
    how, t, y, y_new, step, c2, evals, steps = _steps(
        cf,
        float(t),
        y,
        float(t_stop),
        float(h),
        bool(contact),
        _EVENT_CODES[event],
        limit,
        starts_t,
        starts_y,
    )
    if path is not None:
        path.append((starts_t[:steps], starts_y[:steps], bool(contact)))
    if how != _CROSSED:
        return t, y, False, evals
    fun = angle_rhs(cf, c2, contact)
    f0, f1 = fun(t, y), fun(t + step, y_new)
    evals += 1  # f0 is the step's first stage: only f1 is new
    if event(y_new, cf) == 0.0:
        return t + step, y_new, True, evals
    x = _event_fraction(event, cf, (y, f0, y_new, f1, step))
    return t + x * step, hermite(y, f0, y_new, f1, step, x), True, evals


def contact_missed(cf, t: float, y: np.ndarray, h: float, t_stop: float):
    """Whether the first RK4 step of a contact starting at ``(t, y)`` already ends with
    the ball off the strings (the contact is shorter than the step, so the separation
    event, which needs a positive compression first, would never fire).

    Returns ``(missed, state after the first step, evaluations)``.
    """
    _, first, _, evals = fixed_phase(cf, t, y, t_stop, h, True, max_steps=1)
    missed = bool(np.all(np.isfinite(first)) and compression_angles(first, cf) <= 0.0)
    return missed, first, evals


def fixed_step_stroke(
    theta0_deg: float,
    delta0_deg: float,
    params: Mapping[str, object],
    h: float,
    t_max: float = 1.0,
    path: list | None = None,
) -> dict[str, float]:
    """One stroke with fixed-step RK4 (step ``h``, s): ``status`` (a code of
    :data:`FIXED_STATUS_NAMES`: ``OK``, ``MISSED_CONTACT``, ``NO_PHI_ZERO``,
    ``NO_APPROACH``, ``STEP_FAILURE`` for a non-finite state, or ``NO_RELEASE``),
    ``v_out_kmh``, the event times ``t_phi0``, ``t_contact_start`` and ``t_separation``
    (s) and ``rhs_evals``.

    The contact state at ``t_c`` is the RK4 state of the step before, advanced by one
    step of the remaining size: the swing is stepped once, to ``phi = 0``.
    The cheap rungs of the model ladder (``contact_model`` other than ``spring``) meet
    the ball at ``phi = 0`` in no time
    (:func:`~tennis_stroke.model.impact.instant_contact`), as on the other paths.

    ``path``, a list, gets the starts of the steps the stroke follows
    (:func:`fixed_phase`'s): the swing to the contact start, then the contact to
    separation.
    """
    initial_angles(theta0_deg, delta0_deg)
    cf = coefficients(resolve_params(params), theta0_deg, delta0_deg)[0]
    out = {"status": OK, "v_out_kmh": math.nan, "rhs_evals": 0}
    out |= dict.fromkeys(("t_phi0", "t_contact_start", "t_separation"), math.nan)
    y0 = np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    instant = cf[CF_CONTACT_MODEL] != 0.0
    swing: list = []
    t0, y, hit, evals = fixed_phase(cf, 0.0, y0, t_max, h, False, swing_event_angles, path=swing)
    out["rhs_evals"] += evals
    if not hit:
        out["status"] = NO_PHI_ZERO if np.all(np.isfinite(y)) else STEP_FAILURE
        return out
    out["t_phi0"] = t0
    t_c = t0 if instant else t0 - cf[CF_LEAD]
    yc = y
    if not instant:  # the swing's last step before t_c, cut short there
        times, states, _ = swing[0]
        k = int(np.searchsorted(times, t_c, side="left"))
        swing = [(times[:k], states[:k], False)]
        if k:
            _, yc, _, evals = fixed_phase(cf, times[k - 1], states[k - 1], t_c, h, False)
            out["rhs_evals"] += evals
        else:  # t_c <= 0
            yc = y0
    if path is not None:
        path.extend(swing)
    out["t_contact_start"] = t_c
    st, sp = math.sin(yc[A_THETA]), math.sin(yc[A_PHI])
    ct, cp = math.cos(yc[A_THETA]), math.cos(yc[A_PHI])
    s, w = incoming_ball(t_c, st, sp, cf)
    if approach_rate(st, ct, sp, cp, yc[A_OMEGA1], yc[A_OMEGA2], w, cf) <= 0.0:
        out["status"] = NO_APPROACH
        return out
    if instant:
        out["v_out_kmh"] = instant_contact(t_c, to_trig(yc), cf)[0]
        out["t_separation"] = t_c
        return out
    y = np.array([*yc, s, w])
    missed, _, evals = contact_missed(cf, t_c, y, h, t_max)
    if missed:
        out["status"] = MISSED_CONTACT
        out["rhs_evals"] += evals
        return out
    t_s, y, hit, evals = fixed_phase(cf, t_c, y, t_max, h, True, compression_angles, path=path)
    out["rhs_evals"] += evals
    if not hit or not np.all(np.isfinite(y)):
        out["status"] = STEP_FAILURE if not np.all(np.isfinite(y)) else NO_RELEASE
        return out
    out["t_separation"] = t_s
    out["v_out_kmh"] = rebound_speed_kmh(t_s, y[A_BALL_W], cf)
    return out


def exercise_rk4() -> None:
    """The calls that compile (or load) what fixed-step RK4 and the solver studies call
    from Python: RK4's compiled steps, the model functions, and scipy's Radau and LSODA
    on the angle layout
    (their Jacobians pass states of another layout)
    (:func:`tennis_stroke.solver.compiled.ensure_compiled`)."""
    from scipy.integrate import solve_ivp

    from ..model.dynamics import contact_duration, effective_mass, hit_offset, mechanical_energy

    fixed_step_stroke(120.0, 81.5, {}, 1e-3)  # the work-precision study's strokes
    cf_row = coefficients(resolve_params({}), 120.0, 81.5)[0]
    y0 = np.array([1.0, 0.0, 10.0, 30.0, 0.0, 20.0])
    trig = (math.sin(1.0), math.cos(1.0), math.sin(0.0), math.cos(0.0))
    hit_offset(trig[0], trig[2], cf_row)  # the stability study's isolated contact
    effective_mass(*trig, cf_row)
    contact_duration(*trig, cf_row)
    mechanical_energy(0.0, y0, cf_row, True)
    contact_missed(cf_row, 0.0, y0, 1e-4, 0.01)
    fixed_phase(cf_row, 0.0, y0, 0.01, 1e-4, True, compression_angles)
    for method in ("Radau", "LSODA"):
        solve_ivp(angle_rhs(cf_row, 0.0, True), (0.0, 1e-3), y0, method=method)
