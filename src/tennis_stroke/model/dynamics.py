"""Equations of motion of the driven double pendulum with a ball: the one home of the physics.

Conventions (Youn, Sec. II)
---------------------------
* Rod 1 (arm+forearm: mass ``M1``, length ``L1``) pivots at the elbow; rod 2 (hand+racket:
  ``M2``, ``L2``) pivots at the wrist.  Both are uniform rods: centres at ``h_i = L_i/2``.
* Angles ``theta`` (rod 1) and ``phi`` (rod 2) are measured from the ``-y`` axis,
  counter-clockwise positive; ``delta = phi - theta``.  Angular velocities are clockwise
  positive: ``omega1 = -dtheta/dt``, ``omega2 = -dphi/dt``.  No gravity.
* The elbow moves with the prescribed velocity of Eq. 13 plus, optionally, the velocity
  given by the extra force of Eq. 14 acting on a mass ``elbow_force_mass`` (Sec. VI).
  The pendulum is integrated in the elbow's frame, where the elbow acceleration ``a_E``
  enters as the fictitious force ``-m a_E`` on every mass (the ``a_x, a_y`` terms of Eq. 7).
* The ball moves along x.  Its state is ``s = x_b - x_E`` and ``w = v_b - V_x^E`` (position
  and velocity relative to the elbow).  The hitting point is at ``x_H - x_E = L1 sin(theta)
  + (h2 + h_H) sin(phi)`` (Eq. 10).  The compression ``s - (x_H - x_E)`` is positive while
  the ball presses on the strings; the spring pushes the ball towards ``-x`` with
  ``k * compression`` and the racket towards ``+x`` with the same force (Newton's third
  law; Eqs. 9-11 as printed have the signs of ball and racket force equal, see
  ``docs/equations.md``).  One-sidedness is not an ``if`` here: the contact phase starts
  at zero compression and ends at the separation event.

Two state layouts share the physics of :func:`rhs_trig`:

* *trig layout* (the compiled path): ``sin(theta), cos(theta), sin(phi), cos(phi), omega1,
  omega2, theta, phi`` (+ ``s, w`` in contact).  Carrying sines and cosines as states
  makes the right-hand side polynomial (no transcendental calls), which is what makes the
  compiled solver fast; the angles themselves are carried too (unwrapped, and the event
  ``phi = 0`` is exact even for a step longer than half a turn).
* *angle layout* (the scipy reference path): ``theta, phi, omega1, omega2, s, w``.

Per-stroke coefficients are packed in a float array ``cf`` (layout ``CF_*``) built by
:func:`coefficients`; the numba functions below read only ``cf``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from numba import njit

# Trig layout (compiled path).
SIN_TH, COS_TH, SIN_PH, COS_PH, OMEGA1, OMEGA2, THETA, PHI, BALL_S, BALL_W = range(10)
N_CONTACT = 10  # components in contact; the swing integrates the first 8
# Angle layout (reference path); OMEGA1/OMEGA2 are not shared with the trig layout.
A_THETA, A_PHI, A_OMEGA1, A_OMEGA2, A_BALL_S, A_BALL_W = range(6)

# Layout of the per-stroke coefficient array.
(
    CF_L1,
    CF_LH,
    CF_M1,
    CF_M2,
    CF_H1,
    CF_H2,
    CF_I1,
    CF_I2,
    CF_M11,
    CF_M22,
    CF_M12,
    CF_A1,
    CF_A2,
    CF_C1,
    CF_C2,
    CF_TAU,
    CF_C2_OFF,
    CF_K,
    CF_MB,
    CF_COUPLING,
    CF_VX1,
    CF_VX2,
    CF_VY1,
    CF_VY2,
    CF_FX,
    CF_FY,
    CF_TF,
    CF_TD,
    CF_LEAD,
    CF_VBALL,
    CF_THETA0,
    CF_PHI0,
    CF_FORCE_ON,
    CF_CONTACT_MODEL,
    CF_DAMP,
) = range(35)
N_CF = 35
#: The columns the free swing does not read (the ball, the spring and the contact's
#: timing): strokes whose rows differ only in these swing alike, step for step, so the
#: compiled solver swings once for a run of such rows (``SWING_COLUMNS``: the others).
CONTACT_ONLY_COLUMNS = (
    CF_LH,
    CF_K,
    CF_MB,
    CF_COUPLING,
    CF_LEAD,
    CF_VBALL,
    CF_CONTACT_MODEL,
    CF_DAMP,
)
SWING_COLUMNS = np.array([c for c in range(N_CF) if c not in CONTACT_ONLY_COLUMNS], dtype=np.int64)

#: The rungs of the model ladder (``contact_model``, :data:`tennis_stroke.model.params.
#: MODEL_OPTIONS`) by their id in ``cf[CF_CONTACT_MODEL]``: the paper's spring contact
#: (with the damping of a ball that loses energy when ``restitution < 1``), the
#: instantaneous impact at ``phi = 0`` and the two swing-only criteria
#: (:mod:`tennis_stroke.model.impact`).
CONTACT_MODEL_IDS = {"spring": 0, "impact": 1, "swing_speed": 2, "swing_omega2": 3}
SPRING = 0

_COUPLING_FACTOR = {"newton": 1.0, "paper_eq8": 2.0}
#: m/s -> km/h (the paper quotes rebound speeds in km/h).
MS_TO_KMH = 3.6

#: numba options of every compiled function: cached on disk; numpy's float semantics
#: (division by zero gives inf/nan, the integrator rejects such steps).
JIT = {"cache": True, "error_model": "numpy", "no_cfunc_wrapper": True}
#: For the hot path: also allow fused multiply-add and multiplication by a reciprocal.
JIT_FAST = {**JIT, "fastmath": {"contract", "arcp"}}
#: For functions only compiled code calls: without the wrapper that lets Python call
#: them (compiling those wrappers cost about a fifth of the solver's cold compile).
JIT_INNER = {**JIT, "no_cpython_wrapper": True}
JIT_FAST_INNER = {**JIT_FAST, "no_cpython_wrapper": True}


def _is_choice(value: object) -> bool:
    """A reading's choice: a string, or an array of strings (one per stroke)."""
    return isinstance(value, str) or (isinstance(value, np.ndarray) and value.dtype.kind in "UO")


