"""The one table of units and long names of every variable and coordinate written to a
result file (CF ``units`` and ``long_name``), and :func:`cf_attrs`, which every writer
(:mod:`tennis_stroke.io.netcdf`, the experiments, the studies, the inference) uses.

Metadata only: no compiled module imports it, so editing a long name recompiles nothing.
The model parameters that are file axes take their unit and label from the parameter
table.
"""

from __future__ import annotations

from ..model.params import PARAMETERS

_SPEED = "km/h"
#: The model parameters that are axes of result files: their unit and label are the
#: parameter table's (:data:`tennis_stroke.model.params.PARAMETERS`), written once.
_PARAMETER_AXES = ("M2", "L1", "C2", "tau", "F0", "k_contact")
#: The stroke result fields (:data:`tennis_stroke.solver.results.RESULT_FIELDS`) under
#: their file names: name -> (unit, long name).
RESULT_VARIABLES: dict[str, tuple[str, str]] = {
    "status": ("1", "stroke status code (see attribute flag_meanings)"),
    "v_out": (_SPEED, "rebound speed of the ball towards -x"),
    "t_phi0": ("s", "time at which phi reaches 0 in the free swing (t0)"),
    "t_contact_start": ("s", "time at which ball contact starts (t_c)"),
    "t_separation": ("s", "time at which the ball leaves the strings"),
    "theta_deg_at_phi0": ("degree", "rod-1 angle theta at phi = 0"),
    "omega1_phi0": ("rad/s", "rod-1 angular velocity at phi = 0"),
    "omega2_phi0": ("rad/s", "rod-2 angular velocity at phi = 0"),
    "theta_deg_contact": ("degree", "rod-1 angle theta at contact start"),
    "omega1_contact": ("rad/s", "rod-1 angular velocity at contact start"),
    "omega2_contact": ("rad/s", "rod-2 angular velocity at contact start"),
    "omega2_max": ("rad/s", "maximum rod-2 angular velocity over the stroke"),
    "rhs_evals": ("1", "right-hand-side evaluations of the stroke"),
    "steps": ("1", "accepted integration steps of the stroke"),
}
#: Every other variable and coordinate written to a result file: name -> (unit, long
#: name).
OTHER_VARIABLES: dict[str, tuple[str, str]] = {
    **{k: (PARAMETERS[k].unit, PARAMETERS[k].description) for k in _PARAMETER_AXES},
    # grid axes and stroke coordinates
    "theta0": ("degree", "initial rod-1 angle theta(0) from -y"),
    "delta0": ("degree", "initial angle delta(0) = phi(0) - theta(0) between the rods"),
    "psi_F": ("degree", "direction of the elbow force from +x"),
    "tau_F": ("s", "delay of the force pulse after tau_H"),
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
    "evaluated_strokes": ("1", "strokes of the optimum search at this point"),
    # curves of single strokes
    "omega1": ("rad/s", "rod-1 angular velocity (clockwise)"),
    "omega2": ("rad/s", "rod-2 angular velocity (clockwise)"),
    "theta": ("degree", "rod-1 angle from -y"),
    "phi": ("degree", "rod-2 angle from -y"),
    "x_elbow": ("m", "elbow x position"),
    "y_elbow": ("m", "elbow y position"),
    "x_wrist": ("m", "wrist x position (end of rod 1)"),
    "y_wrist": ("m", "wrist y position (end of rod 1)"),
    "x_racket": ("m", "racket end x position (end of rod 2)"),
    "y_racket": ("m", "racket end y position (end of rod 2)"),
    "x_hit": ("m", "hitting point x position"),
    "y_hit": ("m", "hitting point y position"),
    "kinetic_energy": ("J", "kinetic energy of the two rods (lab frame)"),
    # a stroke in the lab frame (tennis_stroke.stroke_dataset)
    "vx_elbow": ("m/s", "elbow x velocity"),
    "vy_elbow": ("m/s", "elbow y velocity"),
    "vx_wrist": ("m/s", "wrist x velocity (end of rod 1)"),
    "vy_wrist": ("m/s", "wrist y velocity (end of rod 1)"),
    "vx_racket": ("m/s", "racket end x velocity (end of rod 2)"),
    "vy_racket": ("m/s", "racket end y velocity (end of rod 2)"),
    "vx_hit": ("m/s", "hitting point x velocity"),
    "vy_hit": ("m/s", "hitting point y velocity"),
    "speed_hit": ("m/s", "hitting point speed (lab frame)"),
    "x_ball": ("m", "ball x position (the ball moves along x)"),
    "vx_ball": ("m/s", "ball x velocity"),
    # speed-against-accuracy studies
    "method": ("1", "integrator"),
    "setting": ("1", "tolerance rtol = atol, or RK4 step (s)"),
    "scene": ("1", "scene of the work-precision study (config solver_study.scenes)"),
    "v_out_error": (_SPEED, "|v_out error| against the independent reference"),
    "event_time_error": ("s", "largest |event time error| (t_phi0, t_c, separation)"),
    "state_error": ("rad/s", "RMS error of (omega1, omega2) at fixed times"),
    "us_per_stroke": ("us", "wall time per stroke, one thread (median)"),
    "us_per_stroke_low": ("us", "wall time per stroke, low end of its spread"),
    "us_per_stroke_high": ("us", "wall time per stroke, high end of its spread"),
    "failed": ("1", "strokes without status ok"),
    "reference_failed": ("1", "strokes the reference did not finish ok (not compared)"),
    "scene_params": ("1", "the scene's model parameters (a value, or [low, high] drawn uniformly)"),
    "rule": ("1", "cheapest method @ setting meeting the required accuracy (rule table)"),
    "step": ("s", "fixed step"),
    "point": ("1", "index of the step of a method"),
    "order": ("1", "theoretical order of the method"),
    "slope": ("1", "fitted slope of log error against log step"),
    "omega_error": ("rad/s", "largest |omega1, omega2 error| at the end of the swing"),
    "case": ("1", "method @ setting"),
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
#: The one table of CF metadata: every variable and coordinate of a result file, by its
#: name in the file -> (unit, long name).  :func:`cf_attrs` reads it.
VARIABLES: dict[str, tuple[str, str]] = {**RESULT_VARIABLES, **OTHER_VARIABLES}


def unit_of(name: str) -> str:
    """The unit of the file variable or coordinate ``name`` (:data:`VARIABLES`), without
    its long name: what the claims' check compares a claim's unit with (the inference
    reads no label of the table: ``tests/inference/test_labels.py``); KeyError if the
    table has no such name."""
    return VARIABLES[name][0]


def cf_attrs(name: str, **extra) -> dict[str, object]:
    """``units`` and ``long_name`` of the file variable ``name`` (:data:`VARIABLES`), with
    ``extra`` attributes."""
    units, long_name = VARIABLES[name]
    return {"units": units, "long_name": long_name, **extra}
