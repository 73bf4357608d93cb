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
#: File name of a result field where it differs from the field's name.
FILE_NAMES = {"v_out_kmh": "v_out"}

_SPEED = "km/h"
#: Every other variable and coordinate written to a result file: name -> (unit, long
#: name).  Together with :data:`RESULT_FIELDS` (under their file names) the one table of
#: CF metadata; :func:`cf_attrs` reads it.
OTHER_VARIABLES: dict[str, tuple[str, str]] = {
    # grid axes and stroke coordinates
    "theta0": ("degree", "initial rod-1 angle theta(0) from -y"),
    "delta0": ("degree", "initial angle delta(0) = phi(0) - theta(0) between the rods"),
    "M2": ("kg", "mass of rod 2 (hand+racket)"),
    "L1": ("m", "length of rod 1 (elbow to hand, projected)"),
    "C2": ("N m", "wrist torque C2"),
    "tau": ("s", "delay of the wrist torque C2"),
    "psi_F": ("degree", "direction of the elbow force from +x"),
    "tau_F": ("s", "delay of the force pulse after tau_H"),
    "F0": ("N", "amplitude of the elbow force (Eq. 14)"),
    "stroke": ("1", "stroke index"),
    "label": ("1", "stroke label"),
    # The time axis of the sampled strokes is named "t", not "time": it is the time since
    # the stroke starts, without an epoch, for which CF defines no standard name (standard
    # name "time" needs units "<unit> since <epoch>", CF 4.4, which xarray would decode as
    # dates), and the CF checker asks standard name "time" of any axis named "time" (5.1).
    "t": ("s", "time since the stroke starts"),
    # optima of the maps
    "best_delta0": ("degree", "delta0 of the fastest rebound"),
    "best_tau": ("s", "delay of the fastest rebound"),
    "best_v_out": (_SPEED, "fastest rebound speed"),
    "v_out_tau0": (_SPEED, "rebound speed at tau = 0"),
    "v_out_best": (_SPEED, "fastest rebound speed over the initial angles"),
    "theta0_best": ("degree", "theta0 of the fastest rebound"),
    "delta0_best": ("degree", "delta0 of the fastest rebound"),
    "theta_c": ("degree", "|theta| at phi = 0 of the fastest rebound"),
    "failed_strokes": ("1", "failed strokes of the optimum search at this point"),
    # curves of single strokes
    "omega1": ("rad/s", "rod-1 angular velocity (clockwise)"),
    "omega2": ("rad/s", "rod-2 angular velocity (clockwise)"),
    "theta": ("degree", "rod-1 angle from -y"),
    "phi": ("degree", "rod-2 angle from -y"),
    "x_elbow": ("m", "elbow x position"),
    "y_elbow": ("m", "elbow y position"),
    # speed-against-accuracy studies
    "method": ("1", "integrator"),
    "setting": ("1", "tolerance rtol = atol, or RK4 step (s)"),
    "error_kmh": (_SPEED, "largest |v_out error|"),
    "us_per_stroke": ("us", "cost per stroke, one thread"),
    "rhs_evals_per_stroke": ("1", "right-hand-side evaluations per stroke (mean)"),
    "failed": ("1", "strokes without status ok"),
    "case": ("1", "method @ setting"),
    "k_contact": ("N/m", "spring constant"),
    "outcome": ("1", "outcome code (see flag_meanings)"),
    "v_exit": ("m/s", "ball velocity after separation (lab frame, along x)"),
    "duration": ("s", "contact duration"),
    "energy_change": ("1", "relative change of the mechanical energy"),
    "expected_duration": ("s", "two-body contact duration pi sqrt(mu/k)"),
    "v_out_spring": (_SPEED, "v_out, spring contact (paper)"),
    "v_out_impact": (_SPEED, "v_out, instantaneous impact at phi=0"),
    "search": ("1", "steps"),
    "v_err": (_SPEED, "largest error of the best v_out"),
    "theta0_err": ("degree", "largest error of the best theta0"),
    "delta0_err": ("degree", "largest error of the best delta0"),
    "seconds": ("s", "wall time of the search over all points (all threads)"),
}
VARIABLES: dict[str, tuple[str, str]] = {
    **{FILE_NAMES.get(k, k): (unit, name) for k, (_, unit, name) in RESULT_FIELDS.items()},
    **OTHER_VARIABLES,
}


def cf_attrs(name: str, **extra) -> dict[str, object]:
    """``units`` and ``long_name`` of the file variable ``name`` (:data:`VARIABLES`), with
    ``extra`` attributes."""
    units, long_name = VARIABLES[name]
    return {"units": units, "long_name": long_name, **extra}


#: Result fields that count (integers in files and in the command line's output).
COUNT_FIELDS = ("status", "rhs_evals", "steps")


def results_from_output(out: np.ndarray, shape: tuple[int, ...]) -> dict[str, np.ndarray]:
    """Named result arrays of ``shape`` from compiled output rows (angles in degrees)."""
    res = {}
    for name, (col, _, _) in RESULT_FIELDS.items():
        values = out[:, col].reshape(shape)
        if name in COUNT_FIELDS:
            values = values.astype(np.int64)
        elif name in _DEGREE_FIELDS:
            values = np.degrees(values)
        res[name] = values
    return res
