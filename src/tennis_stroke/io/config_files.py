"""The YAML files the package reads (config, claims, readings): one reader whose errors
name the file, the line and the column.

Two departures from PyYAML's YAML 1.1 reading, both to refuse or avoid a silently wrong
value: a key given twice in one mapping is an error (YAML 1.1 keeps the last), and a
number in exponent form without a dot (``2e-3``, ``1e6``) is a number, as in YAML 1.2
(YAML 1.1 reads it as a string).

One rule of every file: each number is finite (:func:`non_finite_numbers`); YAML's
``.nan`` and ``.inf`` are numbers to a schema, and a NaN passes every bound.
"""

from __future__ import annotations

import copy
import functools
import math
import re
from collections.abc import Iterator, Mapping
from pathlib import Path

import yaml


class _DuplicateKey(yaml.MarkedYAMLError):
    pass


class _NoDuplicates:
    """A YAML loader's mapping constructor that refuses a duplicate key."""

    def construct_mapping(self, node, deep=False):
        seen = set()
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            if key in seen:
                raise _DuplicateKey(
                    None,
                    None,
                    f"duplicate key {key!r} (a key may appear once)",
                    key_node.start_mark,
                )
            seen.add(key)
        return super().construct_mapping(node, deep)


class _Loader(_NoDuplicates, yaml.SafeLoader):
    """SafeLoader with YAML 1.2 floats and duplicate keys refused."""


#: The same loader on libyaml's parser where PyYAML has it (about 10 times faster: the
#: workflow reads its config files on every call); its errors are reported by
#: :class:`_Loader`, whose messages name the line the same way everywhere.
_FastLoader = (
    type("_FastLoader", (_NoDuplicates, yaml.CSafeLoader), {})
    if getattr(yaml, "__with_libyaml__", False)
    else _Loader
)
_YAML12_FLOAT = re.compile(r"^[-+]?(?:[0-9][0-9_]*)(?:\.[0-9_]*)?[eE][-+]?[0-9]+$")
for _loader in {_Loader, _FastLoader}:
    _loader.add_implicit_resolver("tag:yaml.org,2002:float", _YAML12_FLOAT, list("-+0123456789"))


class ConfigFileError(ValueError):
    """A YAML file (config, claims, readings) cannot be read; the message is one line
    naming the file (and the line of a syntax error)."""


#: The most values a YAML file of the project may hold once its aliases are expanded: a
#: config is a few hundred; an alias bomb (nine levels of nine references) is 9^9.
MAX_VALUES = 100_000


def expanded_size(data: object) -> int:
    """How many values ``data`` holds once every alias is expanded (each mapping, list and
    scalar counts one; keys do not), counted without expanding: a node met again adds
    its count."""
    sizes: dict[int, int] = {}

    def size(node: object) -> int:
        if not isinstance(node, dict | list):
            return 1
        if id(node) not in sizes:
            sizes[id(node)] = 1  # a node inside itself (a recursive alias) counts once
            values = node.values() if isinstance(node, dict) else node
            sizes[id(node)] = 1 + sum(size(v) for v in values)
        return sizes[id(node)]

    return size(data)


def _bounded(data: object, path: str | Path) -> object:
    """``data``, or one line (:class:`ConfigFileError`) if it holds more than
    :data:`MAX_VALUES` values once its aliases are expanded: every reader of the file
    (a scenario's checks, the schema's, ``sorted_data``) walks it expanded."""
    count = expanded_size(data)
    if count > MAX_VALUES:
        raise ConfigFileError(
            f"{path}: holds {count:.3g} values once its YAML aliases are expanded, more than "
            f"{MAX_VALUES:,} (an alias bomb?): write the values out"
        )
    return data


@functools.lru_cache(maxsize=16)
def _parsed(text: str, path: str) -> object:
    """``text`` parsed, once per text in a process (a Snakemake start reads the claims
    three times); callers get a copy."""
    return _bounded(yaml.load(text, Loader=_FastLoader), path)  # noqa: S506 (SafeLoader)


