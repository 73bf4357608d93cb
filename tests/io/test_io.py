"""Result files: atomic writes, permissions and provenance."""

import os
import stat
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tennis_stroke.io.netcdf import OutputError, check_writable, result_dataset, write_netcdf
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver.stroke import SolverSettings, strike_batch


def _dataset():
    theta0, delta0 = np.array([80.0, 100.0]), np.array([20.0, 40.0])
    res = strike_batch(theta0[:, None], delta0[None, :])
    return result_dataset(
        res, {"theta0": theta0, "delta0": delta0}, resolve_params(), SolverSettings()
    )


def test_write_is_atomic_and_leaves_no_temporary(tmp_path):
    path = write_netcdf(_dataset(), tmp_path / "a.nc")
    assert [p.name for p in tmp_path.iterdir()] == ["a.nc"]
    with xr.open_dataset(path) as ds:
        assert ds["v_out"].shape == (2, 2)
        assert ds.attrs["git_commit"]


def test_failed_write_keeps_the_old_file(tmp_path, monkeypatch):
    path = write_netcdf(_dataset(), tmp_path / "a.nc")
    before = path.read_bytes()

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", broken)
    with pytest.raises(OutputError, match="disk full"):
        write_netcdf(_dataset(), path)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["a.nc"]


@pytest.mark.parametrize(
    "umask, mode",
    [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)],
    ids=["umask-022", "umask-077", "umask-002"],
)
@pytest.mark.parametrize("proc", [True, False], ids=["from-proc", "set-and-reset"])
def test_result_files_get_the_permissions_the_umask_gives_new_files(
    tmp_path, monkeypatch, umask, mode, proc
):
    if not proc:
        read_text = Path.read_text

        def no_proc(self, *args, **kwargs):
            if str(self).startswith("/proc"):
                raise FileNotFoundError(self)
            return read_text(self, *args, **kwargs)

        monkeypatch.setattr(Path, "read_text", no_proc)
    old = os.umask(umask)
    try:
        path = write_netcdf(_dataset(), tmp_path / "a.nc")
        assert os.umask(umask) == umask  # the write left the umask as it was
    finally:
        os.umask(old)
    assert stat.S_IMODE(path.stat().st_mode) == mode


def test_check_writable_rejects_directories(tmp_path):
    with pytest.raises(OutputError, match="is a directory"):
        check_writable(tmp_path)
