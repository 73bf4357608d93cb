"""One run at a time in a working folder (pipeline.checkout.hold_folder), in one
process against a holder in another: the second run is told another is active and is
never advised to --unlock; a dead run's locks are removed.  End to end (whatif beside
whatif, beside a plain snakemake, snakemake --unlock): test_stops.py."""

import os
import subprocess
import sys

import pytest

from tennis_stroke.pipeline import checkout

#: A process holding the folder's flock, as a live run's Snakemake does.
HOLDER = """
import fcntl, os, sys
fd = os.open(".snakemake", os.O_RDONLY)
fcntl.flock(fd, fcntl.LOCK_EX)
print("held", flush=True)
sys.stdin.read()
"""


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(checkout, "_HELD", [])
    (tmp_path / ".snakemake" / "locks").mkdir(parents=True)
    (tmp_path / ".snakemake" / "locks" / "0.output.lock").write_text("results/claims.csv\n")
    return tmp_path


def test_a_second_run_is_told_another_is_active_and_never_to_unlock(folder):
    with subprocess.Popen(
        [sys.executable, "-c", HOLDER], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    ) as holder:
        assert holder.stdout.readline() == "held\n"
        line = checkout.hold_folder(["-j2", "report"])
        holder.stdin.close()
    assert line == (
        f"another run is active in this folder (Snakemake, pid {holder.pid}): wait for it "
        f"to end, or stop it (kill -INT {holder.pid})"
    )
    assert "--unlock" not in line
    assert (folder / ".snakemake" / "locks" / "0.output.lock").exists()  # the live run's


def test_a_dead_run_s_locks_are_removed_in_one_line(folder, capsys):
    assert checkout.hold_folder(["--cores", "2", "report"]) is None
    assert not list((folder / ".snakemake" / "locks").iterdir())
    assert capsys.readouterr().err.startswith("tennis-stroke: removed the locks of an earlier run")
    for fd in checkout._HELD:
        os.close(fd)


# --- a folder the planned jobs cannot write -------------------------------------------


def test_a_folder_the_planned_jobs_cannot_write_is_one_line_naming_it(tmp_path, monkeypatch):
    """Issue 66, case 8: with results/figures not writable, `snakemake --forcerun` of a
    figure ended in a 60-line traceback. The files the planned jobs write (outputs, logs,
    benchmark files) are checked once, before any job: a folder that is not writable, or
    a name in the way that is a file, is named in one line with the files it would hold;
    a folder yet to be made below a writable one is no problem. (The tests run as root,
    for whom no mode bit makes a folder read-only: ``os.access`` stands in.)"""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "results" / "figures").mkdir(parents=True)
    planned = [
        "results/figures/fig09_v_tau.png",
        "results/figures/fig02_angle_map.png",
        "logs/benchmarks/figure_fig09_v_tau.tsv",
        "logs/figure/fig09_v_tau.log",
    ]
    assert checkout.unwritable_folders(planned) is None
    real = os.access
    blocked = os.path.abspath("results/figures")
    monkeypatch.setattr(
        os, "access", lambda p, mode: os.path.abspath(p) != blocked and real(p, mode)
    )
    line = checkout.unwritable_folders(planned)
    assert line is not None and "\n" not in line
    assert "'results/figures' is not writable" in line, line
    assert "results/figures/fig02_angle_map.png" in line and "logs" not in line, line
    monkeypatch.setattr(os, "access", real)
    (tmp_path / "logs").write_text("a file where the logs' folder goes\n")
    line = checkout.unwritable_folders(planned)
    assert "'logs' is not a folder" in line and "logs/figure/fig09_v_tau.log" in line, line
    assert "results/figures" not in line, line
