"""The state probe of the work-precision study reads a stroke's omegas on the solve that
gave its result: each the same as a separate solve ending at that time."""

import math

import numpy as np
from conftest import FIG4_A

from tennis_stroke.model.dynamics import (
    A_OMEGA1,
    A_OMEGA2,
    A_PHI,
    A_THETA,
    CF_PHI0,
    CF_THETA0,
    coefficients,
    contact_duration,
    incoming_ball,
)
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver.reference import dense_phase, solve_stroke
from tennis_stroke.solver.rk4 import fixed_phase, fixed_step_stroke
from tennis_stroke.studies.probe import path_omegas, probe_times, segment_omegas

CF = coefficients(resolve_params({}), *FIG4_A)[0]
START = np.array([CF[CF_THETA0], CF[CF_PHI0], 0.0, 0.0])


def _with_ball(t_c: float, y: np.ndarray) -> np.ndarray:
    """The contact's first state: the ball put at the hitting point, as the strokes do."""
    s, w = incoming_ball(t_c, math.sin(y[A_THETA]), math.sin(y[A_PHI]), CF)
    return np.array([*y[:4], s, w])


def _times(t_c: float, t_sep: float) -> np.ndarray:
    """The probe's times over the stroke, and more in its contact (a few ms): just
    before and after its start, inside, and at separation."""
    inside = t_c + (t_sep - t_c) * np.array([-0.01, 0.01, 0.3, 0.7])
    return np.sort(np.r_[probe_times(t_sep, 8), inside])


def test_rk4_omegas_are_a_separate_run_to_each_time_bit_for_bit():
    """A run of its own from the phase's start to each time (the swing from rest, the
    contact from the stroke's contact start) gives the probe's omegas exactly: the probe
    starts it where that run would be, on the stroke's own steps."""
    h, path = 1e-3, []
    res = fixed_step_stroke(*FIG4_A, {}, h, path=path)
    t_c, t_sep = res["t_contact_start"], res["t_separation"]
    times = _times(t_c, t_sep)
    y_c = _with_ball(t_c, fixed_phase(CF, 0.0, START, t_c, h, False)[1])
    separate = [
        fixed_phase(CF, 0.0, START, t, h, False)[1]
        if t <= t_c
        else fixed_phase(CF, t_c, y_c, t, h, True)[1]
        for t in times
    ]
    expected = np.array([y[[A_OMEGA1, A_OMEGA2]] for y in separate])
    np.testing.assert_array_equal(path_omegas(path, CF, h, times), expected)


def test_scipy_omegas_are_a_separate_solve_to_each_time_within_its_tolerance():
    """The dense output of the stroke's own solve against a separate solve ending at each
    time, from the phase's start: they differ by the method's local error only, far below
    what the omegas change between the times (tens of rad/s over a stroke)."""
    tol = 1e-10
    stroke = solve_stroke(*FIG4_A, method="DOP853", rtol=tol, atol=tol)
    t_c, t_sep = stroke.result["t_contact_start"], stroke.result["t_separation"]
    times = _times(t_c, t_sep)
    y_c = _with_ball(t_c, stroke.states(np.array([t_c]))[:4, 0])
    th, ph = y_c[A_THETA], y_c[A_PHI]
    cap = contact_duration(math.sin(th), math.cos(th), math.sin(ph), math.cos(ph), CF) / 2.0
    separate = [
        dense_phase(CF, 0.0, START, t, False, "DOP853", tol, tol)[1]
        if t <= t_c
        else dense_phase(CF, t_c, y_c, t, True, "DOP853", tol, tol, cap)[1]
        for t in times
    ]
    expected = np.array([y[[A_OMEGA1, A_OMEGA2]] for y in separate])
    assert np.ptp(expected) > 10.0
    np.testing.assert_allclose(segment_omegas(stroke.segments, times), expected, rtol=0, atol=1e-8)
