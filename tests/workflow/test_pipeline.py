"""The workflow scripts' helpers: a failing job's traceback goes to its log."""

import sys

import pytest

from tennis_stroke.pipeline.jobs import logged


def test_output_goes_to_the_log(tmp_path):
    log = tmp_path / "logs" / "job.log"
    with logged(log):
        print("hello from the job")
        print("to stderr", file=sys.stderr)
    assert log.read_text() == "hello from the job\nto stderr\n"


def test_an_exception_ends_the_job_with_one_line_and_the_traceback_in_the_log(tmp_path, capsys):
    log = tmp_path / "job.log"
    with pytest.raises(SystemExit) as done:
        with logged(log):
            print("working")
            raise ValueError("theta0 grid is empty\nsecond line")
    assert done.value.code == 1
    err = capsys.readouterr().err
    assert err == (
        f"tennis-stroke job failed: ValueError: theta0 grid is empty (traceback in {log})\n"
    )
    text = log.read_text()
    assert text.startswith("working\nTraceback (most recent call last):")
    assert "ValueError: theta0 grid is empty" in text


def test_save_marks_a_chunk_with_its_position(tmp_path):
    """A chunk file records which chunk of its map it is (the workflow's map scripts)."""
    import xarray as xr

    from tennis_stroke.pipeline.jobs import save

    class Wildcards:
        chunk, chunks = "1", "3"

    ds = xr.Dataset({"v": ("theta0", [1.0, 2.0])}, coords={"theta0": [60.0, 61.0]})
    save(ds, tmp_path / "c.nc", {"x": 1}, 0.5, chunk_of=Wildcards())
    with xr.open_dataset(tmp_path / "c.nc") as out:
        assert (out.attrs["chunk_index"], out.attrs["chunk_count"]) == (1, 3)
        assert out.attrs["chunk_dim"] == "theta0"
