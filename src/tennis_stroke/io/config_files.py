"""The YAML files the package reads (config, claims, readings): one reader whose errors
name the file, the line and the column.
"""

from __future__ import annotations

from pathlib import Path

import yaml


class ConfigFileError(ValueError):
    """A YAML file (config, claims, readings) cannot be read; the message is one line
    naming the file (and the line of a syntax error)."""


def load_yaml(path: str | Path) -> object:
    """The contents of the YAML file ``path``.

    Raises
    ------
    ConfigFileError
        The file is missing or unreadable, or not YAML: ``FILE, line L, column C: problem``
        (lines and columns from 1).
    """
    try:
        text = Path(path).read_text()
    except OSError as exc:
        raise ConfigFileError(f"cannot read {str(path)!r}: {exc.strerror}") from None
    try:
        return yaml.safe_load(text)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f", line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        problem = " ".join(str(exc.problem or exc.context or "invalid YAML").split())
        raise ConfigFileError(f"{path}{where}: YAML syntax error: {problem}") from None
    except yaml.YAMLError as exc:
        problem = " ".join(str(exc).split())
        raise ConfigFileError(f"{path}: YAML syntax error: {problem}") from None
