"""A damaged result file is told from a whole one without reading it
(tennis_stroke.io.netcdf.damage): truncated, garbage, empty; a whole file passes."""

import numpy as np
import xarray as xr

from tennis_stroke.io.netcdf import damage, write_netcdf


def _whole(path):
    ds = xr.Dataset(
        {"v_out": (("theta0",), np.arange(5000.0), {"units": "km/h", "long_name": "v"})},
        coords={"theta0": ("theta0", np.arange(5000.0), {"units": "degree", "long_name": "t"})},
    )
    return write_netcdf(ds, path)


def test_a_whole_file_passes_and_a_truncated_one_is_named(tmp_path):
    path = _whole(tmp_path / "map.nc")
    assert damage(path) is None
    size = path.stat().st_size
    with open(path, "r+b") as f:
        f.truncate(size // 2)
    assert damage(path) == f"truncated ({size // 2} of its {size} bytes)"


def test_garbage_and_empty_files_are_damaged(tmp_path):
    (tmp_path / "g.nc").write_bytes(b"garbage" * 20)
    (tmp_path / "e.nc").write_bytes(b"")
    assert "no HDF5 signature" in damage(tmp_path / "g.nc")
    assert "no HDF5 signature" in damage(tmp_path / "e.nc")
    (tmp_path / "h.nc").write_bytes(b"\x89HDF\r\n\x1a\n\x02")
    assert "truncated" in damage(tmp_path / "h.nc")
