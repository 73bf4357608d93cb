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
