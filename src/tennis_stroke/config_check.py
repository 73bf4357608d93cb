"""Checks of the workflow configuration, each failure one line naming the key and the rule.

:func:`config_errors` applies the JSON schema (``workflow/schemas/config.schema.yaml``),
then what a schema cannot say (a range's ``stop`` below its ``start``, an empty grid, a
search range the wrong way round), then the model overrides through
:func:`tennis_stroke.model.params.resolve_params`, which knows every parameter's unit and
bounds.  The Snakefile prints the first message and exits before any job starts.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from pathlib import Path

import jsonschema
import yaml

from .model.params import ParameterError, resolve_params


def _path(parts) -> str:
    return ".".join(str(p) for p in parts) or "(top level)"


def _schema_errors(config: Mapping, schema: Mapping) -> Iterator[str]:
    validator = jsonschema.Draft202012Validator(schema)
    for error in sorted(validator.iter_errors(config), key=lambda e: list(e.absolute_path)):
        if error.validator == "required":
            missing = error.message.split("'")[1]
            yield f"config key {_path([*error.absolute_path, missing])!r} is missing (required)"
        elif error.validator == "additionalProperties":
            yield (f"config key {_path(error.absolute_path)!r}: {error.message} (unknown key)")
        else:
            yield (
                f"config key {_path(error.absolute_path)!r}: {error.message} "
                f"(rule: {error.validator})"
            )


def _walk(node, parts=()) -> Iterator[tuple[tuple, object]]:
    yield parts, node
    if isinstance(node, Mapping):
        for key, value in node.items():
            yield from _walk(value, (*parts, key))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from _walk(value, (*parts, i))


def _semantic_errors(config: Mapping) -> Iterator[str]:
    for parts, node in _walk(config):
        if isinstance(node, float) and not math.isfinite(node):
            yield f"config key {_path(parts)!r}: {node} is not a finite number (rule: finite)"
        if isinstance(node, Mapping) and {"start", "stop"} <= set(node):
            start, stop = node["start"], node["stop"]
            if isinstance(start, int | float) and isinstance(stop, int | float) and stop < start:
                yield (
                    f"config key {_path(parts)!r}: stop {stop} is below start {start} "
                    "(rule: stop >= start)"
                )
        if (
            parts
            and str(parts[-1]).endswith("_range")
            and isinstance(node, list)
            and len(node) == 2
            and all(isinstance(v, int | float) for v in node)
            and node[1] <= node[0]
        ):
            yield (
                f"config key {_path(parts)!r}: {node} is empty or reversed (rule: lower < upper)"
            )
    try:
        resolve_params(config.get("model") or {})
    except ParameterError as exc:
        yield f"config key 'model': {exc}"


def _number(text: str):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def numbers_from_strings(node):
    """``node`` with every string that spells a number turned into that number.

    Snakemake's ``--config key={a: 2}`` reads nested values with YAML's BaseLoader, as
    strings (``'2'``); this restores the numbers the YAML file would have given.  No
    string option of the config spells a number.
    """
    if isinstance(node, Mapping):
        return {key: numbers_from_strings(value) for key, value in node.items()}
    if isinstance(node, list):
        return [numbers_from_strings(value) for value in node]
    return _number(node) if isinstance(node, str) else node


def config_errors(config: Mapping, schema_path: str | Path) -> list[str]:
    """Every problem of ``config`` as one-line messages (empty: the config is good)."""
    schema = yaml.safe_load(Path(schema_path).read_text())
    errors = list(_schema_errors(config, schema))
    return errors or list(_semantic_errors(config))
