"""The inference's files carry no label of the units table (tennis_stroke.io.units): the
workflow leaves the table out of the inference jobs' code inputs, so a new long name
reruns none of them (workflow/rules/common.smk, UNITS).  Checked on the source: no
inference module takes a label from the table, directly or through a writer that does."""

import re
from pathlib import Path

import pytest

INFERENCE = Path(__file__).resolve().parents[2] / "src" / "tennis_stroke" / "inference"
#: What writes the table's labels into a dataset.
LABEL_WRITERS = ("cf_attrs", "result_dataset", "relabelled", "VARIABLES")
#: What an inference module may take from the table: a unit, never a label (the claims'
#: check compares a claim's unit with its measure's).
UNIT_READERS = {"unit_of"}


@pytest.mark.parametrize("path", sorted(INFERENCE.glob("*.py")), ids=lambda p: p.name)
def test_no_inference_module_writes_a_label_of_the_units_table(path):
    text = path.read_text()
    assert not [w for w in LABEL_WRITERS if w in text], path.name
    imported = re.findall(r"from \.\.io\.units import \(?([\w, ]+)", text)
    assert {n.strip() for names in imported for n in names.split(",")} <= UNIT_READERS
    assert not re.search(r"from \.\.io import [^\n]*\bunits\b|import [\w.]*io\.units", text)


@pytest.mark.parametrize(
    "path", sorted(p for p in INFERENCE.glob("*.py") if p.name != "labels.py"), ids=lambda p: p.name
)
def test_the_inference_labels_come_from_its_one_table(path):
    """No inference module writes a long name of its own: each comes from
    tennis_stroke.inference.labels, where a name has one label."""
    assert "long_name" not in path.read_text(), path.name


def test_every_label_of_the_table_is_used_and_fills_its_fields():
    from tennis_stroke.inference.labels import LABELS, attrs

    text = "".join(p.read_text() for p in INFERENCE.glob("*.py") if p.name != "labels.py")
    unused = [key for key in LABELS if f'"{key}"' not in text]
    assert not unused
    for key, (_, long_name) in LABELS.items():
        fields = {f: "x" for f in re.findall(r"{(\w+)}", long_name)}
        assert "{" not in attrs(key, **fields)["long_name"]


def test_a_label_names_its_unit_only_where_it_has_one():
    from tennis_stroke.inference.labels import attrs

    assert attrs("paper_value") == {"long_name": "paper's value"}
    assert attrs("unknown", "kg", name="M2") == {"long_name": "M2", "units": "kg"}
    assert attrs("rms")["units"] == "1"
    with pytest.raises(KeyError):
        attrs("no such label")
