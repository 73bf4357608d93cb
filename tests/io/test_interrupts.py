"""SIGINT and SIGTERM while a result file is written (tennis_stroke.io.interrupts): the
write finishes, no temporary file is left, the earlier file is kept, and the signal then
takes effect; the command line ends with one line and 130 or 143."""

import ast
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr
from conftest import ROOT

from tennis_stroke.io import netcdf
from tennis_stroke.io.interrupts import (
    PARENT_ENV,
    Terminated,
    _alive,
    deferred_signals,
    process_identity,
    terminate_raises,
)


def _dataset():
    return xr.Dataset(
        {"v_out": ("theta0", np.arange(3.0), {"units": "km/h", "long_name": "v"})},
        coords={"theta0": ("theta0", np.arange(3.0), {"units": "degree", "long_name": "t"})},
    )


@pytest.mark.parametrize("signum, raised", [(signal.SIGINT, KeyboardInterrupt)])
def test_a_signal_during_a_write_waits_for_it_and_keeps_the_old_file(
    tmp_path, monkeypatch, signum, raised
):
    path = tmp_path / "map.nc"
    path.write_bytes(b"the earlier result")
    real = xr.Dataset.to_netcdf
    finished = []

    def interrupted_write(self, *args, **kwargs):
        os.kill(os.getpid(), signum)  # arrives while the library writes
        out = real(self, *args, **kwargs)
        finished.append(True)
        return out

    monkeypatch.setattr(xr.Dataset, "to_netcdf", interrupted_write)
    with pytest.raises(raised):
        netcdf.write_netcdf(_dataset(), path)
    assert finished == [True]  # the library was not interrupted inside
    assert path.read_bytes() == b"the earlier result"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.nc"]


@pytest.mark.parametrize("made", [1, 2], ids=["the writability probe", "the write's file"])
def test_a_signal_as_a_temporary_file_is_made_leaves_none(tmp_path, monkeypatch, made):
    """SIGTERM right after a temporary file beside the output is made (the probe of
    check_writable, then the write's own): nothing is left, the old file is kept.  Before,
    the signal came before the deferral began and the file stayed (a workflow run's
    SIGTERM, CI 2026-12-03)."""
    path = tmp_path / "map.nc"
    path.write_bytes(b"the earlier result")
    real, calls = netcdf.temporary_beside, []

    def signalled(target):
        tmp = real(target)
        calls.append(tmp)
        if len(calls) == made:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(0.01)  # delivered here, were it not deferred
        return tmp

    monkeypatch.setattr(netcdf, "temporary_beside", signalled)
    with terminate_raises(), pytest.raises(Terminated):
        netcdf.write_netcdf(_dataset(), path)
    assert len(calls) == made
    assert path.read_bytes() == b"the earlier result"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.nc"]


def test_sigterm_raises_terminated_after_the_deferred_block():
    with terminate_raises(), pytest.raises(Terminated):
        with deferred_signals() as received:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(0.01)
            assert received == [signal.SIGTERM]  # recorded, not acted on yet


def test_the_previous_sigterm_handler_is_back_after_the_block():
    """A test run that calls the command line in its own process still ends on SIGTERM
    (make test kept running after SIGTERM to its process group)."""
    before = signal.getsignal(signal.SIGTERM)
    with terminate_raises():
        assert signal.getsignal(signal.SIGTERM) is not before
    assert signal.getsignal(signal.SIGTERM) is before


