"""The cheapest rung of the model ladder: an instantaneous elastic impact.

Instead of the spring contact (Eqs. 9-12), the ball meets the racket at ``phi = 0`` (the
paper's ``t0``) in a perfectly elastic collision with the racket's effective mass at the
hitting point (:func:`~tennis_stroke.model.dynamics.effective_mass`, from the inertia
matrix), which moves with the hitting point's velocity along x.  Only the swing is
needed.
"""

from __future__ import annotations

import math

from .dynamics import CF_L1, CF_LH, CF_MB, CF_VBALL, MS_TO_KMH, effective_mass, elbow_velocity


def impact_rebound_kmh(theta_rad: float, omega1: float, omega2: float, t0: float, cf) -> float:
    """Rebound speed towards ``-x`` (km/h) of the elastic impact at ``phi = 0``.

    Parameters
    ----------
    theta_rad : float
        Rod-1 angle at ``phi = 0`` (rad).
    omega1, omega2 : float
        Angular velocities there (rad/s, clockwise positive).
    t0 : float
        Time of ``phi = 0`` (s).
    cf : ndarray
        Stroke coefficients.

    Notes
    -----
    With the effective mass ``m``, the hitting point's velocity ``v_H`` and the ball's
    ``v_b`` (both along x), the ball leaves with ``((m_b - m) v_b + 2 m v_H) / (m_b + m)``.
    """
    st, ct = math.sin(theta_rad), math.cos(theta_rad)
    m = effective_mass(st, ct, 0.0, 1.0, cf)
    v_hit = elbow_velocity(t0, cf)[0] - cf[CF_L1] * omega1 * ct - cf[CF_LH] * omega2
    mb = cf[CF_MB]
    return -MS_TO_KMH * ((mb - m) * cf[CF_VBALL] + 2.0 * m * v_hit) / (mb + m)
