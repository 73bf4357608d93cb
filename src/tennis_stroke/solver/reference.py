"""The independent path: the same stroke with :func:`scipy.integrate.solve_ivp`.

It shares only the model with the compiled path (:mod:`tennis_stroke.model.dynamics`:
the equations through :func:`tennis_stroke.model.dynamics.rhs_angles`, the torque
schedule, the events, the ball at the contact start and the rebound speed), never the
compiled driver; state layout (angles
instead of sines and cosines), integrator, event location and restart at the contact
start are scipy's.  The phase splitting is the same (torque switches, ``phi = 0``,
contact start, separation), so the two paths can be compared stroke by stroke.  It is
used for verification (the stroke numbers, and the figures' curves of
:mod:`tennis_stroke.solver.curves`), for the benchmark baseline and for one stroke over
time from Python (:func:`tennis_stroke.stroke_dataset`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..model.dynamics import (
    A_BALL_S,
    A_BALL_W,
    A_OMEGA1,
    A_OMEGA2,
    A_PHI,
    A_THETA,
    CF_CONTACT_MODEL,
    CF_LEAD,
    CF_PHI0,
    CF_THETA0,
    MS_TO_KMH,
    N_CF,
    angle_rhs,
    approach_rate,
    ball_in_lab,
    coefficients,
    compression_angles,
    contact_duration,
    elbow_position,
    elbow_velocity,
    incoming_ball,
    next_switch,
    rebound_speed_kmh,
    rod_points,
    rod_velocities,
    to_trig,
    wrist_torque,
)
from ..model.impact import instant_contact
from ..model.params import ParameterError, initial_angles, one_stroke, resolve_params
from .compiled import ensure_compiled
from .results import (
    EARLY_CONTACT,
    NO_APPROACH,
    NO_PHI_ZERO,
    NO_RELEASE,
    OK,
    RESULT_FIELDS,
    STATUS_NAMES,
    STEP_FAILURE,
)

#: Samples per phase for ``omega2_max`` on the reference path.
OMEGA2_SAMPLES = 512
#: The longest time :func:`solve_stroke` simulates: ``t_max`` and ``follow_through`` are
#: each at most this (s).  ``solve_ivp`` has no bound on its steps, and past the stroke
#: the elbow's motion (Eq. 13) grows with t^2, so its steps shrink without end: a
#: ``follow_through`` of 1e6 s ran until it was killed.  The paper's strokes last about
#: 0.2 s; its figures show 0.32 s.
MAX_STROKE_TIME = 2.0


@dataclass
class Segment:
    """One integrated phase: time span, contact flag and scipy's dense solution."""

    t0: float
    t1: float
    contact: bool
    sol: object


