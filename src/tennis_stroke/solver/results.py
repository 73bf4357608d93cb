"""What a stroke returns: status codes, the compiled output columns, and the one table
of every variable written to a result file, with its unit and long name.

Every writer (:mod:`tennis_stroke.io`, the experiments, the studies) takes ``units`` and
``long_name`` from :data:`VARIABLES`; the per-stroke result fields of
:data:`RESULT_FIELDS` are the first rows of it.  A result field keeps its name in files,
except the renames of :data:`FILE_NAMES`.
"""

from __future__ import annotations

import numpy as np

# Statuses of a stroke.
OK, NO_PHI_ZERO, EARLY_CONTACT, NO_APPROACH, NO_RELEASE, STEP_FAILURE, LEAD_TOO_LONG = range(7)
#: Status codes and their meanings (written to every result file).
STATUS_NAMES = {
    OK: "ok",
    NO_PHI_ZERO: "no_phi_zero",  # phi never reached 0 before t_max
    EARLY_CONTACT: "early_contact",  # t0 - contact_lead < 0
    NO_APPROACH: "no_approach",  # at contact start the racket does not approach the ball
    NO_RELEASE: "no_release",  # the ball was not released before t_max
    STEP_FAILURE: "step_failure",  # step size underflow, too many steps, non-finite state
    LEAD_TOO_LONG: "lead_too_long",  # contact_lead spans more swing steps than recorded
}

# Output columns of the compiled solver.
(
    O_STATUS,
    O_VOUT,
    O_T_PHI0,
    O_T_CONTACT,
    O_T_SEP,
    O_THETA_PHI0,
    O_W1_PHI0,
    O_W2_PHI0,
    O_THETA_CONTACT,
    O_W1_CONTACT,
    O_W2_CONTACT,
    O_W2_MAX,
    O_NFEV,
    O_NSTEP,
) = range(14)
N_OUT = 14

#: Result fields: name -> (output column, unit, long name).  The one table of CF metadata.
RESULT_FIELDS: dict[str, tuple[int, str, str]] = {
    "status": (O_STATUS, "1", "stroke status code (see attribute flag_meanings)"),
    "v_out_kmh": (O_VOUT, "km/h", "rebound speed of the ball towards -x"),
    "t_phi0": (O_T_PHI0, "s", "time at which phi reaches 0 in the free swing (t0)"),
    "t_contact_start": (O_T_CONTACT, "s", "time at which ball contact starts (t_c)"),
    "t_separation": (O_T_SEP, "s", "time at which the ball leaves the strings"),
    "theta_deg_at_phi0": (O_THETA_PHI0, "degree", "rod-1 angle theta at phi = 0"),
    "omega1_phi0": (O_W1_PHI0, "rad/s", "rod-1 angular velocity at phi = 0"),
    "omega2_phi0": (O_W2_PHI0, "rad/s", "rod-2 angular velocity at phi = 0"),
    "theta_deg_contact": (O_THETA_CONTACT, "degree", "rod-1 angle theta at contact start"),
    "omega1_contact": (O_W1_CONTACT, "rad/s", "rod-1 angular velocity at contact start"),
    "omega2_contact": (O_W2_CONTACT, "rad/s", "rod-2 angular velocity at contact start"),
    "omega2_max": (O_W2_MAX, "rad/s", "maximum rod-2 angular velocity over the stroke"),
    "rhs_evals": (O_NFEV, "1", "right-hand-side evaluations of the stroke"),
    "steps": (O_NSTEP, "1", "accepted integration steps of the stroke"),
}
_DEGREE_FIELDS = ("theta_deg_at_phi0", "theta_deg_contact")


def results_from_output(out: np.ndarray, shape: tuple[int, ...]) -> dict[str, np.ndarray]:
    """Named result arrays of ``shape`` from compiled output rows (angles in degrees)."""
    res = {}
    for name, (col, _, _) in RESULT_FIELDS.items():
        values = out[:, col].reshape(shape)
        if name in ("status", "rhs_evals", "steps"):
            values = values.astype(np.int64)
        elif name in _DEGREE_FIELDS:
            values = np.degrees(values)
        res[name] = values
    return res
