"""Validate CITATION.cff against the Citation File Format 1.2.0 schema, one line per
problem (exit status 1), with the project's own jsonschema.

Usage: ``python tools/citation_check.py [CITATION.cff]``

The schema (``tools/cff/schema-1.2.0.json``, draft-07) is the one `cffconvert` 2.0.0
ships, from https://citation-file-format.github.io/1.2.0/schema.json (CC-BY-4.0).
`cffconvert` itself pins jsonschema 3.2, which would downgrade the project's (the config
checks need 4), so it is not installed; its reading is kept: timestamps are read as
text (``date-released: 2026-12-07`` is the string the schema asks for).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import jsonschema
import yaml

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "tools" / "cff" / "schema-1.2.0.json"


class _Loader(yaml.SafeLoader):
    """YAML as cffconvert reads CITATION.cff: timestamps stay text."""


_Loader.add_constructor("tag:yaml.org,2002:timestamp", yaml.SafeLoader.construct_yaml_str)


def problems(path: str | Path) -> list[str]:
    """Every way ``path`` departs from the CFF 1.2.0 schema (empty: valid)."""
    try:
        data = yaml.load(Path(path).read_text(), Loader=_Loader)
    except (OSError, yaml.YAMLError) as exc:
        return [f"{path}: cannot be read ({str(exc).splitlines()[0]})"]
    validator = jsonschema.Draft7Validator(json.loads(SCHEMA.read_text()))
    out = []
    for error in sorted(validator.iter_errors(data), key=lambda e: list(e.absolute_path)):
        where = ".".join(map(str, error.absolute_path)) or "(top level)"
        out.append(f"{path}: {where}: {error.message}")
    return out


def main(argv: list[str]) -> int:
    path = argv[0] if argv else ROOT / "CITATION.cff"
    found = problems(path)
    for line in found:
        print(line, file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
