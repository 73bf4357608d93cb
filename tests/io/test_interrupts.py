"""SIGINT and SIGTERM while a result file is written (tennis_stroke.io.interrupts): the
write finishes, no temporary file is left, the earlier file is kept, and the signal then
takes effect; the command line ends with one line and 130 or 143."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr

from tennis_stroke.io import netcdf
from tennis_stroke.io.interrupts import Terminated, deferred_signals, terminate_raises


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


def test_sigterm_raises_terminated_after_the_deferred_block():
    terminate_raises()
    try:
        with pytest.raises(Terminated):
            with deferred_signals() as received:
                os.kill(os.getpid(), signal.SIGTERM)
                time.sleep(0.01)
                assert received == [signal.SIGTERM]  # recorded, not acted on yet
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


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
