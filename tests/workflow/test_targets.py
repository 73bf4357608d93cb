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


def test_damaged_results_are_listed_and_a_results_file_is_one(tmp_path):
    from tennis_stroke.pipeline.targets import damaged_results

    (tmp_path / "results" / "chunks").mkdir(parents=True)
    (tmp_path / "results" / "chunks" / "0-of-1.nc").write_bytes(b"garbage")
    (tmp_path / "results" / "note.txt").write_text("not a result")
    found = damaged_results(tmp_path / "results")
    assert [p for p, _ in found] == [str(tmp_path / "results" / "chunks" / "0-of-1.nc")]
    (tmp_path / "plain").write_text("a file")
    assert damaged_results(tmp_path / "plain") == [
        (str(tmp_path / "plain"), "a file where the results folder should be")
    ]