@dataclass
class ReferenceStroke:
    """Result of :func:`solve_stroke` (or :func:`free_swing`): the result fields, the
    phases, and what the stroke was computed from.

    Attributes
    ----------
    result : dict
        The result fields (those of the compiled path,
        :data:`tennis_stroke.solver.results.RESULT_FIELDS`, plus ``status_name``).
    segments : list of Segment
        The integrated phases in time order, each with scipy's dense solution.
    cf : ndarray, shape (N_CF,)
        The stroke's coefficients (:func:`tennis_stroke.model.dynamics.coefficients`).
    params : dict
        The resolved parameters (:func:`tennis_stroke.model.params.resolve_params`).
    solver : dict
        The integrator: ``path``, ``method``, ``rtol``, ``atol``, ``follow_through``.
    """

    result: dict[str, float]
    segments: list[Segment] = field(default_factory=list)
    cf: np.ndarray = field(default_factory=lambda: np.full(N_CF, np.nan))
    params: dict[str, object] = field(default_factory=dict)
    solver: dict[str, object] = field(default_factory=dict)

    def states(self, times: np.ndarray) -> np.ndarray:
        """The state in the angle layout, shape ``(6, *times.shape)``: ``theta, phi`` (rad),
        ``omega1, omega2`` (rad/s), the ball's ``s`` (m) and ``w`` (m/s) relative to the
        elbow (:mod:`tennis_stroke.model.dynamics`).

        NaN outside the actual stroke (the swing until the contact start, the contact
        until separation, then the follow-through if simulated), and for the ball outside
        the contact.  At a phase boundary the later phase's value is given.
        """
        times = np.asarray(times, dtype=float)
        out = np.full((6, *times.shape), np.nan)
        for seg in self.segments:
            mask = (times >= seg.t0) & (times <= seg.t1)
            if np.any(mask):
                y = seg.sol(times[mask])
                out[:, mask] = np.nan
                out[: y.shape[0], mask] = y
        return out

    def sample(self, times: np.ndarray) -> dict[str, np.ndarray]:
        """``theta, phi`` (rad), ``omega1, omega2`` (rad/s) of the actual stroke at ``times``.

        The actual stroke is the swing until the contact start, the contact until
        separation, then the follow-through (if simulated); NaN outside.  A stroke that
        failed before its contact is the swing computed until it failed.
        """
        y = self.states(times)
        return {
            "theta": y[A_THETA],
            "phi": y[A_PHI],
            "omega1": y[A_OMEGA1],
            "omega2": y[A_OMEGA2],
        }

    def lab_frame(self, times: np.ndarray) -> dict[str, np.ndarray]:
        """The stroke at ``times`` (s) in the lab frame, every quantity from the model's
        functions (:mod:`tennis_stroke.model.dynamics`), NaN outside the actual stroke.

        Returns
        -------
        dict of ndarray, each shaped like ``times``
            ``theta, phi`` (rad), ``omega1, omega2`` (rad/s, clockwise positive);
            ``x_elbow, y_elbow`` (m), ``vx_elbow, vy_elbow`` (m/s); the positions
            ``x_P, y_P`` (m) and velocities ``vx_P, vy_P`` (m/s) of the wrist, the
            racket's end and the hitting point (``P`` = ``wrist``, ``racket``, ``hit``;
            :func:`tennis_stroke.model.dynamics.rod_points`,
            :func:`tennis_stroke.model.dynamics.rod_velocities`) and the hitting point's
            speed ``speed_hit`` (m/s); the ball's position ``x_ball`` (m) and velocity
            ``vx_ball`` (m/s) along x (the model's ball moves along x only).

        Notes
        -----
        In the contact the ball is the integrated state.  Outside it the ball flies free
        (the model has no gravity): towards ``+x`` at ``ball_speed`` until the contact
        start, where :func:`tennis_stroke.model.dynamics.incoming_ball` puts it at the
        hitting point, and from separation on at its velocity then, the rebound speed
        towards ``-x`` (``-v_out_kmh / 3.6`` m/s; the instantaneous rungs of the model
        ladder: the ball leaves the hitting point at ``t0``).  The outgoing ball is
        given only for a stroke whose status is ``ok``.
        """
        times = np.asarray(times, dtype=float)
        cf = self.cf
        y = self.states(times)
        theta, phi, w1, w2 = y[A_THETA], y[A_PHI], y[A_OMEGA1], y[A_OMEGA2]
        simulated = np.isfinite(theta)
        elbow = _elbow(times, cf, simulated)
        out = {"theta": theta, "phi": phi, "omega1": w1, "omega2": w2, **elbow}
        out.update(rod_points(theta, phi, elbow["x_elbow"], elbow["y_elbow"], cf))
        vel = rod_velocities(theta, phi, w1, w2, elbow["vx_elbow"], elbow["vy_elbow"], cf)
        out.update(vel)
        out["speed_hit"] = np.hypot(vel["vx_hit"], vel["vy_hit"])
        x_ball, v_ball = ball_in_lab(y[A_BALL_S], y[A_BALL_W], elbow["x_elbow"], elbow["vx_elbow"])
        for t_ref, x_ref, v_ref, side in self._free_ball():
            free = simulated & np.isnan(x_ball) & (side * (times - t_ref) >= 0.0)
            x_ball[free] = x_ref + v_ref * (times[free] - t_ref)
            v_ball[free] = v_ref
        out["x_ball"], out["vx_ball"] = x_ball, v_ball
        return out

    def _free_ball(self) -> list[tuple[float, float, float, int]]:
        """The free ball's legs, ``(t, x, v, side)``: its lab-frame position (m) and
        velocity (m/s) at time ``t`` (s), valid before ``t`` (side -1: the incoming ball,
        from the contact start) or after it (side +1: the outgoing ball, from separation,
        where the compression is 0: the ball is at the hitting point)."""
        cf, res = self.cf, self.result
        t_c = res.get("t_contact_start", math.nan)
        if not math.isfinite(t_c):
            return []
        y_c = self.states(np.array([t_c]))[:, 0]
        s, w = incoming_ball(t_c, math.sin(y_c[A_THETA]), math.sin(y_c[A_PHI]), cf)
        x_in, v_in = ball_in_lab(s, w, elbow_position(t_c, cf)[0], elbow_velocity(t_c, cf)[0])
        legs = [(t_c, x_in, v_in, -1)]
        if res.get("status") == OK:
            t_sep = res["t_separation"]
            y_sep = self.states(np.array([t_sep]))[:, 0]
            x_sep = rod_points(y_sep[A_THETA], y_sep[A_PHI], *elbow_position(t_sep, cf), cf)
            legs.append((t_sep, float(x_sep["x_hit"]), -res["v_out_kmh"] / MS_TO_KMH, 1))
        return legs


