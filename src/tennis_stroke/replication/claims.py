"""The paper's claims, evaluated against the result files.

``config/claims.yaml`` lists every claim: ``id``, ``source``, ``quantity``, ``unit``,
``paper_value``, ``tolerance`` (absolute, in the claim's unit), ``expectation``
(``reproduce`` or ``known_deviation`` with a ``reason``) and ``measure``: how to compute
the reproduced value from the results, either a variable of a file
(``{file, var, sel, abs}``) or a named measurement of :data:`MEASUREMENTS`
(``{function, file, ...}``).  Qualitative claims are measurements returning 1 (true) or
0 (false), with ``paper_value: 1`` and ``tolerance: 0``.

:func:`evaluate` returns the table written to ``results/claims.csv`` with the columns
``id, source, quantity, unit, paper_value, reproduced_value, tolerance, status``.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr
import yaml

from .measures import MEASUREMENTS

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
EXPECTATIONS = ("reproduce", "known_deviation")


class ClaimError(ValueError):
    """A claim definition is malformed (message is one line)."""


def within(value, paper, tolerance):
    """True where ``value`` is finite and within ``tolerance`` of ``paper`` (the rule of
    every claim; a rounding margin of 1e-12)."""
    value = np.asarray(value, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.isfinite(value) & (np.abs(value - paper) <= np.asarray(tolerance) + 1e-12)


def measure(spec: Mapping, files: Mapping[str, xr.Dataset]) -> float:
    """The value a claim's ``measure`` computes from the result files (by key)."""
    spec = dict(spec)
    if "function" in spec:
        fn = MEASUREMENTS.get(spec.pop("function"))
        if fn is None:
            raise ClaimError(f"unknown measurement in {spec}")
        names = spec.pop("file")
        names = names if isinstance(names, list) else [names]
        return float(fn(*(files[n] for n in names), **spec))
    da = files[spec["file"]][spec["var"]]
    if "sel" in spec:
        da = da.isel(spec["sel"])
    value = float(da)
    return abs(value) if spec.get("abs") else value


def load_claims(path: str | Path) -> list[dict]:
    """Read and check ``claims.yaml``."""
    claims = yaml.safe_load(Path(path).read_text())["claims"]
    seen = set()
    for c in claims:
        for key in (
            "id",
            "source",
            "quantity",
            "unit",
            "paper_value",
            "tolerance",
            "expectation",
            "measure",
        ):
            if key not in c:
                raise ClaimError(f"claim {c.get('id', '?')!r} lacks {key!r}")
        if c["expectation"] not in EXPECTATIONS:
            raise ClaimError(f"claim {c['id']!r}: expectation must be one of {EXPECTATIONS}")
        if c["expectation"] == "known_deviation" and not c.get("reason"):
            raise ClaimError(f"claim {c['id']!r}: a known deviation needs a reason")
        if c["tolerance"] < 0:
            raise ClaimError(f"claim {c['id']!r}: tolerance must be >= 0")
        if c["id"] in seen:
            raise ClaimError(f"duplicate claim id {c['id']!r}")
        seen.add(c["id"])
    return claims


def load_statements(path: str | Path) -> dict[str, str]:
    """What the paper says about each figure (``statements`` of ``claims.yaml``), by the
    figure's key (``fig02`` ... ``fig14``)."""
    return dict(yaml.safe_load(Path(path).read_text()).get("statements") or {})


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
