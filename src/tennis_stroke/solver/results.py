"""What a stroke returns: status codes, the compiled output columns and the result
fields read from them.

A result field keeps its name in files, except the renames of :data:`FILE_NAMES`.  The
units and long names of every variable written to a file are not here but in
:mod:`tennis_stroke.io.units`: this module is part of the compiled solver (its cache key,
:mod:`tennis_stroke._cache`), so a new long name must not recompile it.
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

#: Result fields: name -> output column of the compiled solver.  Their units and long
#: names are in the one table of them, :data:`tennis_stroke.io.units.VARIABLES`.
RESULT_FIELDS: dict[str, int] = {
    "status": O_STATUS,
    "v_out_kmh": O_VOUT,
    "t_phi0": O_T_PHI0,
    "t_contact_start": O_T_CONTACT,
    "t_separation": O_T_SEP,
    "theta_deg_at_phi0": O_THETA_PHI0,
    "omega1_phi0": O_W1_PHI0,
    "omega2_phi0": O_W2_PHI0,
    "theta_deg_contact": O_THETA_CONTACT,
    "omega1_contact": O_W1_CONTACT,
    "omega2_contact": O_W2_CONTACT,
    "omega2_max": O_W2_MAX,
    "rhs_evals": O_NFEV,
    "steps": O_NSTEP,
}
#: Result fields in degrees (the compiled solver returns radians).
DEGREE_FIELDS = ("theta_deg_at_phi0", "theta_deg_contact")
#: File name of a result field where it differs from the field's name.
FILE_NAMES = {"v_out_kmh": "v_out"}

#: Result fields that count (integers in files and in the command line's output).
COUNT_FIELDS = ("status", "rhs_evals", "steps")


def results_from_output(out: np.ndarray, shape: tuple[int, ...]) -> dict[str, np.ndarray]:
    """Named result arrays of ``shape`` from compiled output rows (angles in degrees)."""
    res = {}
    for name, col in RESULT_FIELDS.items():
        values = out[:, col].reshape(shape)
        if name in COUNT_FIELDS:
            values = values.astype(np.int64)
        elif name in DEGREE_FIELDS:
            values = np.degrees(values)
        res[name] = values
    return res