def _elbow(times: np.ndarray, cf: np.ndarray, simulated: np.ndarray) -> dict[str, np.ndarray]:
    """The elbow's position (m) and velocity (m/s) at ``times`` (s), NaN where the stroke
    is not ``simulated`` (:func:`tennis_stroke.model.dynamics.elbow_position`,
    :func:`tennis_stroke.model.dynamics.elbow_velocity`)."""
    names = ("x_elbow", "y_elbow", "vx_elbow", "vy_elbow")
    rows = [(*elbow_position(t, cf), *elbow_velocity(t, cf)) for t in times.ravel()]
    table = np.array(rows, dtype=float).reshape(-1, 4)
    return {
        name: np.where(simulated, table[:, k].reshape(times.shape), np.nan)
        for k, name in enumerate(names)
    }


def _run(t, y, t_stop, cf, contact, events, method, rtol, atol, max_step, segments):
    """solve_ivp through the torque switches; returns (t, y, event_hit, nfev, ok)."""
    ensure_compiled("reference", exercise_reference)
    nfev = 0
    while True:
        t_seg = next_switch(t, cf, t_stop)
        c2 = wrist_torque(t, t_seg, cf)
        sol = solve_ivp(
            angle_rhs(cf, c2, contact),
            (t, t_seg),
            y,
            method=method,
            rtol=rtol,
            atol=atol,
            events=events,
            dense_output=True,
            max_step=max_step,
        )
        nfev += sol.nfev
        if sol.status == -1:
            return t, y, False, nfev, False
        hit = sol.status == 1
        t_new = float(sol.t_events[0][0]) if hit else float(sol.t[-1])
        segments.append(Segment(t, t_new, contact, sol.sol))
        t, y = t_new, (sol.y_events[0][0] if hit else sol.y[:, -1])
        if hit or t >= t_stop:
            return t, y, hit, nfev, True