def _number_of(table: Mapping[str, float], choice) -> float | np.ndarray:
    """The number ``table`` gives a choice, or each of an array of choices (one per
    stroke).  (This module imports nothing of the package: tools/generate_kernels.py
    loads it alone.)"""
    return np.vectorize(table.__getitem__, otypes=[float])(choice)


def coefficients(params: Mapping[str, object], theta0_deg, delta0_deg) -> np.ndarray:
    """Pack resolved parameters and initial angles into per-stroke coefficient rows.

    Parameters
    ----------
    params : mapping
        Output of :func:`tennis_stroke.model.params.resolve_params` (scalars or arrays).
    theta0_deg, delta0_deg : array_like
        Initial angles ``theta(0)`` and ``delta(0) = phi(0) - theta(0)`` (degrees).

    Returns
    -------
    ndarray, shape (n_strokes, N_CF)
        One row per stroke, all arrays broadcast together and flattened (C order).
    """
    g = {k: np.asarray(v, dtype=float) for k, v in params.items() if not _is_choice(v)}
    th0 = np.radians(np.asarray(theta0_deg, dtype=float))
    ph0 = th0 + np.radians(np.asarray(delta0_deg, dtype=float))
    shape = np.broadcast_shapes(th0.shape, ph0.shape, *(v.shape for v in g.values()))
    h1, h2 = g["L1"] / 2.0, g["L2"] / 2.0
    psi = np.radians(g["psi_F_deg"])
    cols = {
        CF_L1: g["L1"],
        CF_LH: h2 + g["h_hit"],
        CF_M1: g["M1"],
        CF_M2: g["M2"],
        CF_H1: h1,
        CF_H2: h2,
        CF_I1: g["I1_cm"],
        CF_I2: g["I2_cm"],
        CF_M11: g["I1_cm"] + g["M1"] * h1**2 + g["M2"] * g["L1"] ** 2,
        CF_M22: g["I2_cm"] + g["M2"] * h2**2,
        CF_M12: g["M2"] * h2 * g["L1"],
        CF_A1: g["M1"] * h1 + g["M2"] * g["L1"],
        CF_A2: g["M2"] * h2,
        CF_C1: g["C1"],
        CF_C2: g["C2"],
        CF_TAU: g["tau"],
        CF_C2_OFF: g["C2_off"],
        CF_K: g["k_contact"],
        CF_MB: g["ball_mass"],
        CF_COUPLING: _number_of(_COUPLING_FACTOR, params["collision_coupling"]),
        CF_VX1: g["vx_t1"],
        CF_VX2: g["vx_t2"],
        CF_VY1: g["vy_t1"],
        CF_VY2: g["vy_t2"],
        CF_FX: g["F0"] * np.cos(psi) / g["elbow_force_mass"],
        CF_FY: g["F0"] * np.sin(psi) / g["elbow_force_mass"],
        CF_TF: g["t_F"],
        CF_TD: g["t_d"],
        CF_LEAD: g["contact_lead"],
        CF_VBALL: g["ball_speed"],
        CF_THETA0: th0,
        CF_PHI0: ph0,
        CF_FORCE_ON: (g["F0"] != 0.0).astype(float),
        CF_CONTACT_MODEL: _number_of(CONTACT_MODEL_IDS, params["contact_model"]),
        CF_DAMP: contact_damping(g["restitution"], g["ball_mass"], g["M2"], g["k_contact"]),
    }
    # The columns that are one value for every stroke go in as one row, copied to every
    # stroke at once; only the others are written column by column (strided writes,
    # most of this function's time on a large grid).
    if sorted(cols) != list(range(N_CF)):  # a column left out would silently stay 0
        raise AssertionError("coefficients(): the columns do not cover the layout")
    row = np.zeros(N_CF)
    varying = {}
    for col, val in cols.items():
        if np.ndim(val) == 0:
            row[col] = val
        else:
            varying[col] = val
    out = np.empty((*shape, N_CF))
    out[...] = row
    for col, val in varying.items():
        out[..., col] = val
    return out.reshape(-1, N_CF)


