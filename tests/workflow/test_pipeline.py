"""The workflow scripts' helpers: a failing job's traceback goes to its log."""

import sys
from pathlib import Path

import pytest

from tennis_stroke.pipeline.jobs import SPLIT_PREFIX, logged


def test_output_goes_to_the_log(tmp_path):
    log = tmp_path / "logs" / "job.log"
    with logged(log):
        print("hello from the job")
        print("to stderr", file=sys.stderr)
    lines = log.read_text().splitlines()
    assert lines[:2] == ["hello from the job", "to stderr"]
    assert len(lines) == 3 and lines[2].startswith(SPLIT_PREFIX)  # then where time went


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


@pytest.mark.process
def test_a_job_log_ends_with_where_its_time_went(tmp_path):
    """logged() ends a job's log with its time split, and the benchmark that sums the
    splits per job kind reads it back: a job that writes a file has writing > 0, a job
    that sleeps has its compute, and the parts add up to less than the process's age."""
    import subprocess
    import sys
    import textwrap

    from tennis_stroke.pipeline.jobs import SPLIT_PARTS, SPLIT_PREFIX

    log = tmp_path / "logs" / "angle_maps" / "fig2" / "0-of-1.log"
    script = textwrap.dedent(
        f"""
        import time
        import numpy as np, xarray as xr
        from tennis_stroke.pipeline.jobs import logged, save
        with logged({str(log)!r}):
            time.sleep(0.3)
            save(xr.Dataset({{"v": ("x", np.arange(3.0))}}), {str(tmp_path / "a.nc")!r}, {{}}, 0.3)
        """
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    last = log.read_text().splitlines()[-1]
    assert last.startswith(SPLIT_PREFIX)
    parts = dict(p.rsplit(" ", 1) for p in last[len(SPLIT_PREFIX) + 1 :].split(", "))
    assert list(parts) == list(SPLIT_PARTS)
    values = {k: float(v) for k, v in parts.items()}
    assert values["compute"] >= 0.3 and values["writing"] > 0 and values["imports"] > 0
    assert values["start-up"] >= 0

    bench = tmp_path / "logs" / "benchmarks" / "angle_maps" / "fig2_0-of-1.tsv"
    bench.parent.mkdir(parents=True)
    bench.write_text("s\th:m:s\tmax_rss\tcpu_time\n1.5\t0:00:01\t100\t1.2\n")
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    try:
        from job_split import split_table
    finally:
        sys.path.pop(0)
    table = split_table(tmp_path / "logs", tmp_path / "logs" / "benchmarks")
    assert table.loc["simulation", "jobs"] == 1 and table.loc["simulation", "wall"] == 1.5
    assert table.loc["simulation", "compute"] == pytest.approx(values["compute"], abs=1e-3)
