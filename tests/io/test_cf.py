"""Result files follow CF 1.10: the IOOS compliance checker (``cf:1.10``) finds no high-
or medium-priority failure in any of them, and can run every check on each."""

import warnings

import numpy as np
import pytest
import xarray as xr
from compliance_checker.runner import CheckSuite
from conftest import result_files

from tennis_stroke.io.compare import result_differences
from tennis_stroke.io.netcdf import provenance, result_dataset, write_netcdf
from tennis_stroke.io.units import cf_attrs
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver.results import COUNT_FIELDS, RESULT_FIELDS
from tennis_stroke.solver.settings import SolverSettings

CF = "cf:1.10"


@pytest.fixture(scope="module")
def suite():
    with warnings.catch_warnings():
        # the checker's deprecated non-CF suites warn when they load; CF is not among them
        warnings.simplefilter("ignore")
        CheckSuite.load_all_available_checkers()
    return CheckSuite()


def cf_failures(suite, path) -> list[str]:
    """The high- and medium-priority failures of ``cf:1.10`` on the file ``path`` (name:
    messages), and the checks that could not run on it."""
    ds = suite.load_dataset(str(path))
    try:
        groups, errors = suite.run_all(ds, [CF], skip_checks=[])[CF]
    finally:
        ds.close()
    report = suite.build_structure(CF, groups, str(path))
    failures = [
        f"{result.name}: {' '.join(result.msgs)}"
        for result in report["high_priorities"] + report["medium_priorities"]
        if result.value[0] < result.value[1]
    ]
    failures += [f"{check} could not run: {exc}" for check, (exc, _) in errors.items()]
    return failures


def _grid_map():
    """A map as the grid experiments write it: float axes, integer status with flags."""
    theta0, delta0 = np.array([80.0, 100.0]), np.array([20.0, 40.0, 60.0])
    results = {
        name: np.zeros((2, 3), dtype=np.int64 if name in COUNT_FIELDS else float)
        for name in RESULT_FIELDS
    }
    results["v_out_kmh"][0, 0] = np.nan  # a failed stroke
    return result_dataset(
        results, {"theta0": theta0, "delta0": delta0}, resolve_params(), SolverSettings()
    )


def _table():
    """A table as the studies write it: a string axis, and flags on a float variable."""
    ds = xr.Dataset(
        {
            "v_out_error": (("method", "setting"), np.ones((2, 2)), cf_attrs("v_out_error")),
            "outcome": (
                ("method", "setting"),
                np.array([[0.0, 1.0], [1.0, np.nan]]),
                cf_attrs("outcome", flag_values=np.arange(2), flag_meanings="ok failed"),
            ),
        },
        coords={
            "method": ("method", ["tennis_stroke.DP54", "scipy.RK45"], cf_attrs("method")),
            "setting": ("setting", [1e-6, 1e-8], cf_attrs("setting")),
        },
    )
    ds.attrs.update(provenance(resolve_params(), SolverSettings()))
    return ds


@pytest.mark.parametrize("make", [_grid_map, _table])
def test_a_written_dataset_passes_the_cf_checker_with_the_same_values(suite, tmp_path, make):
    ds = make()
    before = ds.copy(deep=True)
    path = write_netcdf(ds, tmp_path / "a.nc")
    assert not cf_failures(suite, path)
    assert result_differences(ds, path) == []
    # writing leaves the caller's dataset (attributes, encodings) as it was
    assert ds.identical(before)
    assert all(ds[name].encoding == before[name].encoding for name in ds.variables)


def test_a_rewritten_result_file_keeps_its_values_and_layout(tmp_path):
    ds = _table()
    first = write_netcdf(ds, tmp_path / "a.nc")
    second = write_netcdf(xr.load_dataset(first), tmp_path / "b.nc")
    assert result_differences(first, second) == []
    with xr.open_dataset(second) as back:
        assert back.indexes["method"].tolist() == ["tennis_stroke.DP54", "scipy.RK45"]
        assert back["outcome"].attrs["flag_values"].dtype == back["outcome"].dtype


def test_every_result_file_of_the_workflow_passes_the_cf_checker(suite, tiny_run):
    files = result_files(tiny_run, chunks=True)
    assert any("chunks" in name for name in files), files
    failures = {name: cf_failures(suite, tiny_run / name) for name in files}
    failing = {name: found for name, found in failures.items() if found}
    assert not failing, "\n".join(
        f"{name}:\n  " + "\n  ".join(found) for name, found in failing.items()
    )