@pytest.mark.signals
@pytest.mark.parametrize("signum, status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_sweep_stopped_by_a_signal_ends_in_one_line(tmp_path, signum, status):
    out = tmp_path / "map.nc"
    command = [
        sys.executable,
        "-m",
        "tennis_stroke.cli",
        "sweep",
        "--theta0",
        "60:120:1201",
        "--delta0",
        "0:90:1801",
        "--threads",
        "1",
        "--no-progress",
        "--out",
        str(out),
    ]
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(4.0)  # past start-up, inside the sweep
    proc.send_signal(signum)
    start = time.perf_counter()
    stdout, stderr = proc.communicate(timeout=30)
    assert time.perf_counter() - start < 5
    assert proc.returncode == status, stderr
    assert len(stderr.strip().splitlines()) == 1 and "Traceback" not in stderr
    assert list(tmp_path.iterdir()) == []


JOB = """
import sys, time
from tennis_stroke.io.interrupts import Terminated, stop_with_snakemake, terminate_raises
with terminate_raises():
    try:
        with stop_with_snakemake():
            print("running", flush=True)
            time.sleep(60)
    except Terminated:
        sys.exit(143)
"""


@pytest.mark.signals
def test_a_job_stops_when_its_snakemake_is_killed():
    """After kill -9 of Snakemake its jobs computed on and wrote their files: a job
    watches the Snakemake process named in its environment and stops within a second."""
    with subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"]) as parent:
        env = {**os.environ, PARENT_ENV: process_identity(parent.pid)}
        with subprocess.Popen(
            [sys.executable, "-c", JOB],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        ) as job:
            assert job.stdout.readline() == "running\n"
            time.sleep(1.0)
            assert job.poll() is None  # its Snakemake is alive: it runs on
            parent.kill()
            parent.wait()
            _, stderr = job.communicate(timeout=10)
    assert job.returncode == 143
    assert f"its Snakemake (pid {parent.pid}) ended: stopping" in stderr


def test_a_reused_pid_is_not_taken_for_the_snakemake_process():
    """The identity holds the process's start time: another process that got the PID
    later is not the job's Snakemake."""
    mine = process_identity(os.getpid())
    pid, start = mine.split(":")
    assert start.isdigit()
    assert _alive(mine) and not _alive(f"{pid}:{int(start) + 1}")


#: A workflow job's script in miniature: signals made quiet first, then an import that
#: takes a while (scipy's, in the claims job of issue 56).
QUIET_SCRIPT = """
from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()

import slow_import
"""


@pytest.mark.signals
@pytest.mark.parametrize(
    "signum, status, line",
    [
        (signal.SIGINT, 130, "tennis-stroke job interrupted\n"),
        (signal.SIGTERM, 143, "tennis-stroke job terminated\n"),
    ],
)
def test_a_signal_while_a_job_imports_is_one_line(tmp_path, signum, status, line):
    """Ctrl-C during `make report` printed 30 lines of traceback from inside scipy's import
    in a job's script, before its logged block: now one line and the signal's status."""
    (tmp_path / "slow_import.py").write_text(
        'print("importing", flush=True)\nimport time\ntime.sleep(60)\n'
    )
    with subprocess.Popen(
        [sys.executable, "-c", QUIET_SCRIPT],
        env={**os.environ, "PYTHONPATH": str(tmp_path)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    ) as job:
        assert job.stdout.readline() == "importing\n"
        job.send_signal(signum)
        _, stderr = job.communicate(timeout=30)
    assert stderr == line
    assert job.returncode == status


def test_every_workflow_script_makes_signals_quiet_before_its_imports():
    """Each script's first statements (after its docstring) make signals quiet; only
    then does it import anything else (tests/io: the behaviour)."""
    scripts = sorted((ROOT / "workflow" / "scripts").glob("*.py"))
    assert len(scripts) >= 10
    for path in scripts:
        body = ast.parse(path.read_text()).body[1:3]  # after the docstring
        assert [ast.unparse(node) for node in body] == [
            "from tennis_stroke.io.interrupts import quiet_job_stops",
            "quiet_job_stops()",
        ], path.name


def test_snakemake_s_sigterm_handler_takes_the_lock_its_main_thread_may_hold():
    """Why `tennis-stroke whatif` never passes SIGTERM on (``FORWARDED``): Snakemake's
    handler waits for the scheduler's lock, a ``threading.Lock``, which the main thread,
    where the handler runs, holds while it handles a stopped job: there it waits for
    ever.  (Should Snakemake stop taking the lock, this fails and SIGTERM may be passed
    on again.)"""
    import threading
    import types

    from snakemake.scheduling.job_scheduler import JobScheduler

    scheduler = types.SimpleNamespace(
        _lock=threading.Lock(), _open_jobs=threading.Semaphore(0), _user_kill=None
    )
    with scheduler._lock:  # the main thread in the scheduling loop's `with self._lock`
        handler = threading.Thread(target=JobScheduler.exit_gracefully, args=(scheduler,))
        handler.start()
        handler.join(0.5)
        assert handler.is_alive() and scheduler._user_kill is None
    handler.join(5)
    assert scheduler._user_kill == "graceful"


#: A command in place of Snakemake: it records the first signal it gets in ``argv[1]``.
RECORDING = """
import pathlib, signal, sys, time
out = pathlib.Path(sys.argv[1])
def record(signum, frame):
    out.write_text(signal.Signals(signum).name)
    sys.exit(0)
for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
    signal.signal(s, record)
out.with_suffix(".ready").touch()
while True:
    time.sleep(0.01)
"""


@pytest.mark.signals
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_a_stop_reaches_the_snakemake_of_a_command_as_ctrl_c(tmp_path, signum):
    """SIGTERM or SIGHUP to a command that runs Snakemake (``run_forwarding``, as
    `tennis-stroke whatif` does) reaches Snakemake's process group as SIGINT, and the
    command still ends as terminated."""
    out = tmp_path / "got"
    parent = (
        "import sys\nfrom tennis_stroke.io.interrupts import Terminated, run_forwarding\n"
        f"try:\n    run_forwarding([sys.executable, '-c', {RECORDING!r}, {str(out)!r}])\n"
        "except Terminated:\n    sys.exit(143)\n"
    )
    with subprocess.Popen([sys.executable, "-c", parent]) as command:
        deadline = time.monotonic() + 60
        while not out.with_suffix(".ready").exists():
            assert command.poll() is None and time.monotonic() < deadline
            time.sleep(0.01)
        command.send_signal(signum)
        assert command.wait(timeout=30) == 143
    assert out.read_text() == "SIGINT"
