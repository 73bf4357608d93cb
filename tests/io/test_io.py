"""Result files: atomic writes, permissions and provenance."""

import os
import stat
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tennis_stroke.io import netcdf
from tennis_stroke.io.errors import ResultError
from tennis_stroke.io.netcdf import (
    OutputError,
    check_writable,
    load_result,
    result_dataset,
    write_netcdf,
)
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


def _gone_pid() -> int:
    """The id of a process that ran and ended (reaped: no process has it now)."""
    import subprocess

    done = subprocess.Popen(["true"])
    done.wait()
    return done.pid


def test_a_temporary_whose_writer_is_gone_is_removed_by_the_next_write(tmp_path):
    """Was: a ``kill -9`` of a sweep while it wrote left a hidden 38 MB ``.out.nc.XXXX.tmp``
    for ever (issue 66, case 15).  Only the target's temporaries whose writer is gone go:
    a live writer's (a concurrent sweep into the same file), another machine's (a shared
    folder) and another file's stay."""
    host, gone, live = netcdf._host(), _gone_pid(), os.getppid()
    names = {
        "stale": f".out.nc.{host}.{gone}.abcd_123.tmp",
        "live writer": f".out.nc.{host}.{live}.efgh_456.tmp",
        "another machine": f".out.nc.elsewhere.{gone}.ijkl_789.tmp",
        "another file": f".other.nc.{host}.{gone}.mnop_012.tmp",
        "unnamed, old": ".out.nc.qrst_345.tmp",  # the earlier writer's, a day old
        "unnamed, new": ".out.nc.uvwx_678.tmp",
    }
    for name in names.values():
        (tmp_path / name).write_bytes(b"partial")
    old = time.time() - netcdf.STALE_UNNAMED_SECONDS - 60
    os.utime(tmp_path / names["unnamed, old"], (old, old))
    write_netcdf(_dataset(), tmp_path / "out.nc")
    left = {p.name for p in tmp_path.iterdir()}
    assert left == {"out.nc", *names.values()} - {names["stale"], names["unnamed, old"]}


def test_a_temporary_names_its_writer(tmp_path):
    """What the removal reads: this machine and this process, in the target's pattern."""
    tmp = netcdf.temporary_beside(tmp_path / "out.nc")
    match = netcdf._temporary_name(tmp_path / "out.nc").fullmatch(tmp.name)
    assert match and (match["host"], int(match["pid"])) == (netcdf._host(), os.getpid())
    assert netcdf.remove_stale_temporaries(tmp_path / "out.nc") == []  # its writer runs


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


def test_a_replaced_result_keeps_its_mode_and_a_read_only_one_is_refused(tmp_path):
    path = tmp_path / "map.nc"
    write_netcdf(_map(np.ones(3)), path)
    path.chmod(0o640)
    write_netcdf(_map(np.full(3, 2.0)), path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o640
    np.testing.assert_array_equal(load_result(path)["v_out"].values, 2.0)
    path.chmod(0o444)
    with pytest.raises(OutputError, match="is read-only"):
        write_netcdf(_map(np.full(3, 3.0)), path)
    np.testing.assert_array_equal(load_result(path)["v_out"].values, 2.0)
    assert [p.name for p in tmp_path.iterdir()] == ["map.nc"]


def _map(values):
    return xr.Dataset(
        {"v_out": (("theta0",), values, {"units": "km/h", "long_name": "rebound speed"})},
        coords={"theta0": ("theta0", np.arange(values.size, dtype=float), {"units": "degree"})},
    )


def test_every_array_is_written_with_a_checksum_and_read_back_the_same(tmp_path):
    values = np.linspace(100.0, 150.0, 4096)
    write_netcdf(_map(values), tmp_path / "map.nc")
    ds = load_result(tmp_path / "map.nc")
    assert all(ds[name].encoding.get("fletcher32") for name in ds.variables)
    np.testing.assert_array_equal(ds["v_out"].values, values)


def test_a_damaged_byte_inside_a_result_is_refused_naming_the_file(tmp_path):
    """The superblock check cannot see a byte changed among the data; without the
    checksum the file reads back with one wrong number and no error."""
    values = np.linspace(100.0, 150.0, 4096)
    path = tmp_path / "map.nc"
    write_netcdf(_map(values), path)
    data = bytearray(path.read_bytes())
    at = data.find(values[2000:2008].tobytes())
    assert at > 0  # the array's bytes, uncompressed
    data[at + 3] ^= 0x10
    path.write_bytes(bytes(data))
    with pytest.raises(ResultError, match=r"map\.nc.*cannot be read.*checksum"):
        load_result(path)


def test_a_missing_or_foreign_result_is_refused_naming_it(tmp_path):
    rebuild = r"nothing\.nc.*missing: make it with: snakemake -j2 .*nothing\.nc"
    with pytest.raises(ResultError, match=rebuild):
        load_result(tmp_path / "nothing.nc")
    (tmp_path / "folder.nc").mkdir()
    with pytest.raises(ResultError, match=r"folder\.nc.*not a file"):
        load_result(tmp_path / "folder.nc")
    (tmp_path / "text.nc").write_text("not a result")
    with pytest.raises(ResultError, match=r"text\.nc.*no HDF5 signature"):
        load_result(tmp_path / "text.nc")


def test_only_a_change_of_what_the_jobs_read_marks_a_commit_dirty(tmp_path):
    """Editing config/scenarios.yaml (a what-if), a doc or a test stamped every later
    paper file `-dirty`; a change of the code or the paper's config still does."""
    import subprocess

    from tennis_stroke.io.netcdf import commit_of

    def git(*args):
        subprocess.run(["git", *args], cwd=tmp_path, check=True, capture_output=True)

    (tmp_path / "src").mkdir()
    (tmp_path / "config").mkdir()
    files = ["src/code.py", "config/config.yaml", "config/scenarios.yaml", "README.md"]
    for name in files:
        (tmp_path / name).write_text("x\n")
    git("init", "-q")
    git("add", ".")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "c")
    clean = commit_of(tmp_path / "src")
    assert len(clean) == 40
    for name in ("config/scenarios.yaml", "README.md"):
        (tmp_path / name).write_text("y\n")
    assert commit_of(tmp_path / "src") == clean
    for name in ("src/code.py", "config/config.yaml"):
        (tmp_path / name).write_text("y\n")
        assert commit_of(tmp_path / "src") == f"{clean}-dirty", name
        git("checkout", "--", name)
