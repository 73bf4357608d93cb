"""The cheap rungs of the model ladder: the ball meets the racket at ``phi = 0`` (the
paper's ``t0``) in no time, so only the swing is integrated.

* ``impact``: an instantaneous collision with the racket's effective mass at the hitting
  point (:func:`~tennis_stroke.model.dynamics.effective_mass`, from the inertia matrix),
  which moves with the hitting point's velocity along x.  It is the limit of a stiff
  spring contact with the same ball and the same reading of the collision force: the
  closing speed reverses with the coefficient of restitution the contact's dashpot gives
  at that mass (:func:`impact_restitution`; 1 for the elastic ball), and the racket takes
  the collision impulse times the coupling factor (1: Newton's third law; 2: Eq. 8 as
  printed, ``collision_coupling="paper_eq8"``).  The impulse changes the rods' angular
  velocities, so the follow-through goes on from them.
* ``swing_speed``: no ball at all; the swing is scored by the speed of the hitting point
  along x at ``phi = 0``, ``v_H`` (negative: towards ``-x``), written as the speed of a
  ball that rebounds elastically from a racket too heavy to slow down: ``v_out = v_ball -
  2 v_H`` (the ``m -> infinity`` limit of the impact).
* ``swing_omega2``: no ball; the swing is scored by the racket's angular velocity
  ``omega2`` at ``phi = 0`` (Cross's criterion, the paper's ref. [9]), written as the same
  rebound from a heavy racket turning about a fixed wrist: ``v_out = 2 (h2 + h_H)
  omega2 + v_ball``.

The two swing rungs give speeds only to share the claims' measurements: any increasing
function of their criterion has the same optima, thresholds and trends, so a claim that
quotes a ball speed or a ratio of speeds has no answer under them
(:mod:`tennis_stroke.inference.ladder`).  Conventions as in
:mod:`tennis_stroke.model.dynamics`.
"""

from __future__ import annotations

import math

from numba import njit

from .dynamics import (
    CF_CONTACT_MODEL,
    CF_COUPLING,
    CF_DAMP,
    CF_K,
    CF_L1,
    CF_LH,
    CF_M11,
    CF_M12,
    CF_M22,
    CF_MB,
    CF_VBALL,
    COS_PH,
    COS_TH,
    JIT,
    MS_TO_KMH,
    OMEGA1,
    OMEGA2,
    SIN_PH,
    SIN_TH,
    effective_mass,
    elbow_velocity,
)

IMPACT, SWING_SPEED, SWING_OMEGA2 = 1, 2, 3


@njit(**JIT)
def impact_restitution(mu, cf):
    """Coefficient of restitution of the contact's dashpot (``c = cf[CF_DAMP]``, spring
    ``k``) for a relative motion of reduced mass ``mu`` (kg): ``exp(-pi zeta /
    sqrt(1 - zeta^2))`` with ``zeta = c / (2 sqrt(k mu))``, 0 if overdamped (the ball does
    not come back off the strings), exactly 1 without a dashpot.  The restitution a user
    sets (``restitution``) is this at Eq. 12's reduced mass of the ball and a free racket
    (:func:`tennis_stroke.model.dynamics.contact_damping`); at the racket's effective mass it
    differs (the ball's losses do not depend on the racket, its restitution does)."""
    zeta = cf[CF_DAMP] / (2.0 * math.sqrt(cf[CF_K] * mu))
    if zeta >= 1.0:
        return 0.0
    return math.exp(-math.pi * zeta / math.sqrt(1.0 - zeta * zeta))


@njit(**JIT)
def instant_contact(t, y, cf):
    """The cheap rungs' collision at ``t`` (s) in the state ``y`` (trig layout, at
    ``phi = 0``): ``(v_out_kmh, omega1, omega2)``, the ball's speed towards ``-x`` (km/h)
    and the rods' angular velocities (rad/s) after it.

    Notes
    -----
    With the hitting point's Jacobian ``j = (L1 cos(theta), (h2+h_H) cos(phi))`` (its
    velocity along x is ``V_x^E - j . omega``), the effective mass ``m = 1/(j M^-1 j^T)``,
    the coupling factor ``g`` (the racket feels ``g`` times the force on the ball), the
    reduced mass of the relative motion ``mu = 1/(1/m_b + g/m)`` and the closing speed
    ``u = v_b - v_H``, the ball takes the impulse ``J = -(1 + e) mu u`` and the racket
    ``-g J`` at the hitting point, which changes the angular velocities by ``g M^-1 j^T
    J`` (``M``: the rods' inertia matrix of Eq. 6).  The closing speed after is ``-e u``;
    with Newton's third law (``g = 1``) momentum along x at the hitting point is kept.
    """
    model = cf[CF_CONTACT_MODEL]
    st, ct, sp, cp = y[SIN_TH], y[COS_TH], y[SIN_PH], y[COS_PH]
    w1, w2 = y[OMEGA1], y[OMEGA2]
    v_ball = cf[CF_VBALL]
    if model == SWING_OMEGA2:
        return MS_TO_KMH * (2.0 * cf[CF_LH] * w2 + v_ball), w1, w2
    j1, j2 = cf[CF_L1] * ct, cf[CF_LH] * cp
    v_hit = elbow_velocity(t, cf)[0] - j1 * w1 - j2 * w2
    if model == SWING_SPEED:
        return MS_TO_KMH * (v_ball - 2.0 * v_hit), w1, w2
    m = effective_mass(st, ct, sp, cp, cf)
    mb, g = cf[CF_MB], cf[CF_COUPLING]
    mu = mb * m / (m + g * mb)
    impulse = -(1.0 + impact_restitution(mu, cf)) * mu * (v_ball - v_hit)  # on the ball, x
    # M dw = g j J (the racket's impulse -g J acts against the hitting point's -j . omega)
    mc = cf[CF_M12] * (cp * ct + sp * st)
    m11, m22 = cf[CF_M11], cf[CF_M22]
    det = m11 * m22 - mc * mc
    dw1 = (m22 * j1 - mc * j2) * g * impulse / det
    dw2 = (m11 * j2 - mc * j1) * g * impulse / det
    return -MS_TO_KMH * (v_ball + impulse / mb), w1 + dw1, w2 + dw2
