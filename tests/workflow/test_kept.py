"""The previous results kept before any job and put back after a failed run
(tennis_stroke.pipeline.kept), without Snakemake; the workflow's own failed and stopped
runs are in test_workflow_failsafe.py."""

import os

from tennis_stroke.pipeline.kept import KEPT, STALE_TIME, keep, restore


def test_a_result_missing_after_the_run_is_put_back_dated_1970(tmp_path):
    (tmp_path / "results" / "a").mkdir(parents=True)
    (tmp_path / "report").mkdir()
    (tmp_path / "logs").mkdir()
    for name, text in [
        ("results/a/x.nc", "x"),
        ("results/y.csv", "y"),
        ("report/index.html", "p"),
        ("logs/l.log", "l"),
    ]:
        (tmp_path / name).write_text(text)
    kept = keep(tmp_path)
    assert kept == ["results/a/x.nc", "results/y.csv", "report/index.html"]
    assert os.path.samefile(tmp_path / KEPT / "results/a/x.nc", tmp_path / "results/a/x.nc")
    (tmp_path / "results/a/x.nc").unlink()  # removed by Snakemake when its job started
    (tmp_path / "results/y.csv").unlink()
    (tmp_path / "results/y.csv").write_text("new")  # made by its job
    (tmp_path / "results/z.nc").write_text("z")  # new in this run
    assert restore(kept, tmp_path) == ["results/a/x.nc"]
    assert (tmp_path / "results/a/x.nc").read_text() == "x"
    assert (tmp_path / "results/a/x.nc").stat().st_mtime == STALE_TIME
    assert (tmp_path / "results/y.csv").read_text() == "new"
    assert restore(kept, tmp_path) == []  # once


def test_keeping_again_replaces_what_was_kept(tmp_path):
    (tmp_path / "results").mkdir()
    (tmp_path / "results/x.nc").write_text("old")
    keep(tmp_path)
    (tmp_path / "results/x.nc").unlink()
    (tmp_path / "results/w.nc").write_text("w")
    assert keep(tmp_path) == ["results/w.nc"]
    assert not (tmp_path / KEPT / "results/x.nc").exists()
    assert keep(tmp_path / "none") == []
