"""The inference's files carry no label of the units table (tennis_stroke.io.units): the
workflow leaves the table out of the inference jobs' code inputs, so a new long name
reruns none of them (workflow/rules/common.smk, UNITS).  Checked on the source: no
inference module takes a label from the table, directly or through a writer that does."""

from pathlib import Path

import pytest

INFERENCE = Path(__file__).resolve().parents[2] / "src" / "tennis_stroke" / "inference"
#: What writes the table's labels into a dataset.
LABEL_WRITERS = ("cf_attrs", "result_dataset", "relabelled", "VARIABLES", "io.units")


@pytest.mark.parametrize("path", sorted(INFERENCE.glob("*.py")), ids=lambda p: p.name)
def test_no_inference_module_writes_a_label_of_the_units_table(path):
    text = path.read_text()
    assert not [w for w in LABEL_WRITERS if w in text], path.name