def dense_phase(
    cf: np.ndarray,
    t: float,
    y: np.ndarray,
    t_stop: float,
    contact: bool,
    method: str,
    rtol: float,
    atol: float,
    max_step: float = np.inf,
) -> tuple[ReferenceStroke, np.ndarray, bool]:
    """One phase kind (the swing, or the contact with ``contact``) from ``(t, y)`` (angle
    layout) to ``t_stop`` (s) through the torque switches, no event: ``(dense, y, ok)``,
    the phase's dense output (:meth:`ReferenceStroke.sample`; its ``result`` holds
    ``rhs_evals``), the state at ``t_stop`` and whether ``solve_ivp`` succeeded."""
    dense = ReferenceStroke({})
    _, y, _, nfev, ok = _run(
        t, y, t_stop, cf, contact, None, method, rtol, atol, max_step, dense.segments
    )
    dense.result["rhs_evals"] = nfev
    return dense, y, ok


def free_swing(
    theta0_deg: float,
    delta0_deg: float,
    t_end: float,
    params: Mapping[str, object] | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-10,
) -> ReferenceStroke:
    """The pendulum swung from rest without the ball until ``t_end`` (s): the independent
    check of the figures' free-swing curves (:mod:`tennis_stroke.solver.curves`).

    The paper computes the swing without the ball and the collision separately (Sec. II);
    its figures of omega(t) (Figs. 4, 10) show the swing.  ``result`` holds no stroke
    numbers (see :func:`solve_stroke` for those).
    """
    resolved = resolve_params(params)
    one_stroke("free_swing", resolved, theta0_deg, delta0_deg)
    initial_angles(theta0_deg, delta0_deg)
    _check_options(rtol=rtol, atol=atol, t_end=t_end)
    cf = coefficients(resolved, theta0_deg, delta0_deg)[0]
    solver = {"path": "scipy solve_ivp", "method": "DOP853", "rtol": rtol, "atol": atol}
    ref = ReferenceStroke({}, cf=cf, params=resolved, solver={**solver, "t_end": t_end})
    y0 = np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    _run(0.0, y0, t_end, cf, False, None, "DOP853", rtol, atol, np.inf, ref.segments)
    return ref


def solve_stroke(
    theta0_deg: float,
    delta0_deg: float,
    params: Mapping[str, object] | None = None,
    method: str = "DOP853",
    rtol: float = 1e-12,
    atol: float = 1e-12,
    t_max: float = 1.0,
    contact_min_steps: float = 2.0,
    follow_through: float = 0.0,
) -> ReferenceStroke:
    """One stroke with ``solve_ivp``; same phases, statuses and fields as the compiled path.

    Parameters
    ----------
    theta0_deg, delta0_deg : float
        Initial angles (degrees).
    params : mapping, optional
        Parameter overrides and readings (scalars only).
    method : str
        Any ``solve_ivp`` method name.
    rtol, atol : float
        Tolerances passed to ``solve_ivp``.
    t_max : float
        Longest simulated stroke (s), at most :data:`MAX_STROKE_TIME`.
    contact_min_steps : float
        The contact phase's ``max_step`` is the two-body contact duration over this
        (> 0).
    follow_through : float
        Free swing after separation (s), for ``omega2_max`` and to see the stroke go on
        (0 to :data:`MAX_STROKE_TIME`).

    Returns
    -------
    ReferenceStroke
        The result fields (``.result``) and the trajectory: :meth:`ReferenceStroke.sample`
        (angles and rates), :meth:`ReferenceStroke.lab_frame` (the elbow, the racket's
        points and the ball in the lab frame) or, with names and units as an
        ``xarray.Dataset``, :func:`tennis_stroke.stroke_dataset`.

    Raises
    ------
    ParameterError
        An option that is not a finite number in its range, an array among the
        angles or parameters (one stroke: scalars only), an initial angle against the
        rule of :data:`tennis_stroke.model.params.INITIAL_ANGLES`.

    Examples
    --------
    >>> stroke = solve_stroke(120.0, 81.5, follow_through=0.05)  # Fig. 4's stroke a
    >>> round(stroke.result["v_out_kmh"], 2)
    155.68
    """
    resolved = resolve_params(params)
    one_stroke("solve_stroke", resolved, theta0_deg, delta0_deg)
    initial_angles(theta0_deg, delta0_deg)
    _check_options(rtol=rtol, atol=atol, t_max=t_max, contact_min_steps=contact_min_steps)
    _check_options(follow_through=follow_through, lower=0.0)
    cf = coefficients(resolved, theta0_deg, delta0_deg)[0]
    res = {name: math.nan for name in RESULT_FIELDS}
    res["rhs_evals"] = 0
    solver = {"path": "scipy solve_ivp", "method": method, "rtol": rtol, "atol": atol}
    solver.update(t_max=t_max, contact_min_steps=contact_min_steps, follow_through=follow_through)
    ref = ReferenceStroke(res, cf=cf, params=resolved, solver=solver)
    code = _phases(ref, cf, (method, rtol, atol), t_max, contact_min_steps, follow_through)
    return _finished(ref, code)


