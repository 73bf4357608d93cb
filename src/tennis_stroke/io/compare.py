"""Two results compared bit for bit, except what differs between two runs of one job
(:data:`tennis_stroke.io.netcdf.RUN_ATTRS`, timings).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from .netcdf import RUN_ATTRS, load_result


def _loaded(source) -> xr.Dataset:
    if isinstance(source, xr.Dataset):
        return source
    return load_result(source)


def same_grid(a: xr.DataArray, b: xr.DataArray) -> bool:
    """Whether two variables lie on one grid: the same dimensions, and the same values
    along each that has a coordinate (what a difference of the two needs)."""
    return (a.dims, a.shape) == (b.dims, b.shape) and all(
        a[d].size == b[d].size and np.array_equal(a[d].values, b[d].values)
        for d in a.dims
        if d in a.coords
    )


def result_differences(a, b, also_differ: Sequence[str] = ()) -> list[str]:
    """How two results (datasets or netCDF paths) differ; empty when they are the same.

    The same means: every data variable and coordinate bit for bit (values, dtype,
    dimensions, attributes; strings compare as strings, whether read back as unicode or,
    from a character array, as objects), except wall-clock measurements (variables with a
    ``timing`` attribute), and every global attribute (configuration, parameters, versions, commit)
    except :data:`RUN_ATTRS` and ``also_differ``.
    """
    a, b = _loaded(a), _loaded(b)
    problems = []
    if set(a.variables) != set(b.variables):
        only = sorted(set(a.variables) ^ set(b.variables))
        problems.append(f"variables in one file only: {', '.join(map(str, only))}")
    for name in sorted(set(a.variables) & set(b.variables), key=str):
        if "timing" in a[name].attrs:
            continue
        va, vb = a[name].variable, b[name].variable
        if _kind(va.values) != _kind(vb.values) or not _same_value(va.values, vb.values):
            problems.append(f"variable {name}: values or dtype differ{_change(va, vb)}")
        elif not va.identical(vb):
            problems.append(f"variable {name}: dimensions or attributes differ")
    differ = {*RUN_ATTRS, *also_differ}
    for key in sorted(set(a.attrs) | set(b.attrs)):
        if key in differ:
            continue
        if key not in a.attrs or key not in b.attrs:
            problems.append(f"global attribute {key}: in one file only")
        elif not _same_value(a.attrs[key], b.attrs[key]):
            problems.append(f"global attribute {key}: differs")
    return problems


def _kind(values: np.ndarray) -> object:
    """The dtype of ``values``, or ``"str"`` for strings: xarray reads a string coordinate
    back as unicode from a variable-length string, as objects from a character array."""
    if values.dtype.kind == "U" or (
        values.dtype.kind == "O" and all(isinstance(v, str) for v in values.ravel())
    ):
        return "str"
    return values.dtype


def _same_value(x, y) -> bool:
    """Attribute values equal (NaN equals NaN in numbers)."""
    x, y = np.asarray(x), np.asarray(y)
    numeric = x.dtype.kind in "fc" and y.dtype.kind in "fc"
    return x.shape == y.shape and bool(np.array_equal(x, y, equal_nan=numeric))


def _change(va: xr.Variable, vb: xr.Variable) -> str:
    """For two float variables of one shape and dtype: how many values differ and by how
    much at most (absolute, and relative to the larger magnitude), as ``"; ..."``."""
    x, y = va.values, vb.values
    if x.shape != y.shape or x.dtype != y.dtype or x.dtype.kind != "f":
        return ""
    same = (x == y) | (np.isnan(x) & np.isnan(y))
    n = int((~same).sum())
    finite = ~same & np.isfinite(x) & np.isfinite(y)
    if not finite.any():
        return f"; {n} of {x.size} values (NaN or inf in one only)"
    d = np.abs(x[finite] - y[finite])
    rel = d / np.maximum(np.abs(x[finite]), np.abs(y[finite]))
    return f"; {n} of {x.size} values, by at most {d.max():.3g} (relative {rel.max():.3g})" + (
        "" if finite.sum() == n else f", {n - int(finite.sum())} NaN or inf in one only"
    )