def damping_ratio(restitution):
    """Damping ratio ``zeta`` of a linear spring-dashpot whose two free bodies part with
    the coefficient of restitution ``restitution`` (separation at zero compression):
    ``e = exp(-pi zeta / sqrt(1 - zeta^2))``, so ``zeta = -ln e / sqrt(pi^2 + ln^2 e)``
    (0 for ``e = 1``)."""
    log_e = np.log(np.asarray(restitution, dtype=float))
    return -log_e / np.sqrt(np.pi**2 + log_e**2)


def contact_damping(restitution, ball_mass, racket_mass, k_contact):
    """Dashpot constant ``c = 2 zeta sqrt(k mu)`` (N s/m) of the contact (Eq. 12's
    two-body oscillator of the ball and a free racket: ``mu = m_b M2/(m_b + M2)``) that
    gives the coefficient of restitution ``restitution`` (:func:`damping_ratio`); exactly
    0 for an elastic ball (``restitution = 1``)."""
    mb, m2 = np.asarray(ball_mass, dtype=float), np.asarray(racket_mass, dtype=float)
    mu = mb * m2 / (mb + m2)
    return 2.0 * damping_ratio(restitution) * np.sqrt(np.asarray(k_contact, dtype=float) * mu)


@njit(**JIT_INNER)
def elbow_pulse(t, cf):
    """Acceleration of the extra elbow force, Eq. 14 divided by ``elbow_force_mass`` (m/s^2)."""
    u = (t - cf[CF_TF]) / cf[CF_TD]
    pulse = math.exp(-u * u)
    return cf[CF_FX] * pulse, cf[CF_FY] * pulse


