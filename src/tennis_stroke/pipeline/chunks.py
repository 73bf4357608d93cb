"""Maps split into independent chunks along their first axis, and gathered again.

A map (Figs. 2-3, 5-9, 13) is a grid of strokes, and every stroke (or, for Figs. 5-6,
every optimum search) is computed independently of the others.  A chunk is a contiguous
block of rows of the map's first axis
(:func:`tennis_stroke.experiments.grids.chunk_rows`, the same blocks as
:func:`numpy.array_split`); the experiment function runs on those rows only, and
:func:`gather_chunks` concatenates the chunk datasets along that axis.  Chunking
therefore never changes a number: the gathered dataset equals the unchunked one bit for
bit (tested in ``tests/workflow/test_chunking.py`` and ``tests/workflow/test_workflow.py``).

Each chunk file records ``chunk_dim``, ``chunk_index`` and ``chunk_count``; the gathered
file records ``chunk_count`` and the chunks' wall times.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr

#: Attributes of a chunk file that describe the chunk, not the map.
CHUNK_ATTRS = ("chunk_dim", "chunk_index", "chunk_count")
#: Attributes that differ between the chunks of one map (all others must agree).
PER_CHUNK_ATTRS = ("chunk_index", "wall_time_s", "history")


class ChunkError(ValueError):
    """The chunk files do not form one complete map (message is one line)."""


def mark_chunk(ds: xr.Dataset, index: int, count: int) -> xr.Dataset:
    """Record in ``ds`` which chunk of the map it holds: rows of its first dimension."""
    ds.attrs.update(
        {"chunk_dim": next(iter(ds.sizes)), "chunk_index": int(index), "chunk_count": int(count)}
    )
    return ds


def _same(a, b) -> bool:
    return bool(np.array_equal(np.asarray(a), np.asarray(b)))


def _fit_string_width(var: xr.Variable) -> None:
    """Drop a string encoding (read from the first chunk) narrower than the gathered
    strings: written with it, a longer string of a later chunk was cut (a fixed-width
    ``dtype``) or renamed its dimension with a warning (``char_dim_name``).  A width that
    fits is kept, so a file whose first chunk held the longest strings is written as
    before."""
    if var.dtype.kind not in "OSU" or var.size == 0:
        return
    texts = [str(v) for v in np.asarray(var.values).ravel()]
    dtype = var.encoding.get("dtype")
    if dtype is not None and np.dtype(dtype).kind == "U":
        if np.dtype(dtype).itemsize // 4 < max(map(len, texts)):  # characters
            var.encoding.pop("dtype")
    width = re.fullmatch(r"string(\d+)", str(var.encoding.get("char_dim_name", "")))
    if width and int(width[1]) < max(len(t.encode()) for t in texts):  # bytes
        var.encoding.pop("char_dim_name")


def gather_chunks(paths: Sequence[str | Path]) -> xr.Dataset:
    """One map from its chunk files, in chunk order, along the recorded dimension.

    Raises
    ------
    ChunkError
        A chunk is missing or repeated, or the chunks disagree on the dimension, the
        count, or anything outside the chunked rows (the other axes, the parameters).

    Notes
    -----
    The gathered file keeps the first chunk's ``history`` and records the sum of the
    chunks' wall times (``wall_time_s``) and each one (``chunk_wall_times_s``).
    """
    parts = []
    for path in paths:
        try:
            with xr.open_dataset(path) as ds:
                parts.append(ds.load())
        except (OSError, ValueError, RuntimeError) as exc:
            problem = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise ChunkError(
                f"chunk file {str(path)!r} cannot be read ({problem}): remove it and rerun"
            ) from None
    if not parts:
        raise ChunkError("no chunk files to gather")
    first = parts[0].attrs
    if any(key not in p.attrs for p in parts for key in CHUNK_ATTRS):
        raise ChunkError("a file to gather has no chunk attributes (chunk_dim, chunk_index)")
    dim, count = first["chunk_dim"], int(first["chunk_count"])
    indices = sorted(int(p.attrs["chunk_index"]) for p in parts)
    if indices != list(range(count)):
        raise ChunkError(f"chunks {indices} do not make up 0..{count - 1} of the map")
    if any(p.attrs["chunk_dim"] != dim or int(p.attrs["chunk_count"]) != count for p in parts):
        raise ChunkError("chunks disagree on the chunked dimension or the chunk count")
    for key in sorted(set(first) - set(PER_CHUNK_ATTRS)):
        if any(not _same(p.attrs.get(key), first[key]) for p in parts):
            raise ChunkError(f"chunks disagree on attribute {key!r}: not one map")
    parts.sort(key=lambda p: int(p.attrs["chunk_index"]))
    wall_times = [float(p.attrs.get("wall_time_s", np.nan)) for p in parts]
    try:
        ds = xr.concat(
            parts,
            dim=dim,
            data_vars="minimal",
            coords="minimal",
            compat="equals",
            join="exact",
            combine_attrs="override",
        )
    except ValueError as exc:
        raise ChunkError(f"chunks do not fit together: {str(exc).splitlines()[0]}") from None
    for var in ds.variables.values():
        _fit_string_width(var)
    for key in ("chunk_dim", "chunk_index"):
        ds.attrs.pop(key)
    ds.attrs["chunk_wall_times_s"] = np.asarray(wall_times)
    ds.attrs["wall_time_s"] = float(np.sum(wall_times))
    return ds
