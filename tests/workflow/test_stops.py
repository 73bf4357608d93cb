"""Stops: a signal to a command that runs the workflow for the user (tennis-stroke
whatif) reaches Snakemake and its jobs, which stop; what an interrupted or killed run
leaves, the next run handles by itself."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import CHECKOUT, ROOT, workdir
from tiny import TINY, TINY_READINGS

#: The workflow end to end: slow (pytest -m 'not slow' leaves it out).
pytestmark = pytest.mark.workflow


@pytest.mark.signals
@pytest.mark.parametrize(
    ("signum", "status", "line"),
    [
        (signal.SIGINT, 130, "tennis-stroke: interrupted"),
        (signal.SIGTERM, 143, "tennis-stroke: terminated"),
        (signal.SIGHUP, 143, "tennis-stroke: terminated"),
    ],
)
def test_whatif_stopped_by_a_signal_leaves_no_lock(tmp_path, signum, status, line):
    """Ctrl-C (the terminal's SIGINT to the command's process group), SIGTERM or a closed
    terminal (SIGHUP) while `tennis-stroke whatif` runs the workflow: Snakemake gets the
    signal once, stops its jobs and removes its locks, the command ends with one line
    and the signal's status, and the next run needs no --unlock.  (subprocess.run killed
    Snakemake 0.25 s after Ctrl-C, and at once on SIGTERM, before it removed its locks.)"""
    checkout = tmp_path / "checkout"
    checkout.mkdir()
    for name in CHECKOUT:
        (checkout / name).symlink_to(ROOT / name)
    workdir(checkout, TINY, TINY_READINGS)
    command = [str(Path(sys.executable).with_name("tennis-stroke")), "whatif", "sig"]
    run = subprocess.Popen(
        [*command, "--set", "M2=0.35", "--figure", "fig2", "--cores", "1"],
        cwd=checkout,
        start_new_session=True,  # its own process group, as a terminal's foreground job
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    locks = checkout / ".snakemake" / "locks"
    deadline = time.monotonic() + 120
    while not (locks.is_dir() and any(locks.iterdir())):
        assert run.poll() is None, run.communicate()
        assert time.monotonic() < deadline, "Snakemake took no lock in 120 s"
        time.sleep(0.05)
    time.sleep(0.5)  # a job under way
    os.killpg(run.pid, signum)
    out, err = run.communicate(timeout=300)
    assert run.returncode == status, err[-2000:]
    assert err.strip().splitlines()[-1] == line and "Traceback" not in err, err[-2000:]
    assert not list(locks.iterdir()), sorted(p.name for p in locks.iterdir())
    again = subprocess.run(
        [sys.executable, "-m", "snakemake", "-n", "--cores", "1", "results/claims.csv"],
        cwd=checkout,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert again.returncode == 0 and "LockException" not in again.stderr, again.stderr[-2000:]