@njit(**JIT)
def elbow_acceleration(t, cf):
    """Elbow acceleration ``(a_x, a_y)`` (m/s^2): derivative of Eq. 13 plus the Eq. 14 pulse."""
    ax = cf[CF_VX1] + 2.0 * cf[CF_VX2] * t
    ay = cf[CF_VY1] + 2.0 * cf[CF_VY2] * t
    if cf[CF_FORCE_ON] == 0.0:
        return ax, ay
    px, py = elbow_pulse(t, cf)
    return ax + px, ay + py


@njit(**JIT_INNER)
def _pulse_integrals(t, cf):
    """First and second time integrals from 0 of the Eq. 14 pulse ``exp(-((t-t_F)/t_d)^2)``."""
    td, tf = cf[CF_TD], cf[CF_TF]
    root_pi = math.sqrt(math.pi)
    u, u0 = (t - tf) / td, -tf / td
    first = 0.5 * root_pi * td * (math.erf(u) - math.erf(u0))
    antider_u = u * math.erf(u) + math.exp(-u * u) / root_pi
    antider_0 = u0 * math.erf(u0) + math.exp(-u0 * u0) / root_pi
    second = 0.5 * root_pi * td * (td * (antider_u - antider_0) - t * math.erf(u0))
    return first, second


@njit(**JIT)
def elbow_velocity(t, cf):
    """Elbow velocity ``(V_x, V_y)`` (m/s) at time ``t`` (s), zero at ``t = 0`` (Eq. 13)."""
    vx = (cf[CF_VX1] + cf[CF_VX2] * t) * t
    vy = (cf[CF_VY1] + cf[CF_VY2] * t) * t
    if cf[CF_FORCE_ON] == 0.0:
        return vx, vy
    first, _ = _pulse_integrals(t, cf)
    return vx + cf[CF_FX] * first, vy + cf[CF_FY] * first


@njit(**JIT)
def elbow_position(t, cf):
    """Elbow position ``(x_E, y_E)`` (m) at time ``t`` (s), the origin at ``t = 0``."""
    x = (0.5 * cf[CF_VX1] + cf[CF_VX2] * t / 3.0) * t * t
    y = (0.5 * cf[CF_VY1] + cf[CF_VY2] * t / 3.0) * t * t
    if cf[CF_FORCE_ON] == 0.0:
        return x, y
    _, second = _pulse_integrals(t, cf)
    return x + cf[CF_FX] * second, y + cf[CF_FY] * second


def rod_points(theta, phi, x_elbow, y_elbow, cf) -> dict[str, np.ndarray]:
    """The stick figure in the lab frame (m): the wrist (end of rod 1), the racket's end
    (end of rod 2) and the hitting point (``h2 + h_H`` along rod 2, Eq. 10), from the
    angles (rad, from ``-y``, counter-clockwise) and the elbow's position; numpy arrays
    broadcast.  ``cf``: one stroke's coefficients (:func:`coefficients`)."""
    st, ct, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    l1, l2 = cf[CF_L1], 2.0 * cf[CF_H2]
    x_w, y_w = x_elbow + l1 * st, y_elbow - l1 * ct
    return {
        "x_wrist": x_w,
        "y_wrist": y_w,
        "x_racket": x_w + l2 * sp,
        "y_racket": y_w - l2 * cp,
        "x_hit": x_w + cf[CF_LH] * sp,
        "y_hit": y_w - cf[CF_LH] * cp,
    }


def rod_velocities(theta, phi, omega1, omega2, vx_elbow, vy_elbow, cf) -> dict[str, np.ndarray]:
    """Lab-frame velocities (m/s) of the points of :func:`rod_points`: the time
    derivatives of their positions, with ``dtheta/dt = -omega1`` and ``dphi/dt = -omega2``
    (rad/s, clockwise positive) and the elbow's velocity (:func:`elbow_velocity`); numpy
    arrays broadcast.  Along x the hitting point's velocity relative to the elbow is the
    ``-(L1 omega1 cos(theta) + (h2 + h_H) omega2 cos(phi))`` of :func:`approach_rate`."""
    st, ct, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    l1, l2 = cf[CF_L1], 2.0 * cf[CF_H2]
    # d/dt of (L sin(a), -L cos(a)) is L (cos(a), sin(a)) da/dt, with da/dt = -omega
    vx_w, vy_w = vx_elbow - l1 * omega1 * ct, vy_elbow - l1 * omega1 * st
    return {
        "vx_wrist": vx_w,
        "vy_wrist": vy_w,
        "vx_racket": vx_w - l2 * omega2 * cp,
        "vy_racket": vy_w - l2 * omega2 * sp,
        "vx_hit": vx_w - cf[CF_LH] * omega2 * cp,
        "vy_hit": vy_w - cf[CF_LH] * omega2 * sp,
    }


