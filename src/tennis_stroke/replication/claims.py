"""The claims table: every claim of ``config/claims.yaml`` measured on the result files,
with its status (``results/claims.csv``), and the check of a finished table.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from ..inference.claims import cause, difference, grid_half_step, measure, within
from ..inference.optimum_claims import judged
from ..io.netcdf import load_result
from .robustness import EVIDENCE, ROBUSTNESS

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
    "measure",
    "fit_set",
    "map_value",
    "map_difference",
    "map_cause",
    "objective_gap",
    "flat",
    "edge",
]


#: The declared fields of a claim (``config/claims.yaml``) that its row records as they
#: are: a table whose row differs in one of them was computed from other claims (stale).
RECORDED = ("source", "quantity", "unit", "expectation", "reason", "measure")


def measure_text(spec: Mapping) -> str:
    """A claim's ``measure`` as its row records it: JSON, keys sorted, so that the same
    measure is the same text."""
    return json.dumps(spec, sort_keys=True, separators=(", ", ": "))


def _recorded(claim: Mapping, key: str) -> str:
    """The declared ``key`` of a claim as the table's text holds it."""
    return measure_text(claim["measure"]) if key == "measure" else str(claim.get(key, ""))


def _datasets(files: Mapping[str, str | Path | xr.Dataset]) -> dict[str, xr.Dataset]:
    return {k: v if isinstance(v, xr.Dataset) else load_result(v) for k, v in files.items()}


def evaluate(
    claims: list[dict],
    files: Mapping[str, str | Path | xr.Dataset],
    fit_of_claim: Mapping[str, str] | None = None,
    maps: Mapping[str, str | Path | xr.Dataset] | None = None,
    flat_gap: float | None = None,
) -> pd.DataFrame:
    """Evaluate every claim against the result files (``files``: key -> path or dataset).

    ``fit_of_claim``: claim id -> the fit set (``config/readings.yaml``) that uses it; the
    ``fit_set`` column marks those claims, which chose the readings and so cannot confirm
    them: within tolerance their status is ``used_for_fit``, not ``pass``.  ``maps``: the
    workflow's full maps, when ``files`` are the targeted evaluation's
    (:func:`tennis_stroke.inference.targeted.targeted_files`): the same measurement on
    them is ``map_value``, and ``map_difference`` its distance from the reproduced value
    in tolerances (:func:`tennis_stroke.inference.validation.difference`), ``map_cause``
    why they differ (:func:`~tennis_stroke.inference.validation.cause`).  A claim that
    locates an optimum gets the two rules of
    :mod:`tennis_stroke.inference.optimum_claims`: ``objective_gap`` and ``flat`` (with
    ``flat_gap``, km/h: ``config/readings.yaml``'s ``evidence``) and ``edge``, read on
    the full maps (``maps``, else ``files``).
    """
    datasets = _datasets(files)
    on_maps = _datasets(maps) if maps is not None else None
    fit_of_claim = fit_of_claim or {}
    rows = []
    for c in claims:
        value = measure(c["measure"], datasets)
        map_value = measure(c["measure"], on_maps) if on_maps is not None else value
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
                "measure": measure_text(c["measure"]),
                "fit_set": fit_set,
                "map_value": map_value,
                "map_difference": float(difference(value, map_value, c["tolerance"])),
                "map_cause": str(
                    cause(value, map_value, c["tolerance"], grid_half_step(c, on_maps))
                )
                if on_maps is not None
                else "agrees",
                **judged(
                    c["measure"],
                    value,
                    c["paper_value"],
                    datasets,
                    on_maps if on_maps is not None else datasets,
                    flat_gap,
                ),
            }
        )
    return pd.DataFrame(rows, columns=COLUMNS)


#: The statuses a claims table may hold.
STATUSES = ("pass", "fail", "known_deviation", "used_for_fit")
#: Each status in the words every reader sees (the report's scoreboard, the README's
#: results, ``tennis-stroke claims``): a symbol, the verb for one claim, the verb for
#: several.
STATUS_WORDS = {
    "pass": ("\u2713", "reproduces", "reproduce"),
    "known_deviation": ("!", "deviates", "deviate"),
    "fail": ("\u2717", "fails", "fail"),
    "used_for_fit": ("\u25cb", "used for fit", "used for fit"),
}


def status_count(n: int, status: str) -> str:
    """``26 reproduce``, ``1 deviates``: a count of claims with the verb of ``status``."""
    return f"{n} {STATUS_WORDS[status][1 if n == 1 else 2]}"


def cause_of(claim: Mapping) -> str:
    """Why a claim outside its tolerance (status ``known_deviation`` or ``fail``) is: its
    evidence class (:data:`~tennis_stroke.replication.robustness.EVIDENCE`), else
    ``fail`` (a failure without one) or ``other`` (a declared deviation without one);
    ``""`` for a claim within its tolerance."""
    if claim["status"] not in ("known_deviation", "fail"):
        return ""
    evidence = claim.get("evidence")
    if evidence is not None and not pd.isna(evidence) and str(evidence):
        return str(evidence)
    return "fail" if claim["status"] == "fail" else "other"


