"""ReScience C's metadata template (``tools/rescience/metadata-draft.yaml``, vendored
unchanged) and the shape its parser reads, for the tests of ``report/metadata.yaml``."""

import yaml
from conftest import ROOT

TEMPLATE = yaml.safe_load((ROOT / "tools" / "rescience" / "metadata-draft.yaml").read_text())
#: Keys of ours after the template's (its parser reads none it does not know).
OURS = ("software",)


def shape(value):
    """A value's shape as the template's parser reads it: a list of one-key maps (its
    keys in order), a list of records (the keys of each), a map (its keys), a value."""
    if isinstance(value, list) and all(isinstance(v, dict) and len(v) == 1 for v in value):
        return ("one-key maps", [next(iter(v)) for v in value])
    if isinstance(value, list) and all(isinstance(v, dict) for v in value):
        return ("records", sorted({tuple(v) for v in value}))
    if isinstance(value, dict | list):
        return (type(value).__name__, None)
    return ("value", None)


def departures(meta: dict) -> list[str]:
    """Where ``meta`` departs from the template, key by key: its keys (the template's in
    order, then :data:`OURS`), then each key's shape (empty: none)."""
    if list(meta) != [*TEMPLATE, *OURS]:
        return [f"keys {list(meta)} are not the template's {[*TEMPLATE, *OURS]}"]
    return [
        f"{key}: {shape(meta[key])} is not the template's {shape(value)}"
        for key, value in TEMPLATE.items()
        if shape(meta[key]) != shape(value)
    ]