def ball_in_lab(s, w, x_elbow, vx_elbow):
    """The ball's position ``x_b`` (m) and velocity ``v_b`` (m/s) along x in the lab frame
    from its state relative to the elbow, ``s = x_b - x_E`` and ``w = v_b - V_x^E``, and
    the elbow's ``x_E``, ``V_x^E``; numpy arrays broadcast."""
    return x_elbow + s, vx_elbow + w


@njit(**JIT)
def next_switch(t, cf, t_limit):
    """First switch of the wrist torque (``tau`` or ``C2_off``) after ``t`` (s), or
    ``t_limit``: the torque schedule's phase boundaries."""
    nxt = t_limit
    for s in (cf[CF_TAU], cf[CF_C2_OFF]):
        if t < s < nxt:
            nxt = s
    return nxt


@njit(**JIT)
def wrist_torque(t_a, t_b, cf):
    """Wrist torque (N m) on an interval ``(t_a, t_b)`` that contains no switch: ``C2``
    from ``tau`` until ``C2_off``, else 0."""
    mid = 0.5 * (t_a + t_b)
    return cf[CF_C2] if cf[CF_TAU] <= mid < cf[CF_C2_OFF] else 0.0


@njit(**JIT_FAST)
def rhs_trig(t, y, cf, c2, contact):
    """Right-hand side ``dy/dt`` in the trig layout: Eqs. 6-8 from the Lagrangian.

    Parameters
    ----------
    t : float
        Time (s).
    y : tuple of 10 float
        ``sin(theta), cos(theta), sin(phi), cos(phi), omega1, omega2, theta, phi, s, w``.
    cf : tuple or ndarray, length N_CF
        Stroke coefficients (:func:`coefficients`).
    c2 : float
        Wrist torque in this phase (N m); the phase driver switches it at ``tau``.
    contact : bool
        Whether the ball spring acts (constant over a phase; a run-time flag of the
        compiled kernels, one kernel for both phases).  Outside contact the ball
        derivatives are 0.

    Returns
    -------
    tuple of 10 float

    Notes
    -----
    With ``M11 = I1 + M1 h1^2 + M2 L1^2``, ``M22 = I2 + M2 h2^2``, ``M12 = M2 h2 L1``::

        M11 w1' + M12 cos(phi-theta) w2' = P + P_col
        M12 cos(phi-theta) w1' + M22 w2' = Q + Q_col

    with P, Q of Eq. 7 and the generalised forces of the ball's force ``F_r`` (+x) on
    the racket at the hitting point, ``P_col = -F_r L1 cos(theta)``, ``Q_col = -F_r
    (h2+h_H) cos(phi)``.  Solving gives Eq. 6 with ``S_1, S_2`` equal to half of Eq. 8
    as printed (``docs/equations.md``; ``collision_coupling="paper_eq8"`` doubles
    ``F_r``).  The spring force on the ball is ``-k (x_b - x_H)`` (Eqs. 9-11); the ball
    also feels the fictitious force ``-m_b a_E`` of the elbow frame.  A ball that loses
    energy (``restitution < 1``) adds the dashpot force ``-c d(x_b - x_H)/dt``
    (:func:`contact_damping`; ``c = 0`` for the paper's elastic ball: the term is skipped).

    The elbow acceleration is written out here rather than calling
    :func:`elbow_acceleration`: a numba call costs as much as this whole function
    (``tests/model/test_dynamics.py`` checks the two agree).
    """
    st, ct, sp, cp, w1, w2, _, _, s, w = y
    ax = cf[CF_VX1] + 2.0 * cf[CF_VX2] * t
    ay = cf[CF_VY1] + 2.0 * cf[CF_VY2] * t
    if cf[CF_FORCE_ON] != 0.0:
        px, py = elbow_pulse(t, cf)
        ax += px
        ay += py
    sd = sp * ct - cp * st  # sin(phi - theta)
    cd = cp * ct + sp * st  # cos(phi - theta)
    m12 = cf[CF_M12]
    p = cf[CF_C1] - c2 - m12 * w2 * w2 * sd + cf[CF_A1] * (ax * ct + ay * st)
    q = c2 + m12 * w1 * w1 * sd + cf[CF_A2] * (ax * cp + ay * sp)
    ds = 0.0
    dw = 0.0
    if contact:
        force_on_ball = -cf[CF_K] * (s - (cf[CF_L1] * st + cf[CF_LH] * sp))
        if cf[CF_DAMP] != 0.0:  # a ball that loses energy: the dashpot of ``restitution``
            force_on_ball -= cf[CF_DAMP] * (w + cf[CF_L1] * w1 * ct + cf[CF_LH] * w2 * cp)
        force_on_racket = -force_on_ball * cf[CF_COUPLING]
        p -= force_on_racket * cf[CF_L1] * ct
        q -= force_on_racket * cf[CF_LH] * cp
        ds = w
        dw = force_on_ball / cf[CF_MB] - ax
    m11, m22 = cf[CF_M11], cf[CF_M22]
    mc = m12 * cd
    det = m11 * m22 - mc * mc
    return (
        -w1 * ct,
        w1 * st,
        -w2 * cp,
        w2 * sp,
        (p * m22 - q * mc) / det,
        (q * m11 - p * mc) / det,
        -w1,
        -w2,
        ds,
        dw,
    )


