"""Identification of the paper's readings: score every candidate against Fig. 4.

The paper states, for the two strokes of its Fig. 4 (Sec. III), the contact times, the
forearm angles at contact, the angular velocities at contact and the rebound speeds: the
claims of ``config/claims.yaml`` marked ``identification: true``
(:func:`targets_from_claims`), with their declared tolerances.
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
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import pandas as pd

from ..solver.results import FILE_NAMES
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


_QUOTED_FIELDS = {
    "contact": {
        "theta": "theta_deg_contact",
        "omega1": "omega1_contact",
        "omega2": "omega2_contact",
    },
    "phi0": {"theta": "theta_deg_at_phi0", "omega1": "omega1_phi0", "omega2": "omega2_phi0"},
}

#: Which simulated number a claim's file variable stands for: ``theta``/``omega`` are
#: read at the instant a ``*_quoted_at`` candidate names (the paper calls both the
#: contact start and ``phi = 0`` "the contact time"); the others are result fields.
_QUANTITY_OF_VARIABLE = {
    "t_phi0": "t_phi0",
    FILE_NAMES["v_out_kmh"]: "v_out_kmh",
    **{
        field: f"{kind}@quoted"
        for fields in _QUOTED_FIELDS.values()
        for kind, field in fields.items()
    },
}


def targets_from_claims(claims: Sequence[Mapping], strokes: Sequence[Sequence[float]]):
    """The fit targets: every claim marked ``identification: true`` (``config/claims.yaml``,
    the only home of the paper's numbers), on the Fig. 4 strokes ``(theta0, delta0)``
    (degrees) its ``measure.sel.stroke`` indexes.

    Raises
    ------
    ValueError
        A marked claim does not read a single Fig. 4 stroke variable this identification
        knows (one line, with the claim's id).
    """
    targets = []
    for c in claims:
        if not c.get("identification"):
            continue
        m = c["measure"]
        var = m.get("var")
        if m.get("file") != "fig4" or var not in _QUANTITY_OF_VARIABLE or "sel" not in m:
            raise ValueError(f"claim {c['id']!r}: identification needs a Fig. 4 stroke variable")
        stroke = tuple(float(x) for x in strokes[int(m["sel"]["stroke"])])
        targets.append(
            Target(
                c["id"],
                stroke,
                _QUANTITY_OF_VARIABLE[var],
                float(c["paper_value"]),
                float(c["tolerance"]),
                c["unit"],
            )
        )
    return tuple(targets)


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


def _value(result: dict, quantity: str, quoting: dict[str, str]) -> float:
    if quantity.endswith("@quoted"):
        kind = quantity.removesuffix("@quoted")
        instant = quoting["theta_quoted_at" if kind == "theta" else "omega_quoted_at"]
        key = _QUOTED_FIELDS[instant][kind]
        value = result[key]
        # the paper quotes the forearm angle as a magnitude (theta is below -y at contact)
        return abs(value) if key.startswith("theta") else value
    return result[quantity]


def score_readings(
    targets: Sequence[Target | Mapping], settings: SolverSettings | None = None
) -> pd.DataFrame:
    """Score every combination of :data:`CANDIDATES` against ``targets``
    (:func:`targets_from_claims`).

    Returns
    -------
    pandas.DataFrame
        One row per combination: the readings, ``passed`` (targets within tolerance),
        ``score`` (RMS of error / tolerance) and one column per target with the
        simulated value; sorted best first (most passed, then lowest score).
    """
    targets = [
        t if isinstance(t, Target) else Target(**{**t, "stroke": tuple(t["stroke"])})
        for t in targets
    ]
    rows = []
    model_keys = [k for k in CANDIDATES if k not in QUOTING]
    for combo in itertools.product(*(CANDIDATES[k] for k in model_keys)):
        readings = dict(zip(model_keys, combo, strict=True))
        strokes = dict.fromkeys(t.stroke for t in targets)
        results = {stroke: strike(*stroke, readings, settings) for stroke in strokes}
        for instants in itertools.product(*(CANDIDATES[k] for k in QUOTING)):
            quoting = dict(zip(QUOTING, instants, strict=True))
            row = {**readings, **quoting}
            normalised = []
            for target in targets:
                value = _value(results[target.stroke], target.quantity, quoting)
                row[target.name] = value
                normalised.append((value - target.paper) / target.tolerance)
            row["passed"] = sum(abs(x) <= 1.0 for x in normalised)
            row["score"] = (sum(x * x for x in normalised) / len(normalised)) ** 0.5
            rows.append(row)
    table = pd.DataFrame(rows)
    return table.sort_values(["passed", "score"], ascending=[False, True], ignore_index=True)


def paper_row(targets: Sequence[Target]) -> dict[str, float]:
    """The paper's values of ``targets``, for printing beside the table."""
    return {t.name: t.paper for t in targets}


def best_readings(
    targets: Sequence[Target], settings: SolverSettings | None = None, rows: int = 10
) -> str:
    """The paper's values and the ``rows`` best-scoring combinations, as text
    (``tennis-stroke identify``)."""
    table = score_readings(targets, settings)
    columns = [*CANDIDATES, "passed", "score", *paper_row(targets)]
    return f"paper: {paper_row(targets)}\n" + table[columns].head(rows).round(3).to_string(
        index=False
    )