@dataclass(frozen=True)
class Tally:
    """One count line of a claims table: the ``total`` claims of one set and how they
    split (``parts``: key and count, in a fixed order, none of zero), each claim of the
    set in exactly one part, so the parts always add up to the total."""

    total: int
    parts: tuple[tuple[str, int], ...]

    def __getitem__(self, key: str) -> int:
        return dict(self.parts).get(key, 0)


def _tally(keys: pd.Series, order: Sequence[str] = ()) -> Tally:
    """The :class:`Tally` of ``keys`` (one per claim of a set): ``order`` first, any
    other key after it in the order of its first claim."""
    counts = keys.value_counts(sort=False)
    ordered = [k for k in order if k in counts] + [k for k in keys.unique() if k not in order]
    return Tally(int(len(keys)), tuple((str(k), int(counts[k])) for k in ordered))


#: The sets every count of a claims table is made of (:func:`tally`), each a partition.
TALLIES = {
    "claims": "every claim: held out (they confirm or not) or used for fit",
    "held": "the held-out claims by status: pass, known_deviation, fail",
    "fit": "the claims used for fit: within their tolerance or outside it",
    "known_deviation": "the held-out claims that deviate as declared, by cause",
    "fail": "the held-out claims that fail unexpectedly, by cause",
    "outside": "the claims used for fit outside their tolerance, by cause",
    "outside_tolerance": "every claim outside its tolerance (held out or not), by cause",
    "robustness": "the held-out claims by robustness class (a table that has the column)",
}


def tally(table: pd.DataFrame) -> dict[str, Tally]:
    """Every count a page quotes of a claims ``table``, by name (:data:`TALLIES`), each a
    partition of one set of claims: the report's scoreboard and its causes, the README's
    and the article's counts are read from here, so no two of them count one claim twice
    or leave one out.  A claim is held out when it is in no fit set (``fit_set`` empty,
    whatever its status); a claim used for fit is within or outside its tolerance
    whatever the configuration did to it."""
    held = table["fit_set"].astype(str) == ""
    status = table["status"].astype(str)
    causes = pd.Series([cause_of(c) for c in table.to_dict("records")], index=table.index)
    outside = status.isin(("known_deviation", "fail"))
    order = (*EVIDENCE, "fail", "other")
    classes = table["robustness"].astype(str) if "robustness" in table else None
    return {
        "claims": _tally(held.map({True: "held", False: "fit"}), ("held", "fit")),
        "held": _tally(status[held], ("pass", "known_deviation", "fail")),
        "fit": _tally(outside[~held].map({False: "within", True: "outside"}), ("within",)),
        "known_deviation": _tally(causes[held & (status == "known_deviation")], order),
        "fail": _tally(causes[held & (status == "fail")], order),
        "outside": _tally(causes[~held & outside], order),
        "outside_tolerance": _tally(causes[outside], order),
        **({"robustness": _tally(classes[held], ROBUSTNESS)} if classes is not None else {}),
    }


class ClaimsTableError(ValueError):
    """A claims table is not one the claims job wrote (message is one line)."""