@njit(**JIT)
def hit_offset(st, sp, cf):
    """``x_H - x_E``: the hitting point relative to the elbow along x (m), Eq. 10."""
    return cf[CF_L1] * st + cf[CF_LH] * sp


@njit(**JIT_INNER)
def swing_event(y, cf):
    """``phi`` (rad), trig layout: the free swing ends where it falls through 0 (``t0``)."""
    return y[PHI]


@njit(**JIT)
def compression(y, cf):
    """Compression ``x_b - x_H`` of the strings (m), trig layout: positive while the ball
    presses on them; the contact ends where it falls through 0 (separation)."""
    return y[BALL_S] - hit_offset(y[SIN_TH], y[SIN_PH], cf)


@njit(**JIT)
def swing_event_angles(y, cf):
    """:func:`swing_event` in the angle layout: ``phi`` (rad)."""
    return y[A_PHI]


@njit(**JIT)
def compression_angles(y, cf):
    """:func:`compression` in the angle layout (m)."""
    return y[A_BALL_S] - hit_offset(math.sin(y[A_THETA]), math.sin(y[A_PHI]), cf)


@njit(**JIT)
def incoming_ball(t, st, sp, cf):
    """Ball state ``(s, w)`` relative to the elbow at the contact start ``t`` (s): at the
    hitting point (zero compression), moving at ``ball_speed`` along +x (lab frame)."""
    return hit_offset(st, sp, cf), cf[CF_VBALL] - elbow_velocity(t, cf)[0]


@njit(**JIT)
def rebound_speed_kmh(t, w, cf):
    """Speed of the ball towards ``-x`` (km/h), lab frame, from its velocity ``w`` (m/s)
    relative to the elbow at time ``t`` (s)."""
    return -MS_TO_KMH * (w + elbow_velocity(t, cf)[0])