def load_yaml(path: str | Path) -> object:
    """The contents of the YAML file ``path``.

    Raises
    ------
    ConfigFileError
        The file is missing or unreadable, or not YAML: ``FILE, line L, column C: problem``
        (lines and columns from 1).
    """
    try:
        text = Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigFileError(
            f"{path}: not a UTF-8 text file (byte {exc.start}: {exc.reason})"
        ) from None
    except OSError as exc:
        raise ConfigFileError(f"cannot read {str(path)!r}: {exc.strerror}") from None
    try:
        return copy.deepcopy(_parsed(text, str(path)))
    except yaml.YAMLError:
        pass  # said below, as the pure-Python parser says it
    try:
        return _bounded(yaml.load(text, Loader=_Loader), path)  # noqa: S506 (a SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f", line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        problem = " ".join(str(exc.problem or exc.context or "invalid YAML").split())
        raise ConfigFileError(f"{path}{where}: YAML syntax error: {problem}") from None
    except yaml.YAMLError as exc:
        problem = " ".join(str(exc).split())
        raise ConfigFileError(f"{path}: YAML syntax error: {problem}") from None


def schema_errors(data: object, schema: Mapping, what: str) -> list[str]:
    """Every place where ``data`` breaks the JSON ``schema``, one line each, in the order
    of the keys: ``{what} key 'a.b' ...`` naming the key and the rule (``what``: config,
    readings)."""
    import jsonschema

    validator = jsonschema.Draft202012Validator(schema)
    out = []
    for error in sorted(validator.iter_errors(data), key=lambda e: list(e.absolute_path)):
        parts = list(error.absolute_path)
        if error.validator == "required":
            missing = error.message.split("'")[1]
            out.append(f"{what} key {dotted_key([*parts, missing])!r} is missing (required)")
        elif error.validator == "additionalProperties":
            allowed = error.schema.get("properties", {})
            extra = [k for k in error.instance if k not in allowed]
            known = [dotted_key([*parts, k]) for k in allowed]
            hint = did_you_mean(dotted_key([*parts, extra[0]]), known) if extra else ""
            out.append(f"{what} key {dotted_key(parts)!r}: {error.message} (unknown key){hint}")
        else:
            out.append(
                f"{what} key {dotted_key(parts)!r}: {error.message} (rule: {error.validator})"
            )
    return out


def did_you_mean(name: str, known) -> str:
    """`` (did you mean M2?)``: the closest of the names ``known`` to ``name``, a name
    nobody knows (at most three, by difflib's ratio, at least 0.6), or ``""`` when none
    is close.  The one hint of every command that takes a name or a key (``--set``,
    ``config explain``) and of the config's schema."""
    import difflib

    close = difflib.get_close_matches(name, list(known), n=3, cutoff=0.6)
    return f" (did you mean {', '.join(close)}?)" if close else ""


def config_keys(node, parts: tuple = ()):
    """Every dotted key of a config, at every depth, each before the keys inside it: its
    sections, their keys, a range and its ``start``, ``stop`` and ``step`` (a list is one
    key)."""
    if isinstance(node, Mapping):
        for key, value in node.items():
            path = (*parts, str(key))
            yield ".".join(path)
            yield from config_keys(value, path)


def walk(node, parts: tuple = ()) -> Iterator[tuple[tuple, object]]:
    """Every value of a file's data with its key's path (``dotted_key``), in the file's
    order, each mapping and list before what it holds."""
    yield parts, node
    if isinstance(node, Mapping):
        for key, value in node.items():
            yield from walk(value, (*parts, key))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from walk(value, (*parts, i))


def non_finite_numbers(node, parts: tuple = ()) -> Iterator[tuple[tuple, float]]:
    """Every number of a config file's data that is not finite (``.nan``, ``.inf``), with
    its key's path (``dotted_key``), in the file's order: the rule that every number of
    the config, claims and readings files is finite (a NaN compares false with every
    bound, so a schema's ``minimum`` lets it through)."""
    for path, value in walk(node, parts):
        if isinstance(value, float) and not math.isfinite(value):
            yield path, value


def dotted_key(parts) -> str:
    """A config key's path as written in messages: ``a.b.0``."""
    return ".".join(str(p) for p in parts) or "(top level)"


class ConfigKeyError(KeyError):
    """A config key the config does not have (one line)."""

    def __str__(self) -> str:
        return str(self.args[0])


def value_at(config: Mapping, key: str):
    """The value of the dotted config ``key`` (``a.b.0``: a number indexes a list): the
    one walker of dotted keys."""
    node = config
    for part in key.split(".") if key else ():
        try:
            node = node[int(part)] if isinstance(node, list) else node[part]
        except (KeyError, IndexError, ValueError, TypeError):
            raise ConfigKeyError(f"config key {key!r} is missing") from None
    return node