def read_table(csv_path: str | Path, expected_ids: Sequence[str] | None = None) -> pd.DataFrame:
    """A claims table, checked: readable (a UTF-8 byte-order mark is allowed), every
    column of :data:`COLUMNS`, known statuses, a number in every reproduced value, and
    with ``expected_ids`` (``config/claims.yaml``'s) exactly those claims in that order.

    Raises
    ------
    ClaimsTableError
        One line naming the file and what is wrong with it.
    """
    try:
        table = pd.read_csv(csv_path, keep_default_na=False, encoding="utf-8-sig", dtype=str)
    except FileNotFoundError:
        raise ClaimsTableError(
            f"claims table {str(csv_path)!r} does not exist (run the workflow first)"
        ) from None
    except (OSError, UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        problem = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise ClaimsTableError(f"{csv_path}: not a claims table ({problem})") from None
    missing = [c for c in COLUMNS if c not in table.columns]
    if missing:
        raise ClaimsTableError(f"{csv_path}: column {missing[0]!r} is missing (not a claims table)")
    for i, row in table.iterrows():
        if row["status"] not in STATUSES:
            raise ClaimsTableError(
                f"{csv_path}: row {i + 2} (claim {row['id']!r}) has status {row['status']!r}, "
                f"not one of {', '.join(STATUSES)}"
            )
        try:
            float(row["reproduced_value"])
        except ValueError:
            raise ClaimsTableError(
                f"{csv_path}: row {i + 2} (claim {row['id']!r}) has no reproduced value"
            ) from None
    if expected_ids is not None and list(table["id"]) != list(expected_ids):
        raise ClaimsTableError(
            f"{csv_path}: holds {len(table)} claims, config/claims.yaml declares "
            f"{len(expected_ids)} (or they differ): a table of another run or a damaged one"
        )
    return table


def consistency_errors(table: pd.DataFrame, claims: Sequence[Mapping], name: str) -> list[str]:
    """Rows of a claims ``table`` (named ``name``) that the claims job cannot have written
    from the declared ``claims``: a paper value or tolerance other than the declared one,
    or any other declared field it records (:data:`RECORDED`, the measure among them: a
    stale table, computed before a claim was edited), or a status other than the one its
    reproduced value gives (the rule of :func:`evaluate`; a table edited by hand).  One
    line each."""
    declared = {c["id"]: c for c in claims}
    out = []
    other = (
        ": a table of other claims (config/claims.yaml changed since the claims job wrote "
        "it: stale, rerun snakemake -j2 report; or edited by hand)"
    )
    for i, row in enumerate(table.to_dict("records")):
        c = declared.get(row["id"])
        if c is None:
            continue  # read_table checks the ids
        where = f"{name}: row {i + 2} (claim {row['id']!r})"
        for key in ("paper_value", "tolerance"):
            if not np.isclose(float(row[key]), float(c[key]), rtol=1e-12, atol=0.0):
                out.append(f"{where} has {key} {row[key]}, config/claims.yaml {c[key]}{other}")
        for key in RECORDED:
            if str(row[key]) != _recorded(c, key):
                out.append(
                    f"{where} has {key} {row[key]!r}, config/claims.yaml "
                    f"{_recorded(c, key)!r}{other}"
                )
        ok = bool(within(float(row["reproduced_value"]), c["paper_value"], c["tolerance"]))
        if ok:
            status = "used_for_fit" if row["fit_set"] else "pass"
        else:
            status = "known_deviation" if c["expectation"] == "known_deviation" else "fail"
        if row["status"] != status:
            out.append(
                f"{where} has status {row['status']!r}, but its reproduced value "
                f"{float(row['reproduced_value']):.6g} gives {status!r} (edited by hand?)"
            )
    return out


def checked_table(csv_path: str | Path, claims: Sequence[Mapping]) -> pd.DataFrame:
    """The claims table as every reader of it accepts it (`tennis-stroke claims`, the
    report, the article): :func:`read_table` with the declared ``claims``' ids, and every
    row one the claims job can have written from them (:func:`consistency_errors`: a
    passing row whose value is nan, inf or far outside its tolerance is refused).

    Raises
    ------
    ClaimsTableError
        One line: the first problem found.
    """
    table = read_table(csv_path, [c["id"] for c in claims])
    errors = consistency_errors(table, claims, str(csv_path))
    if errors:
        raise ClaimsTableError(errors[0])
    return table


def check(
    csv_path: str | Path = "results/claims.csv",
    expected_ids=None,
    claims: Sequence[Mapping] | None = None,
) -> int:
    """Print the counts of a claims table and every failed claim; 1 if a claim marked
    ``reproduce`` failed or a claim's searched value differs from the map's without a
    cause (``map_cause``; and in the validation files of ``robustness/validation`` beside
    the table, if there are any), else 0 (``tennis-stroke claims``).  With the declared
    ``claims``, a row the claims job cannot have written from them
    (:func:`consistency_errors`) raises :class:`ClaimsTableError`.  A table that is not one the
    claims job wrote raises :class:`ClaimsTableError` (:func:`read_table`)."""
    if claims is None:
        table = read_table(csv_path, expected_ids)
    else:
        table = checked_table(csv_path, claims)
    failed = table[table["status"] == "fail"]
    counts = table["status"].value_counts()
    shown = ", ".join(status_count(int(n), status) for status, n in counts.items())
    print(f"claims: {len(table)} ({shown})")
    for _, row in failed.iterrows():
        print(
            f"FAIL {row['id']}: paper {row['paper_value']} {row['unit']}, reproduced "
            f"{float(row['reproduced_value']):.6g} (tolerance {row['tolerance']})"
        )
    unexplained = [
        f"UNEXPLAINED {row['id']} (default reading): "
        f"searched {float(row['reproduced_value']):.6g}, "
        f"map {float(row['map_value']):.6g} {row['unit']}"
        for _, row in table[table["map_cause"] == "unexplained"].iterrows()
    ]
    unexplained += _unexplained_in_validation(Path(csv_path).parent / "robustness" / "validation")
    for line in unexplained:
        print(line)
    return 1 if len(failed) or unexplained else 0


def _unexplained_in_validation(folder: Path) -> list[str]:
    """A line for every claim and reading of the validation files in ``folder`` (if
    any) whose searched value differs from the map's without a cause."""
    out = []
    for path in sorted(folder.glob("*.nc")):
        ds = load_result(path)
        bad = np.argwhere(ds["cause"].values == "unexplained")
        for r, c in bad:
            out.append(
                f"UNEXPLAINED {ds['claim'].values[c]} "
                f"(reading {int(ds['reading'].values[r])}): "
                f"searched {float(ds['targeted_value'].values[r, c]):.6g}, "
                f"map {float(ds['map_value'].values[r, c]):.6g} ({path.name})"
            )
    return out