#: The options of :func:`solve_stroke` that are durations, at most :data:`MAX_STROKE_TIME`.
_DURATIONS = ("t_max", "follow_through", "t_end")


def _check_options(lower: float | None = None, **options: object) -> None:
    """Each of ``options`` (by name) a finite number above 0 (at least ``lower`` where
    given) and, for a duration, at most :data:`MAX_STROKE_TIME`; a
    :class:`tennis_stroke.model.params.ParameterError` naming it otherwise (NaN or inf
    made the phases loop for ever)."""
    for name, value in options.items():
        number = isinstance(value, int | float | np.integer | np.floating) and not isinstance(
            value, bool | np.bool_
        )
        low = ">= 0" if lower is not None else "> 0"
        high = f" and <= {MAX_STROKE_TIME:g} s" if name in _DURATIONS else ""
        fits = number and math.isfinite(value)
        fits = fits and (value >= lower if lower is not None else value > 0)
        fits = fits and (name not in _DURATIONS or value <= MAX_STROKE_TIME)
        if not fits:
            raise ParameterError(
                f"argument {name!r} must be a finite number {low}{high}, got {value!r}"
            )


def _finished(ref: ReferenceStroke, code: int) -> ReferenceStroke:
    """``ref`` with its status, its angles in degrees and, for a stroke that succeeded,
    ``omega2_max`` sampled on its segments (a check of the compiled peak finder)."""
    res = ref.result
    res["status"] = code
    res["status_name"] = STATUS_NAMES[code]
    for key in ("theta_deg_at_phi0", "theta_deg_contact"):
        res[key] = math.degrees(res[key])
    if code == OK:
        res["omega2_max"] = float(
            max(
                np.max(seg.sol(np.linspace(seg.t0, seg.t1, OMEGA2_SAMPLES))[A_OMEGA2])
                for seg in ref.segments
            )
        )
    return ref


def _phases(ref, cf, opts, t_max, contact_min_steps, follow_through) -> int:
    """The stroke's phases, into ``ref`` (``opts``: method, rtol, atol): the swing to
    phi = 0, the contact start, then the contact (spring or instantaneous) and the follow
    through.  Returns the status code."""
    res = ref.result
    swing: list[Segment] = []
    t0, y, code = _swing(cf, opts, t_max, swing, res)
    instant = cf[CF_CONTACT_MODEL] != 0.0  # a cheap rung of the model ladder: no contact phase
    t_c = t0 if instant else t0 - cf[CF_LEAD]
    if code == OK and t_c < 0.0:
        code = EARLY_CONTACT
    if code != OK:
        ref.segments = swing  # the swing that was computed
        return code
    yc = _contact_start(ref, swing, t_c)
    st, ct = math.sin(yc[A_THETA]), math.cos(yc[A_THETA])
    sp, cp = math.sin(yc[A_PHI]), math.cos(yc[A_PHI])
    s_ball, w = incoming_ball(t_c, st, sp, cf)
    if approach_rate(st, ct, sp, cp, yc[A_OMEGA1], yc[A_OMEGA2], w, cf) <= 0.0:
        return NO_APPROACH
    if instant:
        res["v_out_kmh"], w1, w2 = instant_contact(t_c, to_trig(yc), cf)
        res["t_separation"] = t_c
        y_after = np.array([yc[A_THETA], yc[A_PHI], w1, w2])
        return OK if _follow(t_c, y_after, follow_through, cf, *opts, res, ref) else STEP_FAILURE
    max_step = contact_duration(st, ct, sp, cp, cf) / contact_min_steps
    return _spring_contact(
        ref, cf, opts, t_c, np.array([*yc, s_ball, w]), t_max, max_step, follow_through
    )


