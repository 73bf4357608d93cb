"""Whether a configuration is the paper's: the one the replication is graded on.

The paper states some inputs of its experiments (Fig. 7's delta0 = 26.1 deg, C2 = 5 N m,
the Table I directions, ...): ``config/claims.yaml`` declares each (section ``inputs``)
with the config key that holds it and where the paper says it.  A configuration departs
from the paper's where one of those keys holds another value, or where it overrides a
model parameter or reading (config key ``model``: the parameters' defaults are the
paper's values and the default readings, :data:`~tennis_stroke.model.params.PARAMETERS`).
Grids, chunks, searches and the solver are ours, not the paper's, and never depart.

The claims job writes, beside each claims table, the record of the configuration it was
computed under (:func:`configuration_record`): the scenario, if any, and the departures.
The replication gate (``tennis-stroke claims``, ``make report``, the README check) grades
a table only when its record says it is the paper's configuration.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import yaml

from ..experiments.specs import shown, sorted_data
from ..io.config_files import ConfigFileError, ConfigKeyError, load_yaml, value_at
from ..model.params import PARAMETERS, READINGS

#: The file beside a claims table that records its configuration.
RECORD_NAME = "configuration.yaml"


class PaperConfigError(ValueError):
    """The declared paper inputs or a configuration record cannot be read (one line)."""


def load_paper_inputs(path: str | Path) -> list[dict]:
    """The paper's stated inputs of ``path`` (``config/claims.yaml``, section
    ``inputs``): each ``{key, value, source}``, checked."""
    try:
        raw = load_yaml(path)
    except ConfigFileError as exc:
        raise PaperConfigError(str(exc)) from None
    inputs = raw.get("inputs") if isinstance(raw, Mapping) else None
    if not isinstance(inputs, list) or not inputs:
        raise PaperConfigError(f"{path}: no list of the paper's inputs (key 'inputs')")
    for i, item in enumerate(inputs):
        if not isinstance(item, Mapping) or set(item) != {"key", "value", "source"}:
            raise PaperConfigError(
                f"{path}: input {i + 1} must have exactly key, value and source, got {item!r}"
            )
        if not isinstance(item["key"], str) or not item["key"]:
            raise PaperConfigError(f"{path}: input {i + 1}: key must be a config key")
    return [dict(item) for item in inputs]


def _same(a, b) -> bool:
    try:
        return bool(np.array_equal(np.asarray(a, float), np.asarray(b, float)))
    except (TypeError, ValueError):
        return a == b


def departures(config: Mapping, inputs: Sequence[Mapping]) -> list[dict]:
    """Where ``config`` departs from the paper's configuration: each declared input it
    holds another value of, then each model override other than the parameter's or
    reading's default, as ``{key, value, paper_value, source}``."""
    out = []
    for item in inputs:
        try:
            value = value_at(config, item["key"])
        except ConfigKeyError:
            value = None
        if not _same(value, item["value"]):
            out.append({**item, "value": sorted_data(value), "paper_value": item["value"]})
    for name, value in sorted((config.get("model") or {}).items()):
        if name in PARAMETERS:
            default, source = PARAMETERS[name].default, "the model's parameters (Sec. III)"
        elif name in READINGS:
            default, source = READINGS[name].default, "the default reading (docs/assumptions.md)"
        else:
            default, source = None, "the model"
        if not _same(value, default):
            out.append(
                {"key": f"model.{name}", "value": value, "paper_value": default, "source": source}
            )
    return [{k: d[k] for k in ("key", "value", "paper_value", "source")} for d in out]


def configuration_record(
    config: Mapping, inputs: Sequence[Mapping], scenario: Mapping | None = None
) -> dict:
    """The record of the configuration a claims table was computed under: the scenario
    (``{name, overrides, changes}``, or None for the paper's configuration) and the
    departures from the paper's (:func:`departures`)."""
    return {
        "scenario": sorted_data(scenario) if scenario else None,
        "departures": departures(config, inputs),
    }


def write_record(record: Mapping, path: str | Path) -> None:
    """Write a configuration record (YAML, with a comment saying what it is)."""
    head = (
        "# The configuration the claims table beside this file was computed under, written\n"
        "# by the claims job: the scenario (null: the paper's configuration) and where it\n"
        "# departs from the paper's stated inputs (config/claims.yaml, inputs).\n"
    )
    Path(path).write_text(head + yaml.safe_dump(dict(record), sort_keys=False))


def read_record(claims_csv: str | Path) -> dict:
    """The configuration record beside the claims table ``claims_csv``."""
    path = Path(claims_csv).with_name(RECORD_NAME)
    if not path.is_file():
        raise PaperConfigError(
            f"{path} is missing: the configuration {claims_csv} was computed under is "
            "unknown (rerun the claims job: snakemake -j2 report)"
        )
    try:
        record = load_yaml(path)
    except ConfigFileError as exc:
        raise PaperConfigError(str(exc)) from None
    if not isinstance(record, Mapping) or set(record) != {"scenario", "departures"}:
        raise PaperConfigError(f"{path}: not a configuration record")
    departures, scenario = record["departures"], record["scenario"]
    if not isinstance(departures, list) or not all(
        isinstance(d, Mapping) and {"key", "value", "paper_value", "source"} <= set(d)
        for d in departures
    ):
        raise PaperConfigError(
            f"{path}: departures must be a list of key, value, paper_value, source"
        )
    if scenario is not None and not (
        isinstance(scenario, Mapping)
        and {"name", "changes"} <= set(scenario)
        and isinstance(scenario["changes"], list)
        and all(isinstance(c, Mapping) and "text" in c for c in scenario["changes"])
    ):
        raise PaperConfigError(f"{path}: scenario must be null or have a name and its changes")
    return dict(record)


def departure_lines(record: Mapping) -> list[str]:
    """Each departure of a record as a line: key, value, the paper's value and source."""
    return [
        f"{d['key']} = {shown(d['value'])} (the paper's {shown(d['paper_value'])}: {d['source']})"
        for d in record["departures"]
    ]


def describe_departures(record: Mapping) -> str:
    """The departures of a record in one line."""
    return "; ".join(departure_lines(record))
