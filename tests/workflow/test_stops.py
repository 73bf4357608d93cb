"""Stops: a signal to a command that runs the workflow for the user (tennis-stroke
whatif) reaches Snakemake and its jobs, which stop; what an interrupted or killed run
leaves, the next run handles by itself."""

import os
import shutil
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


#: The tennis-stroke command of this environment.
EXE = str(Path(sys.executable).with_name("tennis-stroke"))
#: A new scenario whose strokes cannot finish (each runs to the step limit) on a finer
#: Fig. 2 grid: its map job computes for a long while, far past any stop (the
#: slow-failing strokes of issue 56).
SLOW = [
    "--set",
    "C1=-1e6",
    "--set",
    "angle_maps.theta0.step=0.25",
    "--set",
    "angle_maps.delta0.step=10",
    "--figure",
    "fig2",
    "--cores",
    "1",
]
#: Seconds a stop may take, start-up and shutdown of Snakemake included: a fail-safe
#: bound, not a timing (without the stops, the map job computed on for minutes).
STOP_BOUND = 20.0


def _checkout(tmp_path: Path) -> Path:
    """A checkout of the project (its code linked) with the tiny configuration."""
    checkout = tmp_path / "checkout"
    checkout.mkdir()
    for name in CHECKOUT:
        (checkout / name).symlink_to(ROOT / name)
    return workdir(checkout, TINY, TINY_READINGS)


def _whatif(checkout: Path, name: str, *options: str, err: Path) -> subprocess.Popen:
    """``tennis-stroke whatif NAME OPTIONS`` in ``checkout``, in a session of its own (as
    a terminal's foreground job), its stderr to the file ``err`` (a pipe would stay open
    as long as anything the command started runs)."""
    with open(err, "w") as stderr:
        return subprocess.Popen(
            [EXE, "whatif", name, *options],
            cwd=checkout,
            start_new_session=True,
            # a closed terminal's default: a run under nohup ignores SIGHUP, and passes that on
            preexec_fn=lambda: signal.signal(signal.SIGHUP, signal.SIG_DFL),
            stdout=subprocess.DEVNULL,
            stderr=stderr,
        )


def _computing(checkout: Path, name: str, run: subprocess.Popen) -> None:
    """Wait until a job of scenario ``name`` computes: its log is opened after the
    job's imports (pipeline.jobs.logged)."""
    logs = checkout / "logs" / "scenarios" / name
    deadline = time.monotonic() + 300
    while not (logs.is_dir() and any(logs.rglob("*.log"))):
        assert run.poll() is None, "the run ended before a job of the scenario computed"
        assert time.monotonic() < deadline, "no job of the scenario started in 300 s"
        time.sleep(0.05)
    time.sleep(0.5)  # inside the strokes


def _left(session: int) -> list[str]:
    """The processes still running in ``session`` (a command and all it started)."""
    found = subprocess.run(["pgrep", "-s", str(session)], capture_output=True, text=True)
    return found.stdout.split()