def _swing(cf, opts, t_max, swing, res) -> tuple[float, np.ndarray, int]:
    """The free swing from rest to phi = 0 (segments into ``swing``): ``(t0, state,
    code)``, with the phi = 0 fields into ``res``."""

    def phi_zero(t, y):
        return y[A_PHI]

    phi_zero.terminal, phi_zero.direction = True, -1
    y0 = np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    t0, y, hit, nfev, ok = _run(0.0, y0, t_max, cf, False, [phi_zero], *opts, np.inf, swing)
    res["rhs_evals"] += nfev
    if not ok:
        return t0, y, STEP_FAILURE
    if not hit:
        return t0, y, NO_PHI_ZERO
    res.update(
        t_phi0=t0, theta_deg_at_phi0=y[A_THETA], omega1_phi0=y[A_OMEGA1], omega2_phi0=y[A_OMEGA2]
    )
    return t0, y, OK


def _contact_start(ref: ReferenceStroke, swing: list[Segment], t_c: float) -> np.ndarray:
    """The swing's state at the contact start ``t_c`` (its fields into ``ref.result``);
    the stroke's segments become the swing cut there."""
    yc = next(s for s in swing if s.t0 <= t_c <= s.t1).sol(t_c)
    ref.segments = [s for s in swing if s.t0 < t_c]
    ref.segments[-1] = Segment(ref.segments[-1].t0, t_c, False, ref.segments[-1].sol)
    ref.result.update(
        t_contact_start=t_c,
        theta_deg_contact=yc[A_THETA],
        omega1_contact=yc[A_OMEGA1],
        omega2_contact=yc[A_OMEGA2],
    )
    return yc


def _spring_contact(ref, cf, opts, t_c, y, t_max, max_step, follow_through) -> int:
    """The spring contact from ``t_c`` (state ``y`` with the ball) to separation, then
    the follow-through; returns the status code."""
    res = ref.result

    def separation(t, y):
        return compression_angles(y, cf)

    separation.terminal, separation.direction = True, -1
    t_sep, y, hit, nfev, ok = _run(
        t_c, y, t_max, cf, True, [separation], *opts, max_step, ref.segments
    )
    res["rhs_evals"] += nfev
    if not ok:
        return STEP_FAILURE
    if not hit:
        return NO_RELEASE
    res["t_separation"] = t_sep
    res["v_out_kmh"] = rebound_speed_kmh(t_sep, y[A_BALL_W], cf)
    return OK if _follow(t_sep, y[:4], follow_through, cf, *opts, res, ref) else STEP_FAILURE


def _follow(t, y, duration, cf, method, rtol, atol, res, ref) -> bool:
    """The free swing for ``duration`` (s) after the ball has left; False on a failure."""
    if duration <= 0.0:
        return True
    _, _, _, nfev, ok = _run(
        t, y, t + duration, cf, False, None, method, rtol, atol, np.inf, ref.segments
    )
    res["rhs_evals"] += nfev
    return ok


def exercise_reference() -> None:
    """The calls that compile (or load) scipy's reference path's right-hand sides
    (:func:`tennis_stroke.solver.compiled.ensure_compiled`), and the model's functions
    that :meth:`ReferenceStroke.lab_frame` calls from Python."""
    solve_stroke(120.0, 81.5, rtol=1e-6, atol=1e-6, follow_through=0.01).lab_frame(
        np.array([0.0, 0.5])
    )
    free_swing(120.0, 81.5, 0.05)
