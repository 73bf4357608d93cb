"""The one table of units and long names of the inference's files (identification,
multiverse, robustness, model ladder, validation), in the style of the io layer's
table of units (``io/units.py``), and :func:`attrs`, which every inference writer uses.

A name has one label in every file where it means the same; a name that means something
else in one file is keyed ``"<file>.<name>"`` (``"ladder.within"``).  A long name may
hold fields (``"reading {name}"``), filled by :func:`attrs`.  Values in each claim's own
unit have no ``units`` here: the unit is the ``claim_unit`` variable beside them, and
:func:`tennis_stroke.io.netcdf.labelled` gives them units ``"1"``.

The inference jobs do not import the io layer's table (``tests/inference/
test_labels.py``), so a label there reruns none of them; a label here reruns only them.
"""

from __future__ import annotations

from collections.abc import Sequence

#: name -> (units, or ``None`` for a value in the claim's unit or a text; long name).
LABELS: dict[str, tuple[str | None, str]] = {
    # every claims file
    "claim": (None, "claim id (config/claims.yaml)"),
    "paper_value": (None, "paper's value"),
    "tolerance": (None, "declared tolerance"),
    "claim_unit": (None, "unit of the claim"),
    "fit_set": (None, "fit set that uses the claim (empty: held out)"),
    "reading": (None, "reading {name}"),
    "unknown": (None, "{name}"),
    "index": ("1", "{name}"),
    "residual": ("1", "normalised residual (simulated - paper) / tolerance"),
    # identification: fits, profiles, leave-one-out
    "fitted": (None, "fitted {name}"),
    "identification.value": (None, "simulated value of the fit claim (the claim's unit)"),
    "identification.passed": ("1", "fit claims within tolerance"),
    "identification.score": ("1", "RMS normalised residual"),
    "score_along": ("1", "RMS normalised residual along {name}"),
    "passed_along": ("1", "fit claims within tolerance along {name}"),
    "in_range": ("1", "1 inside the declared range, 0 exploratory"),
    "refit_along": (None, "{other} refitted along {name}"),
    "predicted": (None, "prediction of the left-out claim (the claim's unit)"),
    "loo.residual": ("1", "normalised residual of the left-out prediction"),
    # multiverse screen
    "rms": ("1", "RMS normalised residual of the fit set"),
    "consistent": ("1", "1 if consistent with the paper (config/readings.yaml)"),
    "max_abs_residual": ("1", "bound on every normalised residual"),
    "max_rms": ("1", "bound on the RMS normalised residual (fallback)"),
    "multiverse.fit_set": (None, "fit set"),
    "multiverse.point_combination": ("1", "discrete combination of the consistent pair"),
    "multiverse.point_candidate": ("1", "Sobol candidate of the consistent pair"),
    # robustness
    "robustness.value": (None, "reproduced value of the claim (its unit: claim_unit)"),
    "robustness.within": ("1", "1 if within the claim's declared tolerance"),
    # model ladder
    "ladder.value": (None, "value of the claim under the rung (its unit: claim_unit)"),
    "comparable": ("1", "1 if the rung can answer the claim"),
    "ladder.within": ("1", "1 if comparable and within the claim's declared tolerance"),
    "from_reference": ("1", "distance from the reference rung's value in tolerances"),
    "rhs_evals": ("1", "right-hand-side evaluations of the compiled solver"),
    "seconds": ("s", "wall time of the file's computation"),
    "contact_model": (None, "model"),
    "restitution": ("1", "coefficient of restitution of the ball"),
    "method": (None, "integrator"),
    "rtol": ("1", "relative tolerance"),
    "atol": ("1", "absolute tolerance"),
    "file_group": (None, "experiment group of the file (-1: no claim reads it)"),
    "claim_group": (None, "experiment group of the files the claim reads"),
    "claim_files": (None, "the result files the claim reads (keys, comma-separated)"),
    "scored_by_ball": ("1", "1 if the claim reads the ball's rebound speed"),
    "expectation": (None, "expectation of config/claims.yaml"),
    "rung": (None, "rung of the ladder"),
    "file": (None, "result file (key)"),
    # validation of the targeted searches against the maps
    "targeted_value": (None, "value by the targeted search (its unit: claim_unit)"),
    "map_value": (None, "value from the full maps (its unit: claim_unit)"),
    "difference": ("1", "|targeted - map| in tolerances (qualitative: 0 same, 1 not)"),
    "agrees": ("1", "1 if within {agreement} tolerance (qualitative: the same)"),
    "grid_half_step": (
        None,
        "half the map's grid step the map value is read on (0: refined between grid "
        "points; its unit: claim_unit)",
    ),
    "cause": (None, "agrees, grid_step (the map's grid limits it) or unexplained"),
    "validation.reading": ("1", "index of the kept reading"),
}


def attrs(key: str, units: str | None = None, **fields) -> dict[str, str]:
    """``long_name`` (its fields filled from ``fields``) and ``units`` of ``key`` in
    :data:`LABELS`; ``units`` given here is the unit of a variable whose unit varies
    (an unknown's)."""
    table_units, long_name = LABELS[key]
    out = {"long_name": long_name.format(**fields)}
    if units is not None or table_units is not None:
        out["units"] = units if units is not None else table_units
    return out


def variable(dims, values, key: str, units: str | None = None, **fields) -> tuple:
    """An xarray ``(dims, values, attrs)`` tuple labelled from :data:`LABELS`."""
    return dims, values, attrs(key, units, **fields)


def claim_facts(
    paper: Sequence[float], tolerance: Sequence[float], units: Sequence[str]
) -> dict[str, tuple]:
    """The per-claim variables of every claims file: the paper's value, the declared
    tolerance and the claim's unit."""
    return {
        "paper_value": variable("claim", paper, "paper_value"),
        "tolerance": variable("claim", tolerance, "tolerance"),
        "claim_unit": variable("claim", units, "claim_unit"),
    }