@pytest.mark.signals
@pytest.mark.parametrize(
    ("signum", "status", "line"),
    [
        (signal.SIGINT, 130, "tennis-stroke: interrupted"),
        (signal.SIGTERM, 143, "tennis-stroke: terminated"),
        (signal.SIGHUP, 143, "tennis-stroke: terminated"),
    ],
)
def test_whatif_stopped_by_a_signal_stops_its_jobs_and_the_next_run_starts(
    tmp_path, signum, status, line
):
    """Ctrl-C (the terminal's SIGINT to the command's process group), SIGTERM or a closed
    terminal (SIGHUP) while `tennis-stroke whatif` runs a job of strokes that fail
    slowly: the signal reaches Snakemake and its job, which stops at its next stroke;
    the command ends with one line and the signal's status, leaving no process and no
    lock; the next run of the same scenario starts.  Issue 56: SIGTERM went to Snakemake
    alone, which waited for its job ('Will exit after finishing currently running jobs',
    still running 95 s later); after SIGINT the job's outputs stayed marked incomplete
    and the next whatif failed with IncompleteFilesException (whatif has no
    --rerun-incomplete).  (subprocess.run killed Snakemake 0.25 s after Ctrl-C, and at
    once on SIGTERM, before it removed its locks.)"""
    checkout = _checkout(tmp_path)
    run = _whatif(checkout, "slow", *SLOW, err=tmp_path / "err")
    _computing(checkout, "slow", run)
    os.killpg(run.pid, signum)
    sent = time.monotonic()
    try:
        run.wait(timeout=300)
        stopped_after = time.monotonic() - sent
    finally:
        for pid in _left(run.pid):
            os.kill(int(pid), signal.SIGKILL)
    err = (tmp_path / "err").read_text()
    assert run.returncode == status, err[-2000:]
    assert err.strip().splitlines()[-1] == line and "Traceback" not in err, err[-2000:]
    assert stopped_after < STOP_BOUND, f"stopped {stopped_after:.1f} s after the signal"
    assert _left(run.pid) == []  # no job outlives the command
    locks = checkout / ".snakemake" / "locks"
    assert not list(locks.iterdir()), sorted(p.name for p in locks.iterdir())
    again = subprocess.run(
        [EXE, "whatif", "slow", *SLOW, "-n"],
        cwd=checkout,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert again.returncode == 0, again.stderr[-2000:]
    assert "IncompleteFilesException" not in again.stderr + again.stdout


@pytest.mark.signals
def test_a_killed_whatif_leaves_no_job_running_and_the_next_run_starts(tmp_path):
    """kill -9 of `tennis-stroke whatif` left Snakemake (in a process group of its own)
    running unseen; it wrote the scenario's page 45 s later (issue 56).  Now Snakemake
    dies with the command (the kernel's parent-death signal) and its job, which watches
    it, stops; the next run removes the dead run's locks by itself and starts."""
    checkout = _checkout(tmp_path)
    run = _whatif(checkout, "slow", *SLOW, err=tmp_path / "first")
    _computing(checkout, "slow", run)
    run.kill()
    run.wait()
    deadline = time.monotonic() + STOP_BOUND
    while _left(run.pid) and time.monotonic() < deadline:
        time.sleep(0.1)
    left = _left(run.pid)
    for pid in left:
        os.kill(int(pid), signal.SIGKILL)
    assert left == [], "processes of the killed whatif still running"
    assert not list((checkout / "results" / "scenarios").rglob("fig2.nc"))
    assert list((checkout / ".snakemake" / "locks").iterdir())  # left by the dead run
    shutil.rmtree(checkout / "logs" / "scenarios")  # the next job's log tells it started
    second = _whatif(checkout, "slow", *SLOW, err=tmp_path / "second")
    _computing(checkout, "slow", second)  # not refused: no LockException
    os.killpg(second.pid, signal.SIGINT)
    second.wait(timeout=300)
    err = (tmp_path / "second").read_text()
    assert "removed the locks of an earlier run" in err, err[-2000:]
    assert "LockException" not in err and "IncompleteFilesException" not in err


@pytest.mark.signals
def test_a_second_run_in_the_folder_is_told_another_is_active(tmp_path):
    """Two runs in one checkout: a whatif while another runs was told to --unlock (a
    LockException), harmful while the other run is live; a second `make report` got an
    IncompleteFilesException.  Now each is one line naming the active run, before
    anything starts, and `snakemake --unlock` is refused likewise, keeping its locks."""
    checkout = _checkout(tmp_path)
    run = _whatif(checkout, "slow", *SLOW, err=tmp_path / "err")
    try:
        _computing(checkout, "slow", run)
        # whatif's one child: Snakemake
        children = subprocess.run(["pgrep", "-P", str(run.pid)], capture_output=True, text=True)
        pid = children.stdout.split()[0]
        second = [
            [EXE, "whatif", "other", "--set", "M2=0.35", "--figure", "fig2", "--cores", "1"],
            [sys.executable, "-m", "snakemake", "--cores", "1", "results/claims.csv"],
            [sys.executable, "-m", "snakemake", "--unlock"],
        ]
        for command in second:
            done = subprocess.run(
                command, cwd=checkout, capture_output=True, text=True, timeout=300
            )
            lines = [x for x in done.stderr.splitlines() if "tennis-stroke" in x]
            assert done.returncode == 1, done.stderr[-2000:]
            assert len(lines) == 1 and "LockException" not in done.stderr, done.stderr[-2000:]
            assert lines[0].startswith(
                f"tennis-stroke error: another run is active in this folder (Snakemake, pid {pid})"
            )
            assert "--unlock" not in done.stderr  # never advised, not even not to
        assert list((checkout / ".snakemake" / "locks").iterdir())  # the live run's, kept
    finally:
        os.killpg(run.pid, signal.SIGINT)
        run.wait(timeout=300)
