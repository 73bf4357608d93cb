"""The work-precision table: its shape and the order of its errors."""

from tennis_stroke.studies.sampling import sample_strokes
from tennis_stroke.studies.work_precision import work_precision


def test_work_precision_table_shape_and_order():
    s = sample_strokes(2, seed=2)
    ds = work_precision(s, [1e-4, 1e-8], [1e-6], [1e-3], scipy_methods=("DOP853",), repeats=1)
    assert ds["error_kmh"].dims == ("method", "setting")
    compiled = ds["error_kmh"].isel(method=1)
    assert float(compiled.sel(setting=1e-8)) < float(compiled.sel(setting=1e-4))
    assert float(ds["failed"].sum()) == 0
