"""Shared fixtures: the paper's default parameters and handy coefficient rows."""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from tennis_stroke.model.dynamics import coefficients
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver._kernels import coefficient_tuple

#: The two strokes of the paper's Fig. 4: (theta0, delta0) in degrees.
FIG4_A = (120.0, 81.5)
FIG4_B = (75.0, 39.0)


@pytest.fixture(autouse=True)
def _raise_on_float_errors():
    """Floating-point warnings are errors in tests."""
    with np.errstate(divide="raise", over="raise", invalid="raise", under="ignore"):
        yield


def coefficient_row(theta0=90.0, delta0=30.0, **overrides):
    """One coefficient row (array) for the given angles and parameter overrides."""
    return coefficients(resolve_params(overrides), theta0, delta0)[0]


def coefficient_tup(theta0=90.0, delta0=30.0, **overrides):
    """The same as a tuple, as the compiled kernels take it."""
    return coefficient_tuple(coefficient_row(theta0, delta0, **overrides))


ROOT = Path(__file__).resolve().parents[1]


def snakemake_command(targets, workdir, *options) -> list[str]:
    """Command line running this project's Snakefile on ``targets`` (a path or a list) in
    ``workdir``; targets come first, as options that take several values would swallow
    them."""
    targets = [targets] if isinstance(targets, str) else list(targets)
    snakemake = Path(sys.executable).with_name("snakemake")
    return [
        str(snakemake),
        *targets,
        "-s",
        str(ROOT / "Snakefile"),
        "--directory",
        str(workdir),
        *options,
    ]


def run_snakemake(targets, workdir, *options, timeout=300):
    """Run :func:`snakemake_command`; returns the completed process."""
    command = snakemake_command(targets, workdir, *options)
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout)


#: Global attributes that differ between two runs of the same job, and only those: when
#: the file was written, and wall-clock timings (of the job, of a map's chunks, of the
#: model ladder's two models).
RUN_ATTRS = (
    "history",
    "wall_time_s",
    "chunk_wall_times_s",
    "us_per_stroke_spring",
    "us_per_stroke_impact_python",
)


def _dataset(source) -> xr.Dataset:
    if isinstance(source, xr.Dataset):
        return source
    with xr.open_dataset(source) as ds:
        return ds.load()


def assert_same_results(a, b, also_differ=()):
    """Two results (datasets or netCDF paths) are the same: every data variable and
    coordinate bit for bit (values, dtype, dimensions, attributes), except wall-clock
    measurements (variables with a ``timing`` attribute), and every global attribute
    (configuration, parameters, versions, commit) except :data:`RUN_ATTRS` and
    ``also_differ``."""
    a, b = _dataset(a), _dataset(b)
    assert set(a.variables) == set(b.variables)
    for name in a.variables:
        if "timing" in a[name].attrs:
            continue
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name, strict=True)
        xr.testing.assert_identical(a[name].variable, b[name].variable)
    differ = {*RUN_ATTRS, *also_differ}
    kept = [{k: v for k, v in d.attrs.items() if k not in differ} for d in (a, b)]
    xr.testing.assert_identical(xr.Dataset(attrs=kept[0]), xr.Dataset(attrs=kept[1]))


def workdir(parent, config):
    """A working directory for the Snakefile holding ``config`` and the claims."""
    (parent / "config").mkdir(parents=True)
    (parent / "config" / "config.yaml").write_text(yaml.safe_dump(config))
    shutil.copy(ROOT / "config" / "claims.yaml", parent / "config" / "claims.yaml")
    return parent


def result_files(work, chunks=False):
    """The result files under ``work`` (relative paths); with ``chunks``, map chunks too."""
    return sorted(
        str(p.relative_to(work))
        for p in (work / "results").rglob("*.nc")
        if chunks or "chunks" not in p.parts
    )
