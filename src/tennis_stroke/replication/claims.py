"""The claims table: every claim of ``config/claims.yaml`` measured on the result files,
with its status (``results/claims.csv``), and the check of a finished table.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import pandas as pd
import xarray as xr

from ..inference.claims import measure, within

COLUMNS = [
    "id",
    "source",
    "quantity",
    "unit",
    "paper_value",
    "reproduced_value",
    "tolerance",
    "status",
    "expectation",
    "reason",
    "fit_set",
]


def evaluate(
    claims: list[dict],
    files: Mapping[str, str | Path | xr.Dataset],
    fit_of_claim: Mapping[str, str] | None = None,
) -> pd.DataFrame:
    """Evaluate every claim against the result files (``files``: key -> path or dataset).

    ``fit_of_claim``: claim id -> the fit set (``config/readings.yaml``) that uses it; the
    ``fit_set`` column marks those claims, which chose the readings and so cannot confirm
    them: within tolerance their status is ``used_for_fit``, not ``pass``.
    """
    datasets = {k: v if isinstance(v, xr.Dataset) else xr.load_dataset(v) for k, v in files.items()}
    fit_of_claim = fit_of_claim or {}
    rows = []
    for c in claims:
        value = measure(c["measure"], datasets)
        ok = bool(within(value, c["paper_value"], c["tolerance"]))
        fit_set = fit_of_claim.get(c["id"], "")
        if ok:
            # a claim that chose the readings cannot confirm them
            status = "used_for_fit" if fit_set else "pass"
        else:
            status = "known_deviation" if c["expectation"] == "known_deviation" else "fail"
        rows.append(
            {
                "id": c["id"],
                "source": c["source"],
                "quantity": c["quantity"],
                "unit": c["unit"],
                "paper_value": c["paper_value"],
                "reproduced_value": value,
                "tolerance": c["tolerance"],
                "status": status,
                "expectation": c["expectation"],
                "reason": c.get("reason", ""),
                "fit_set": fit_set,
            }
        )
    return pd.DataFrame(rows, columns=COLUMNS)


def check(csv_path: str | Path = "results/claims.csv") -> int:
    """Print the counts of a claims table and every failed claim; 1 if a claim marked
    ``reproduce`` failed, else 0 (``tennis-stroke claims``)."""
    table = pd.read_csv(csv_path, keep_default_na=False)
    failed = table[table["status"] == "fail"]
    counts = table["status"].value_counts().to_dict()
    print(f"claims: {counts}")
    for _, row in failed.iterrows():
        print(
            f"FAIL {row['id']}: paper {row['paper_value']} {row['unit']}, reproduced "
            f"{float(row['reproduced_value']):.6g} (tolerance {row['tolerance']})"
        )
    return 1 if len(failed) else 0
