"""The targets make report names (tennis_stroke.pipeline.targets): every result file,
figure, the claims table and the report page, each once."""

from tennis_stroke.experiments.specs import RESULT_FILES
from tennis_stroke.pipeline.targets import targets
from tennis_stroke.replication.registry import FIGURES


def test_every_final_file_is_a_target_once():
    names = targets()
    assert len(names) == len(set(names))
    assert set(RESULT_FILES.values()) <= set(names)
    assert {f"results/figures/{f}.png" for f in FIGURES} <= set(names)
    assert {"results/claims.csv", "report/index.html"} <= set(names)
