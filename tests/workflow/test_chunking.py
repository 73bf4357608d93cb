"""Chunked maps: the gathered chunks equal the unchunked map, bit for bit."""

import numpy as np
import pytest
import xarray as xr
from conftest import assert_same_results

from tennis_stroke import SolverSettings
from tennis_stroke.experiments.grids import chunk_count, chunk_rows
from tennis_stroke.experiments.maps import angle_map, delay_map, elbow_force_map, mass_length_map
from tennis_stroke.io.netcdf import write_netcdf
from tennis_stroke.pipeline.chunks import ChunkError, gather_chunks, mark_chunk

SETTINGS = SolverSettings()
THETA0 = np.array([60.0, 75.0, 90.0, 105.0, 120.0])
DELTA0 = np.array([10.0, 40.0, 70.0])


@pytest.mark.parametrize("rows, count", [(1, 1), (5, 2), (7, 3), (10, 10), (3, 5)])
def test_chunks_cover_every_row_once_in_order(rows, count):
    values = np.arange(rows, dtype=float)
    n = chunk_count(count, rows)
    assert 1 <= n <= rows
    parts = [chunk_rows(values, i, n) for i in range(n)]
    assert all(p.size for p in parts)
    np.testing.assert_array_equal(np.concatenate(parts), values)


def test_bad_chunk_requests_raise():
    with pytest.raises(ValueError, match="chunk count must be >= 1"):
        chunk_count(0, 10)
    with pytest.raises(ValueError, match="outside 0..1"):
        chunk_rows(np.arange(4.0), 2, 2)


def _chunked(compute, values, dim, count, tmp_path):
    paths = []
    for i in range(count):
        ds = mark_chunk(compute(chunk_rows(values, i, count)), i, count)
        assert ds.attrs["chunk_dim"] == dim  # the map's first axis
        ds.attrs["wall_time_s"] = float(i)
        paths.append(write_netcdf(ds, tmp_path / f"{i}-of-{count}.nc"))
    return gather_chunks(paths[::-1])  # order on disk must not matter


EXPERIMENTS = {
    "angle_map": (
        lambda rows: angle_map(rows, DELTA0, {"L1": 0.4}, SETTINGS, 1),
        THETA0,
        "theta0",
    ),
    "delay_map": (
        lambda rows: delay_map("C2", rows, np.array([0.0, 0.1]), 90.0, 26.1, {}, SETTINGS, 1),
        np.array([1.0, 2.5, 5.0]),
        "C2",
    ),
    "elbow_force_map": (
        lambda rows: elbow_force_map(
            rows, np.array([-0.05, 0.0]), 0.185, 90.0, 52.5, {"tau": 0.185}, SETTINGS, 1
        ),
        np.array([0.0, 90.0, 180.0, 270.0]),
        "psi_F",
    ),
    "mass_length_map": (
        lambda rows: mass_length_map(
            rows, np.array([0.3]), 30.0, 15.0, (60.0, 120.0), (0.0, 90.0), {}, SETTINGS, 1
        ),
        np.array([0.2, 0.3, 0.4]),
        "M2",
    ),
}


@pytest.mark.parametrize("name", sorted(EXPERIMENTS))
@pytest.mark.parametrize("count", [2, 3])
def test_gathered_chunks_equal_the_unchunked_map_bit_for_bit(name, count, tmp_path):
    compute, values, dim = EXPERIMENTS[name]
    whole = write_netcdf(compute(values), tmp_path / "whole.nc")
    gathered = _chunked(compute, values, dim, count, tmp_path)
    assert_same_results(gathered, whole, also_differ=["chunk_count"])
    assert gathered.attrs["chunk_count"] == count
    assert gathered.attrs["wall_time_s"] == sum(range(count))
    assert "chunk_index" not in gathered.attrs


def test_missing_or_foreign_chunks_are_refused(tmp_path):
    compute, values, _ = EXPERIMENTS["angle_map"]
    paths = []
    for i in range(3):
        ds = mark_chunk(compute(chunk_rows(values, i, 3)), i, 3)
        paths.append(write_netcdf(ds, tmp_path / f"{i}.nc"))
    with pytest.raises(ChunkError, match=r"chunks \[0, 2\] do not make up 0..2"):
        gather_chunks([paths[0], paths[2]])
    other = angle_map(chunk_rows(values, 1, 3), DELTA0, {"L1": 0.3}, SETTINGS, 1)
    write_netcdf(mark_chunk(other, 1, 3), paths[1])
    with pytest.raises(ChunkError, match="chunks disagree on attribute 'param_"):
        gather_chunks(paths)
    plain = compute(values)
    with pytest.raises(ChunkError, match="no chunk attributes"):
        gather_chunks([write_netcdf(plain, tmp_path / "plain.nc")])


def test_a_garbage_chunk_file_is_named(tmp_path):
    from tennis_stroke.pipeline.chunks import ChunkError, gather_chunks

    bad = tmp_path / "0-of-1.nc"
    bad.write_bytes(b"garbage")
    with pytest.raises(ChunkError, match=f"chunk file {str(bad)!r} cannot be read"):
        gather_chunks([bad])


def test_strings_longer_than_the_first_chunk_s_are_gathered_whole(tmp_path):
    """A string variable or coordinate (the work-precision study's scenes) read back from
    a chunk file keeps that file's string width in its encoding: written with it, the
    gathered file cut every longer string of the later chunks."""
    texts, names = ["short", "a much longer description"], ["a", "longer_name"]
    paths = []
    for i in range(2):
        ds = xr.Dataset(
            {"text": ("scene", [texts[i]]), "x": ("scene", [float(i)])},
            coords={"scene": [names[i]]},
        )
        paths.append(write_netcdf(mark_chunk(ds, i, 2), tmp_path / f"{i}-of-2.nc"))
    gathered = write_netcdf(gather_chunks(paths), tmp_path / "gathered.nc")
    with xr.open_dataset(gathered) as back:
        assert list(back["text"].values) == texts
        assert list(back["scene"].values) == names