@njit(**JIT)
def to_trig(y_angles):
    """Angle layout (4 or 6 components) -> trig-layout tuple of 10."""
    th, ph = y_angles[A_THETA], y_angles[A_PHI]
    s = y_angles[A_BALL_S] if y_angles.size > 4 else 0.0
    w = y_angles[A_BALL_W] if y_angles.size > 4 else 0.0
    return (
        math.sin(th),
        math.cos(th),
        math.sin(ph),
        math.cos(ph),
        y_angles[A_OMEGA1],
        y_angles[A_OMEGA2],
        th,
        ph,
        s,
        w,
    )


def to_angles(y_trig) -> np.ndarray:
    """Trig-layout tuple of 10 -> angle-layout array of 6 (contact state)."""
    return np.array(
        [
            y_trig[THETA],
            y_trig[PHI],
            y_trig[OMEGA1],
            y_trig[OMEGA2],
            y_trig[BALL_S],
            y_trig[BALL_W],
        ]
    )


@njit(**JIT)
def rhs_angles(t, y, cf, c2, contact, dydt):
    """``dy/dt`` in the angle layout (reference path): :func:`rhs_trig` plus the kinematics
    ``d theta/dt = -omega1``, ``d phi/dt = -omega2``.

    ``y`` has 4 components (free swing) or 6 (contact); ``dydt`` is written in place.
    """
    d = rhs_trig(t, to_trig(y), cf, c2, contact)
    dydt[A_THETA] = -y[A_OMEGA1]
    dydt[A_PHI] = -y[A_OMEGA2]
    dydt[A_OMEGA1] = d[OMEGA1]
    dydt[A_OMEGA2] = d[OMEGA2]
    if y.size > 4:
        dydt[A_BALL_S] = d[BALL_S]
        dydt[A_BALL_W] = d[BALL_W]


def angle_rhs(cf, c2: float, contact: bool):
    """The right-hand side of :func:`rhs_angles` as ``f(t, y) -> dy/dt`` (a new array),
    for generic integrators (``solve_ivp``, fixed-step RK4) in one phase with wrist torque
    ``c2`` (N m)."""

    def fun(t, y):
        dydt = np.empty_like(y)
        rhs_angles(t, y, cf, c2, contact, dydt)
        return dydt

    return fun


@njit(**JIT)
def approach_rate(st, ct, sp, cp, w1, w2, w, cf):
    """Rate of change of the compression ``x_b - x_H`` (m/s) for a free ball.

    ``w`` is the ball velocity relative to the elbow (m/s); positive: closing in.
    """
    return w + cf[CF_L1] * w1 * ct + cf[CF_LH] * w2 * cp


@njit(**JIT)
def effective_mass(st, ct, sp, cp, cf):
    """Racket mass felt by the ball at the hitting point along x (kg), ``1/(J M^-1 J^T)``."""
    j1 = cf[CF_L1] * ct
    j2 = cf[CF_LH] * cp
    mc = cf[CF_M12] * (cp * ct + sp * st)
    m11, m22 = cf[CF_M11], cf[CF_M22]
    det = m11 * m22 - mc * mc
    return det / (m22 * j1 * j1 - 2.0 * mc * j1 * j2 + m11 * j2 * j2)


@njit(**JIT)
def contact_duration(st, ct, sp, cp, cf):
    """Two-body contact duration ``pi sqrt(mu/k)`` (s) at the hitting point.

    ``mu`` is the reduced mass of the ball and the racket's :func:`effective_mass`; the
    solvers cap their contact steps at a fraction of it, so no contact is stepped over.
    """
    m = effective_mass(st, ct, sp, cp, cf)
    mu = cf[CF_MB] * m / (cf[CF_MB] + m)
    return math.pi * math.sqrt(mu / cf[CF_K])


