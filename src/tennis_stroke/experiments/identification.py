"""Identification of the paper's readings: score every candidate against Fig. 4.

The paper states, for the two strokes of its Fig. 4 (Sec. III), the contact times, the
forearm angles at contact, the angular velocities at contact and the rebound speeds.
Every combination of candidate readings (moments of inertia, contact lead, collision
coupling, spring constant, and the instant at which omega and theta are quoted) is
simulated and scored against those ten numbers with the project's declared tolerances.
The defaults of :data:`tennis_stroke.model.params.READINGS` are the best-scoring combination;
``docs/assumptions.md`` shows the table.

Because these numbers choose the readings, they cannot also confirm them: the claims
report marks them as used for identification.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import pandas as pd

from ..solver.settings import SolverSettings
from ..solver.stroke import strike


@dataclass(frozen=True)
class Target:
    """One number of Fig. 4: stroke, result field(s), paper value, tolerance, unit."""

    name: str
    stroke: tuple[float, float]
    quantity: str
    paper: float
    tolerance: float
    unit: str


FIG4_A = (120.0, 81.5)
FIG4_B = (75.0, 39.0)

#: The Fig. 4 numbers (Sec. III).  ``theta@quoted`` and ``omega*@quoted`` are read at the
#: instants given by the ``theta_quoted_at`` and ``omega_quoted_at`` candidates (contact
#: start or phi = 0: the paper calls both "the contact time").  Tolerances: the
#: project's declared ones (times 2 ms, angles 1 degree, angular velocities 0.5 rad/s,
#: speeds 1 km/h).
TARGETS = (
    Target("t_a", FIG4_A, "t_phi0", 0.198, 2e-3, "s"),
    Target("t_b", FIG4_B, "t_phi0", 0.220, 2e-3, "s"),
    Target("theta_c_a", FIG4_A, "theta@quoted", 11.5, 1.0, "degree"),
    Target("theta_c_b", FIG4_B, "theta@quoted", 87.1, 1.0, "degree"),
    Target("omega1_a", FIG4_A, "omega1@quoted", 11.34, 0.5, "rad/s"),
    Target("omega1_b", FIG4_B, "omega1@quoted", 17.9, 0.5, "rad/s"),
    Target("omega2_a", FIG4_A, "omega2@quoted", 37.98, 0.5, "rad/s"),
    Target("omega2_b", FIG4_B, "omega2@quoted", 37.98, 0.5, "rad/s"),
    Target("v_out_a", FIG4_A, "v_out_kmh", 156.0, 1.0, "km/h"),
    Target("v_out_b", FIG4_B, "v_out_kmh", 141.0, 1.0, "km/h"),
)

#: Candidate values of each reading (the spring constant and the quoting instant are
#: readings of the figures, not model options).
CANDIDATES = {
    "inertia": ("uniform_rod", "paper_text"),
    "contact_lead_rule": ("half_period", "quarter_period", "zero"),
    "collision_coupling": ("newton", "paper_eq8"),
    "k_contact": (188.0, 1000.0, 19000.0),
    "theta_quoted_at": ("phi0", "contact"),
    "omega_quoted_at": ("phi0", "contact"),
}
#: Candidates that only choose which simulated number stands for the paper's.
QUOTING = ("theta_quoted_at", "omega_quoted_at")

_QUOTED_FIELDS = {
    "contact": {
        "theta": "theta_deg_contact",
        "omega1": "omega1_contact",
        "omega2": "omega2_contact",
    },
    "phi0": {"theta": "theta_deg_at_phi0", "omega1": "omega1_phi0", "omega2": "omega2_phi0"},
}


def _value(result: dict, quantity: str, quoting: dict[str, str]) -> float:
    if quantity.endswith("@quoted"):
        kind = quantity.removesuffix("@quoted")
        instant = quoting["theta_quoted_at" if kind == "theta" else "omega_quoted_at"]
        key = _QUOTED_FIELDS[instant][kind]
        value = result[key]
        # the paper quotes the forearm angle as a magnitude (theta is below -y at contact)
        return abs(value) if key.startswith("theta") else value
    return result[quantity]


def score_readings(settings: SolverSettings | None = None) -> pd.DataFrame:
    """Score every combination of :data:`CANDIDATES` against :data:`TARGETS`.

    Returns
    -------
    pandas.DataFrame
        One row per combination: the readings, ``passed`` (targets within tolerance),
        ``score`` (RMS of error / tolerance) and one column per target with the
        simulated value; sorted best first (most passed, then lowest score).
    """
    rows = []
    model_keys = [k for k in CANDIDATES if k not in QUOTING]
    for combo in itertools.product(*(CANDIDATES[k] for k in model_keys)):
        readings = dict(zip(model_keys, combo, strict=True))
        results = {stroke: strike(*stroke, readings, settings) for stroke in (FIG4_A, FIG4_B)}
        for instants in itertools.product(*(CANDIDATES[k] for k in QUOTING)):
            quoting = dict(zip(QUOTING, instants, strict=True))
            row = {**readings, **quoting}
            normalised = []
            for target in TARGETS:
                value = _value(results[target.stroke], target.quantity, quoting)
                row[target.name] = value
                normalised.append((value - target.paper) / target.tolerance)
            row["passed"] = sum(abs(x) <= 1.0 for x in normalised)
            row["score"] = (sum(x * x for x in normalised) / len(normalised)) ** 0.5
            rows.append(row)
    table = pd.DataFrame(rows)
    return table.sort_values(["passed", "score"], ascending=[False, True], ignore_index=True)


def paper_row() -> dict[str, float]:
    """The paper's values of :data:`TARGETS`, for printing beside the table."""
    return {t.name: t.paper for t in TARGETS}


def best_readings(settings: SolverSettings | None = None, rows: int = 10) -> str:
    """The paper's values and the ``rows`` best-scoring combinations, as text
    (``tennis-stroke identify``)."""
    table = score_readings(settings)
    columns = [*CANDIDATES, "passed", "score", *paper_row()]
    return f"paper: {paper_row()}\n" + table[columns].head(rows).round(3).to_string(index=False)
