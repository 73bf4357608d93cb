"""Result files: atomic writes and provenance."""

import numpy as np
import pytest
import xarray as xr

from tennis_stroke.io import OutputError, check_writable, result_dataset, write_netcdf
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


def test_check_writable_rejects_directories(tmp_path):
    with pytest.raises(OutputError, match="is a directory"):
        check_writable(tmp_path)