@njit(**JIT)
def mechanical_energy(t, y, cf, contact):
    """Kinetic energy of both rods and the ball plus the spring energy, lab frame (J).

    ``y`` in the angle layout; the ball counts only in ``contact``.
    """
    th, ph, w1, w2 = y[A_THETA], y[A_PHI], y[A_OMEGA1], y[A_OMEGA2]
    vex, vey = elbow_velocity(t, cf)
    l1, h1, h2 = cf[CF_L1], cf[CF_H1], cf[CF_H2]
    v1x = vex - h1 * w1 * math.cos(th)
    v1y = vey - h1 * w1 * math.sin(th)
    v2x = vex - l1 * w1 * math.cos(th) - h2 * w2 * math.cos(ph)
    v2y = vey - l1 * w1 * math.sin(th) - h2 * w2 * math.sin(ph)
    energy = 0.5 * (cf[CF_M1] * (v1x * v1x + v1y * v1y) + cf[CF_I1] * w1 * w1)
    energy += 0.5 * (cf[CF_M2] * (v2x * v2x + v2y * v2y) + cf[CF_I2] * w2 * w2)
    if contact:
        vb = y[A_BALL_W] + vex
        c = compression_angles(y, cf)
        energy += 0.5 * cf[CF_MB] * vb * vb + 0.5 * cf[CF_K] * c * c
    return energy


@njit(**JIT)
def compression_rate_angles(y, cf):
    """``d(x_b - x_H)/dt`` (m/s) in the angle layout (contact state)."""
    th, ph = y[A_THETA], y[A_PHI]
    return (
        y[A_BALL_W]
        + cf[CF_L1] * y[A_OMEGA1] * math.cos(th)
        + cf[CF_LH] * y[A_OMEGA2] * (math.cos(ph))
    )


@njit(**JIT)
def contact_force_angles(y, cf):
    """Force of the ball on the racket along +x (N), angle layout: the spring's
    ``k (x_b - x_H)`` plus the dashpot's ``c d(x_b - x_H)/dt`` (Newton's third law)."""
    return cf[CF_K] * compression_angles(y, cf) + cf[CF_DAMP] * compression_rate_angles(y, cf)


@njit(**JIT)
def dissipated_power(y, cf):
    """Power the dashpot of a lossy ball takes out of the contact (W), angle layout:
    ``c (d(x_b - x_H)/dt)^2`` (0 for the elastic ball)."""
    rate = compression_rate_angles(y, cf)
    return cf[CF_DAMP] * rate * rate


@njit(**JIT)
def input_power(t, y, cf, c2, contact):
    """Power delivered by the joint torques and by the elbow drive (W), angle layout.

    The torques give ``C1 w1 + C2 (w2 - w1)``; the elbow pushes the pendulum with the
    joint force ``F_E = M1 a1 + M2 a2 - F_r x`` (accelerations of the rod centres, lab
    frame) at the elbow velocity ``V_E``.  Its time integral equals the change of
    :func:`mechanical_energy` when the equations of motion are right.
    """
    dydt = np.empty(y.size)
    rhs_angles(t, y, cf, c2, contact, dydt)
    th, ph, w1, w2 = y[A_THETA], y[A_PHI], y[A_OMEGA1], y[A_OMEGA2]
    dw1, dw2 = dydt[A_OMEGA1], dydt[A_OMEGA2]
    ax, ay = elbow_acceleration(t, cf)
    vex, vey = elbow_velocity(t, cf)
    st, ct, sp, cp = math.sin(th), math.cos(th), math.sin(ph), math.cos(ph)
    l1, h1, h2 = cf[CF_L1], cf[CF_H1], cf[CF_H2]
    # d/dt of (-h w cos, -h w sin): -h w' (cos, sin) - h w^2 (sin, -cos)
    a1x = ax - h1 * (dw1 * ct + w1 * w1 * st)
    a1y = ay - h1 * (dw1 * st - w1 * w1 * ct)
    a2x = ax - l1 * (dw1 * ct + w1 * w1 * st) - h2 * (dw2 * cp + w2 * w2 * sp)
    a2y = ay - l1 * (dw1 * st - w1 * w1 * ct) - h2 * (dw2 * sp - w2 * w2 * cp)
    fex = cf[CF_M1] * a1x + cf[CF_M2] * a2x
    fey = cf[CF_M1] * a1y + cf[CF_M2] * a2y
    if contact:
        fex -= contact_force_angles(y, cf) * cf[CF_COUPLING]
    return cf[CF_C1] * w1 + c2 * (w2 - w1) + fex * vex + fey * vey
